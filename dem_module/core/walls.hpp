// Rigid walls and the tool: bodies made of line segments that move at a prescribed velocity and
// push discs with the contact law of DESIGN section 4 (a segment's end is a rounded corner). The
// force on each body is summed every step: the tool force is the sum of its contact forces.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/energy.hpp"
#include "core/force_buffers.hpp"
#include "core/interaction_law.hpp"
#include "core/particles.hpp"
#include "core/viscous_damping.hpp"
#include "wire/state_archive.hpp"

namespace rockcut::dem {

struct Segment {
  double ax, ay, bx, by;  ///< end points at t = 0 [m]
  std::uint32_t body;
};

struct WallBody {
  std::string name;
  double velocity_x = 0.0, velocity_y = 0.0;  ///< [m/s]
  double offset_x = 0.0, offset_y = 0.0;      ///< displacement since t = 0 [m]
  double force_x = 0.0, force_y = 0.0;        ///< force of the discs on the body, last step [N/m]
  double previous_force_x = 0.0, previous_force_y = 0.0;  ///< the step before (work trapezoid)
  /// Friction coefficient of this body's contacts; negative: the contact law's (lubricated
  /// platens of a loading test are frictionless while the grains keep theirs).
  double friction = -1.0;
};

class WallSet {
 public:
  /// Adds a body made of the polyline through `vertices` (x0, y0, x1, y1, ...); closed if asked.
  std::uint32_t add_body(const std::string& name, const std::vector<double>& vertices,
                         bool closed, double velocity_x, double velocity_y);
  bool empty() const { return segments_.empty(); }
  const std::vector<WallBody>& bodies() const { return bodies_; }
  /// Gives body `body` its own friction coefficient (>= 0) instead of the contact law's.
  void set_friction(std::uint32_t body, double friction) { bodies_.at(body).friction = friction; }
  /// Sets body `body`'s x velocity from the next move on (a servo-controlled wall).
  void set_velocity_x(std::uint32_t body, double velocity_x) { bodies_[body].velocity_x = velocity_x; }
  const std::vector<Segment>& segments() const { return segments_; }
  /// The discs of the listed (disc, segment) pairs, in list order.
  const std::vector<std::uint32_t>& listed_particles() const { return particle_; }

  /// Moves every body by its velocity over dt.
  void move(double dt);
  /// Largest body displacement since the last rebuild [m] (for the neighbour-list skin).
  double displacement_since_rebuild() const;
  /// Lists the (disc, segment) pairs closer than r + skin, keeping their tangential history.
  void rebuild(const Particles& p, double skin_m);
  /// Adds wall forces on the discs into `out`, sets each body's force, and adds the work the
  /// bodies did on the discs over dt to `boundary_work_j` and what friction, the dashpots and
  /// the rolling springs dissipated to `sums`.
  void compute(const Particles& p, const ContactLaw& law, double dt, ForceView out,
               double& boundary_work_j, ContactDissipation& sums);
  /// Elastic energy in the disc-wall contacts [J/m] (normal and tangential springs).
  double strain_energy(const Particles& p, const ContactLaw& law) const;
  /// Largest overlap of a disc with a wall as a ratio of its radius; `particle` gets the disc.
  double largest_overlap_ratio(const Particles& p, std::int64_t& particle) const;
  /// Checkpoint (core/dem_state.cpp): the bodies' motion and forces and the listed pairs.
  void save_state(state::StateArchive& a) const;
  void load_state(const state::StateArchive& a, std::size_t particles);

 private:
  template <bool kDashpots, bool kRolling>
  void compute_impl(const Particles& p, const ContactLaw& law, double dt, ForceView out,
                    ContactDissipation& sums);
  /// Overlap of listed pair k (disc radius minus its distance to the moved segment) [m].
  double pair_overlap(const Particles& p, std::size_t k) const;

  std::vector<WallBody> bodies_;
  std::vector<Segment> segments_;
  std::vector<double> offset_at_rebuild_;  // 2 per body
  std::vector<std::uint32_t> particle_, segment_;
  std::vector<double> shear_force_;
  std::vector<double> rolling_moment_;  ///< rolling spring's moment on the disc [N m/m]
  /// The dashpots' forces of the last evaluation (the F^n end of their trapezoid; 0 without).
  std::vector<PairDashpots> dashpot_;
  std::vector<std::uint64_t> old_keys_;  // rebuild scratch
  std::vector<double> old_shear_, old_rolling_;
  std::vector<PairDashpots> old_dashpot_;
};

}  // namespace rockcut::dem
