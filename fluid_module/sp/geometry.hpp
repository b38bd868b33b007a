// Per-step SP geometry on the current positions: kernel values per pair, SP volumes, the CSPM
// correction matrices and Lucy's div r (paper sections 3.2-3.3). Everything the operators
// (sp/operators.hpp) and the models need is computed here once per step, pair by pair in the CSR
// order of the neighbour list.
//
// Per pair only W, F and the neighbour index are stored (20 bytes); the passes recompute x_j - x_i
// from the positions, which costs two loads of a cache line they read anyway. Storing the
// differences too doubled the memory traffic of every pass, and the passes are bound by it (58,000
// particles: 1.3 million listed pairs).
//
// Only the pairs inside the support are kept. The neighbour list reaches 1.1 h (its skin, so that
// it is rebuilt rarely), and the ring from h to 1.1 h holds about a sixth of its pairs, all with
// W = F = 0: terms every pass would add as exact zeros. Each row keeps its slots in the list's CSR
// arrays (row_begin = the list's offsets) and ends early (row_end), so dropping them needs no
// second copy.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "sp/kernel.hpp"
#include "sp/neighbours.hpp"

namespace rockcut::fluid::sp {

/// How the CSPM gradient of a particle is corrected (see correction_matrices in geometry.cpp).
enum class Correction : std::uint8_t {
  full = 0,       ///< L_i is well conditioned: the full 2x2 inverse
  projected = 1,  ///< L_i is (nearly) rank one, e.g. a chain of particles: 1D along its axis
  none = 2,       ///< no neighbour in the support: zero gradient
};

struct Geometry {
  std::vector<double> position;  ///< the positions of this step [m], interleaved x, y
  /// Row i holds the pairs (i, neighbours[k]) with k in [row_begin[i], row_end[i]): the listed
  /// neighbours closer than h, sorted by index, never i itself. Symmetric: j is in row i exactly
  /// when i is in row j.
  std::vector<int> row_begin, row_end, neighbours;
  // Per pair, at the same index k as `neighbours`.
  std::vector<double> w;       ///< W_ij [1/m^2]
  std::vector<double> f;       ///< F_ij = W'(r_ij) / r_ij [1/m^4], so grad_i W_ij = F_ij (x_i - x_j)
  // Per particle.
  std::vector<double> volume;  ///< SP volume V_i [m^2]
  /// The inverse of L_i = sum_j V_j (x_j - x_i) (x) grad_i W_ij (symmetric, 3 per particle:
  /// xx, xy, yy), or its safe replacement (see `correction`).
  std::vector<double> l_inverse;
  std::vector<Correction> correction;
  /// tr L_i = sum_j V_j (-F_ij) r_ij^2 [1]: 2 for an exact second moment (continuum interior),
  /// about 1 at a straight surface. The consistent Laplacian's renormalisation
  /// (sp/consistent_laplacian.hpp).
  std::vector<double> l_trace;
  std::vector<double> div_r;   ///< Lucy's uncorrected div r (eq. 24) [1]
  /// Lucy's uncorrected gradient of the constant 1 with the sign flipped, sum_j (m_j / rho_j)
  /// F_ij (x_j - x_i) [1/m], 2 per particle: 0 inside, the outward normal at a surface.
  std::vector<double> normal;
  /// The volume iterates V^0 .. V^(m-1) of the m refinements, n each (`volume` is V^m). A local
  /// refresh (refresh_geometry) recomputes each of them on its own ring of rows.
  std::vector<double> volume_iterates;
  unsigned volume_iterations = 0;

  std::size_t particles() const { return volume.size(); }
  /// The pairs inside the support, both directions (counted over the rows).
  std::size_t pairs() const {
    std::size_t count = 0;
    for (std::size_t i = 0; i < row_end.size(); ++i) {
      count += static_cast<std::size_t>(row_end[i] - row_begin[i]);
    }
    return count;
  }
  /// Counts the geometries computed into this object (the implicit model's matrix pattern
  /// follows the rows and is rebuilt when this changes).
  std::uint64_t version = 0;
};

/// The eigenvalue ratio below which L_i counts as ill-conditioned and the gradient is taken along
/// its dominant axis only. Inside a packing L_i is close to the identity and at a straight
/// surface close to I / 2 (ratio 1); a chain of particles or a strip one or two particles wide
/// gives a ratio near 0, where the full inverse would amplify noise across the chain 1 / ratio
/// times. 0.05 bounds that amplification at 20.
inline constexpr double kMinEigenRatio = 0.05;

/// The rows a per-row loop visits: all of them, or a list (a local refresh's rings).
struct AllRows {
  int n;
  int size() const { return n; }
  int operator[](int r) const { return r; }
};
struct RowList {
  const std::vector<int>& rows;
  int size() const { return static_cast<int>(rows.size()); }
  int operator[](int r) const { return rows[static_cast<std::size_t>(r)]; }
};

/// Recomputes `geo` for `position` (interleaved x, y [m]) with the lists of `list` (current for
/// these positions). SP volumes: V_i = 1 / sum_j W_ij (self term included), then
/// `volume_iterations` times V_i <- V_i / sum_j V_j W_ij. `lucy_volume` [m^2] are the volumes
/// m_j / rho_j of eq. 24 (constant per particle).
void update_geometry(const NeighbourList& list, const WendlandC2& kernel,
                     std::span<const double> position, std::span<const double> lucy_volume,
                     unsigned volume_iterations, Geometry& geo);

/// Scratch of refresh_geometry, kept between calls (no allocation once sizes settle).
struct LocalRefresh {
  std::vector<std::uint8_t> level;  ///< per particle: its ring (0 = moved), 0xff = none
  std::vector<int> rows;            ///< the rings' rows, breadth first
  std::vector<int> stage;           ///< the rows of one stage, in index order
  /// After a refresh: the rows whose step coefficients (sp/step_operator.hpp) changed, in index
  /// order (ring volume_iterations + 3).
  std::vector<int> coefficient_rows;
};

/// A local refresh: moves the particles `moved` to `position` in geo.position, and recomputes
/// every row that depends on them, ring by ring of neighbour rows: the pair kernels and V^0 of
/// the rows that list a moved particle (ring 1), each volume iterate one ring further, L_i, div r
/// and the normal one more. The result is, bit for bit, update_geometry on the new geo.position
/// (X': some particles moved, the others where the geometry had them), because every row is
/// computed alone in a fixed order. `list` must be the list of the geometry (not rebuilt since),
/// and valid for X'. Returns false and changes nothing when the rings would hold more than
/// max_fraction of the particles (a full update is then cheaper) or `geo` does not match `list`.
bool refresh_geometry(const NeighbourList& list, const WendlandC2& kernel,
                      std::span<const double> position, std::span<const int> moved,
                      std::span<const double> lucy_volume, unsigned volume_iterations,
                      double max_fraction, LocalRefresh& scratch, Geometry& geo);

}  // namespace rockcut::fluid::sp
