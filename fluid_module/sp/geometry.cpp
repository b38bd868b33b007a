#include "sp/geometry.hpp"

#include <cmath>

#include "sp/surface_detection.hpp"

// Every loop here is a per-particle gather over the symmetric neighbour rows: OpenMP threads
// (fluid.threads) split the particles and give the same bits for any thread count.

namespace rockcut::fluid::sp {

namespace {

// Pair kernel values of the listed pairs inside the support, packed at the start of each row's
// slots, and the Shepard volumes V_i = 1 / sum_j W_ij. Raw restrict pointers and local constants:
// with the vectors' own pointers the compiler must assume that each store may change them (and
// the kernel's constants) and reloads them for every pair (measured: 1.5x). Every pair is written
// and the write position advances only for a pair inside: a branch on it would be mispredicted
// for the sixth of the pairs that lie in the skin.
template <class Rows>
void pair_kernels(const Rows& rows, const NeighbourList& list, const WendlandC2& kernel,
                  const double* x, Geometry& g, double* volume0) {
  const int count = rows.size();
  const int* __restrict off = list.offsets().data();
  const int* __restrict nb = list.neighbours().data();
  int* __restrict kept = g.neighbours.data();
  int* __restrict row_end = g.row_end.data();
  double* __restrict ws = g.w.data();
  double* __restrict fs = g.f.data();
  double* __restrict volume = volume0;
  const WendlandC2 k = kernel;  // a local copy: its constants stay in registers
  const double w0 = k.w0();
#pragma omp parallel for schedule(static)
  for (int r = 0; r < count; ++r) {
    const int i = rows[r];
    const double xi = x[2 * i], yi = x[2 * i + 1];
    double sum_w = w0;
    int out = off[i];
    for (int p = off[i]; p < off[i + 1]; ++p) {
      const int j = nb[p];
      const double dx = x[2 * j] - xi, dy = x[2 * j + 1] - yi;
      double w, f;
      k.w_and_f(std::sqrt(dx * dx + dy * dy), w, f);
      kept[out] = j;
      ws[out] = w;
      fs[out] = f;
      out += (w != 0.0) | (f != 0.0);
      sum_w += w;  // (+0 beyond h: the same bits as leaving it out)
    }
    row_end[i] = out;
    volume[i] = 1.0 / sum_w;
  }
}

// One partition-of-unity refinement V_i <- V_i / sum_j V_j W_ij (Jacobi: all from the old V),
// from the iterate v into out.
template <class Rows>
void refine_volumes(const Rows& rows, double w0, const double* v, double* out, Geometry& g) {
  const int count = rows.size();
  const int* begin = g.row_begin.data();
  const int* end = g.row_end.data();
  const int* nb = g.neighbours.data();
#pragma omp parallel for schedule(static)
  for (int r = 0; r < count; ++r) {
    const int i = rows[r];
    double s = v[i] * w0;
    for (int k = begin[i]; k < end[i]; ++k) s += v[nb[k]] * g.w[k];
    out[i] = v[i] / s;
  }
}

// L_i = sum_j V_j (x_j - x_i) (x) grad_i W_ij = sum_j V_j (-F_ij) d d^T with d = x_j - x_i: the
// CSPM correction of eq. 16 in its 2x2 matrix form (symmetric, positive semi-definite), and
// Lucy's div r of eq. 24, sum_j (m_j / rho_j) (x_j - x_i) . grad_i W_ij = sum_j V_j (-F_ij) r^2.
// The difference form (x_j - x_i) is used so that div r does not depend on where the origin is.
// With the same volumes, -sum_j (m_j / rho_j) grad_i W_ij points out of the surface.
template <class Rows>
void correction_matrices(const Rows& rows, std::span<const double> lucy_volume, Geometry& g) {
  const int count = rows.size();
  const int* begin = g.row_begin.data();
  const int* end = g.row_end.data();
  const int* nb = g.neighbours.data();
  const double* v = g.volume.data();
  const double* vl = lucy_volume.data();
  const double* x = g.position.data();
#pragma omp parallel for schedule(static)
  for (int r = 0; r < count; ++r) {
    const int i = rows[r];
    double a = 0.0, b = 0.0, c = 0.0, divr = 0.0, nx = 0.0, ny = 0.0;
    const double xi = x[2 * i], yi = x[2 * i + 1];
    for (int k = begin[i]; k < end[i]; ++k) {
      const int j = nb[k];
      const double dx = x[2 * j] - xi, dy = x[2 * j + 1] - yi, mf = -g.f[k];
      const double s = v[j] * mf;
      a += s * dx * dx;
      b += s * dx * dy;
      c += s * dy * dy;
      divr += div_r_pair_term(vl[j], mf, dx, dy);  // eq. 24
      nx -= vl[j] * mf * dx;
      ny -= vl[j] * mf * dy;
    }
    g.div_r[i] = divr;
    g.l_trace[i] = a + c;
    g.normal[2 * i] = nx;
    g.normal[2 * i + 1] = ny;
    // Eigenvalues of [[a, b], [b, c]]: lambda = m +- d.
    const double m = 0.5 * (a + c), h = 0.5 * (a - c);
    const double d = std::sqrt(h * h + b * b);
    const double l1 = m + d, l2 = m - d;
    double* inv = g.l_inverse.data() + 3 * i;
    if (!(l1 > 1e-12)) {
      // No neighbour inside the support (L_i is dimensionless, ~1 inside a packing).
      inv[0] = inv[1] = inv[2] = 0.0;
      g.correction[i] = Correction::none;
    } else if (l2 >= kMinEigenRatio * l1) {
      const double det = a * c - b * b;
      inv[0] = c / det;
      inv[1] = -b / det;
      inv[2] = a / det;
      g.correction[i] = Correction::full;
    } else {
      // Pseudo-inverse restricted to the dominant axis e: e e^T / lambda_1. The gradient is then
      // exact along the axis (a chain reproduces its own finite differences) and zero across it.
      double ex = b, ey = l1 - a;
      if (ex * ex + ey * ey < 1e-30 * (l1 * l1)) {  // b = 0 and a >= c: the axis is x
        ex = 1.0;
        ey = 0.0;
      }
      const double norm2 = ex * ex + ey * ey;
      inv[0] = ex * ex / (norm2 * l1);
      inv[1] = ex * ey / (norm2 * l1);
      inv[2] = ey * ey / (norm2 * l1);
      g.correction[i] = Correction::projected;
    }
  }
}

// The volume iterate m of a geometry with `iterations` refinements: V^iterations is geo.volume.
double* volume_iterate(Geometry& g, unsigned m, unsigned iterations) {
  return m == iterations ? g.volume.data() : g.volume_iterates.data() + m * g.volume.size();
}

// The stages of a geometry, each over its rows (all of them, or the rings of a local refresh).
template <class Rows>
void kernel_stage(const Rows& rows, const NeighbourList& list, const WendlandC2& kernel,
                  unsigned iterations, Geometry& g) {
  pair_kernels(rows, list, kernel, g.position.data(), g, volume_iterate(g, 0, iterations));
}
template <class Rows>
void volume_stage(const Rows& rows, double w0, unsigned m, unsigned iterations, Geometry& g) {
  refine_volumes(rows, w0, volume_iterate(g, m - 1, iterations), volume_iterate(g, m, iterations),
                 g);
}

// Rows with level[i] <= ring, in index order (the order of a full update's memory sweep).
void rows_within(const std::vector<std::uint8_t>& level, unsigned ring, std::vector<int>& out) {
  out.clear();
  for (std::size_t i = 0; i < level.size(); ++i) {
    if (level[i] <= ring) out.push_back(static_cast<int>(i));
  }
}

}  // namespace

void update_geometry(const NeighbourList& list, const WendlandC2& kernel,
                     std::span<const double> position, std::span<const double> lucy_volume,
                     unsigned volume_iterations, Geometry& geo) {
  const std::size_t n = list.particles();
  const std::size_t pairs = list.pairs();
  // Sizes change only with the particle count or a rebuild; resize keeps the capacity.
  geo.position.assign(position.begin(), position.end());
  geo.row_begin.assign(list.offsets().begin(),
                       list.offsets().begin() + static_cast<std::ptrdiff_t>(n));
  geo.row_end.resize(n);
  geo.neighbours.resize(pairs);
  geo.w.resize(pairs);
  geo.f.resize(pairs);
  geo.volume.resize(n);
  geo.volume_iterates.resize(volume_iterations * n);
  geo.l_inverse.resize(3 * n);
  geo.correction.resize(n);
  geo.l_trace.resize(n);
  geo.div_r.resize(n);
  geo.normal.resize(2 * n);
  const AllRows all{static_cast<int>(n)};
  kernel_stage(all, list, kernel, volume_iterations, geo);
  for (unsigned m = 1; m <= volume_iterations; ++m) {
    volume_stage(all, kernel.w0(), m, volume_iterations, geo);
  }
  correction_matrices(all, lucy_volume, geo);
  geo.volume_iterations = volume_iterations;
  ++geo.version;
}

bool refresh_geometry(const NeighbourList& list, const WendlandC2& kernel,
                      std::span<const double> position, std::span<const int> moved,
                      std::span<const double> lucy_volume, unsigned volume_iterations,
                      double max_fraction, LocalRefresh& s, Geometry& geo) {
  const std::size_t n = geo.particles();
  if (list.particles() != n || list.pairs() != geo.neighbours.size() ||
      position.size() != 2 * n || geo.volume_iterations != volume_iterations) {
    return false;
  }
  // The rings, breadth first from the moved particles (level 0). Ring 1 follows the list's rows:
  // any listed pair of a moved particle may have crossed h. From ring 1 on the geometry's rows of
  // the old configuration serve: a pair inside h in X' but not before has a moved end, so both
  // its ends are in ring 1 already.
  const unsigned rings = volume_iterations + 3;
  constexpr std::uint8_t kNone = 0xff;
  s.level.assign(n, kNone);
  s.rows.clear();
  for (int i : moved) {
    if (s.level[static_cast<std::size_t>(i)] == kNone) {
      s.level[static_cast<std::size_t>(i)] = 0;
      s.rows.push_back(i);
    }
  }
  const auto limit = static_cast<std::size_t>(max_fraction * static_cast<double>(n));
  std::size_t from = 0;
  for (unsigned ring = 1; ring <= rings; ++ring) {
    const std::size_t to = s.rows.size();
    const int* nb = ring == 1 ? list.neighbours().data() : geo.neighbours.data();
    const int* begin = ring == 1 ? list.offsets().data() : geo.row_begin.data();
    const int* end = ring == 1 ? list.offsets().data() + 1 : geo.row_end.data();
    for (std::size_t r = from; r < to; ++r) {
      const int i = s.rows[r];
      for (int k = begin[i]; k < end[i]; ++k) {
        const auto j = static_cast<std::size_t>(nb[k]);
        if (s.level[j] != kNone) continue;
        s.level[j] = static_cast<std::uint8_t>(ring);
        s.rows.push_back(nb[k]);
      }
    }
    if (s.rows.size() > limit) return false;  // nothing changed yet
    from = to;
  }

  // X': the moved particles at their new positions, the others where the geometry had them.
  for (int i : moved) {
    geo.position[2 * i] = position[2 * i];
    geo.position[2 * i + 1] = position[2 * i + 1];
  }
  rows_within(s.level, 1, s.stage);
  kernel_stage(RowList{s.stage}, list, kernel, volume_iterations, geo);
  for (unsigned m = 1; m <= volume_iterations; ++m) {
    rows_within(s.level, 1 + m, s.stage);
    volume_stage(RowList{s.stage}, kernel.w0(), m, volume_iterations, geo);
  }
  rows_within(s.level, volume_iterations + 2, s.stage);
  correction_matrices(RowList{s.stage}, lucy_volume, geo);
  rows_within(s.level, rings, s.coefficient_rows);
  ++geo.version;
  return true;
}

}  // namespace rockcut::fluid::sp
