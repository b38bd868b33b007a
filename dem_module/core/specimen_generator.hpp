// Seeded dense random packing of discs for the rock specimen (DESIGN section 4 "Specimen"; paper
// section 3.1): the advancing-front method of Feng, Han & Owen (2003), "An advancing front packing
// of polygons, ellipses and spheres".
//
// Properties (each one is tested in tests/dem/specimen_generator_test.cpp):
//  - reproducible bit for bit from the seed: std::mt19937_64 with our own mapping of its output to
//    [r_min, r_max] (std::uniform_real_distribution is implementation-defined), and only correctly
//    rounded IEEE arithmetic (+ - * / sqrt) in the geometry;
//  - no overlap: every new disc touches its two parents exactly (up to round-off) and is checked
//    against its neighbours, so the largest overlap is round-off only, bounded by
//    packing_overlap_tolerance_m(spec) (a few ulp of the coordinates), and the specimen starts at zero
//    stress;
//  - dense (packing fraction ~0.8 for r in [0.2, 0.4] mm) with many touching pairs (each new disc
//    touches two others, so the mean coordination is close to 4);
//  - every returned disc lies entirely inside the region; they are numbered row by row of a
//    2 r_max cell grid (row-major in y, then x) so that neighbours are close in memory;
//  - fast: O(N log N); the 0.2 m x 0.1 m block with r in [0.2, 0.4] mm (~55,200 discs at packing
//    fraction 0.809; the paper quotes ~58,000) takes ~30 ms (bench/bench_specimen.cpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace rockcut::dem {

struct PackingRegion {
  enum class Shape { rectangle, circle } shape = Shape::rectangle;
  double center_x_m = 0, center_y_m = 0;
  double width_m = 0, height_m = 0;  ///< rectangle
  double radius_m = 0;               ///< circle (e.g. a Brazilian test disc)
};

struct PackingSpec {
  PackingRegion region;
  double radius_min_m = 0, radius_max_m = 0;  ///< radii are uniform in [radius_min_m, radius_max_m]
  std::uint64_t seed = 1;
};

struct Packing {
  std::vector<double> x_m, y_m, radius_m;
  /// Initial velocity [m/s] and spin [rad/s] per disc (a packing file's optional columns): empty,
  /// or one value per disc.
  std::vector<double> vx_m_s, vy_m_s, omega_rad_s;
  std::size_t size() const { return radius_m.size(); }
  bool has_motion() const { return !vx_m_s.empty(); }
};

/// The largest overlap (negative surface gap) generate_packing(spec) can leave between two discs:
/// round-off only, 64 ulp of the largest coordinate magnitude (|centre| + region extent), i.e.
/// ~3e-15 m for the 0.2 m x 0.1 m block at the origin. Pairs placed touching by construction have
/// |gap| of a few 1e-17 m.
double packing_overlap_tolerance_m(const PackingSpec& spec);

/// Throws std::invalid_argument naming the field ("radius_min_m > radius_max_m", non-positive or
/// non-finite sizes, region smaller than a disc, more than ~5e7 discs) for bad input.
Packing generate_packing(const PackingSpec& spec);

struct PackingStats {
  double packing_fraction = 0;   ///< sum(pi r^2) / region area
  double porosity = 0;           ///< 1 - packing_fraction
  double mean_coordination = 0;  ///< 2 * touching_pairs / N
  double max_overlap_m = 0;      ///< max(0, -min surface gap) over all pairs
  std::size_t touching_pairs = 0;
};

/// Coordination counts pairs whose surface gap is <= gap_tolerance_m (the bond criterion).
/// All pairs are found with a cell grid: O(N).
PackingStats packing_stats(const Packing& p, const PackingRegion& region, double gap_tolerance_m);

}  // namespace rockcut::dem
