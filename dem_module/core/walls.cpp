#include "core/walls.hpp"

#include <algorithm>
#include <cmath>

#include "core/rolling_resistance.hpp"
#include "core/viscous_damping.hpp"

namespace rockcut::dem {

namespace {

struct Closest {
  double qx, qy;  // closest point on the segment
};

Closest closest_point(double px, double py, double ax, double ay, double bx, double by) {
  const double ex = bx - ax, ey = by - ay;
  const double len2 = ex * ex + ey * ey;
  double s = len2 > 0 ? ((px - ax) * ex + (py - ay) * ey) / len2 : 0.0;
  s = std::clamp(s, 0.0, 1.0);
  return {ax + s * ex, ay + s * ey};
}

}  // namespace

std::uint32_t WallSet::add_body(const std::string& name, const std::vector<double>& vertices,
                                bool closed, double velocity_x, double velocity_y) {
  const auto body = static_cast<std::uint32_t>(bodies_.size());
  WallBody b;
  b.name = name;
  b.velocity_x = velocity_x;
  b.velocity_y = velocity_y;
  bodies_.push_back(b);
  offset_at_rebuild_.insert(offset_at_rebuild_.end(), {0.0, 0.0});
  const std::size_t n = vertices.size() / 2;
  for (std::size_t k = 0; k + 1 < n + (closed ? 1 : 0); ++k) {
    const std::size_t a = k, c = (k + 1) % n;
    segments_.push_back({vertices[2 * a], vertices[2 * a + 1], vertices[2 * c], vertices[2 * c + 1], body});
  }
  return body;
}

void WallSet::move(double dt) {
  for (WallBody& b : bodies_) {
    b.offset_x += b.velocity_x * dt;
    b.offset_y += b.velocity_y * dt;
  }
}

double WallSet::displacement_since_rebuild() const {
  double d = 0.0;
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    d = std::max(d, std::hypot(bodies_[b].offset_x - offset_at_rebuild_[2 * b],
                               bodies_[b].offset_y - offset_at_rebuild_[2 * b + 1]));
  }
  return d;
}

void WallSet::rebuild(const Particles& p, double skin_m) {
  // Keep the tangential history of the pairs that carry one (the list is in (segment, particle)
  // order, so the keys come out sorted); member buffers: no allocation in steady state.
  old_keys_.clear();
  old_shear_.clear();
  old_rolling_.clear();
  old_dashpot_.clear();
  for (std::size_t k = 0; k < particle_.size(); ++k) {
    if (shear_force_[k] != 0.0 || rolling_moment_[k] != 0.0 || dashpot_[k].any()) {
      old_keys_.push_back((static_cast<std::uint64_t>(segment_[k]) << 32) | particle_[k]);
      old_shear_.push_back(shear_force_[k]);
      old_rolling_.push_back(rolling_moment_[k]);
      old_dashpot_.push_back(dashpot_[k]);
    }
  }
  particle_.clear();
  segment_.clear();
  shear_force_.clear();
  rolling_moment_.clear();
  dashpot_.clear();
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    offset_at_rebuild_[2 * b] = bodies_[b].offset_x;
    offset_at_rebuild_[2 * b + 1] = bodies_[b].offset_y;
  }
  const std::size_t n = p.size();
  for (std::uint32_t s = 0; s < segments_.size(); ++s) {
    const Segment& seg = segments_[s];
    const WallBody& b = bodies_[seg.body];
    const double ax = seg.ax + b.offset_x, ay = seg.ay + b.offset_y;
    const double bx = seg.bx + b.offset_x, by = seg.by + b.offset_y;
    for (std::uint32_t i = 0; i < n; ++i) {
      const double px = p.position[2 * i], py = p.position[2 * i + 1];
      const Closest c = closest_point(px, py, ax, ay, bx, by);
      const double reach = p.radius[i] + skin_m;
      const double dx = px - c.qx, dy = py - c.qy;
      if (dx * dx + dy * dy > reach * reach) continue;
      particle_.push_back(i);
      segment_.push_back(s);
      const std::uint64_t key = (static_cast<std::uint64_t>(s) << 32) | i;
      const auto it = std::lower_bound(old_keys_.begin(), old_keys_.end(), key);
      const bool known = it != old_keys_.end() && *it == key;
      const auto at = static_cast<std::size_t>(it - old_keys_.begin());
      shear_force_.push_back(known ? old_shear_[at] : 0.0);
      rolling_moment_.push_back(known ? old_rolling_[at] : 0.0);
      dashpot_.push_back(known ? old_dashpot_[at] : PairDashpots{});
    }
  }
}

template <bool kDashpots, bool kRolling>
void WallSet::compute_impl(const Particles& p, const ContactLaw& law, double dt, ForceView out,
                           ContactDissipation& sums) {
  const double kn = law.normal_stiffness_pa, ks = law.shear_stiffness_pa, mu = law.friction;
  const double cn_scale = kDashpots ? dashpot_scale(law.damping_ratio, kn) : 0.0;
  const double ct_scale = kDashpots ? dashpot_scale(law.damping_ratio, ks) : 0.0;
  for (std::size_t k = 0; k < particle_.size(); ++k) {
    const std::uint32_t i = particle_[k];
    const Segment& seg = segments_[segment_[k]];
    WallBody& b = bodies_[seg.body];
    const double px = p.position[2 * i], py = p.position[2 * i + 1], r = p.radius[i];
    const Closest c = closest_point(px, py, seg.ax + b.offset_x, seg.ay + b.offset_y,
                                    seg.bx + b.offset_x, seg.by + b.offset_y);
    const double dx = px - c.qx, dy = py - c.qy;
    const double d2 = dx * dx + dy * dy;
    if (d2 >= r * r || d2 == 0.0) {
      // Apart: springs and dashpots released as a contact's are (ContactList::compute_impl).
      const bool was_touching =
          shear_force_[k] != 0.0 || (kRolling && rolling_moment_[k] != 0.0) ||
          (kDashpots && dashpot_[k].any());
      if (was_touching) {
        const double dist = std::sqrt(d2);
        const double nx = d2 > 0.0 ? dx / dist : 0.0, ny = d2 > 0.0 ? dy / dist : 0.0;
        const double dvx = p.velocity[2 * i] - b.velocity_x;
        const double dvy = p.velocity[2 * i + 1] - b.velocity_y;
        const double vt = shear_spring_velocity(dvx, dvy, nx, ny, p.angular_velocity[i] * r, 0.0);
        release_on_opening(shear_force_[k], ks, vt * dt, sums.friction_j);
        if constexpr (kRolling) {
          rolling_released(rolling_moment_[k], ks * r * r, p.angular_velocity[i], dt,
                           sums.rolling_j);
        }
        if constexpr (kDashpots) {
          dashpots_released(dashpot_[k], dvx * nx + dvy * ny, vt, dt, sums.viscous_j);
        }
      }
      continue;
    }
    const double dist = std::sqrt(d2);
    const double nx = dx / dist, ny = dy / dist;  // from the wall to the disc
    const double tx = -ny, ty = nx;
    const double fn = contact_normal_force(kn, r - dist);
    // Disc contact point relative to the wall, rotation included (the wall does not spin).
    const double dvx = p.velocity[2 * i] - b.velocity_x, dvy = p.velocity[2 * i + 1] - b.velocity_y;
    const double vt = shear_spring_velocity(dvx, dvy, nx, ny, p.angular_velocity[i] * r, 0.0);
    const double limit = (b.friction >= 0.0 ? b.friction : mu) * fn;
    const double trial = shear_spring_update(shear_force_[k], ks, vt, dt);
    const double fs = coulomb_limited(shear_force_[k], trial, limit, ks, sums.friction_j);
    shear_force_[k] = fs;
    double moment = -fs * r;
    if constexpr (kRolling) {  // against a wall R_r = r and w_j = 0
      const double m = rolling_moment_update(rolling_moment_[k], ks * r * r,
                                             p.angular_velocity[i], dt,
                                             law.rolling_friction * r * fn, sums.rolling_j);
      rolling_moment_[k] = m;
      moment += m;
    }
    double fn_total = fn, fs_total = fs;
    if constexpr (kDashpots) {  // as the contacts' (core/contact_list.cpp), m_eff = m_i
      const PairDashpots d = pair_dashpots(cn_scale, fs == trial ? ct_scale : 0.0,
                                           sqrt_effective_mass(p.inv_mass[i], 0.0),
                                           dvx * nx + dvy * ny, vt, dt, dashpot_[k],
                                           sums.viscous_j);
      fn_total += d.normal;
      fs_total += d.tangential;
      moment -= d.tangential * r;
    }
    const PairForce f = pair_force(fn_total, fs_total, nx, ny, tx, ty);  // on the disc
    const double fx = f.fx, fy = f.fy;
    out.add(i, fx, fy, moment);
    b.force_x -= fx;
    b.force_y -= fy;
  }
}

void WallSet::compute(const Particles& p, const ContactLaw& law, double dt, ForceView out,
                      double& boundary_work_j, ContactDissipation& sums) {
  for (WallBody& b : bodies_) {
    b.previous_force_x = b.force_x;
    b.previous_force_y = b.force_y;
    b.force_x = b.force_y = 0.0;
  }
  with_pair_laws(law, [&](auto dashpots, auto rolling) {
    compute_impl<dashpots(), rolling()>(p, law, dt, out, sums);
  });
  // Work of each body on the discs over the last drift: the trapezoid of its force, as Verlet
  // moves under the mean of the forces at both ends of a step.
  for (const WallBody& b : bodies_) {
    boundary_work_j -= 0.5 * ((b.previous_force_x + b.force_x) * b.velocity_x +
                              (b.previous_force_y + b.force_y) * b.velocity_y) * dt;
  }
}

double WallSet::pair_overlap(const Particles& p, std::size_t k) const {
  const std::uint32_t i = particle_[k];
  const Segment& seg = segments_[segment_[k]];
  const WallBody& b = bodies_[seg.body];
  const double px = p.position[2 * i], py = p.position[2 * i + 1];
  const Closest c = closest_point(px, py, seg.ax + b.offset_x, seg.ay + b.offset_y,
                                  seg.bx + b.offset_x, seg.by + b.offset_y);
  return p.radius[i] - std::hypot(px - c.qx, py - c.qy);
}

double WallSet::strain_energy(const Particles& p, const ContactLaw& law) const {
  double e = 0.0;
  for (std::size_t k = 0; k < particle_.size(); ++k) {
    const double overlap = pair_overlap(p, k);
    if (overlap <= 0) continue;
    e += 0.5 * law.normal_stiffness_pa * overlap * overlap;
    if (law.shear_stiffness_pa > 0) {
      e += 0.5 * shear_force_[k] * shear_force_[k] / law.shear_stiffness_pa;
    }
    if (rolling_moment_[k] != 0.0) {
      const double r = p.radius[particle_[k]];
      e += rolling_energy(rolling_moment_[k], law.shear_stiffness_pa * r * r);
    }
  }
  return e;
}

double WallSet::largest_overlap_ratio(const Particles& p, std::int64_t& particle) const {
  double largest = 0.0;
  for (std::size_t k = 0; k < particle_.size(); ++k) {
    const std::uint32_t i = particle_[k];
    const double ratio = pair_overlap(p, k) / p.radius[i];
    if (ratio > largest) {
      largest = ratio;
      particle = i;
    }
  }
  return largest;
}

}  // namespace rockcut::dem
