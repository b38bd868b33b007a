// Particle sets and model drivers for the SP tests: lattices, jittered lattices, the committed
// random packing (cases/verification/packing_30mm.txt, a 30 mm window of a dense random packing of
// discs with radii in [0.2, 0.4] mm), and a loop that deforms particles uniformly as
// dem.prescribed_motion does.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <span>

#include "models/explicit_model.hpp"
#include "models/implicit_model.hpp"

namespace rockcut::fluid::test {

struct Particles {
  std::vector<double> position;  ///< interleaved x, y [m]
  std::vector<double> radius;    ///< [m]
  std::size_t size() const { return radius.size(); }
  double x(std::size_t i) const { return position[2 * i]; }
  double y(std::size_t i) const { return position[2 * i + 1]; }
};

/// nx * ny discs of radius `radius_m` at spacing `spacing_m` from the origin (0, 0).
Particles lattice(int nx, int ny, double spacing_m, double radius_m);
/// The lattice with every centre moved by up to +-jitter * spacing in x and y (seeded).
Particles jittered(int nx, int ny, double spacing_m, double jitter, std::uint64_t seed);
/// cases/verification/packing_30mm.txt (2563 discs, centred on the origin, 30 mm wide).
Particles random_packing();

/// Distance of particle i's centre from the nearest side of the particles' bounding box.
std::vector<double> distance_to_box(const Particles& p);

/// Table 1 parameters with smoothing length h and the given sealed sides (left, right, bottom,
/// top).
sp::SpParams table1(double h_m, std::array<bool, 4> sealed = {false, false, false, false});

/// The Laplacian of the given form: eq. 20 (sp/operators.hpp) or the consistent one
/// (sp/consistent_laplacian.hpp).
void apply_laplacian(sp::LaplacianForm form, const sp::Geometry& geo, std::span<const double> a,
                     std::span<double> lap);
/// The volume in which that Laplacian is symmetric (and conserved): V_i, or V_i / s_i.
double laplacian_weight(sp::LaplacianForm form, const sp::Geometry& geo, std::size_t i);

/// A model initialised on the particles: its geometry and neighbour lists are the operators' input.
struct Initialised {
  Initialised(const Particles& p, double h_m, unsigned volume_iterations = 3)
      : particles(p), model(with_iterations(table1(h_m), volume_iterations)) {
    model.initialise({p.radius, p.position});
  }
  const sp::NeighbourList& list() const { return model.neighbour_list(); }
  const sp::Geometry& geo() const { return model.geometry(); }
  static sp::SpParams with_iterations(sp::SpParams s, unsigned k) {
    s.volume_iterations = k;
    return s;
  }
  Particles particles;
  sp::ExplicitModel model;
};

/// Drives a model with a uniform deformation v = diag(exx, eyy) (x - origin), as
/// dem.prescribed_motion does, sending positions and displacements.
class Driver {
 public:
  Driver(FluidModel& model, const Particles& p);
  /// One fluid step of dt at the given strain rates [1/s].
  void step(double dt_s, double exx_per_s = 0.0, double eyy_per_s = 0.0);
  const std::vector<double>& force() const { return force_; }
  const std::vector<double>& position() const { return x_; }
  double time_s() const { return t_; }

 private:
  FluidModel& model_;
  std::vector<double> x_, d_, v_, force_;
  double t_ = 0.0;
};

/// Compresses the driven packing uniformly, `steps` steps of dt at `rate` per axis [1/s], and
/// returns the undrained pressure that gives: p_hydro - alpha M sum d(eps_v), with
/// d(eps_v) = 2 a / (1 + a) and a = rate dt, the CSPM divergence of the step's displacement on
/// the new positions (exact for this linear field).
double compress_undrained(Driver& drive, const sp::SpParams& params, double rate_per_s,
                          double dt_s, int steps);

}  // namespace rockcut::fluid::test
