// Where the energy of a run went (DESIGN section 5): the DEM's ledger at the end of the run, as
// shares of what came in. Under local damping (eq. 10) that damping takes most of a cut's tool
// work and sets the size of the tool force (docs/model.md, "Damping").
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "observers/run_observer.hpp"

namespace rockcut::coupler {

/// The DEM's ledger [J per m of thickness], the names of its step-report scalars.
struct EnergyBudget {
  double boundary_work_j = 0.0;  ///< work of the walls and the tool on the discs
  double external_work_j = 0.0;  ///< work of the external (fluid) force
  double gravity_work_j = 0.0;
  double damping_j = 0.0;        ///< dissipated by local damping (eq. 10)
  double friction_j = 0.0;       ///< dissipated by sliding contacts
  double broken_bond_j = 0.0;    ///< strain energy released by broken bonds
  double viscous_damping_j = 0.0;  ///< dissipated by the dashpots (0 from a DEM without them)
  /// The bonds' part of viscous_damping_j (the intact rock's vibration); the rest is the
  /// contacts' and the walls' (collisions of loose discs and chips).
  double viscous_damping_bonds_j = 0.0;
  double bond_softening_j = 0.0;  ///< the part of broken_bond_j softening bonds dissipated
  double rolling_j = 0.0;          ///< dissipated by rolling resistance (likewise)
  /// Taken out by the coupling lag's dashpot (Coupling.lag_correction; 0 without it).
  double lag_correction_j = 0.0;
  double kinetic_energy_j = 0.0;
  double strain_energy_j = 0.0;
  double imbalance_j = 0.0;      ///< given - held (energy_imbalance_j)

  /// The terms as summary.json writes them: the step-report scalars' names [J/m], without the
  /// imbalance (summary.json has its relative form).
  std::vector<std::pair<const char*, double>> terms() const;
  /// The initial energy: given - work = held + imbalance - work (0 within round-off of the work).
  double initial_j() const;
  /// What came in: the initial energy and every work term that is positive.
  double input_j() const;
};

/// The budget from a step report's scalars; none unless the DEM reported its ledger.
std::optional<EnergyBudget> energy_budget(
    const std::vector<std::pair<std::string, double>>& scalars);

/// One line: what came in, and each sink's share of it. A negative work term is a sink (the pore
/// fluid takes energy in a cut); `external` names the external force ("pore fluid" in a coupled
/// run).
std::string describe(const EnergyBudget& budget, const std::string& external);

/// The energy report at the end of a run: the imbalance and the budget into summary.json and one
/// line each on stderr (nothing when the DEM reports no ledger).
class EnergyReport : public RunObserver {
 public:
  /// `external`: what the external force is ("pore fluid" in a coupled run).
  explicit EnergyReport(std::string external) : external_(std::move(external)) {}
  bool finish(const RunClock& clock, Summary& summary, bool completed) override;

 private:
  std::string external_;
};

}  // namespace rockcut::coupler
