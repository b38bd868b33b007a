// Which particles carry a boundary condition (paper section 3.3).
//
// A particle whose Lucy div r (eq. 24) is at most the threshold (1.5) is a surface particle. A
// surface particle meets free water, and is held at p_hydro (Dirichlet), unless it lies against a
// wall: then it keeps the natural no-flux condition of the SP Laplacian.
//
// Walls are the sealed sides of the initial bounding box of the particle centres. A surface
// particle faces a side when its outward normal (Lucy's gradient of the constant 1,
// Geometry::normal) is within 60 degrees of the side's and it lies close to it: within h of a
// sealed side (the whole surface layer along a wall), within its own radius of an open side (the
// outer layer of the free surface itself: a disc touching the free surface has its centre at most
// r_max - r_min from the box of the centres, the next layer lies about a diameter further in).
// Rigid walls and the tool of a coupled scene (their segments come from the DEM every exchange,
// wire field "wall_segments") seal the particles that face them: a surface particle whose centre
// lies within h of a segment, with the outward normal within 60 degrees of the direction to the
// segment's nearest point, keeps the no-flux condition (section 3.3: "equipment moving through
// the rock"), whatever the box sides say.
// Otherwise:
//  - facing an open side: drained, also where it faces a sealed side too (the corner particle
//    between a wall and the free surface drains);
//  - facing a sealed side (and no open one): sealed;
//  - facing no side (a crack, a cut face, a chip, a fragment): drained if any side is open, i.e.
//    internal surfaces are taken as connected to the free water; with every side sealed nothing
//    drains.
// Why normals and two distances: the layer that div r <= 1.5 marks is up to ~0.4 h thick, and two
// particles thick near corners at h / spacing >= 4. A distance test alone drained the second
// layer along the walls; a common distance drained particles against a wall one layer below the
// free surface.
#pragma once

#include <array>
#include <cstdint>
#include <span>

namespace rockcut::fluid::sp {

enum class Boundary : std::uint8_t { interior = 0, drained = 1, sealed = 2 };

/// The sides of the initial bounding box of the particle centres, and which of them are walls.
struct Sides {
  enum Side { left = 0, right = 1, bottom = 2, top = 3 };
  std::array<bool, 4> sealed{false, false, false, false};
  std::array<double, 4> at_m{0, 0, 0, 0};  ///< x of left/right, y of bottom/top [m]

  /// The bounding box of `position` (interleaved x, y [m]).
  void fit(std::span<const double> position);
  bool any_open() const { return !(sealed[0] && sealed[1] && sealed[2] && sealed[3]); }
};

struct BoundaryCounts {
  std::size_t drained = 0, sealed = 0;
};

/// Classifies every particle (see above): `normal` 2 per particle, h [m] the kernel support,
/// `segments` 4 per rigid segment (ax, ay, bx, by) [m], possibly none.
BoundaryCounts classify_boundary(std::span<const double> div_r, std::span<const double> normal,
                                 double surface_div_r, double h_m,
                                 std::span<const double> position, std::span<const double> radius,
                                 const Sides& sides, std::span<Boundary> out,
                                 std::span<const double> segments = {});

}  // namespace rockcut::fluid::sp
