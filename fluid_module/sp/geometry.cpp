#include "sp/geometry.hpp"

#include <cmath>

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
void pair_kernels(const NeighbourList& list, const WendlandC2& kernel, const double* x,
                  Geometry& g) {
  const int n = static_cast<int>(list.particles());
  const int* __restrict off = list.offsets().data();
  const int* __restrict nb = list.neighbours().data();
  int* __restrict kept = g.neighbours.data();
  int* __restrict row_end = g.row_end.data();
  double* __restrict ws = g.w.data();
  double* __restrict fs = g.f.data();
  double* __restrict volume = g.volume.data();
  const WendlandC2 k = kernel;  // a local copy: its constants stay in registers
  const double w0 = k.w0();
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
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

// One partition-of-unity refinement V_i <- V_i / sum_j V_j W_ij (Jacobi: all from the old V).
void refine_volumes(double w0, Geometry& g) {
  const int n = static_cast<int>(g.particles());
  const int* begin = g.row_begin.data();
  const int* end = g.row_end.data();
  const int* nb = g.neighbours.data();
  const double* v = g.volume.data();
  double* out = g.scratch.data();
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    double s = v[i] * w0;
    for (int k = begin[i]; k < end[i]; ++k) s += v[nb[k]] * g.w[k];
    out[i] = v[i] / s;
  }
  g.volume.swap(g.scratch);
}

// L_i = sum_j V_j (x_j - x_i) (x) grad_i W_ij = sum_j V_j (-F_ij) d d^T with d = x_j - x_i: the
// CSPM correction of eq. 16 in its 2x2 matrix form (symmetric, positive semi-definite), and
// Lucy's div r of eq. 24, sum_j (m_j / rho_j) (x_j - x_i) . grad_i W_ij = sum_j V_j (-F_ij) r^2.
// The difference form (x_j - x_i) is used so that div r does not depend on where the origin is.
// With the same volumes, -sum_j (m_j / rho_j) grad_i W_ij points out of the surface.
void correction_matrices(std::span<const double> lucy_volume, Geometry& g) {
  const int n = static_cast<int>(g.particles());
  const int* begin = g.row_begin.data();
  const int* end = g.row_end.data();
  const int* nb = g.neighbours.data();
  const double* v = g.volume.data();
  const double* vl = lucy_volume.data();
  const double* x = g.position.data();
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    double a = 0.0, b = 0.0, c = 0.0, divr = 0.0, nx = 0.0, ny = 0.0;
    const double xi = x[2 * i], yi = x[2 * i + 1];
    for (int k = begin[i]; k < end[i]; ++k) {
      const int j = nb[k];
      const double dx = x[2 * j] - xi, dy = x[2 * j + 1] - yi, mf = -g.f[k];
      const double s = v[j] * mf;
      a += s * dx * dx;
      b += s * dx * dy;
      c += s * dy * dy;
      divr += vl[j] * mf * (dx * dx + dy * dy);
      nx -= vl[j] * mf * dx;
      ny -= vl[j] * mf * dy;
    }
    g.div_r[i] = divr;
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
  geo.scratch.resize(n);
  geo.l_inverse.resize(3 * n);
  geo.correction.resize(n);
  geo.div_r.resize(n);
  geo.normal.resize(2 * n);
  pair_kernels(list, kernel, geo.position.data(), geo);
  for (unsigned k = 0; k < volume_iterations; ++k) refine_volumes(kernel.w0(), geo);
  correction_matrices(lucy_volume, geo);
  ++geo.version;
}

}  // namespace rockcut::fluid::sp
