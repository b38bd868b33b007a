#include "core/contact_list.hpp"

#include <algorithm>
#include <cmath>

#include "core/bonds.hpp"
#include "core/cell_grid.hpp"
#include "core/rolling_resistance.hpp"
#include "core/viscous_damping.hpp"

namespace rockcut::dem {

namespace {
std::uint64_t key(std::uint32_t i, std::uint32_t j) {
  return (static_cast<std::uint64_t>(i) << 32) | j;
}
}  // namespace

void ContactList::rebuild(const Particles& p, const BondSet& bonds, double skin_m,
                          CellGrid& grid) {
  begin_rebuild(p, skin_m, grid, 1);
  search(p, bonds, skin_m, grid, 0, 1);
  size_join();
  join(0);
}

void ContactList::begin_rebuild(const Particles& p, double skin_m, CellGrid& grid, int threads) {
  // Remember the history of pairs that carry a tangential force, sorted by pair for the search's
  // lookups (a pair is listed once, so the order is unique). Only those pairs are sorted, as
  // contiguous records.
  history_.clear();
  for (std::size_t k = 0; k < i_.size(); ++k) {
    if (shear_force_[k] != 0.0 || rolling_moment_[k] != 0.0 || dashpot_[k].any()) {
      history_.push_back({key(i_[k], j_[k]), shear_force_[k], rolling_moment_[k], dashpot_[k]});
    }
  }
  std::sort(history_.begin(), history_.end(),
            [](const History& a, const History& b) { return a.key < b.key; });
  double r_max = 0.0;
  for (double r : p.radius) r_max = std::max(r_max, r);
  grid.build(p.position, 2.0 * r_max + skin_m);
  found_.resize(static_cast<std::size_t>(threads));
}

void ContactList::search(const Particles& p, const BondSet& bonds, double skin_m,
                         const CellGrid& grid, int t, int threads) {
  Found& f = found_[static_cast<std::size_t>(t)];
  f.i.clear();
  f.j.clear();
  f.shear.clear();
  f.rolling.clear();
  f.dashpot.clear();
  const double* x = p.position.data();
  const double* r = p.radius.data();
  // The particles in contiguous shares, each in ascending order: joined in thread order, the
  // pairs come in rebuild()'s order (particle by particle, as for_each_near_pair visits them).
  const std::size_t n = p.size();
  const std::size_t begin = n * static_cast<std::size_t>(t) / static_cast<std::size_t>(threads);
  const std::size_t end = n * static_cast<std::size_t>(t + 1) / static_cast<std::size_t>(threads);
  for (std::size_t a = begin; a < end; ++a) {
    grid.for_each_neighbour_of(static_cast<std::uint32_t>(a), [&](std::uint32_t a0,
                                                                   std::uint32_t b) {
      const double dx = x[2 * b] - x[2 * a0], dy = x[2 * b + 1] - x[2 * a0 + 1];
      const double reach = r[a0] + r[b] + skin_m;
      if (dx * dx + dy * dy > reach * reach) return;
      const std::uint32_t lo = std::min(a0, b), hi = std::max(a0, b);
      if (bonds.bonded(lo, hi)) return;
      f.i.push_back(lo);
      f.j.push_back(hi);
      const std::uint64_t k = key(lo, hi);
      const auto it = std::lower_bound(history_.begin(), history_.end(), k,
                                       [](const History& h, std::uint64_t v) { return h.key < v; });
      const bool known = it != history_.end() && it->key == k;
      f.shear.push_back(known ? it->shear : 0.0);
      f.rolling.push_back(known ? it->rolling : 0.0);
      f.dashpot.push_back(known ? it->dashpot : PairDashpots{});
    });
  }
}

void ContactList::size_join() {
  offset_.resize(found_.size());
  std::size_t total = 0;
  for (std::size_t t = 0; t < found_.size(); ++t) {
    offset_[t] = total;
    total += found_[t].i.size();
  }
  i_.resize(total);
  j_.resize(total);
  shear_force_.resize(total);
  rolling_moment_.resize(total);
  dashpot_.resize(total);
}

void ContactList::join(int t) {
  const Found& f = found_[static_cast<std::size_t>(t)];
  const auto at = static_cast<std::ptrdiff_t>(offset_[static_cast<std::size_t>(t)]);
  std::copy(f.i.begin(), f.i.end(), i_.begin() + at);
  std::copy(f.j.begin(), f.j.end(), j_.begin() + at);
  std::copy(f.shear.begin(), f.shear.end(), shear_force_.begin() + at);
  std::copy(f.rolling.begin(), f.rolling.end(), rolling_moment_.begin() + at);
  std::copy(f.dashpot.begin(), f.dashpot.end(), dashpot_.begin() + at);
}

void ContactList::add_pairs(const std::vector<std::uint32_t>& pairs) {
  for (std::size_t k = 0; k + 1 < pairs.size(); k += 2) {
    i_.push_back(std::min(pairs[k], pairs[k + 1]));
    j_.push_back(std::max(pairs[k], pairs[k + 1]));
    shear_force_.push_back(0.0);
    rolling_moment_.push_back(0.0);
    dashpot_.push_back(PairDashpots{});
  }
}

template <bool kDashpots, bool kRolling>
void ContactList::compute_impl(const Particles& p, const ContactLaw& law, double dt,
                               std::size_t begin, std::size_t end, ForceView out,
                               ContactDissipation& sums) {
  const double* x = p.position.data();
  const double* v = p.velocity.data();
  const double* w = p.angular_velocity.data();
  const double* r = p.radius.data();
  const double* inv_m = p.inv_mass.data();
  const double kn = law.normal_stiffness_pa, ks = law.shear_stiffness_pa, mu = law.friction;
  const double cn_scale = kDashpots ? dashpot_scale(law.damping_ratio, kn) : 0.0;
  const double ct_scale = kDashpots ? dashpot_scale(law.damping_ratio, ks) : 0.0;
  const double mu_r = law.rolling_friction;
  double friction = 0.0, viscous = 0.0, rolling = 0.0;
  // The per-pair arrays hoisted: the stores through `out` would make the loop reload them.
  double* shear = shear_force_.data();
  double* rolling_moment = rolling_moment_.data();
  PairDashpots* dashpot = dashpot_.data();
  for (std::size_t k = begin; k < end; ++k) {
    const std::uint32_t i = i_[k], j = j_[k];
    const double dx = x[2 * j] - x[2 * i], dy = x[2 * j + 1] - x[2 * i + 1];
    const double rsum = r[i] + r[j];
    const double d2 = dx * dx + dy * dy;
    if (d2 >= rsum * rsum) {
      // Apart: the normal force, and with it the Coulomb limit, fell to zero within the drift.
      // A pair that was touching releases its springs and dashpots, each booked as they left
      // the kick (only those: the rest of the skin's pairs skip this).
      const bool was_touching =
          shear[k] != 0.0 || (kRolling && rolling_moment[k] != 0.0) ||
          (kDashpots && dashpot[k].any());
      if (was_touching) {
        const double len = std::sqrt(d2);
        const double nx = dx / len, ny = dy / len;
        const double vt = shear_spring_velocity(v[2 * j] - v[2 * i], v[2 * j + 1] - v[2 * i + 1],
                                                nx, ny, w[i] * r[i], w[j] * r[j]);
        release_on_opening(shear[k], ks, vt * dt, friction);
        if constexpr (kRolling) {
          const double rr = rolling_radius(r[i], r[j]);
          rolling_released(rolling_moment[k], ks * rr * rr, w[i] - w[j], dt, rolling);
        }
        if constexpr (kDashpots) {
          const double vn = (v[2 * j] - v[2 * i]) * nx + (v[2 * j + 1] - v[2 * i + 1]) * ny;
          dashpots_released(dashpot[k], vn, vt, dt, viscous);
        }
      }
      continue;
    }
    const double len = std::sqrt(d2);
    const double nx = dx / len, ny = dy / len;
    const double tx = -ny, ty = nx;
    const double fn = contact_normal_force(kn, rsum - len);
    const double vt = shear_spring_velocity(v[2 * j] - v[2 * i], v[2 * j + 1] - v[2 * i + 1], nx,
                                            ny, w[i] * r[i], w[j] * r[j]);
    const double trial = shear_spring_update(shear[k], ks, vt, dt);
    const double fs = coulomb_limited(shear[k], trial, mu * fn, ks, friction);
    shear[k] = fs;
    double moment_i = -fs * r[i], moment_j = -fs * r[j];
    if constexpr (kRolling) {
      const double rr = rolling_radius(r[i], r[j]);
      const double m = rolling_moment_update(rolling_moment[k], ks * rr * rr, w[i] - w[j], dt,
                                             mu_r * rr * fn, rolling);
      rolling_moment[k] = m;
      moment_i += m;
      moment_j -= m;
    }
    if constexpr (kDashpots) {
      // The normal dashpot acts over the whole contact (it may pull at the end of a collision:
      // the linear spring-dashpot whose restitution core/viscous_damping.hpp states); the
      // tangential one while the contact sticks (sliding dissipates through friction).
      const double vn = (v[2 * j] - v[2 * i]) * nx + (v[2 * j + 1] - v[2 * i + 1]) * ny;
      const PairDashpots d = pair_dashpots(cn_scale, fs == trial ? ct_scale : 0.0,
                                           sqrt_effective_mass(inv_m[i], inv_m[j]), vn, vt, dt,
                                           dashpot[k], viscous);
      const PairForce f = pair_force(fn + d.normal, fs + d.tangential, nx, ny, tx, ty);
      out.add_pair(i, j, f.fx, f.fy, moment_i - d.tangential * r[i],
                   moment_j - d.tangential * r[j]);
    } else {
      const PairForce f = pair_force(fn, fs, nx, ny, tx, ty);  // on j
      out.add_pair(i, j, f.fx, f.fy, moment_i, moment_j);
    }
  }
  sums.friction_j += friction;
  sums.viscous_j += viscous;
  sums.rolling_j += rolling;
}

void ContactList::compute(const Particles& p, const ContactLaw& law, double dt,
                          std::size_t begin, std::size_t end, ForceView out,
                          ContactDissipation& sums) {
  with_pair_laws(law, [&](auto dashpots, auto rolling) {
    compute_impl<dashpots(), rolling()>(p, law, dt, begin, end, out, sums);
  });
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
    if (rolling_moment_[k] != 0.0) {
      const double rr = rolling_radius(p.radius[i], p.radius[j]);
      e += rolling_energy(rolling_moment_[k], law.shear_stiffness_pa * rr * rr);
    }
  }
  return e;
}

}  // namespace rockcut::dem
