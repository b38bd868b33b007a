// Which particles carry a boundary condition (paper section 3.3).
//
// A particle whose Lucy div r (eq. 24) is at most the threshold (1.5) is a surface particle. A
// surface particle meets free water, and is held at p_hydro (Dirichlet), unless it lies against a
// wall: then it keeps the natural no-flux condition of the SP Laplacian. Walls are the sealed
// sides of the specimen's initial bounding box (of the particle centres): a surface particle is
// sealed when its centre lies within its radius of a sealed side and not within its radius of an
// open side (a corner between a wall and the free surface drains). Within one radius: a disc
// touching a wall has its centre at most r_max - r_min from the box of the centres, and the next
// layer lies at least a diameter further in. A surface particle near no side (a crack, a cut
// face, a chip) drains if any side is open, i.e. internal surfaces are taken as connected to the
// free water; with every side sealed nothing drains.
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

/// Classifies every particle. Returns the number of drained and sealed surface particles.
struct BoundaryCounts {
  std::size_t drained = 0, sealed = 0;
};
BoundaryCounts classify_boundary(std::span<const double> div_r, double surface_div_r,
                                 std::span<const double> position, std::span<const double> radius,
                                 const Sides& sides, std::span<Boundary> out);

}  // namespace rockcut::fluid::sp
