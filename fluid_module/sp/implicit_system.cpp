#include "sp/implicit_system.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "sp/cavitation.hpp"
#include "sp/consistent_laplacian.hpp"

namespace rockcut::fluid::sp {

ImplicitSystem::ImplicitSystem(double tolerance, unsigned max_iterations,
                               LaplacianForm laplacian)
    : tolerance_(tolerance), max_iterations_(max_iterations), laplacian_(laplacian) {}

double ImplicitSystem::mass(const Geometry& geo, int i) const {
  const double v = geo.volume[static_cast<std::size_t>(i)];
  if (laplacian_ == LaplacianForm::paper) return v;
  return v / consistent_laplacian_scale(geo.l_trace[static_cast<std::size_t>(i)]);
}

void ImplicitSystem::rebuild_pattern(const Geometry& geo) {
  const int n = static_cast<int>(geo.particles());
  const int* begin = geo.row_begin.data();
  const int* end = geo.row_end.data();
  const int* nb = geo.neighbours.data();
  a_.resize(n, n);
  a_.resizeNonZeros(static_cast<Eigen::Index>(geo.pairs()) + n);
  row_start_.resize(static_cast<std::size_t>(n));
  int* outer = a_.outerIndexPtr();
  int* inner = a_.innerIndexPtr();
  diagonal_.resize(static_cast<std::size_t>(n));
  // Row i: its neighbours inside the support (sorted) with i inserted in order; the value of the
  // geometry's pair k of row i sits at row_start_[i] + k (+1 if the neighbour comes after i).
  int pos = 0;
  for (int i = 0; i < n; ++i) {
    outer[i] = pos;
    row_start_[i] = pos - begin[i];
    bool placed = false;
    for (int k = begin[i]; k < end[i]; ++k) {
      if (!placed && nb[k] > i) {
        diagonal_[i] = pos;
        inner[pos++] = i;
        placed = true;
      }
      inner[pos++] = nb[k];
    }
    if (!placed) {
      diagonal_[i] = pos;
      inner[pos++] = i;
    }
  }
  outer[n] = pos;
  pattern_of_geometry_ = geo.version;
}

void ImplicitSystem::assemble(double dt_s, double d_m2_s, const Geometry& geo,
                              std::span<const double> source, std::span<const double> p) {
  const int n = static_cast<int>(geo.particles());
  const int* begin = geo.row_begin.data();
  const int* end = geo.row_end.data();
  const int* nb = geo.neighbours.data();
  const double* v = geo.volume.data();
  double* values = a_.valuePtr();
  const double c = dt_s * d_m2_s;
  for (int i = 0; i < n; ++i) {
    const int row = row_start_[i];
    if (fixed_[i] != free) {
      for (int k = begin[i]; k < end[i]; ++k) values[row + k + (nb[k] > i)] = 0.0;
      values[diagonal_[i]] = v[i];
      b_[i] = v[i] * fixed_value_[i];
      continue;
    }
    const double m = mass(geo, i);
    double sum_w = 0.0, flux = 0.0, moved = 0.0;
    for (int k = begin[i]; k < end[i]; ++k) {
      const int j = nb[k];
      const double w = -2.0 * v[i] * v[j] * geo.f[k];  // >= 0
      sum_w += w;
      flux += w * (p[i] - p[j]);
      double& a_ij = values[row + k + (j > i)];
      if (fixed_[j] != free) {
        a_ij = 0.0;
        moved += w * fixed_value_[j];  // the known increment of a fixed neighbour
      } else {
        a_ij = -c * w;
      }
    }
    values[diagonal_[i]] = m + c * sum_w;
    b_[i] = dt_s * (m * source[i] - d_m2_s * flux) + c * moved;
  }
}

double ImplicitSystem::free_residual(int i, double dt_s, double d_m2_s, const Geometry& geo,
                                     std::span<const double> source,
                                     std::span<const double> p) const {
  const int* nb = geo.neighbours.data();
  const double* v = geo.volume.data();
  const double m = mass(geo, i);
  double lhs = m * d_[i], flux = 0.0;
  for (int k = geo.row_begin[i]; k < geo.row_end[i]; ++k) {
    const int j = nb[k];
    const double w = -2.0 * v[i] * v[j] * geo.f[k];
    lhs += dt_s * d_m2_s * w * (d_[i] - d_[j]);
    flux += w * (p[i] - p[j]);
  }
  return dt_s * (m * source[i] - d_m2_s * flux) - lhs;
}

ImplicitReport ImplicitSystem::step(double dt_s, double diffusivity_m2_s, const Geometry& geo,
                                    std::span<const double> source,
                                    std::span<const Boundary> boundary, double p_hydro_pa,
                                    bool cavitation, double p_min_pa, std::span<double> p) {
  const std::size_t n = geo.particles();
  if (pattern_of_geometry_ != geo.version) rebuild_pattern(geo);
  if (static_cast<std::size_t>(b_.size()) != n) {
    b_.setZero(static_cast<Eigen::Index>(n));
    d_.setZero(static_cast<Eigen::Index>(n));
    guess_.setZero(static_cast<Eigen::Index>(n));
  }
  fixed_.resize(n);
  fixed_value_.resize(n);
  // Initial active set: drained particles, and the particles clamped at the end of the last step.
  for (std::size_t i = 0; i < n; ++i) {
    if (boundary[i] == Boundary::drained) {
      fixed_[i] = drained;
      fixed_value_[i] = p_hydro_pa - p[i];
    } else if (cavitation && at_vapour_pressure(p[i], p_min_pa)) {
      fixed_[i] = clamped;
      fixed_value_[i] = p_min_pa - p[i];
    } else {
      fixed_[i] = free;
    }
  }

  ImplicitReport report;
  cg_.setTolerance(tolerance_);
  cg_.setMaxIterations(static_cast<Eigen::Index>(max_iterations_));
  while (true) {
    ++report.rounds;
    for (std::size_t i = 0; i < n; ++i) {
      if (fixed_[i] != free) guess_[i] = fixed_value_[i];
    }
    assemble(dt_s, diffusivity_m2_s, geo, source, p);
    cg_.compute(a_);
    d_ = cg_.solveWithGuess(b_, guess_);
    report.iterations += static_cast<unsigned>(cg_.iterations());
    if (cg_.info() != Eigen::Success) {
      throw std::runtime_error(
          "implicit: the conjugate-gradient solve did not reach the relative residual " +
          std::to_string(tolerance_) + " in " + std::to_string(cg_.iterations()) +
          " iterations (reached " + std::to_string(cg_.error()) +
          "); raise fluid.implicit.max_iterations or fluid.implicit.tolerance, or shorten the "
          "fluid step");
    }
    guess_ = d_;
    if (!cavitation || report.rounds >= kMaxRounds) break;
    bool changed = false;
    const int ni = static_cast<int>(n);
    for (int i = 0; i < ni; ++i) {
      if (fixed_[i] == free && below_vapour_pressure(p[i] + d_[i], p_min_pa)) {
        fixed_[i] = clamped;
        fixed_value_[i] = p_min_pa - p[i];
        changed = true;
      } else if (fixed_[i] == clamped &&
                 free_residual(i, dt_s, diffusivity_m2_s, geo, source, p) > 0.0) {
        fixed_[i] = free;  // inflow exceeds what holding p_min absorbs: eq. 22 releases it
        changed = true;
      }
    }
    if (!changed) break;
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (fixed_[i] == drained) {
      p[i] = p_hydro_pa;
    } else if (fixed_[i] == clamped) {
      p[i] = p_min_pa;
      ++report.clamped;
    } else {
      p[i] += d_[i];
      // Round-off of the solve (or the round cap) must not leave a pressure below p_min.
      if (cavitation && below_vapour_pressure(p[i], p_min_pa)) {
        p[i] = p_min_pa;
        ++report.clamped;
      }
    }
  }
  return report;
}

void ImplicitSystem::set_guess(std::span<const double> guess) {
  const auto n = static_cast<Eigen::Index>(guess.size());
  guess_ = Eigen::Map<const Eigen::VectorXd>(guess.data(), n);
  // step() sizes its vectors only when the count changes: keep b and d consistent with the guess.
  b_.setZero(n);
  d_.setZero(n);
}

}  // namespace rockcut::fluid::sp
