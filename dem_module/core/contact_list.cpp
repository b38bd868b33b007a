#include "core/contact_list.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "core/bonds.hpp"
#include "core/cell_grid.hpp"

namespace rockcut::dem {

namespace {
std::uint64_t key(std::uint32_t i, std::uint32_t j) {
  return (static_cast<std::uint64_t>(i) << 32) | j;
}
}  // namespace

void ContactList::rebuild(const Particles& p, const BondSet& bonds, double skin_m,
                          CellGrid& grid) {
  // Remember the history of pairs that carry a tangential force.
  old_keys_.clear();
  old_shear_.clear();
  order_.resize(i_.size());
  std::iota(order_.begin(), order_.end(), 0u);
  std::sort(order_.begin(), order_.end(),
            [&](std::uint32_t a, std::uint32_t b) { return key(i_[a], j_[a]) < key(i_[b], j_[b]); });
  for (std::uint32_t k : order_) {
    if (shear_force_[k] != 0.0) {
      old_keys_.push_back(key(i_[k], j_[k]));
      old_shear_.push_back(shear_force_[k]);
    }
  }

  double r_max = 0.0;
  for (double r : p.radius) r_max = std::max(r_max, r);
  grid.build(p.position, 2.0 * r_max + skin_m);
  i_.clear();
  j_.clear();
  shear_force_.clear();
  const double* x = p.position.data();
  const double* r = p.radius.data();
  grid.for_each_near_pair([&](std::uint32_t a, std::uint32_t b) {
    const double dx = x[2 * b] - x[2 * a], dy = x[2 * b + 1] - x[2 * a + 1];
    const double reach = r[a] + r[b] + skin_m;
    if (dx * dx + dy * dy > reach * reach) return;
    const std::uint32_t lo = std::min(a, b), hi = std::max(a, b);
    if (bonds.bonded(lo, hi)) return;
    i_.push_back(lo);
    j_.push_back(hi);
    const auto it = std::lower_bound(old_keys_.begin(), old_keys_.end(), key(lo, hi));
    shear_force_.push_back(it != old_keys_.end() && *it == key(lo, hi)
                               ? old_shear_[static_cast<std::size_t>(it - old_keys_.begin())]
                               : 0.0);
  });
}

void ContactList::add_pairs(const std::vector<std::uint32_t>& pairs) {
  for (std::size_t k = 0; k + 1 < pairs.size(); k += 2) {
    i_.push_back(std::min(pairs[k], pairs[k + 1]));
    j_.push_back(std::max(pairs[k], pairs[k + 1]));
    shear_force_.push_back(0.0);
  }
}

void ContactList::compute(const Particles& p, const ContactLaw& law, double dt,
                          std::size_t begin, std::size_t end, ForceView out, double& friction_j) {
  const double* x = p.position.data();
  const double* v = p.velocity.data();
  const double* w = p.angular_velocity.data();
  const double* r = p.radius.data();
  const double kn = law.normal_stiffness_pa, ks = law.shear_stiffness_pa, mu = law.friction;
  double friction = 0.0;
  for (std::size_t k = begin; k < end; ++k) {
    const std::uint32_t i = i_[k], j = j_[k];
    const double dx = x[2 * j] - x[2 * i], dy = x[2 * j + 1] - x[2 * i + 1];
    const double rsum = r[i] + r[j];
    const double d2 = dx * dx + dy * dy;
    if (d2 >= rsum * rsum) {
      shear_force_[k] = 0.0;  // apart: the tangential spring is released
      continue;
    }
    const double len = std::sqrt(d2);
    const double nx = dx / len, ny = dy / len;
    const double tx = -ny, ty = nx;
    const double fn = contact_normal_force(kn, rsum - len);
    const double vt = shear_spring_velocity(v[2 * j] - v[2 * i], v[2 * j + 1] - v[2 * i + 1], nx,
                                            ny, w[i] * r[i], w[j] * r[j]);
    const double fs = coulomb_limited(shear_spring_update(shear_force_[k], ks, vt, dt), mu * fn,
                                      ks, friction);
    shear_force_[k] = fs;
    const PairForce f = pair_force(fn, fs, nx, ny, tx, ty);  // on j
    out.add_pair(i, j, f.fx, f.fy, -fs * r[i], -fs * r[j]);
  }
  friction_j += friction;
}

double ContactList::strain_energy(const Particles& p, const ContactLaw& law) const {
  double e = 0.0;
  for (std::size_t k = 0; k < i_.size(); ++k) {
    const std::uint32_t i = i_[k], j = j_[k];
    const double dx = p.position[2 * j] - p.position[2 * i];
    const double dy = p.position[2 * j + 1] - p.position[2 * i + 1];
    const double overlap = p.radius[i] + p.radius[j] - std::sqrt(dx * dx + dy * dy);
    if (overlap <= 0) continue;
    e += 0.5 * law.normal_stiffness_pa * overlap * overlap +
         0.5 * shear_force_[k] * shear_force_[k] / law.shear_stiffness_pa;
  }
  return e;
}

}  // namespace rockcut::dem
