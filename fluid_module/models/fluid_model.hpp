// The interface every fluid model implements. The service owns the wire; a model sees plain arrays.
// Models are chosen by name in the scene (`fluid.model`) through models/registry.hpp.
#pragma once

#include <cstddef>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "wire/state_archive.hpp"
#include "wire/phase_clock.hpp"

namespace rockcut::fluid {

/// What a limit bounds (sent as wire.proto's LimitKind): the coupler picks limits by it.
enum class LimitKind { other, diffusion, pore_fluid_stiffness, pore_fluid_stiffness_extrapolated };

/// Largest stable step of a model's own integrator.
struct StabilityLimit {
  std::string name;       ///< for the start-up report
  double dt_max_s = 0.0;
  std::string detail;
  bool lag_only = false;  ///< bounds only a lagged coupling (N > 1); N = 1 is always allowed
  std::string remedy;     ///< what to change when it refuses a scene (besides a smaller step)
  LimitKind kind = LimitKind::other;
};

/// Per-step kinematics; only the fields the model listed in needs() are filled.
struct Kinematics {
  std::span<const double> position;       ///< [m], 2 per particle, x^{n+N}
  std::span<const double> velocity_half;  ///< [m/s], 2 per particle, v^{n+N-1/2}
  std::span<const double> displacement;   ///< [m], 2 per particle, since the last exchange
  std::span<const double> wall_segments;  ///< [m], 4 per rigid segment (ax, ay, bx, by), now
};

/// An axis-aligned box over which the pressure is averaged (a pressure node).
struct ProbeBox {
  double x_min_m, y_min_m, x_max_m, y_max_m;
};

/// Static particle data sent once at Init.
struct StaticData {
  std::span<const double> radius;    ///< [m]
  std::span<const double> position;  ///< [m], 2 per particle, initial
};

class FluidModel {
 public:
  virtual ~FluidModel() = default;
  virtual std::string name() const = 0;
  /// Kinematics fields needed every exchange ("position", "velocity_half", "displacement").
  virtual std::vector<std::string> needs() const = 0;
  /// Static fields needed at Init ("radius", "position").
  virtual std::vector<std::string> needs_static() const = 0;
  /// Per-particle fields the model can output besides "force" (e.g. "pressure").
  virtual std::vector<std::string> provides() const = 0;
  virtual std::vector<StabilityLimit> limits() const = 0;
  /// True for a prescribed force field that may supply energy (like gravity); false for a pore
  /// fluid, which only stores and dissipates what the grains do on it (the DEM's energy guard).
  virtual bool supplies_energy() const { return false; }

  virtual void initialise(const StaticData& data) = 0;
  /// Advances the model by dt [s] to time t [s] and writes the force on each particle
  /// (2 per particle, [N per m thickness]) into `force`.
  virtual void step(double dt_s, double time_s, const Kinematics& kinematics,
                    std::span<double> force) = 0;
  /// Each particle's own undrained stiffness against its displacement, K_ii of F = -K u, as 3
  /// values per particle (xx, xy, yy) [Pa], for the current geometry (Coupling.fluid_stiffness
  /// "self"). False for a model that has none to give. Once per step, never per particle.
  virtual bool self_stiffness(std::vector<double>& /*out*/) { return false; }
  /// Writes an output field named in provides() (1 value per particle for scalars).
  virtual void output(const std::string& field, std::vector<double>& values) const = 0;
  /// The mean of p - p_hydro [Pa] over the particles whose centre (in `position`, the last
  /// step's) lies in `box`, and their count. False for a model without a pore pressure.
  virtual bool probe(std::span<const double> /*position*/, const ProbeBox& /*box*/,
                     double& /*mean_pa*/, std::size_t& /*count*/) const {
    return false;
  }
  /// Named scalars of the last step for the time series (FluidResult.scalars; the coupler
  /// prefixes them with "fluid_"). Once per step, never per particle.
  virtual void scalars(std::vector<std::pair<std::string, double>>& out) const { out.clear(); }
  /// Wall time per phase of the model's step (Envelope.phase_times), or none.
  virtual const wire::PhaseClock* phases() const { return nullptr; }
  /// Checkpoint: everything that decides the bits of the next steps and that initialise() does
  /// not rebuild from the scene and the static data. Called between steps.
  virtual void save_state(state::StateArchive& archive) const = 0;
  /// Restart: takes a saved state back after initialise(); throws state::StateError if it does
  /// not fit this model and these particles.
  virtual void load_state(const state::StateArchive& archive) = 0;
};

}  // namespace rockcut::fluid
