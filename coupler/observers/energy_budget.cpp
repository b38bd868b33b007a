#include "observers/energy_budget.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace rockcut::coupler {

namespace {

double get(const NamedValues& scalars, const std::string& key, bool& found) {
  const double* value = find_value(scalars, key);
  found = found && value;
  return value ? *value : 0.0;
}

}  // namespace

std::vector<std::pair<const char*, double>> EnergyBudget::terms() const {
  std::vector<std::pair<const char*, double>> terms = {
          {"boundary_work_j", boundary_work_j}, {"external_work_j", external_work_j},
          {"gravity_work_j", gravity_work_j},   {"damping_j", damping_j},
          {"friction_j", friction_j},           {"broken_bond_j", broken_bond_j},
          {"viscous_damping_j", viscous_damping_j}, {"rolling_j", rolling_j},
          {"kinetic_energy_j", kinetic_energy_j}, {"strain_energy_j", strain_energy_j}};
  if (viscous_damping_j > 0) terms.push_back({"viscous_damping_bonds_j", viscous_damping_bonds_j});
  if (bond_softening_j > 0) terms.push_back({"bond_softening_j", bond_softening_j});
  if (lag_correction_j > 0) terms.push_back({"lag_correction_j", lag_correction_j});
  return terms;
}

double EnergyBudget::initial_j() const {
  const double held = kinetic_energy_j + strain_energy_j + damping_j + friction_j + broken_bond_j +
                      viscous_damping_j + rolling_j + lag_correction_j;
  const double work = boundary_work_j + external_work_j + gravity_work_j;
  const double e0 = held + imbalance_j - work;
  // A specimen at rest and zero stress has E0 = 0, which this difference gives up to round-off.
  const double scale =
      std::abs(boundary_work_j) + std::abs(external_work_j) + std::abs(gravity_work_j);
  return std::abs(e0) <= 1e-9 * scale ? 0.0 : e0;
}

double EnergyBudget::input_j() const {
  return std::max(initial_j(), 0.0) + std::max(boundary_work_j, 0.0) +
         std::max(external_work_j, 0.0) + std::max(gravity_work_j, 0.0);
}

std::optional<EnergyBudget> energy_budget(
    const std::vector<std::pair<std::string, double>>& scalars) {
  bool found = true;
  EnergyBudget b;
  b.boundary_work_j = get(scalars, "boundary_work_j", found);
  b.external_work_j = get(scalars, "external_work_j", found);
  b.gravity_work_j = get(scalars, "gravity_work_j", found);
  b.damping_j = get(scalars, "damping_j", found);
  b.friction_j = get(scalars, "friction_j", found);
  b.broken_bond_j = get(scalars, "broken_bond_j", found);
  b.kinetic_energy_j = get(scalars, "kinetic_energy_j", found);
  b.strain_energy_j = get(scalars, "strain_energy_j", found);
  b.imbalance_j = get(scalars, "energy_imbalance_j", found);
  if (!found) return std::nullopt;
  // Optional: a DEM without dashpots or rolling springs need not report them.
  if (const double* v = find_value(scalars, "viscous_damping_j")) b.viscous_damping_j = *v;
  if (const double* v = find_value(scalars, "viscous_damping_bonds_j")) {
    b.viscous_damping_bonds_j = *v;
  }
  if (const double* v = find_value(scalars, "rolling_j")) b.rolling_j = *v;
  if (const double* v = find_value(scalars, "bond_softening_j")) b.bond_softening_j = *v;
  if (const double* v = find_value(scalars, "lag_correction_j")) b.lag_correction_j = *v;
  return b;
}

std::string describe(const EnergyBudget& b, const std::string& external) {
  const double in = b.input_j();
  if (!(in > 0)) return "nothing came in";
  std::string text;
  const char* sep = "in: ";
  char buf[96];
  auto source = [&](const std::string& what, double j) {  // listed when it gave energy
    if (!(j > 0)) return;
    std::snprintf(buf, sizeof buf, "%s%s %.4g J/m", sep, what.c_str(), j);
    text += buf;
    sep = ", ";
  };
  source("initial", b.initial_j());
  source("walls and tool", b.boundary_work_j);
  source(external, b.external_work_j);
  source("gravity", b.gravity_work_j);
  sep = "; out: ";
  auto sink = [&](const std::string& what, double j) {  // its share of what came in
    std::snprintf(buf, sizeof buf, "%s%s %.1f %%", sep, what.c_str(), 100.0 * j / in);
    text += buf;
    sep = ", ";
  };
  if (b.damping_j > 0 || !(b.viscous_damping_j > 0)) sink("local damping", b.damping_j);
  if (b.viscous_damping_j > 0) {
    sink("viscous damping", b.viscous_damping_j);
    // The bonds' part (never a sink of its own: it is inside the dashpots' share).
    std::snprintf(buf, sizeof buf, " (bonds %.1f %%)", 100.0 * b.viscous_damping_bonds_j / in);
    text += buf;
  }
  sink("friction", b.friction_j);
  if (b.rolling_j > 0) sink("rolling resistance", b.rolling_j);
  if (b.lag_correction_j > 0) sink("the coupling lag's correction", b.lag_correction_j);
  if (b.external_work_j < 0) sink(external, -b.external_work_j);
  if (b.boundary_work_j < 0) sink("walls and tool", -b.boundary_work_j);
  if (b.gravity_work_j < 0) sink("gravity", -b.gravity_work_j);
  sink("broken bonds", b.broken_bond_j);
  if (b.bond_softening_j > 0) {  // the softening bonds' part, inside the broken bonds' share
    std::snprintf(buf, sizeof buf, " (softening %.1f %%)", 100.0 * b.bond_softening_j / in);
    text += buf;
  }
  sink("kinetic + strain", b.kinetic_energy_j + b.strain_energy_j);
  return text;
}

bool EnergyReport::finish(const RunClock& clock, Summary& summary, bool) {
  if (const double* imbalance = clock.scalar("energy_imbalance_rel")) {
    summary.set("energy_imbalance_rel", *imbalance);
    std::fprintf(stderr,
                 "energy     imbalance %.3g of the energy throughput (given = kinetic + "
                 "strain + damping + friction + broken bonds + rolling%s)\n",
                 *imbalance, clock.scalar("lag_correction_j") ? " + the lag's correction" : "");
  }
  if (const std::optional<EnergyBudget> budget = energy_budget(clock.scalars)) {
    for (const auto& [key, value] : budget->terms()) summary.set(key, value);
    std::fprintf(stderr, "energy     %s\n", describe(*budget, external_).c_str());
  }
  // The open water's drag (fluid.open_water_drag): what it took, a part of the fluid's work.
  if (const double* drag = clock.scalar("fluid_drag_work_j")) {
    summary.set("open_water_drag_j", -*drag);
    std::fprintf(stderr, "energy     the open water's drag took %.3g J/m (in the fluid's work)\n",
                 -*drag);
  }
  return true;
}

}  // namespace rockcut::coupler
