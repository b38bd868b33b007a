#include "core/dem_system.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <omp.h>

#include "core/local_damping.hpp"
#include "core/verlet_half_step.hpp"

namespace rockcut::dem {

namespace {
// Default Verlet skin as a fraction of the smallest radius: large enough that a bonded specimen
// rebuilds rarely, small enough that the candidate list stays short.
constexpr double kDefaultSkinFraction = 0.2;

int thread_id() { return omp_get_thread_num(); }

// The static share [begin, end) of `count` items for thread t of `threads`.
std::pair<std::size_t, std::size_t> share(std::size_t count, int t, int threads) {
  const std::size_t per = count / threads, extra = count % threads;
  const std::size_t begin = t * per + std::min<std::size_t>(t, extra);
  return {begin, begin + per + (static_cast<std::size_t>(t) < extra ? 1 : 0)};
}
}  // namespace

DemSystem::DemSystem(Particles particles, const DemSettings& settings, BondSet bonds, WallSet walls)
    : particles_(std::move(particles)),
      settings_(settings),
      bonds_(std::move(bonds)),
      walls_(std::move(walls)) {
  if (settings_.threads < 1) settings_.threads = 1;
  has_pairs_ = settings_.contact.normal_stiffness_pa > 0 || bonds_.size() > 0 || !walls_.empty();
  has_body_forces_ = settings_.gravity_x_m_s2 != 0.0 || settings_.gravity_y_m_s2 != 0.0;
  if (settings_.skin_m <= 0) {
    double r_min = 1e300;
    for (double r : particles_.radius) r_min = std::min(r_min, r);
    settings_.skin_m = particles_.size() ? kDefaultSkinFraction * r_min : 0.0;
  }
  if (has_pairs_) rebuild_neighbours();
  compute_internal_forces();
  finish_forces(0.0);
}

void DemSystem::rebuild_neighbours() {
  const int threads = settings_.threads;
#pragma omp parallel num_threads(threads) if (threads > 1)
  rebuild_neighbours_in_team(threads > 1 ? thread_id() : 0, threads);
}

void DemSystem::rebuild_neighbours_in_team(int t, int threads) {
  const bool contacts = settings_.contact.normal_stiffness_pa > 0;
#pragma omp single
  {
    bonds_.refresh_partners(particles_.size());
    if (contacts) contacts_.begin_rebuild(particles_, settings_.skin_m, grid_, threads);
  }  // implied barrier: the grid and the history are ready
  if (contacts) contacts_.search(particles_, bonds_, settings_.skin_m, grid_, t, threads);
#pragma omp barrier
#pragma omp single
  {
    if (contacts) contacts_.size_join();
    if (!walls_.empty()) walls_.rebuild(particles_, settings_.skin_m);
    max_drift_m_ = 0.0;
    ++rebuilds_;
    buffers_.resize(threads, particles_.size());
  }  // implied barrier: the list sized
  if (contacts) contacts_.join(t);
#pragma omp barrier
  force_window(t, threads);  // reads the joined list
#pragma omp barrier
}

void DemSystem::update_force_windows() {
  const int threads = settings_.threads;
  buffers_.resize(threads, particles_.size());
  for (int t = 0; t < threads; ++t) force_window(t, threads);
}

void DemSystem::force_window(int t, int threads) {
  if (threads < 2) return;
  const std::size_t n = particles_.size();
  const auto [p0, p1] = share(n, t, threads);
  std::size_t lo = n, hi = 0;
  auto note = [&, p0 = p0, p1 = p1](std::uint32_t i) {  // clang 14 captures no structured binding
    if (i < p0 || i >= p1) {
      lo = std::min<std::size_t>(lo, i);
      hi = std::max<std::size_t>(hi, std::size_t(i) + 1);
    }
  };
  // The same shares as pair_forces().
  const auto [b0, b1] = share(bonds_.size(), t, threads);
  for (std::size_t k = b0; k < b1; ++k) {
    note(bonds_.first(k));
    note(bonds_.second(k));
  }
  if (settings_.contact.normal_stiffness_pa > 0) {
    const auto [c0, c1] = share(contacts_.size(), t, threads);
    for (std::size_t k = c0; k < c1; ++k) {
      note(contacts_.first(k));
      note(contacts_.second(k));
    }
  }
  if (t == 0) {
    for (std::uint32_t i : walls_.listed_particles()) note(i);
  }
  buffers_.set_window(t, lo, hi);
}

ThreadSums DemSystem::total_sums() const {
  // A fixed order of addition: the same bits for the same thread count.
  ThreadSums total;
  for (const ThreadSums& s : sums_) {
    total.vmax2 = std::max(total.vmax2, s.vmax2);
    total.external_work_j += s.external_work_j;
    total.gravity_work_j += s.gravity_work_j;
    total.damping_j += s.damping_j;
    total.lag_correction_j += s.lag_correction_j;
    total.pairs.friction_j += s.pairs.friction_j;
    total.pairs.viscous_j += s.pairs.viscous_j;
    total.bond_viscous_j += s.bond_viscous_j;
    total.bond_softening_j += s.bond_softening_j;
    total.pairs.rolling_j += s.pairs.rolling_j;
    total.any_broken = total.any_broken || s.any_broken;
  }
  return total;
}

void DemSystem::book(const ThreadSums& s) {
  ledger_.external_work_j += s.external_work_j;
  ledger_.gravity_work_j += s.gravity_work_j;
  ledger_.damping_j += s.damping_j;
  ledger_.lag_correction_j += s.lag_correction_j;
  ledger_.friction_j += s.pairs.friction_j;
  ledger_.viscous_damping_j += s.pairs.viscous_j;
  ledger_.viscous_damping_bonds_j += s.bond_viscous_j;
  ledger_.broken_bond_j += s.bond_softening_j;
  ledger_.bond_softening_j += s.bond_softening_j;
  ledger_.rolling_j += s.pairs.rolling_j;
}

void DemSystem::start_sums(int threads) {
  sums_.resize(static_cast<std::size_t>(threads));  // allocates only when the count grows
  for (ThreadSums& s : sums_) s = ThreadSums{};
}

void DemSystem::drift_range(std::size_t begin, std::size_t end, double dt, bool kick,
                            bool reset_forces, ThreadSums& sums) {
  double* x = particles_.position.data();
  double* v = particles_.velocity.data();
  double* w = particles_.angular_velocity.data();
  double* f = particles_.force.data();
  double* q = particles_.torque.data();
  const double* inv_i = particles_.inv_inertia.data();
  const double h = 0.5 * dt;
  double* fe = particles_.external_force.data();
  const double* inv_m = particles_.inv_mass.data();
  const double* fd = damping_force_.empty() ? nullptr : damping_force_.data();
  // The extrapolated external force moves on to t^{n+1} after its F^n half of the work.
  const double* fr = extrapolation_.rate.empty() ? nullptr : extrapolation_.rate.data();
  // The grain's own fluid stiffness (core/fluid_self_stiffness.hpp): -K_ii v dt, likewise.
  const double* fk = self_stiffness_.k_pa.empty() ? nullptr : self_stiffness_.k_pa.data();
  // The lag's dashpot (core/fluid_force_passivity.hpp): its F^n half, and the grain's work and S.
  const bool passive = passivity_.active();
  double* pw = passivity_.work_j.data();
  double* ps = passivity_.speed2_dt.data();
  const double* pf = passivity_.force.data();
  const double gx = settings_.gravity_x_m_s2, gy = settings_.gravity_y_m_s2;
  const bool body = has_body_forces_;
  const bool weighed = has_gravity();
  double vmax2 = 0.0, work = 0.0, gravity = 0.0, damping = 0.0, correction = 0.0;
  // Verlet moves x by v^{n+1/2} dt under the mean of F^n and F^{n+1}: each force's work over the
  // drift is the trapezoid 1/2 (F^n + F^{n+1}) . dx. The F^n halves are added here, the F^{n+1}
  // halves in finish_range().
  for (std::size_t i = begin; i < end; ++i) {
    if (kick) {  // eq. 6, fused with the drift: one pass over the particles
      v[2 * i] = half_kick(v[2 * i], h, f[2 * i], inv_m[i]);
      v[2 * i + 1] = half_kick(v[2 * i + 1], h, f[2 * i + 1], inv_m[i]);
      w[i] = half_kick(w[i], h, q[i], inv_i[i]);
    }
    const double vx = v[2 * i], vy = v[2 * i + 1];
    x[2 * i] = drift(x[2 * i], dt, vx);  // eq. 5
    x[2 * i + 1] = drift(x[2 * i + 1], dt, vy);
    vmax2 = std::max(vmax2, vx * vx + vy * vy);
    if (body) {
      work += (fe[2 * i] * vx + fe[2 * i + 1] * vy) * 0.5 * dt;
      if (weighed) gravity += (gx * vx + gy * vy) / inv_m[i] * 0.5 * dt;
    }
    if (passive) {
      pw[i] += ((fe[2 * i] + pf[2 * i]) * vx + (fe[2 * i + 1] + pf[2 * i + 1]) * vy) * 0.5 * dt;
      ps[i] += (vx * vx + vy * vy) * dt;
      correction -= (pf[2 * i] * vx + pf[2 * i + 1] * vy) * 0.5 * dt;
    }
    if (fr) {
      fe[2 * i] += fr[2 * i] * dt;
      fe[2 * i + 1] += fr[2 * i + 1] * dt;
    }
    if (fk) {
      fe[2 * i] -= (fk[3 * i] * vx + fk[3 * i + 1] * vy) * dt;
      fe[2 * i + 1] -= (fk[3 * i + 1] * vx + fk[3 * i + 2] * vy) * dt;
    }
    if (fd) damping -= (fd[3 * i] * vx + fd[3 * i + 1] * vy + fd[3 * i + 2] * w[i]) * 0.5 * dt;
    if (reset_forces) {  // F^n has been used: start F^{n+1} from gravity in the same pass
      f[2 * i] = weighed ? gx / inv_m[i] : 0.0;
      f[2 * i + 1] = weighed ? gy / inv_m[i] : 0.0;
      q[i] = 0.0;
    }
  }
  sums.vmax2 = std::max(sums.vmax2, vmax2);
  sums.external_work_j += work;
  sums.gravity_work_j += gravity;
  sums.damping_j += damping;
  sums.lag_correction_j += correction;
}

void DemSystem::reset_forces_range(std::size_t begin, std::size_t end) {
  double* f = particles_.force.data();
  double* q = particles_.torque.data();
  const double* inv_m = particles_.inv_mass.data();
  const double gx = settings_.gravity_x_m_s2, gy = settings_.gravity_y_m_s2;
  const bool weighed = has_gravity();
  for (std::size_t i = begin; i < end; ++i) {
    f[2 * i] = weighed ? gx / inv_m[i] : 0.0;
    f[2 * i + 1] = weighed ? gy / inv_m[i] : 0.0;
    q[i] = 0.0;
  }
}

void DemSystem::pair_forces(int t, int threads, double dt, ThreadSums& sums) {
  const auto [p0, p1] = share(particles_.size(), t, threads);
  const ForceView out = buffers_.view(t, particles_, p0, p1);
  const auto [b0, b1] = share(bonds_.size(), t, threads);
  bonds_.compute(particles_, dt, b0, b1, out, sums.any_broken,
                 settings_.contact.normal_stiffness_pa, settings_.contact.damping_ratio,
                 sums.pairs.viscous_j, sums.bond_softening_j);
  // The bonds add first to a sum the step started at zero: what it holds now is theirs. The
  // contacts add to the same sum, so the total keeps its order of additions (and its bits).
  sums.bond_viscous_j = sums.pairs.viscous_j;
  if (t == 0) phases_.lap(kBonds);
  if (settings_.contact.normal_stiffness_pa > 0) {
    const auto [c0, c1] = share(contacts_.size(), t, threads);
    contacts_.compute(particles_, settings_.contact, dt, c0, c1, out, sums.pairs);
  }
  if (t == 0) phases_.lap(kContacts);
  // Thread 0 adds the walls, through its view like its pairs; the ledger is written by this
  // thread alone inside the region (in place, so its sums keep their order of additions).
  if (t == 0 && !walls_.empty()) {
    ContactDissipation walls{ledger_.friction_j, ledger_.viscous_damping_j, ledger_.rolling_j};
    walls_.compute(particles_, settings_.contact, dt, out, ledger_.boundary_work_j, walls);
    ledger_.friction_j = walls.friction_j;
    ledger_.viscous_damping_j = walls.viscous_j;
    ledger_.rolling_j = walls.rolling_j;
    phases_.lap(kWalls);
  }
}

void DemSystem::finish_range(std::size_t begin, std::size_t end, double kick_dt, ThreadSums& sums) {
  double* f = particles_.force.data();
  double* q = particles_.torque.data();
  const double* fe = particles_.external_force.data();
  double* v = particles_.velocity.data();
  double* w = particles_.angular_velocity.data();
  const double* inv_m = particles_.inv_mass.data();
  const double* inv_i = particles_.inv_inertia.data();
  const double kick = 0.5 * kick_dt;
  const double gx = settings_.gravity_x_m_s2, gy = settings_.gravity_y_m_s2;
  const double alpha = settings_.local_damping;
  double* fd = damping_force_.data();
  const double h = 0.5 * dt_last_;  // the F^{n+1} half of the trapezoid, see drift_range()
  const bool body = has_body_forces_;
  const bool weighed = has_gravity();
  const bool passive = passivity_.active();
  double* pw = passivity_.work_j.data();
  const double* pc = passivity_.coefficient.data();
  double* pf = passivity_.force.data();
  double damping = 0.0, work = 0.0, gravity = 0.0, correction = 0.0;
  for (std::size_t i = begin; i < end; ++i) {
    double fx = f[2 * i] + fe[2 * i], fy = f[2 * i + 1] + fe[2 * i + 1], tq = q[i];
    const double vx = v[2 * i], vy = v[2 * i + 1];
    if (body) {
      work += (fe[2 * i] * vx + fe[2 * i + 1] * vy) * h;
      if (weighed) gravity += (gx * vx + gy * vy) / inv_m[i] * h;
    }
    if (passive) {  // the lag's dashpot on v^{n+1/2}, and its F^{n+1} half
      const double cx = -pc[i] * vx, cy = -pc[i] * vy;
      pf[2 * i] = cx;
      pf[2 * i + 1] = cy;
      pw[i] += ((fe[2 * i] + cx) * vx + (fe[2 * i + 1] + cy) * vy) * h;
      correction -= (cx * vx + cy * vy) * h;
      fx += cx;
      fy += cy;
    }
    if (alpha > 0) {
      // Eq. 10 per degree of freedom: F_d = -alpha |F| sign(v), with v = v^{n+1/2}.
      const double dx = local_damping_force(alpha, fx, vx);
      const double dy = local_damping_force(alpha, fy, vy);
      const double dq = local_damping_force(alpha, tq, w[i]);
      damping -= (dx * vx + dy * vy + dq * w[i]) * h;
      fd[3 * i] = dx;
      fd[3 * i + 1] = dy;
      fd[3 * i + 2] = dq;
      fx += dx;
      fy += dy;
      tq += dq;
    }
    f[2 * i] = fx;
    f[2 * i + 1] = fy;
    q[i] = tq;
    if (kick_dt > 0) {  // eq. 8, fused: v^{n+1} = v^{n+1/2} + a^{n+1} dt/2
      v[2 * i] = half_kick(v[2 * i], kick, fx, inv_m[i]);
      v[2 * i + 1] = half_kick(v[2 * i + 1], kick, fy, inv_m[i]);
      w[i] = half_kick(w[i], kick, tq, inv_i[i]);
    }
  }
  sums.damping_j += damping;
  sums.lag_correction_j += correction;
  sums.external_work_j += work;
  sums.gravity_work_j += gravity;
}

void DemSystem::kick_drift(double dt, bool kick) {
  const std::size_t n = particles_.size();
  const int threads = settings_.threads;
  phases_.start();
  start_sums(threads);
#pragma omp parallel num_threads(threads) if (threads > 1)
  {
    const int t = threads > 1 ? thread_id() : 0;
    const auto [p0, p1] = share(n, t, threads);
    drift_range(p0, p1, dt, kick, /*reset_forces=*/false, sums_[t]);
  }
  const ThreadSums s = total_sums();
  book(s);
  // A bound on how far any disc moved since the rebuild: sum of the largest step lengths.
  max_drift_m_ += std::sqrt(s.vmax2) * dt;
  walls_.move(dt);
  phases_.lap(kDrift);
}

void DemSystem::set_prescribed_velocity(double t) {
  const PrescribedMotion& m = *settings_.prescribed_motion;
  const bool active = t >= m.start_time_s && t < m.end_time_s;
  const double exx = active ? m.strain_rate_xx_per_s : 0.0;
  const double eyy = active ? m.strain_rate_yy_per_s : 0.0;
  const std::size_t n = particles_.size();
  double* v = particles_.velocity.data();
  const double* x = particles_.position.data();
  for (std::size_t i = 0; i < n; ++i) {
    v[2 * i] = exx * (x[2 * i] - m.origin_x_m);
    v[2 * i + 1] = eyy * (x[2 * i + 1] - m.origin_y_m);
  }
}

void DemSystem::compute_internal_forces() {
  internal_forces_current_ = true;
  const std::size_t n = particles_.size();
  phases_.start();
  if (has_pairs_ && max_drift_m_ + walls_.displacement_since_rebuild() > 0.5 * settings_.skin_m) {
    rebuild_neighbours();
    phases_.lap(kNeighbours);
  }
  const int threads = has_pairs_ ? settings_.threads : 1;
  start_sums(threads);
  const double dt = dt_last_;
  // One parallel region per force evaluation: reset, pair loops, reduction, with barriers between.
#pragma omp parallel num_threads(threads) if (threads > 1)
  {
    const int t = threads > 1 ? thread_id() : 0;
    const auto [p0, p1] = share(n, t, threads);
    reset_forces_range(p0, p1);
    if (has_pairs_) {
#pragma omp barrier
      if (t == 0) phases_.lap(kDrift);
      pair_forces(t, threads, dt, sums_[t]);
#pragma omp barrier
      if (t == 0) phases_.lap(kBarrier);
      buffers_.reduce(particles_, t, p0, p1);
    }
  }
  if (!has_pairs_) return;
  const ThreadSums s = total_sums();
  book(s);
  phases_.lap(kFinish);
  if (s.any_broken) remove_broken_bonds();
  if (!clamped_.empty()) hold_clamped_groups();
  phases_.lap(kBreaks);
}

void DemSystem::remove_broken_bonds() {
  freed_pairs_.clear();
  bonds_.remove_broken(particles_, time_s_, breaks_, freed_pairs_, ledger_);
  if (settings_.contact.normal_stiffness_pa > 0) contacts_.add_pairs(freed_pairs_);
  update_force_windows();  // the shares of the lists have moved
}

std::size_t DemSystem::add_clamped_group(std::vector<std::uint32_t> particles,
                                         double velocity_y_m_s, bool fixed) {
  ClampedGroup g;
  g.particles = std::move(particles);
  g.velocity_y_m_s = velocity_y_m_s;
  g.fixed = fixed;
  clamped_.push_back(std::move(g));
  // The present forces become the first reaction; no step has been taken with it, so no work.
  const double boundary_work = ledger_.boundary_work_j;
  hold_clamped_groups();
  ledger_.boundary_work_j = boundary_work;
  reset_clamped_velocities();
  return clamped_.size() - 1;
}

void DemSystem::hold_clamped_groups() {
  double* f = particles_.force.data();
  double* q = particles_.torque.data();
  for (ClampedGroup& g : clamped_) {
    double reaction = 0.0;
    for (std::uint32_t i : g.particles) {
      reaction += f[2 * i + 1];
      f[2 * i + 1] = 0.0;
      if (g.fixed) {
        f[2 * i] = 0.0;
        q[i] = 0.0;
      }
    }
    // The clamp pushes each disc with -f_y while it moves v dt: trapezoid over the step.
    ledger_.boundary_work_j -= 0.5 * (g.reaction_y_n_per_m + reaction) * g.velocity_y_m_s * dt_last_;
    g.reaction_y_n_per_m = reaction;
  }
}

void DemSystem::reset_clamped_velocities() {
  double* v = particles_.velocity.data();
  double* f = particles_.force.data();
  double* w = particles_.angular_velocity.data();
  double* q = particles_.torque.data();
  for (const ClampedGroup& g : clamped_) {
    for (std::uint32_t i : g.particles) {
      v[2 * i + 1] = g.velocity_y_m_s;
      f[2 * i + 1] = 0.0;  // so the next half kick leaves v_y alone too
      if (g.fixed) {
        v[2 * i] = 0.0;
        w[i] = 0.0;
        f[2 * i] = 0.0;
        q[i] = 0.0;
      }
    }
  }
}

void DemSystem::finish_forces(double kick_dt) {
  const std::size_t n = particles_.size();
  const int threads = settings_.threads;
  if (settings_.local_damping > 0) damping_force_.resize(3 * n);
  phases_.start();
  start_sums(threads);
#pragma omp parallel num_threads(threads) if (threads > 1)
  {
    const int t = threads > 1 ? thread_id() : 0;
    const auto [p0, p1] = share(n, t, threads);
    finish_range(p0, p1, kick_dt, sums_[t]);
  }
  book(total_sums());
  if (!clamped_.empty()) reset_clamped_velocities();
  phases_.lap(kFinish);
}

void DemSystem::step(double dt) {
  if (settings_.prescribed_motion || !has_pairs_) {
    begin_step(dt);
    compute_internal_forces();
    finish_forces(settings_.prescribed_motion ? 0.0 : dt);
    in_split_step_ = false;
    if (!servos_.empty()) steer_servo_walls();
    return;
  }
  if (in_split_step_) throw std::logic_error("step inside a split step");
  full_step(dt);
  if (!servos_.empty()) steer_servo_walls();
}

void DemSystem::steer_servo_walls() {
  const std::vector<WallBody>& bodies = walls_.bodies();
  for (const WallServo& s : servos_) {
    const double length_m = s.loaded_length_m(bodies[s.top].offset_y, bodies[s.bottom].offset_y);
    walls_.set_velocity_x(s.body, s.velocity_x(bodies[s.body].force_x, length_m, dt_last_));
  }
}

void DemSystem::full_step(double dt) {
  // The same arithmetic as begin_step + compute_internal_forces + finish_forces, in one parallel
  // region: each fork, join or barrier wakes a sleeping thread (OMP_WAIT_POLICY=PASSIVE), which
  // costs tens of microseconds here, so the step has three synchronisation points instead of
  // eight. The particle ranges are the same in every phase, so drift, reduction and finish need
  // no barrier between them.
  const std::size_t n = particles_.size();
  const int threads = settings_.threads;
  phases_.start();
  dt_last_ = dt;
  time_s_ += dt;
  ++steps_;
  walls_.move(dt);  // the walls do not depend on the discs: moved before the region
  if (settings_.local_damping > 0) damping_force_.resize(3 * n);
  start_sums(threads);
  // Read before the region: a rebuild inside it resets both.
  const double drift_before_m = max_drift_m_;
  const double walls_moved_m = walls_.displacement_since_rebuild();
  bool rebuilt = false;
#pragma omp parallel num_threads(threads) if (threads > 1)
  {
    const int t = threads > 1 ? thread_id() : 0;
    const auto [p0, p1] = share(n, t, threads);
    drift_range(p0, p1, dt, /*kick=*/true, /*reset_forces=*/true, sums_[t]);
#pragma omp barrier
    if (t == 0) phases_.lap(kDrift);
    // Every thread reaches the same decision from the same numbers.
    double v2 = 0.0;
    for (const ThreadSums& s : sums_) v2 = std::max(v2, s.vmax2);
    // The split step's test with its order of additions (kick_drift, compute_internal_forces).
    const double drift_m = drift_before_m + std::sqrt(v2) * dt;
    if (has_pairs_ && drift_m + walls_moved_m > 0.5 * settings_.skin_m) {
      rebuild_neighbours_in_team(t, threads);  // ends with a barrier: the lists are ready
      if (t == 0) {
        rebuilt = true;
        phases_.lap(kNeighbours);
      }
    }
    pair_forces(t, threads, dt, sums_[t]);
#pragma omp barrier
    if (t == 0) phases_.lap(kBarrier);
    buffers_.reduce(particles_, t, p0, p1);
    if (!clamped_.empty()) {
#pragma omp barrier
#pragma omp single
      hold_clamped_groups();
    }
    finish_range(p0, p1, dt, sums_[t]);
  }
  const ThreadSums s = total_sums();
  book(s);
  if (rebuilt) {
    max_drift_m_ = 0.0;
  } else {
    max_drift_m_ += std::sqrt(s.vmax2) * dt;
  }
  phases_.lap(kFinish);
  if (s.any_broken) remove_broken_bonds();
  if (!clamped_.empty()) reset_clamped_velocities();
  phases_.lap(kBreaks);
  internal_forces_current_ = true;
}

void DemSystem::begin_step(double dt) {
  if (in_split_step_) throw std::logic_error("begin_step inside a split step");
  dt_last_ = dt;
  if (settings_.prescribed_motion) set_prescribed_velocity(time_s_ + 0.5 * dt);  // v^{n+1/2}
  kick_drift(dt, !settings_.prescribed_motion);
  time_s_ += dt;
  ++steps_;
  internal_forces_current_ = false;
  in_split_step_ = true;
}

void DemSystem::finish_step(double dt, std::span<const double> external,
                            std::span<const double> self_stiffness_pa) {
  if (!in_split_step_) throw std::logic_error("finish_step without begin_step");
  check_self_stiffness(self_stiffness_pa);
  hold_external_force(external);  // checks the size first: a refused force changes nothing
  extrapolation_.take(external, time_s_);
  self_stiffness_.take(self_stiffness_pa, particles_.position, time_s_, extrapolation_.rate);
  has_body_forces_ = has_body_forces_ || self_stiffness_.stiffens();  // its work is booked
  if (!internal_forces_current_) compute_internal_forces();
  finish_forces(settings_.prescribed_motion ? 0.0 : dt);
  passivity_.exchange(particles_.position, particles_.external_force, particles_.inv_mass, dt,
                      steps_);
  in_split_step_ = false;
  if (!servos_.empty()) steer_servo_walls();
}

double DemSystem::kinetic_energy() const {
  const std::size_t n = particles_.size();
  double e = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double vx = particles_.velocity[2 * i];
    const double vy = particles_.velocity[2 * i + 1];
    const double w = particles_.angular_velocity[i];
    e += 0.5 * (vx * vx + vy * vy) / particles_.inv_mass[i] +
         0.5 * w * w / particles_.inv_inertia[i];
  }
  return e;
}

double DemSystem::strain_energy() const {
  return bonds_.strain_energy(particles_) + contacts_.strain_energy(particles_, settings_.contact) +
         walls_.strain_energy(particles_, settings_.contact);
}

}  // namespace rockcut::dem
