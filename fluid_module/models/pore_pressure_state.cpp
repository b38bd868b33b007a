// The pore-pressure models' part of a checkpoint. The pressure, the strain rate and the counters
// are saved as they are; the SP geometry is not (at paper scale it is most of the model's memory)
// but rebuilt from the positions it was computed on: the neighbour lists from their last build's
// positions, the geometry by a full update on geo.position (which a local refresh reproduces bit
// for bit, sp/geometry.hpp) and the step's coefficients from the geometry. The boundary is saved,
// since it was classified against the walls of its own time.
#include "models/implicit_model.hpp"
#include "models/pore_pressure_model.hpp"

namespace rockcut::fluid::sp {

using state::StateArchive;
using state::StateError;

void PorePressureModel::save_state(StateArchive& a) const {
  a.put("pressure_pa", pressure_);
  a.put("volumetric_strain_rate_per_s", strain_rate_);
  a.put_values("boundary", boundary_);
  a.put("list_position_at_build_m", list_.position_at_build(), 2);
  a.put_scalar("list_builds", static_cast<double>(list_.builds()));
  a.put("geometry_position_m", geo_.position, 2);
  a.put("walls_at_geometry_m", walls_at_geometry_, 4);
  a.put("counters", std::vector<double>{
                        static_cast<double>(counts_.drained), static_cast<double>(counts_.sealed),
                        static_cast<double>(cavitated_), static_cast<double>(geometry_updates_),
                        static_cast<double>(boundary_updates_), static_cast<double>(local_updates_),
                        static_cast<double>(rows_recomputed_)});
  if (params_.open_water_drag) a.put_scalar("drag_work_j", drag_work_j_);
  save_model_state(a);
}

void PorePressureModel::load_state(const StateArchive& a) {
  self_stiffness_stale_ = true;
  const std::size_t n = radius_.size();
  a.get("pressure_pa", pressure_, n);
  a.get("volumetric_strain_rate_per_s", strain_rate_, n);
  a.get_values("boundary", boundary_, n);
  for (Boundary b : boundary_) {
    if (b != Boundary::interior && b != Boundary::drained && b != Boundary::sealed) {
      throw StateError("state member \"boundary\" holds an unknown class");
    }
  }
  list_.restore(a.values("list_position_at_build_m", 2 * n),
                a.scalar_as<std::uint64_t>("list_builds"));
  const auto position = a.values("geometry_position_m", 2 * n);
  update_geometry(list_, kernel_, position, lucy_volume_, params_.volume_iterations, geo_);
  update_share();
  step_op_.build(geo_);
  a.get("walls_at_geometry_m", walls_at_geometry_);
  if (walls_at_geometry_.size() % 4 != 0) {
    throw StateError("state member \"walls_at_geometry_m\" is not 4 values per segment");
  }
  const auto c = a.values("counters", 7);
  counts_.drained = static_cast<std::size_t>(c[0]);
  counts_.sealed = static_cast<std::size_t>(c[1]);
  cavitated_ = static_cast<std::size_t>(c[2]);
  geometry_updates_ = static_cast<std::uint64_t>(c[3]);
  boundary_updates_ = static_cast<std::uint64_t>(c[4]);
  local_updates_ = static_cast<std::uint64_t>(c[5]);
  rows_recomputed_ = static_cast<std::uint64_t>(c[6]);
  // A state saved without the drag (or before it existed) resumes with none done yet.
  drag_work_j_ = a.has("drag_work_j") ? a.scalar("drag_work_j") : 0.0;
  load_model_state(a);
}

void ImplicitModel::save_model_state(StateArchive& a) const {
  a.put("implicit_guess_pa", system_.guess());
}

void ImplicitModel::load_model_state(const StateArchive& a) {
  const auto guess = a.values("implicit_guess_pa");
  if (!guess.empty() && guess.size() != radius_.size()) {
    throw StateError("state member \"implicit_guess_pa\" has " + std::to_string(guess.size()) +
                     " values for " + std::to_string(radius_.size()) + " particles");
  }
  if (!guess.empty()) system_.set_guess(guess);
}

}  // namespace rockcut::fluid::sp
