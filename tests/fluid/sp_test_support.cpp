#include "fluid/sp_test_support.hpp"

#include "sp/consistent_laplacian.hpp"
#include "sp/operators.hpp"

#include <algorithm>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>
#include <stdexcept>

namespace rockcut::fluid::test {

Particles lattice(int nx, int ny, double spacing_m, double radius_m) {
  Particles p;
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      p.position.push_back(i * spacing_m);
      p.position.push_back(j * spacing_m);
      p.radius.push_back(radius_m);
    }
  }
  return p;
}

Particles jittered(int nx, int ny, double spacing_m, double jitter, std::uint64_t seed) {
  Particles p = lattice(nx, ny, spacing_m, 0.4 * spacing_m);
  std::mt19937_64 rng(seed);
  // Our own mapping to [-1, 1): std::uniform_real_distribution is implementation-defined.
  auto uniform = [&] { return static_cast<double>(rng() >> 11) * 0x1.0p-52 - 1.0; };
  for (double& c : p.position) c += jitter * spacing_m * uniform();
  return p;
}

Particles random_packing() {
  const std::string path = std::string(ROCKCUT_SOURCE_DIR) + "/cases/verification/packing_30mm.txt";
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open " + path);
  Particles p;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream s(line);
    double x, y, r;
    if (s >> x >> y >> r) {
      p.position.push_back(x);
      p.position.push_back(y);
      p.radius.push_back(r);
    }
  }
  return p;
}

std::vector<double> distance_to_box(const Particles& p) {
  double x0 = std::numeric_limits<double>::infinity(), y0 = x0, x1 = -x0, y1 = -x0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    x0 = std::min(x0, p.x(i));
    x1 = std::max(x1, p.x(i));
    y0 = std::min(y0, p.y(i));
    y1 = std::max(y1, p.y(i));
  }
  std::vector<double> d(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    d[i] = std::min({p.x(i) - x0, x1 - p.x(i), p.y(i) - y0, y1 - p.y(i)});
  }
  return d;
}

sp::SpParams table1(double h_m, std::array<bool, 4> sealed) {
  sp::SpParams s;  // the defaults are Table 1's
  s.h_m = h_m;
  s.sealed = sealed;
  return s;
}

Driver::Driver(FluidModel& model, const Particles& p)
    : model_(model), x_(p.position), d_(p.position.size(), 0.0), v_(p.position.size(), 0.0),
      force_(p.position.size(), 0.0) {
  model_.initialise({p.radius, p.position});
  model_.step(0.0, 0.0, {x_, v_, d_, {}}, force_);  // the t = 0 exchange: forces only
}

void Driver::step(double dt_s, double exx, double eyy) {
  // As DemSystem::begin_step with prescribed motion: v^{n+1/2} from x^n, then the drift.
  for (std::size_t i = 0; i < x_.size() / 2; ++i) {
    v_[2 * i] = exx * x_[2 * i];
    v_[2 * i + 1] = eyy * x_[2 * i + 1];
    d_[2 * i] = dt_s * v_[2 * i];
    d_[2 * i + 1] = dt_s * v_[2 * i + 1];
    x_[2 * i] += d_[2 * i];
    x_[2 * i + 1] += d_[2 * i + 1];
  }
  t_ += dt_s;
  model_.step(dt_s, t_, {x_, v_, d_, {}}, force_);
}

double compress_undrained(Driver& drive, const sp::SpParams& params, double rate_per_s,
                          double dt_s, int steps) {
  double expected = params.p_hydro_pa;
  const double am = params.alpha * params.bulk_modulus_pa;
  for (int k = 0; k < steps; ++k) {
    drive.step(dt_s, rate_per_s, rate_per_s);
    const double a = rate_per_s * dt_s;
    expected += -am * 2.0 * a / (1.0 + a);
  }
  return expected;
}

void apply_laplacian(sp::LaplacianForm form, const sp::Geometry& geo, std::span<const double> a,
                     std::span<double> lap) {
  if (form == sp::LaplacianForm::consistent) {
    sp::consistent_laplacian(geo, a, lap);
  } else {
    sp::laplacian(geo, a, lap);
  }
}

double laplacian_weight(sp::LaplacianForm form, const sp::Geometry& geo, std::size_t i) {
  return form == sp::LaplacianForm::paper
             ? geo.volume[i]
             : geo.volume[i] / sp::consistent_laplacian_scale(geo.l_trace[i]);
}

}  // namespace rockcut::fluid::test
