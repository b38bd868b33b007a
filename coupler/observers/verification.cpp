#include "observers/verification.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "run/text_lines.hpp"

namespace rockcut::coupler {

std::vector<std::string> verification_fields(const rockcut::Scene& scene) {
  if (scene.verification().analytical() == "uniform_acceleration") return {};
  return fluid_verification_fields(scene);
}

VerificationResult verify(const rockcut::Scene& scene, const FinalState& state) {
  const rockcut::Verification& v = scene.verification();
  if (v.analytical() != "uniform_acceleration") return verify_fluid(scene, state);
  const std::span<const double> x0 = state.initial_position, x = state.position;
  const double time_s = state.time_s;
  if (x0.size() != x.size()) throw std::invalid_argument("position arrays differ in size");
  double ax = scene.dem().gravity_m_s2().x();
  double ay = scene.dem().gravity_m_s2().y();
  if (scene.has_fluid() && scene.fluid().model() == "prescribed_gradient") {
    const rockcut::Vec2& g = scene.fluid().prescribed_gradient().pressure_gradient_pa_m();
    ax -= g.x() / scene.dem().density_kg_m3();
    ay -= g.y() / scene.dem().density_kg_m3();
  }
  const double vx = scene.dem().initial_velocity_m_s().x();
  const double vy = scene.dem().initial_velocity_m_s().y();
  const double t = time_s;
  const double dx = vx * t + 0.5 * ax * t * t;  // the exact displacement, the same for every disc
  const double dy = vy * t + 0.5 * ay * t * t;

  double err_max = 0.0, err_sq = 0.0, disp_max = 0.0, disp_sq = 0.0;
  for (std::size_t k = 0; k + 1 < x.size(); k += 2) {
    const double ex = x[k] - (x0[k] + dx), ey = x[k + 1] - (x0[k + 1] + dy);
    const double e2 = ex * ex + ey * ey, d2 = dx * dx + dy * dy;
    err_max = std::max(err_max, std::sqrt(e2));
    err_sq += e2;
    disp_max = std::max(disp_max, std::sqrt(d2));
    disp_sq += d2;
  }
  VerificationResult r;
  r.analytical = v.analytical();
  r.tolerance_rel = v.tolerance_rel();
  r.error_max_rel = disp_max > 0 ? err_max / disp_max : err_max;
  r.error_l2_rel = disp_sq > 0 ? std::sqrt(err_sq / disp_sq) : std::sqrt(err_sq);
  r.passed = std::isfinite(r.error_max_rel) && r.error_max_rel <= r.tolerance_rel;
  return r;
}

VerificationCheck::VerificationCheck(const rockcut::Scene& scene)
    : scene_(scene), fields_(verification_fields(scene)) {}

void VerificationCheck::frame(const RunClock&, std::span<const FrameField> fields) {
  for (const FrameField& f : fields) {
    if (f.name == "position") {
      if (initial_position_.empty()) initial_position_.assign(f.values.begin(), f.values.end());
      last_position_.assign(f.values.begin(), f.values.end());
    } else if (std::find(fields_.begin(), fields_.end(), f.name) != fields_.end()) {
      final_fields_[f.name].assign(f.values.begin(), f.values.end());
    }
  }
}

bool VerificationCheck::finish(const RunClock& clock, Summary& summary, bool completed) {
  if (!completed) return true;
  FinalState state{clock.time_s, initial_position_, last_position_, {}};
  for (const auto& [name, values] : final_fields_) state.fields.emplace(name, values);
  const VerificationResult v = verify(scene_, state);
  summary.set("verification", v.analytical);
  summary.set("error_max_rel", v.error_max_rel);
  summary.set("error_l2_rel", v.error_l2_rel);
  summary.set("error_tolerance_rel", v.tolerance_rel);
  summary.set("verification_passed", v.passed);
  std::printf("verification %s: error_max_rel %.3e, error_l2_rel %.3e (tolerance %.1e): %s\n",
              v.analytical.c_str(), v.error_max_rel, v.error_l2_rel, v.tolerance_rel,
              v.passed ? "passed" : "FAILED");
  return v.passed;
}

void VerificationCheck::save_state(state::StateArchive& a) const {
  a.put("initial_position_m", initial_position_, 2);
  a.put("last_position_m", last_position_, 2);
  std::vector<std::string> names;
  for (const auto& [name, values] : final_fields_) {
    names.push_back(name);
    a.put("final_field:" + name, values);
  }
  a.put_text("final_fields", join_lines(names));
}

void VerificationCheck::load_state(const state::StateArchive& a) {
  a.get("initial_position_m", initial_position_);
  a.get("last_position_m", last_position_);
  final_fields_.clear();
  for (const std::string& name : split_lines(a.text("final_fields"))) {
    a.get("final_field:" + name, final_fields_[name]);
  }
}

}  // namespace rockcut::coupler
