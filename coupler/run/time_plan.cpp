#include "run/time_plan.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace rockcut::coupler {

namespace {

std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", v);
  return buf;
}

const Limit* smallest(const std::vector<Limit>& limits) {
  const Limit* best = nullptr;
  for (const Limit& l : limits) {
    if (!best || l.dt_max_s < best->dt_max_s) best = &l;
  }
  return best;
}

std::string describe(const Limit& l) {
  return l.module + " " + l.name + ": dt <= " + fmt(l.dt_max_s) + " s" +
         (l.detail.empty() ? "" : " (" + l.detail + ")");
}

}  // namespace

double smallest_limit_s(const std::vector<Limit>& limits) {
  const Limit* l = smallest(limits);
  return l ? l->dt_max_s : 0.0;
}

TimePlan plan_time(const rockcut::Scene& scene, const std::vector<Limit>& dem_limits,
                   const std::vector<Limit>& fluid_limits, bool coupled) {
  TimePlan plan;
  for (const Limit& l : dem_limits) plan.report.push_back("limit  " + describe(l));
  for (const Limit& l : fluid_limits) plan.report.push_back("limit  " + describe(l) + " (fluid step)");

  const rockcut::Time& time = scene.time();
  // A setting above a limit is refused, or with time.ignore_limits run with a warning.
  const auto refuse = [&](const std::string& why) {
    if (!time.ignore_limits()) throw PlanError(why);
    plan.report.push_back("WARNING " + why + " -- running anyway (time.ignore_limits)");
  };
  const Limit* dem_limit = smallest(dem_limits);
  const Limit* fluid_limit = smallest(fluid_limits);
  // Fluid-only scenes (prescribed motion: the DEM has no limit of its own) take the fluid step as
  // the DEM step, N = 1.
  const bool dt_from_fluid = !time.has_dt_s() && !dem_limit && coupled && fluid_limit;
  if (time.has_dt_s()) {
    if (dem_limit && time.dt_s() > dem_limit->dt_max_s) {
      refuse("time.dt_s = " + fmt(time.dt_s()) + " s exceeds the " + dem_limit->module +
                      " limit " + dem_limit->name + " (" + fmt(dem_limit->dt_max_s) + " s) by " +
                      fmt(time.dt_s() / dem_limit->dt_max_s) + "x; lower time.dt_s or leave it "
                      "out to use dt_safety * limit");
    }
    plan.dt_s = time.dt_s();
    plan.binding = "time.dt_s set in the scene";
  } else if (dem_limit) {
    plan.dt_s = time.dt_safety() * dem_limit->dt_max_s;
    plan.binding = dem_limit->module + " " + dem_limit->name + " x dt_safety " +
                   fmt(time.dt_safety());
  } else if (dt_from_fluid) {
    plan.dt_s = time.dt_safety() * fluid_limit->dt_max_s;
    plan.binding = fluid_limit->module + " " + fluid_limit->name + " x dt_safety " +
                   fmt(time.dt_safety()) + " (no DEM limit: the fluid step is the DEM step)";
  } else {
    throw PlanError("no stability limit bounds the DEM step in this scene (no contacts or bonds); "
                    "set time.dt_s");
  }

  plan.report.push_back("chosen dt = " + fmt(plan.dt_s) + " s (binding: " + plan.binding + ")");
  if (coupled) {
    // The largest N each fluid limit allows; the smallest of them binds. A lag-only limit (the
    // pore fluid's stiffness) never forbids N = 1, where the fluid force does not lag.
    double max_n = 1e9;
    const Limit* binding = nullptr;
    for (const Limit& l : fluid_limits) {
      double n = std::floor(l.dt_max_s / plan.dt_s * (1.0 + 1e-9));
      if (l.lag_only) n = std::max(n, 1.0);
      if (n < 1 && time.ignore_limits()) n = 1;
      if (n < 1) {
        throw PlanError("the fluid limit " + l.name + " (" + fmt(l.dt_max_s) +
                        " s) is below the DEM step " + fmt(plan.dt_s) + " s by " +
                        fmt(plan.dt_s / l.dt_max_s) + "x; lower time.dt_s" +
                        (l.remedy.empty() ? "" : ", or " + l.remedy));
      }
      if (n < max_n) {
        max_n = n;
        binding = &l;
      }
    }
    if (scene.coupling().has_interval()) {
      plan.coupling_interval = scene.coupling().interval();
      if (plan.coupling_interval > max_n) {
        refuse("coupling.interval = " + std::to_string(plan.coupling_interval) +
                        " makes the fluid step " + fmt(plan.coupling_interval * plan.dt_s) +
                        " s, above the " + binding->module + " limit " + binding->name + " (" +
                        fmt(binding->dt_max_s) + " s) by " +
                        fmt(plan.coupling_interval * plan.dt_s / binding->dt_max_s) +
                        "x; use coupling.interval <= " + fmt(max_n) +
                        (binding->remedy.empty() ? "" : ", or " + binding->remedy));
      }
    } else {
      // Stable up to max_n, accurate (docs/accuracy.md) at a fraction of it; without a fluid
      // limit the paper's scheme (N = 1) is kept.
      plan.coupling_interval =
          binding && !dt_from_fluid
              ? static_cast<unsigned>(std::max(
                    1.0, std::floor(scene.coupling().interval_fraction() * std::min(max_n, 1e6))))
              : 1;
    }
    plan.extrapolate_fluid_force =
        plan.coupling_interval > 1 && scene.coupling().fluid_force() == "extrapolated";
    plan.lag_passivity =
        plan.coupling_interval > 1 && scene.coupling().lag_correction() == "passivity";
    plan.fluid_self_stiffness =
        plan.coupling_interval > 1 && scene.coupling().fluid_stiffness() == "self";
    plan.report.push_back(
        "chosen coupling interval N = " + std::to_string(plan.coupling_interval) +
        ", fluid step " + fmt(plan.coupling_interval * plan.dt_s) + " s" +
        (scene.coupling().has_interval() ? " (set in the scene)"
         : dt_from_fluid                 ? " (fluid-only scene: one DEM step per fluid step)"
         : binding ? " (binding: " + binding->name + ", which allows N <= " + fmt(max_n) +
                         "; coupling.interval_fraction " +
                         fmt(scene.coupling().interval_fraction()) + " of it, docs/accuracy.md)"
                                         : " (no fluid limit: the paper's N = 1)"));
    if (plan.extrapolate_fluid_force) {
      plan.report.push_back("between exchanges the DEM extrapolates the fluid's force from its "
                            "last two values (coupling.fluid_force \"extrapolated\")");
    }
    if (plan.fluid_self_stiffness) {
      plan.report.push_back("between exchanges the DEM applies each grain's own pore-fluid "
                            "stiffness against its motion (coupling.fluid_stiffness \"self\")");
    }
  }
  // A step count a double holds exactly, and one a run could finish: 2^53 steps would take years.
  const double steps = std::ceil(time.end_time_s() / plan.dt_s - 1e-9);
  constexpr double kMaxSteps = 9007199254740992.0;  // 2^53
  if (!(steps <= kMaxSteps)) {
    char text[160];
    std::snprintf(text, sizeof text,
                  "time.end_time_s / dt = %.3g steps is more than any run can make (at most "
                  "2^53); shorten the run or raise time.dt_s",
                  steps);
    throw PlanError(text);
  }
  if (!(steps >= 1.0)) {
    char text[200];
    std::snprintf(text, sizeof text,
                  "time.end_time_s = %.3g s is less than one step (dt = %.3g s): the run would "
                  "make no step; lengthen it or lower time.dt_s",
                  time.end_time_s(), plan.dt_s);
    throw PlanError(text);
  }
  plan.total_steps = static_cast<std::uint64_t>(steps);
  plan.report.push_back("steps: " + std::to_string(plan.total_steps) + " to t = " +
                        fmt(time.end_time_s()) + " s");
  return plan;
}

std::vector<Limit> applicable_fluid_limits(const rockcut::Scene& scene, std::vector<Limit> limits) {
  const wire::LimitKind other = scene.coupling().fluid_force() == "extrapolated"
                                    ? wire::LIMIT_KIND_PORE_FLUID_STIFFNESS
                                    : wire::LIMIT_KIND_PORE_FLUID_STIFFNESS_EXTRAPOLATED;
  std::erase_if(limits, [&](const Limit& l) { return l.kind == other; });
  // The lag's energy taken out (Coupling.lag_correction "passivity") moves the extrapolated
  // force's limit by kLagPassivityLimitFactor, measured (docs/record/accuracy.md, "The lag's
  // energy taken out"); the held force's limit was not measured with it and stays.
  if (scene.coupling().lag_correction() == "passivity" &&
      scene.coupling().fluid_force() == "extrapolated") {
    for (Limit& l : limits) {
      if (l.kind != wire::LIMIT_KIND_PORE_FLUID_STIFFNESS_EXTRAPOLATED) continue;
      l.dt_max_s *= kLagPassivityLimitFactor;
      l.detail += "; x " + fmt(kLagPassivityLimitFactor) +
                  " with the lag's energy taken out (coupling.lag_correction \"passivity\")";
    }
  }
  return limits;
}

double pore_fluid_stiffness_limit_s(const std::vector<Limit>& limits) {
  for (const Limit& l : limits) {
    if (l.kind == wire::LIMIT_KIND_PORE_FLUID_STIFFNESS ||
        l.kind == wire::LIMIT_KIND_PORE_FLUID_STIFFNESS_EXTRAPOLATED) {
      return l.dt_max_s;
    }
  }
  return 0.0;
}

}  // namespace rockcut::coupler
