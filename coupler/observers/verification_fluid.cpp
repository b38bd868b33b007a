// Analytical solutions of the pore-pressure equation (eq. 14) for the fluid-only verification
// scenes (DESIGN section 7). Every parameter is taken from the scene itself: D = M kappa / mu,
// alpha M and p_hydro from `fluid`, the load from `dem.prescribed_motion`, the geometry from the
// lattice. Errors are over every particle at the final time, relative to the largest analytical
// pressure change (the excess over p_hydro), so they do not depend on the absolute pressure level.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "observers/verification.hpp"

namespace rockcut::coupler {

namespace {

struct Pore {
  double diffusivity_m2_s;  // D = M kappa / mu
  double alpha_m_pa;        // alpha M
  double p_hydro_pa;        // p_atm + rho_w g H
};

Pore pore_of(const rockcut::Scene& scene) {
  const rockcut::Fluid& f = scene.fluid();
  return {f.bulk_modulus_pa() * f.permeability_m2() / f.viscosity_pa_s(),
          f.biot_coefficient() * f.bulk_modulus_pa(),
          f.atmospheric_pressure_pa() +
              f.water_density_kg_m3() * f.gravity_m_s2() * scene.water_depth_m()};
}

// The prescribed volumetric strain rate and the interval [start, end) in which it acts.
struct Load {
  double strain_rate_per_s = 0.0;
  double start_s = 0.0, end_s = INFINITY;
  /// Volumetric strain applied up to t.
  double strain_at(double t) const {
    return strain_rate_per_s * std::max(0.0, std::min(t, end_s) - start_s);
  }
};

Load load_of(const rockcut::Scene& scene) {
  const rockcut::PrescribedMotion& m = scene.dem().prescribed_motion();
  Load l;
  l.strain_rate_per_s = m.strain_rate_xx_per_s() + m.strain_rate_yy_per_s();
  l.start_s = m.start_time_s();
  if (m.has_end_time_s()) l.end_s = m.end_time_s();
  return l;
}

bool sealed(const rockcut::Scene& scene, const std::string& side) {
  const auto& s = scene.fluid().sealed_sides();
  return std::find(s.begin(), s.end(), side) != s.end();
}

[[noreturn]] void refuse(const std::string& analytical, const std::string& why) {
  throw std::invalid_argument("verification.analytical = \"" + analytical + "\" " + why);
}

// Errors of `p` against `exact`, relative to the exact change over p_hydro.
VerificationResult compare(const rockcut::Scene& scene, std::span<const double> p,
                           const std::vector<double>& exact, double p_hydro_pa) {
  double err_max = 0.0, err_sq = 0.0, ref_max = 0.0, ref_sq = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double e = p[i] - exact[i], r = exact[i] - p_hydro_pa;
    err_max = std::max(err_max, std::abs(e));
    err_sq += e * e;
    ref_max = std::max(ref_max, std::abs(r));
    ref_sq += r * r;
  }
  VerificationResult v;
  v.analytical = scene.verification().analytical();
  v.tolerance_rel = scene.verification().tolerance_rel();
  v.error_max_rel = ref_max > 0 ? err_max / ref_max : err_max;
  v.error_l2_rel = ref_sq > 0 ? std::sqrt(err_sq / ref_sq) : std::sqrt(err_sq);
  v.passed = std::isfinite(v.error_max_rel) && std::isfinite(v.error_l2_rel) &&
             v.error_max_rel <= v.tolerance_rel;
  return v;
}

// Terzaghi's 1D consolidation (Terzaghi 1943) of a column drained at z = 0 (the top row) and sealed
// at z = L, under a constant pressure rate q = -alpha M d(eps_v)/dt applied in [t_s, t_e) (by
// Duhamel's principle from the series for an instantaneous load):
//   p - p_hydro = sum_m (2 q / M_m) sin(M_m z / L) (1 / c_m)
//                 [exp(-c_m (t - min(t, t_e))) - exp(-c_m (t - min(t, t_s)))],
//   M_m = pi (2m + 1) / 2,  c_m = M_m^2 D / L^2.
// On the lattice the no-flux wall of the SP Laplacian lies half a spacing below the last row, so
// L = (ny - 1/2) spacing.
std::vector<double> terzaghi(const rockcut::Scene& scene, const FinalState& s) {
  const Pore pore = pore_of(scene);
  const Load load = load_of(scene);
  const double spacing = scene.dem().lattice().spacing_m();
  double y_top = -INFINITY, y_bottom = INFINITY;
  for (std::size_t k = 1; k < s.initial_position.size(); k += 2) {
    y_top = std::max(y_top, s.initial_position[k]);
    y_bottom = std::min(y_bottom, s.initial_position[k]);
  }
  const double L = y_top - y_bottom + 0.5 * spacing;
  const double q = -pore.alpha_m_pa * load.strain_rate_per_s;
  const double t = s.time_s;
  const double ta = std::min(t, load.start_s), tb = std::min(t, load.end_s);
  // Mode amplitudes; stop when the bound 2 |q| / (M_m c_m) exp(-c_m (t - t_b)) is below 1e-15 of
  // the load's full pressure change (or after 200,000 modes, which only a final time inside the
  // load ramp needs: then the amplitudes fall like 1 / M_m^3).
  const double scale = std::abs(q) * std::max(tb - ta, 1e-300);
  std::vector<double> amplitude, wavenumber;
  for (int m = 0; m < 200000; ++m) {
    const double M = std::numbers::pi * (2 * m + 1) / 2.0;
    const double c = M * M * pore.diffusivity_m2_s / (L * L);
    const double a = 2.0 * q / (M * c) * (std::exp(-c * (t - tb)) - std::exp(-c * (t - ta)));
    amplitude.push_back(a);
    wavenumber.push_back(M / L);
    if (2.0 * std::abs(q) / (M * c) * std::exp(-c * (t - tb)) < 1e-15 * scale) break;
  }
  std::vector<double> exact(s.initial_position.size() / 2);
  for (std::size_t i = 0; i < exact.size(); ++i) {
    const double z = y_top - s.initial_position[2 * i + 1];  // depth below the drained top
    double sum = 0.0;
    for (std::size_t m = 0; m < amplitude.size(); ++m) sum += amplitude[m] * std::sin(wavenumber[m] * z);
    exact[i] = pore.p_hydro_pa + sum;
  }
  return exact;
}

// A Gaussian pulse in the unbounded plane: p - p_hydro = A sigma^2 / s^2 exp(-|x - c|^2 / (2 s^2)),
// s^2 = sigma^2 + 2 D t (the heat kernel convolved with the initial Gaussian).
std::vector<double> gaussian_pulse(const rockcut::Scene& scene, const FinalState& s) {
  const Pore pore = pore_of(scene);
  const rockcut::GaussianPulse& g = scene.fluid().initial_pulse();
  const double s2 = g.sigma_m() * g.sigma_m() + 2.0 * pore.diffusivity_m2_s * s.time_s;
  const double peak = g.amplitude_pa() * g.sigma_m() * g.sigma_m() / s2;
  std::vector<double> exact(s.position.size() / 2);
  for (std::size_t i = 0; i < exact.size(); ++i) {
    const double dx = s.position[2 * i] - g.centre_m().x();
    const double dy = s.position[2 * i + 1] - g.centre_m().y();
    exact[i] = pore.p_hydro_pa + peak * std::exp(-(dx * dx + dy * dy) / (2.0 * s2));
  }
  return exact;
}

// A sealed specimen compressed (or stretched) uniformly: no flow, so dp = -alpha M d(eps_v)
// everywhere (eq. 14 with a uniform pressure, whose Laplacian vanishes). With fluid.cavitation the
// pressure cannot fall below p_min (eq. 22): the load is one constant strain rate, so the pressure
// moves one way, and a specimen stretched past cavitation holds max(p_hydro + dp, p_min).
std::vector<double> undrained_step(const rockcut::Scene& scene, const FinalState& s) {
  const Pore pore = pore_of(scene);
  const double dp = -pore.alpha_m_pa * load_of(scene).strain_at(s.time_s);
  double p = pore.p_hydro_pa + dp;
  if (scene.fluid().cavitation()) p = std::max(p, scene.fluid().cavitation_pressure_pa());
  return std::vector<double>(s.position.size() / 2, p);
}

}  // namespace

std::vector<std::string> fluid_verification_fields(const rockcut::Scene& scene) {
  const std::string& a = scene.verification().analytical();
  const std::string model = scene.has_fluid() ? scene.fluid().model() : "";
  if (model != "explicit" && model != "implicit") {
    refuse(a, "needs a pore-pressure model (fluid.model: \"explicit\" or \"implicit\")");
  }
  if (a == "terzaghi") {
    if (!scene.dem().has_lattice()) refuse(a, "needs dem.lattice (the drainage length is (ny - 1/2) spacing)");
    if (!scene.dem().has_prescribed_motion()) refuse(a, "needs dem.prescribed_motion (the load)");
    if (!sealed(scene, "left") || !sealed(scene, "right") || !sealed(scene, "bottom") ||
        sealed(scene, "top")) {
      refuse(a, "needs fluid.sealed_sides: [\"left\", \"right\", \"bottom\"] (drained at the top only)");
    }
    if (scene.fluid().has_initial_pulse()) refuse(a, "needs no fluid.initial_pulse");
  } else if (a == "gaussian_pulse") {
    if (!scene.fluid().has_initial_pulse()) refuse(a, "needs fluid.initial_pulse");
    const rockcut::PrescribedMotion& m = scene.dem().prescribed_motion();
    if (!scene.dem().has_prescribed_motion() || m.strain_rate_xx_per_s() != 0 ||
        m.strain_rate_yy_per_s() != 0) {
      refuse(a, "needs particles at rest: dem.prescribed_motion with zero strain rates");
    }
  } else if (a == "undrained_step") {
    if (!scene.dem().has_prescribed_motion()) refuse(a, "needs dem.prescribed_motion (the load)");
    for (const char* side : {"left", "right", "bottom", "top"}) {
      if (!sealed(scene, side)) refuse(a, "needs all four fluid.sealed_sides (no drainage)");
    }
    if (scene.fluid().has_initial_pulse()) refuse(a, "needs no fluid.initial_pulse");
  } else {
    refuse(a, "is not a known analytical solution");
  }
  return {"pressure"};
}

VerificationResult verify_fluid(const rockcut::Scene& scene, const FinalState& state) {
  fluid_verification_fields(scene);
  const auto it = state.fields.find("pressure");
  if (it == state.fields.end() || it->second.size() * 2 != state.position.size() ||
      state.initial_position.size() != state.position.size()) {
    throw std::invalid_argument("verification: the final frame lacks the pressure of every particle");
  }
  const std::string& a = scene.verification().analytical();
  const std::vector<double> exact = a == "terzaghi"         ? terzaghi(scene, state)
                                    : a == "gaussian_pulse" ? gaussian_pulse(scene, state)
                                                            : undrained_step(scene, state);
  return compare(scene, it->second, exact, pore_of(scene).p_hydro_pa);
}

}  // namespace rockcut::coupler
