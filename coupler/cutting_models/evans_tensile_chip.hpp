// Evans' tensile chip: the peak force of a chisel that breaks a chip out in tension.
//
// Evans, I. (1962) "A theory of the basic mechanics of coal ploughing", Proc. Int. Symp. Mining
// Research 2:761-798, and Evans (1965) "The force required to cut coal with blunt wedges",
// Int. J. Rock Mech. Min. Sci. 2:1-12; as presented for a chisel with rake angle alpha_r by
// Miedema (2014) section 8.3 ("The Evans model") and in the drag-pick reviews (e.g. Yasar and
// Yilmaz 2018, "Drag pick cutting tests: a comparison between experimental and theoretical
// results", J. Rock Mech. Geotech. Eng.):
//
//   F_c = 2 sigma_t d sin(theta) / (1 - sin(theta)),   theta = (pi/2 - alpha_r) / 2 = alpha / 2
//
//   sigma_t  tensile strength of the rock (BTS) [Pa]
//   d        cut depth [m]
//   alpha_r  rake angle; alpha = 90 deg - alpha_r the blade angle (cutting_force.hpp)
//   F_c      peak horizontal force per metre of width [N/m]
//
// Assumptions: the chip is bounded by a circular crack from the tool tip to the free surface and
// rotates about the crack's end at the surface; the tensile stress is uniform along the crack; the
// tool face is frictionless (Evans), so the tool force is normal to the face: the rock pulls the
// tool down with F_c cot(alpha). A peak force: the chip breaks out at it and the force drops.
#pragma once

#include "cutting_models/cutting_force.hpp"

namespace rockcut::coupler::cutting_models {

/// Evans' peak force at blade angle `blade_angle_deg` (0 < alpha <= 90).
CuttingForce evans_tensile_chip(double tensile_strength_pa, double blade_angle_deg,
                                double cut_depth_m);

}  // namespace rockcut::coupler::cutting_models
