// The parameters of the SP pore-pressure models as plain values. Only params.cpp reads the
// fluid's part of the scene (Init.fluid); the physics takes these.
#pragma once

#include <array>
#include <string>

#include "sp/darcy_diffusivity.hpp"

namespace rockcut::wire {
class FluidConfig;
}

namespace rockcut::fluid::sp {

enum class StrainFrom { displacement, velocity_half };
/// How the force on the grains is discretised (fluid.force_form).
enum class ForceForm { adjoint, gradient };
/// Which Laplacian diffuses the pressure (fluid.laplacian): eq. 20 as the paper writes it, or its
/// renormalised form (sp/consistent_laplacian.hpp).
enum class LaplacianForm { paper, consistent };

struct SpParams {
  double h_m = 0.0015;                 ///< kernel support (smoothing length)
  double alpha = 0.5;                  ///< Biot coefficient
  double bulk_modulus_pa = 2e9;        ///< M
  double permeability_m2 = 1e-14;      ///< kappa
  double viscosity_pa_s = 1e-3;        ///< mu
  double water_density_kg_m3 = 1025.0; ///< rho_w of the free water
  bool open_water_drag = false;        ///< sp/open_water_drag.hpp on the drained grains
  /// The points' spacing in grain spacings (fluid.point_spacing; 1: a point at every grain).
  double point_spacing = 1.0;
  double p_hydro_pa = 101325.0;        ///< p_atm + rho_w g H
  double surface_div_r = 1.5;          ///< eq. 24 threshold
  std::array<bool, 4> sealed{};        ///< left, right, bottom, top (Sides order)
  bool seal_at_walls = false;          ///< the DEM has walls or a tool: get their segments
  /// Grain density of the DEM [kg/m^3] and whether the DEM moves the particles by the fluid force
  /// (false for prescribed motion): together they set the pore-fluid stiffness limit. They, the
  /// damping and seal_at_walls come from the DEM through the protocol (SolidProperties).
  double grain_density_kg_m3 = 2800.0;
  bool dynamic_solid = false;
  double local_damping = 0.7;          ///< the DEM's alpha_d (eq. 10): removes the lag's energy
  double viscous_damping_ratio = 0.0;  ///< the DEM's dashpots' zeta: they remove it too
  double normal_stiffness_pa = 0.0;    ///< the DEM's stiffest normal spring k_n (the dashpots' c)
  bool cavitation = true;
  double p_min_pa = 2340.0;            ///< eq. 22
  StrainFrom strain_from = StrainFrom::displacement;
  ForceForm force_form = ForceForm::adjoint;
  LaplacianForm laplacian = LaplacianForm::consistent;
  unsigned volume_iterations = 3;
  double skin = 0.1;                   ///< neighbour skin, fraction of h
  /// Recompute the SP geometry only after a particle or wall has moved this far, fraction of h
  /// (0: every step).
  double geometry_refresh = 0.0;
  // Implicit model.
  double solver_tolerance = 1e-8;
  unsigned solver_max_iterations = 2000;
  double max_diffusion_number = 0.2;
  // Initial Gaussian pulse on top of p_hydro (amplitude 0: none).
  double pulse_amplitude_pa = 0.0, pulse_x_m = 0.0, pulse_y_m = 0.0, pulse_sigma_m = 1.0;

  /// Pore pressure diffusivity D = M kappa / mu [m^2/s] (Darcy's law, eq. 12, in eq. 14).
  double diffusivity_m2_s() const {
    return darcy_diffusivity_m2_s(bulk_modulus_pa, permeability_m2, viscosity_pa_s);
  }
};

/// Reads the fluid's part of the scene: fluid, water_depth_m and the DEM's solid properties.
/// Ranges are checked by the schema; cross-field problems and missing solid properties throw
/// std::invalid_argument naming the fields.
SpParams sp_params_from_config(const wire::FluidConfig& config);

}  // namespace rockcut::fluid::sp
