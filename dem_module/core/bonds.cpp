#include "core/bonds.hpp"

#include <algorithm>
#include <cmath>

#include "core/bond_softening.hpp"
#include "core/cell_grid.hpp"
#include "core/viscous_damping.hpp"

namespace rockcut::dem {

BondSet BondSet::install(const Particles& p, const BondLaw& law, double gap_tolerance_m,
                         CellGrid& grid) {
  BondSet b;
  b.law_ = law;
  double r_max = 0.0;
  for (double r : p.radius) r_max = std::max(r_max, r);
  grid.build(p.position, 2.0 * r_max + gap_tolerance_m);
  const double* x = p.position.data();
  grid.for_each_near_pair([&](std::uint32_t i, std::uint32_t j) {
    const double dx = x[2 * j] - x[2 * i], dy = x[2 * j + 1] - x[2 * i + 1];
    const double dist = std::sqrt(dx * dx + dy * dy);
    if (dist - p.radius[i] - p.radius[j] <= gap_tolerance_m) {
      b.i_.push_back(std::min(i, j));
      b.j_.push_back(std::max(i, j));
      b.rest_length_.push_back(dist);
    }
  });
  // Bonds in particle order: the force loop then walks memory nearly sequentially.
  std::vector<std::size_t> order(b.i_.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t c) {
    return b.i_[a] != b.i_[c] ? b.i_[a] < b.i_[c] : b.j_[a] < b.j_[c];
  });
  auto permute = [&](auto& v) {
    auto copy = v;
    for (std::size_t k = 0; k < order.size(); ++k) v[k] = copy[order[k]];
  };
  permute(b.i_);
  permute(b.j_);
  permute(b.rest_length_);
  b.shear_force_.assign(b.i_.size(), 0.0);
  b.released_at_break_.assign(b.i_.size(), 0.0);
  b.dashpot_.assign(b.i_.size(), PairDashpots{});
  b.broken_.assign(b.i_.size(), 0);
  if (law.softening_ratio > 0.0) {
    b.damage_.assign(b.i_.size(), 0.0);
    b.damaged_.assign(b.i_.size(), 0);
  }
  b.refresh_partners(p.size());
  b.refresh_pair_masses(p);
  return b;
}

void BondSet::refresh_pair_masses(const Particles& p) {
  sqrt_mass_.resize(i_.size());
  for (std::size_t k = 0; k < i_.size(); ++k) {
    sqrt_mass_[k] = sqrt_effective_mass(p.inv_mass[i_[k]], p.inv_mass[j_[k]]);
  }
}

template <bool kDashpots, bool kSoftening>
void BondSet::compute_impl(const Particles& p, double dt, std::size_t begin, std::size_t end,
                           ForceView out, bool& any_broken, double contact_normal_pa,
                           double damping_ratio, double& viscous_j, double& softening_j) {
  const double* x = p.position.data();
  const double* v = p.velocity.data();
  const double* w = p.angular_velocity.data();
  const double* r = p.radius.data();
  const double* sqrt_m = sqrt_mass_.data();
  const std::uint32_t* bi = i_.data();
  const std::uint32_t* bj = j_.data();
  const double* rest = rest_length_.data();
  double* shear = shear_force_.data();
  PairDashpots* dashpot = dashpot_.data();  // hoisted as the others: the stores through `out`
                                            // would make the loop reload a member's pointer
  const double kn = law_.normal_stiffness_pa, ks_dt = law_.shear_stiffness_pa * dt;
  const double tn = law_.tensile_strength_n_per_m, ts = law_.shear_strength_n_per_m;
  const double tan_phi_b = law_.friction_coefficient;
  const double cn_scale = kDashpots ? dashpot_scale(damping_ratio, kn) : 0.0;
  const double ct_scale = kDashpots ? dashpot_scale(damping_ratio, law_.shear_stiffness_pa) : 0.0;
  // The loop reads a byte per bond, not the damage itself: a double there cost every bond's step
  // 6 %, the byte 1-4 % (bench/README.md, "Softening bonds").
  const std::uint8_t* damaged = damaged_.data();
  double dissipated = 0.0, softened = 0.0;
  bool broke = false;
  for (std::size_t k = begin; k < end; ++k) {
    const std::uint32_t i = bi[k], j = bj[k];
    const double dx = x[2 * j] - x[2 * i], dy = x[2 * j + 1] - x[2 * i + 1];
    const double d2 = dx * dx + dy * dy;
    const double len = std::sqrt(d2);
    const double inv_len = 1.0 / len;
    const double nx = dx * inv_len, ny = dy * inv_len;
    const double tx = -ny, ty = nx;
    // Compression positive. The length is the one install() stored as the rest length, bit for
    // bit, so a bond at rest pulls with exactly zero force (d2 * inv_len differs from it in the
    // last bit: round-off forces that then moved a relaxed block and did work on no ledger).
    const double fn = bond_normal_force(kn, rest[k], len);
    const double vt = shear_spring_velocity(v[2 * j] - v[2 * i], v[2 * j + 1] - v[2 * i + 1], nx,
                                            ny, w[i] * r[i], w[j] * r[j]);
    const double fs = shear_spring_update_hoisted(shear[k], ks_dt, vt);
    // Perfectly brittle: exceeding a strength breaks the bond in this evaluation, with no force.
    // The strengths bound the springs' forces; the dashpots beside them do not break a bond.
    const double ts_fn = bond_shear_strength(ts, tan_phi_b, fn);
    if constexpr (kSoftening) {
      // A damaged bond, or one past its strength, follows the softening law out of the loop.
      if (damaged[k] || bond_breaks(fn, fs, tn, ts_fn)) [[unlikely]] {
        if (soften<kDashpots>(k, p, dt, fn, fs, out, contact_normal_pa, cn_scale, ct_scale,
                              dissipated, softened)) {
          broke = true;
        }
        continue;
      }
    } else if (bond_breaks(fn, fs, tn, ts_fn)) [[unlikely]] {
      break_now<kDashpots>(k, p, dt, fn, fs, ts_fn, out, contact_normal_pa, dissipated);
      broke = true;
      continue;
    }
    shear[k] = fs;
    if constexpr (kDashpots) {
      const double vn = (v[2 * j] - v[2 * i]) * nx + (v[2 * j + 1] - v[2 * i + 1]) * ny;
      const PairDashpots d =
          pair_dashpots(cn_scale, ct_scale, sqrt_m[k], vn, vt, dt, dashpot[k], dissipated);
      const double fn_total = fn + d.normal, fs_total = fs + d.tangential;
      const PairForce f = pair_force(fn_total, fs_total, nx, ny, tx, ty);  // on j
      out.add_pair(i, j, f.fx, f.fy, -fs_total * r[i], -fs_total * r[j]);
    } else {
      const PairForce f = pair_force(fn, fs, nx, ny, tx, ty);  // on j
      out.add_pair(i, j, f.fx, f.fy, -fs * r[i], -fs * r[j]);
    }
  }
  if (broke) any_broken = true;
  viscous_j += dissipated;
  if constexpr (kSoftening) softening_j += softened;
}

BondSet::PairGeometry BondSet::geometry_again(std::size_t k, const Particles& p, double dt) const {
  // As compute_impl formed it (the same expressions, the same bits).
  const double* x = p.position.data();
  const double* v = p.velocity.data();
  PairGeometry g;
  g.i = i_[k];
  g.j = j_[k];
  const double dx = x[2 * g.j] - x[2 * g.i], dy = x[2 * g.j + 1] - x[2 * g.i + 1];
  g.length_m = std::sqrt(dx * dx + dy * dy);
  const double inv_len = 1.0 / g.length_m;
  g.nx = dx * inv_len;
  g.ny = dy * inv_len;
  g.rel_vx = v[2 * g.j] - v[2 * g.i];
  g.rel_vy = v[2 * g.j + 1] - v[2 * g.i + 1];
  // The length before the drift: x^n = x^{n+1} - v^{n+1/2} dt.
  const double dx_before = dx - g.rel_vx * dt, dy_before = dy - g.rel_vy * dt;
  g.length_before_m = std::sqrt(dx_before * dx_before + dy_before * dy_before);
  return g;
}

template <bool kDashpots>
void BondSet::break_now(std::size_t k, const Particles& p, double dt, double fn, double fs,
                        double ts_fn, ForceView out, double contact_normal_pa,
                        double& dissipated_j) {
  const PairGeometry g = geometry_again(k, p, dt);
  const double* w = p.angular_velocity.data();
  const double* r = p.radius.data();
  const std::uint32_t i = g.i, j = g.j;
  const double len = g.length_m, nx = g.nx, ny = g.ny;
  const double kn = law_.normal_stiffness_pa;
  broken_[k] = 1 + static_cast<std::uint8_t>(
                       bond_break_mode(fn, fs, law_.tensile_strength_n_per_m, ts_fn));
  // The springs' forces of the last evaluation: the shear spring's as stored, the normal one's at
  // the length before the drift.
  const double rel_vx = g.rel_vx, rel_vy = g.rel_vy;
  const double fn_before = bond_normal_force(kn, rest_length_[k], g.length_before_m);
  const double fs_before = shear_force_[k];
  shear_force_[k] = fs;
  if constexpr (kDashpots) {  // they acted over the drift into this evaluation
    const double vt = shear_spring_velocity(rel_vx, rel_vy, nx, ny, w[i] * r[i], w[j] * r[j]);
    dashpots_released(dashpot_[k], rel_vx * nx + rel_vy * ny, vt, dt, dissipated_j);
  }
  // The contact spring that replaces the bond acts from this evaluation on. Left for the next
  // one (the pair joins the contact list only in remove_broken), a pair pressed together carried
  // no normal force for one step, and the drift over that step and the next did work on the discs
  // that no spring stored: the ledger of a crushed hexagonal lattice, whose shear breaks happen
  // under large compression, closed only to 2 % (1 % without clamped ends;
  // tests/integration/energy_ledger_test.cpp). The ledger books what the bond released less what
  // this contact keeps (bond_energy_released), so the normal energy passes on.
  const double overlap = r[i] + r[j] - len;
  double fc = 0.0;
  if (contact_normal_pa > 0.0 && overlap > 0.0) {
    fc = contact_normal_force(contact_normal_pa, overlap);
    out.add_pair(i, j, fc * nx, fc * ny, 0.0, 0.0);
  }
  released_at_break_[k] = bond_energy_released(fn_before, fn, fc, fs_before, fs, kn,
                                               law_.shear_stiffness_pa, contact_normal_pa);
}

template <bool kDashpots>
bool BondSet::soften(std::size_t k, const Particles& p, double dt, double fn, double fs,
                     ForceView out, double contact_normal_pa, double cn_scale, double ct_scale,
                     double& dissipated_j, double& softening_j) {
  const PairGeometry g = geometry_again(k, p, dt);
  const double* w = p.angular_velocity.data();
  const double* r = p.radius.data();
  const std::uint32_t i = g.i, j = g.j;
  const double len = g.length_m, nx = g.nx, ny = g.ny;
  const double kn = law_.normal_stiffness_pa, ks = law_.shear_stiffness_pa;
  const double lambda = law_.softening_ratio, ts = law_.shear_strength_n_per_m;
  const double d_before = damage_[k];
  // The last evaluation's opening and the force and energy the law gave it there (the damage has
  // not changed since).
  const double rel_vx = g.rel_vx, rel_vy = g.rel_vy;
  const double open_before = g.length_before_m - rest_length_[k];
  const double open = len - rest_length_[k];
  const double t_before = softened_tension(kn, open_before, d_before, lambda);
  const double e_before = 0.5 * t_before * open_before;
  // Shear first: the slip past the softened limit damages the bond. The normal force below then
  // uses the damage this evaluation leaves, so that the next one finds it again at x^n.
  const double fs_before = shear_force_[k];
  // The spring is cut to its softened limit and booked as friction's is (coulomb_limited).
  double shear_loss = 0.0;
  const double limit = bond_shear_strength(ts, law_.friction_coefficient, fn) * (1.0 - d_before);
  const double fs_after = coulomb_limited(fs_before, fs, limit, ks, shear_loss);
  // The plastic slip (|F_trial| - limit) / k_s over the plastic slip that takes the strength to
  // zero, (1 + lambda) T_s / k_s: the force then falls to zero over lambda elastic slips of total
  // slip, as the tensile envelope over lambda elastic openings.
  double damage = d_before + (std::abs(fs) - std::abs(fs_after)) / ((1.0 + lambda) * ts);
  const bool broke_in_shear = damage >= 1.0;
  if (open > 0.0) {
    damage = std::max(damage, tensile_envelope_damage(open, law_.tensile_strength_n_per_m / kn, lambda));
  }
  const double vt = shear_spring_velocity(rel_vx, rel_vy, nx, ny, w[i] * r[i], w[j] * r[j]);
  const double vn = rel_vx * nx + rel_vy * ny;
  if (damage >= 1.0) {
    broken_[k] = 1 + static_cast<std::uint8_t>(broke_in_shear ? BreakMode::shear : BreakMode::tensile);
    shear_force_[k] = fs;
    if constexpr (kDashpots) dashpots_released(dashpot_[k], vn, vt, dt, dissipated_j);
    // A pair pressed together passes on to its contact, as break_now.
    const double overlap = r[i] + r[j] - len;
    double fc = 0.0;
    if (contact_normal_pa > 0.0 && overlap > 0.0) {
      fc = contact_normal_force(contact_normal_pa, overlap);
      out.add_pair(i, j, fc * nx, fc * ny, 0.0, 0.0);
    }
    // What the kick's trapezoid did on the pair (tension positive: -fc after) and the springs'
    // energy change leave, the contact's energy kept; the shear spring goes from F_b to nothing
    // (bond_energy_released).
    const double normal = 0.5 * (t_before - fc) * (open - open_before) + e_before -
                          (fc > 0.0 ? 0.5 * fc * fc / contact_normal_pa : 0.0);
    released_at_break_[k] = normal + 0.5 * fs_before * fs / ks;
    return true;
  }
  damage_[k] = damage;
  damaged_[k] = damage > 0.0;
  shear_force_[k] = fs_after;
  const double t_after = softened_tension(kn, open, damage, lambda);
  const double e_after = 0.5 * t_after * open;
  softening_j += shear_loss + 0.5 * (t_before + t_after) * (open - open_before) - (e_after - e_before);
  double fn_total = -t_after, fs_total = fs_after;
  if constexpr (kDashpots) {
    const PairDashpots d =
        pair_dashpots(cn_scale, ct_scale, sqrt_mass_[k], vn, vt, dt, dashpot_[k], dissipated_j);
    fn_total += d.normal;
    fs_total += d.tangential;
  }
  const PairForce f = pair_force(fn_total, fs_total, nx, ny, -ny, nx);  // on j
  out.add_pair(i, j, f.fx, f.fy, -fs_total * r[i], -fs_total * r[j]);
  return false;
}

void BondSet::compute(const Particles& p, double dt, std::size_t begin, std::size_t end,
                      ForceView out, bool& any_broken, double contact_normal_pa,
                      double damping_ratio, double& viscous_j, double& softening_j) {
  const bool softening = !damage_.empty();
  if (damping_ratio > 0.0) {
    if (softening) {
      compute_impl<true, true>(p, dt, begin, end, out, any_broken, contact_normal_pa,
                               damping_ratio, viscous_j, softening_j);
    } else {
      compute_impl<true, false>(p, dt, begin, end, out, any_broken, contact_normal_pa,
                                damping_ratio, viscous_j, softening_j);
    }
  } else if (softening) {
    compute_impl<false, true>(p, dt, begin, end, out, any_broken, contact_normal_pa, 0.0,
                              viscous_j, softening_j);
  } else {
    compute_impl<false, false>(p, dt, begin, end, out, any_broken, contact_normal_pa, 0.0,
                               viscous_j, softening_j);
  }
}

void BondSet::remove_broken(const Particles& p, double time_s, std::vector<BondBreak>& breaks,
                            std::vector<std::uint32_t>& freed_pairs, EnergyLedger& ledger) {
  std::size_t keep = 0;
  for (std::size_t k = 0; k < i_.size(); ++k) {
    if (broken_[k]) {
      const std::uint32_t i = i_[k], j = j_[k];
      ledger.broken_bond_j += released_at_break_[k];
      breaks.push_back({static_cast<BreakMode>(broken_[k] - 1), time_s,
                        0.5 * (p.position[2 * i] + p.position[2 * j]),
                        0.5 * (p.position[2 * i + 1] + p.position[2 * j + 1]), i, j});
      freed_pairs.push_back(i);
      freed_pairs.push_back(j);
      continue;
    }
    // Stable compaction keeps the particle order of the list.
    i_[keep] = i_[k];
    j_[keep] = j_[k];
    rest_length_[keep] = rest_length_[k];
    shear_force_[keep] = shear_force_[k];
    dashpot_[keep] = dashpot_[k];
    sqrt_mass_[keep] = sqrt_mass_[k];
    if (!damage_.empty()) {
      damage_[keep] = damage_[k];
      damaged_[keep] = damaged_[k];
    }
    broken_[keep] = 0;
    ++keep;
  }
  i_.resize(keep);
  j_.resize(keep);
  rest_length_.resize(keep);
  shear_force_.resize(keep);
  released_at_break_.resize(keep);
  dashpot_.resize(keep);
  sqrt_mass_.resize(keep);
  broken_.resize(keep);
  if (!damage_.empty()) {
    damage_.resize(keep);
    damaged_.resize(keep);
  }
}

double BondSet::length_m(std::size_t k, const Particles& p) const {
  const std::uint32_t i = i_[k], j = j_[k];
  const double dx = p.position[2 * j] - p.position[2 * i];
  const double dy = p.position[2 * j + 1] - p.position[2 * i + 1];
  return std::sqrt(dx * dx + dy * dy);
}

double BondSet::normal_force(std::size_t k, const Particles& p) const {
  const double len = length_m(k, p);
  if (!damage_.empty()) {
    return -softened_tension(law_.normal_stiffness_pa, len - rest_length_[k], damage_[k],
                             law_.softening_ratio);
  }
  return bond_normal_force(law_.normal_stiffness_pa, rest_length_[k], len);
}

double BondSet::strain_energy(const Particles& p) const {
  const double kn = law_.normal_stiffness_pa, ks = law_.shear_stiffness_pa;
  double e = 0.0;
  for (std::size_t k = 0; k < i_.size(); ++k) {
    if (!damage_.empty() && damage_[k] > 0.0) {  // on its secant in tension
      e += softened_normal_energy(kn, length_m(k, p) - rest_length_[k], damage_[k],
                                  law_.softening_ratio) +
           bond_energy(0.0, shear_force_[k], kn, ks);
      continue;
    }
    e += bond_energy(normal_force(k, p), shear_force_[k], kn, ks);
  }
  return e;
}

void BondSet::count_per_particle(std::size_t n, std::vector<std::uint32_t>& count) const {
  count.assign(n, 0);
  for (std::size_t k = 0; k < i_.size(); ++k) {
    ++count[i_[k]];
    ++count[j_[k]];
  }
}

void BondSet::refresh_partners(std::size_t n) {
  partner_start_.assign(n + 1, 0);
  for (std::size_t k = 0; k < i_.size(); ++k) {
    ++partner_start_[i_[k] + 1];
    ++partner_start_[j_[k] + 1];
  }
  for (std::size_t i = 0; i < n; ++i) partner_start_[i + 1] += partner_start_[i];
  partner_.resize(partner_start_[n]);
  std::vector<std::uint32_t> fill(partner_start_.begin(), partner_start_.end() - 1);
  for (std::size_t k = 0; k < i_.size(); ++k) {
    partner_[fill[i_[k]]++] = j_[k];
    partner_[fill[j_[k]]++] = i_[k];
  }
}

bool BondSet::bonded(std::uint32_t i, std::uint32_t j) const {
  for (std::uint32_t k = partner_start_[i]; k < partner_start_[i + 1]; ++k) {
    if (partner_[k] == j) return true;
  }
  return false;
}

}  // namespace rockcut::dem
