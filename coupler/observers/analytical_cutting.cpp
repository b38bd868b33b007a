#include "observers/analytical_cutting.hpp"

#include <cmath>

#include "cutting_models/evans_tensile_chip.hpp"
#include "cutting_models/failure_mode.hpp"
#include "cutting_models/hyperbaric_flow_type.hpp"
#include "cutting_models/merchant_flow_type.hpp"
#include "cutting_models/nishimatsu_shear_plane.hpp"
#include "scene/tool_geometry.hpp"

namespace rockcut::coupler {

namespace cm = cutting_models;

AnalyticalCutting::AnalyticalCutting(const rockcut::Scene& scene) {
  const rockcut::Rock& rock = scene.rock();
  const rockcut::Tool& tool = scene.dem().tool();
  const double alpha_deg = tool.cutting_angle_deg();
  const double depth_m = tool.cutting_depth_m();
  const double delta_deg = cm::degrees(std::atan(scene.dem().contact().friction()));
  const double c = rock.cohesion_pa(), phi_deg = rock.friction_angle_deg();
  const double n = rock.has_nishimatsu_exponent()
                       ? rock.nishimatsu_exponent()
                       : cm::nishimatsu_exponent_fit(cm::rake_angle_deg(alpha_deg));
  const double blade_height_m = rockcut::scene::tool_face_length_m(tool) * std::sin(cm::radians(alpha_deg));
  double under_pressure_pa = 0.0;  // dry: no pore water
  if (scene.has_fluid()) {
    const rockcut::Fluid& f = scene.fluid();
    under_pressure_pa = cm::cavitation_under_pressure_pa(
        scene.water_depth_m(), f.water_density_kg_m3(), f.gravity_m_s2(),
        f.atmospheric_pressure_pa(), f.cavitation_pressure_pa());
  }
  const cm::FlowTypeForce merchant = cm::merchant_flow_type(c, phi_deg, delta_deg, alpha_deg, depth_m);
  const cm::FlowTypeForce hyperbaric = cm::hyperbaric_flow_type(
      c, phi_deg, delta_deg, alpha_deg, depth_m, blade_height_m, under_pressure_pa);
  models_ = {
      {"evans", cm::evans_tensile_chip(rock.bts_pa(), alpha_deg, depth_m)},
      {"nishimatsu", cm::nishimatsu_shear_plane(c, phi_deg, delta_deg, alpha_deg, depth_m, n)},
      {"merchant", merchant.force},
      {"hyperbaric", hyperbaric.force},
  };
  const cm::FailureMode mode =
      cm::miedema_failure_mode(c, phi_deg, rock.bts_pa(), delta_deg, alpha_deg);
  extra_ = {
      {"analytical_tool_friction_angle_deg", delta_deg},
      {"analytical_nishimatsu_exponent", n},
      {"analytical_merchant_shear_angle_deg", merchant.shear_angle_deg},
      {"analytical_hyperbaric_shear_angle_deg", hyperbaric.shear_angle_deg},
      {"analytical_hyperbaric_under_pressure_pa", under_pressure_pa},
      {"analytical_failure_mode", mode.mode},
      {"analytical_failure_shear_plane_stress_pa", mode.shear_plane_normal_stress_pa},
      {"analytical_failure_least_principal_stress_pa", mode.least_principal_stress_pa},
  };
}

void AnalyticalCutting::write(Summary& summary) const {
  const auto dem_value = [&](const char* key) {
    const auto v = summary.get(key);
    const double* d = v ? std::get_if<double>(&*v) : nullptr;
    return d ? *d : std::nan("");
  };
  const double mean = dem_value("force_horizontal_mean_n_per_m");
  const double peak = dem_value("force_horizontal_peak_n_per_m");
  for (const Model& m : models_) {
    const std::string key = std::string("analytical_") + m.name;
    summary.set(key + "_force_horizontal_n_per_m", m.force.horizontal_n_per_m);
    summary.set(key + "_force_vertical_n_per_m", m.force.vertical_up_n_per_m);
    // DEM over model; null in summary.json where the model has no value (no shear plane).
    summary.set(key + "_ratio_mean", mean / m.force.horizontal_n_per_m);
    summary.set(key + "_ratio_peak", peak / m.force.horizontal_n_per_m);
  }
  for (const auto& [key, value] : extra_) summary.set(key, value);
}

}  // namespace rockcut::coupler
