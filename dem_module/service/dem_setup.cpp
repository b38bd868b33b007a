#include "service/dem_setup.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>

#include "core/lattice.hpp"
#include "core/packing_file.hpp"
#include "core/specimen_generator.hpp"
#include "core/viscous_damping.hpp"
#include "scene/tool_geometry.hpp"

namespace rockcut::dem {

namespace {

std::string num(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", v);
  return b;
}

Particles from_packing(const Packing& packing, double density) {
  Particles p;
  for (std::size_t i = 0; i < packing.x_m.size(); ++i) {
    p.add(packing.x_m[i], packing.y_m[i], packing.radius_m[i], density);
    if (packing.has_motion()) {
      p.velocity[2 * i] = packing.vx_m_s[i];
      p.velocity[2 * i + 1] = packing.vy_m_s[i];
      p.angular_velocity[i] = packing.omega_rad_s[i];
    }
  }
  return p;
}

Particles specimen_particles(const rockcut::Specimen& s, double density, std::string& report) {
  if (s.radius_min_m() > s.radius_max_m()) {
    throw std::invalid_argument("dem.specimen.radius_min_m = " + num(s.radius_min_m()) +
                                " is larger than dem.specimen.radius_max_m = " +
                                num(s.radius_max_m()));
  }
  PackingSpec spec;
  spec.radius_min_m = s.radius_min_m();
  spec.radius_max_m = s.radius_max_m();
  spec.seed = s.seed();
  if (s.shape() == "circle") {
    if (!s.has_diameter_m()) {
      throw std::invalid_argument("dem.specimen.diameter_m is required for shape \"circle\"");
    }
    spec.region.shape = PackingRegion::Shape::circle;
    spec.region.radius_m = 0.5 * s.diameter_m();
    spec.region.center_x_m = s.origin_m().x() + spec.region.radius_m;
    spec.region.center_y_m = s.origin_m().y() + spec.region.radius_m;
  } else {
    if (!s.has_width_m() || !s.has_height_m()) {
      throw std::invalid_argument(
          "dem.specimen.width_m and dem.specimen.height_m are required for shape \"rectangle\"");
    }
    spec.region.shape = PackingRegion::Shape::rectangle;
    spec.region.width_m = s.width_m();
    spec.region.height_m = s.height_m();
    spec.region.center_x_m = s.origin_m().x() + 0.5 * s.width_m();
    spec.region.center_y_m = s.origin_m().y() + 0.5 * s.height_m();
  }
  const Packing packing = generate_packing(spec);
  const PackingStats stats = packing_stats(packing, spec.region, 1e-7);
  char line[200];
  std::snprintf(line, sizeof line,
                "specimen: %zu discs, porosity %.4f, mean coordination %.3f (gap <= 1e-7 m)",
                packing.x_m.size(), stats.porosity, stats.mean_coordination);
  report = line;
  return from_packing(packing, density);
}

Particles particles_from_scene(const rockcut::Dem& dem, std::string& report) {
  switch (dem.particles_case()) {
    case rockcut::Dem::kLattice: {
      const rockcut::Lattice& l = dem.lattice();
      LatticeSpec spec;
      spec.nx = l.nx();
      spec.ny = l.ny();
      spec.spacing_m = l.spacing_m();
      spec.radius_m = l.radius_m();
      spec.origin_x_m = l.origin_m().x();
      spec.origin_y_m = l.origin_m().y();
      spec.density_kg_m3 = dem.density_kg_m3();
      spec.hexagonal = l.arrangement() == "hexagonal";
      return make_lattice(spec);
    }
    case rockcut::Dem::kPackingFile:
      // The coupler makes a relative path absolute (relative to the scene file) before Init.
      // The discs are numbered in cell order, as the generator numbers them (in_cell_order).
      return from_packing(in_cell_order(read_packing_file(dem.packing_file().path())),
                          dem.density_kg_m3());
    case rockcut::Dem::kSpecimen:
      return specimen_particles(dem.specimen(), dem.density_kg_m3(), report);
    case rockcut::Dem::PARTICLES_NOT_SET:
      break;
  }
  throw std::invalid_argument(
      "dem: the scene gives no particles (set dem.lattice, dem.specimen or dem.packing_file)");
}

// The box around the discs' edges and the largest radius.
struct DiscExtent {
  double left = 1e300, right = -1e300, top = -1e300, bottom = 1e300, r_max = 0.0;
};
DiscExtent disc_extent(const Particles& p) {
  DiscExtent e;
  for (std::size_t i = 0; i < p.size(); ++i) {
    e.left = std::min(e.left, p.position[2 * i] - p.radius[i]);
    e.right = std::max(e.right, p.position[2 * i] + p.radius[i]);
    e.top = std::max(e.top, p.position[2 * i + 1] + p.radius[i]);
    e.bottom = std::min(e.bottom, p.position[2 * i + 1] - p.radius[i]);
    e.r_max = std::max(e.r_max, p.radius[i]);
  }
  return e;
}

// Places the chisel at the specimen's upper left: tip `cutting_depth_m` below the top, a gap to
// the left of the leftmost disc.
ToolPlacement add_tool(const rockcut::Tool& t, const Particles& p, WallSet& walls) {
  const DiscExtent extent = disc_extent(p);
  const double left = extent.left, top = extent.top, bottom = extent.bottom;
  if (t.cutting_depth_m() >= top - bottom) {
    throw std::invalid_argument("dem.tool.cutting_depth_m = " + num(t.cutting_depth_m()) +
                                " puts the tool tip outside the specimen (height " +
                                num(top - bottom) + " m)");
  }
  ToolPlacement tool;
  tool.present = true;
  tool.tip_x0_m = left - t.start_gap_m();
  tool.tip_y_m = top - t.cutting_depth_m();
  tool.velocity_m_s = t.velocity_m_s();
  tool.width_m = t.width_m();
  tool.specimen_left_m = left;
  tool.steady_after_m = rockcut::scene::tool_steady_after_m(t);
  const double deg = std::numbers::pi / 180.0;
  const double face = rockcut::scene::tool_face_length_m(t);
  const double a = t.cutting_angle_deg() * deg, b = t.clearance_angle_deg() * deg;
  // Triangle: tip, top of the cutting face (leaning back at the cutting angle), end of the
  // clearance face (rising back at the clearance angle).
  const std::vector<double> vertices = {
      tool.tip_x0_m, tool.tip_y_m,
      tool.tip_x0_m - face * std::cos(a), tool.tip_y_m + face * std::sin(a),
      tool.tip_x0_m - face * std::cos(b), tool.tip_y_m + face * std::sin(b)};
  tool.body = walls.add_body("tool", vertices, true, t.velocity_m_s(), 0.0);
  return tool;
}

// Brazilian loading arcs (loading_test.loading_arc_deg): the discs of the rim layer, two largest
// radii (r_max) deep, whose centres lie within half the arc of the vertical diameter, above the
// disc's centroid (top) and below it (bottom). The rim is the circle about the centroid through
// the outermost disc edges.
void select_loading_arcs(double arc_deg, double r_max, const Particles& p,
                         std::vector<std::uint32_t>& top_arc, std::vector<std::uint32_t>& bottom_arc) {
  double x_c = 0.0, y_c = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    x_c += p.position[2 * i];
    y_c += p.position[2 * i + 1];
  }
  x_c /= static_cast<double>(p.size());
  y_c /= static_cast<double>(p.size());
  double rim_m = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    rim_m = std::max(rim_m, std::hypot(p.position[2 * i] - x_c, p.position[2 * i + 1] - y_c) +
                                p.radius[i]);
  }
  const double half_arc_rad = 0.5 * arc_deg * std::acos(-1.0) / 180.0;
  for (std::uint32_t i = 0; i < p.size(); ++i) {
    const double dx = p.position[2 * i] - x_c, dy = p.position[2 * i + 1] - y_c;
    if (std::hypot(dx, dy) + p.radius[i] < rim_m - 2 * r_max) continue;
    if (std::atan2(std::abs(dx), std::abs(dy)) > half_arc_rad) continue;
    (dy > 0 ? top_arc : bottom_arc).push_back(i);
  }
}

// The particles whose `keep` is set, in their order, with all their state.
Particles kept_particles(const Particles& p, const std::vector<char>& keep) {
  Particles out;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (!keep[i]) continue;
    for (int a = 0; a < 2; ++a) {
      out.position.push_back(p.position[2 * i + a]);
      out.velocity.push_back(p.velocity[2 * i + a]);
      out.force.push_back(p.force[2 * i + a]);
      out.external_force.push_back(p.external_force[2 * i + a]);
    }
    out.angular_velocity.push_back(p.angular_velocity[i]);
    out.torque.push_back(p.torque[i]);
    out.radius.push_back(p.radius[i]);
    out.inv_mass.push_back(p.inv_mass[i]);
    out.inv_inertia.push_back(p.inv_inertia[i]);
  }
  return out;
}

// The fracture test's two edge notches (loading_test.notch_depth_ratio), cut before the bonds are
// installed: the discs whose centres lie within one largest radius of mid-height and within the
// notch depth of the left or right side. Returns the ligament left between them [m].
double cut_edge_notches(double depth_ratio, Particles& p, std::string& report) {
  const auto [left, right, top, bottom, r_max] = disc_extent(p);
  const double depth_m = depth_ratio * (right - left), mid_m = 0.5 * (top + bottom);
  std::vector<char> keep(p.size(), 1);
  std::size_t taken = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double x = p.position[2 * i];
    if ((x < left + depth_m || x > right - depth_m) &&
        std::abs(p.position[2 * i + 1] - mid_m) < r_max) {
      keep[i] = 0;
      ++taken;
    }
  }
  if (depth_m > 0 && taken == 0) {
    throw std::invalid_argument("dem.loading_test.notch_depth_ratio: notches " +
                                std::to_string(depth_m) + " m deep hold no disc; deepen them");
  }
  p = kept_particles(p, keep);
  char line[160];
  std::snprintf(line, sizeof line, "; two edge notches %.4g m deep (%zu discs out), ligament %.4g m",
                depth_m, taken, right - left - 2 * depth_m);
  report += line;
  return right - left - 2 * depth_m;
}

// Platens just touching the specimen's top and bottom, three specimen widths wide, closing at the
// given speed (`fracture`: moving apart with the end layers that pull the specimen). The lateral strain (UCS) or the opening across the horizontal diameter (Brazilian)
// comes from the discs within one largest diameter of the left and right edges.
LoadingRig add_platens(const rockcut::LoadingTest& test, const Particles& p, WallSet& walls,
                       std::vector<std::uint32_t>& top_layer,
                       std::vector<std::uint32_t>& bottom_layer) {
  const bool biaxial = test.kind() == "biaxial";
  const bool ucs = test.kind() == "ucs" || biaxial;  // the same specimen, platens and gauges
  const bool fracture = test.kind() == "fracture";
  if (!fracture && test.has_notch_depth_ratio()) {
    throw std::invalid_argument(
        "dem.loading_test.notch_depth_ratio: only kind \"fracture\" has notches");
  }
  if (fracture && (test.loading_arc_deg() > 0 ||
                   (test.has_clamp_end_layers() && !test.clamp_end_layers()))) {
    throw std::invalid_argument(
        test.loading_arc_deg() > 0
            ? "dem.loading_test.loading_arc_deg: the loading arc is for kind \"brazilian\"; a "
              "fracture specimen is pulled by its end layers"
            : "dem.loading_test.clamp_end_layers: a fracture specimen is pulled by its end "
              "layers; leave it out or true");
  }
  // Each test's holding option belongs to it; refused before anything is built.
  if (biaxial != test.has_confining_stress_pa()) {
    throw std::invalid_argument(
        biaxial ? "dem.loading_test.confining_stress_pa: kind \"biaxial\" needs the stress its "
                  "side walls hold (0 or more, Pa)"
                : "dem.loading_test.confining_stress_pa: only kind \"biaxial\" has side walls to "
                  "hold a confining stress");
  }
  if (ucs && test.loading_arc_deg() > 0) {
    throw std::invalid_argument(
        "dem.loading_test.loading_arc_deg: the loading arc is for kind \"brazilian\"; a UCS "
        "specimen's ends are held with clamp_end_layers");
  }
  if (!ucs && !fracture && test.clamp_end_layers()) {
    throw std::invalid_argument(
        "dem.loading_test.clamp_end_layers: for kind \"ucs\"; a Brazilian disc is held over its "
        "loading arcs with loading_arc_deg");
  }
  const auto [left, right, top, bottom, r_max] = disc_extent(p);
  LoadingRig rig;
  rig.present = true;
  rig.ucs = ucs;
  rig.fracture = fracture;
  rig.height0_m = top - bottom;
  rig.width0_m = right - left;
  const double w = right - left, v = fracture ? -test.platen_speed_m_s() : test.platen_speed_m_s();
  rig.top = walls.add_body("platen_top", {left - w, top, right + w, top}, false, 0.0, -v);
  rig.bottom = walls.add_body("platen_bottom", {left - w, bottom, right + w, bottom}, false, 0.0, v);
  if (test.has_platen_friction()) {
    walls.set_friction(rig.top, test.platen_friction());
    walls.set_friction(rig.bottom, test.platen_friction());
  }
  rig.biaxial = biaxial;
  if (!biaxial && test.has_confinement()) {
    throw std::invalid_argument(
        "dem.loading_test.confinement: only kind \"biaxial\" has a confining stress");
  }
  if (biaxial && test.confinement() == "walls") {
    // Frictionless side walls as long as the specimen is high and a platen's reach beyond: a
    // membrane that presses but does not hold the sides back as they slide.
    rig.side_walls = true;
    const double h = top - bottom;
    rig.left_wall = walls.add_body("side_left", {left, bottom - h, left, top + h}, false, 0.0, 0.0);
    rig.right_wall = walls.add_body("side_right", {right, bottom - h, right, top + h}, false, 0.0, 0.0);
    walls.set_friction(rig.left_wall, 0.0);
    walls.set_friction(rig.right_wall, 0.0);
  }
  if (!rig.ucs && test.loading_arc_deg() > 0) {
    select_loading_arcs(test.loading_arc_deg(), r_max, p, top_layer, bottom_layer);
    if (top_layer.empty() || bottom_layer.empty()) {
      throw std::invalid_argument("dem.loading_test.loading_arc_deg: an arc of " +
                                  std::to_string(test.loading_arc_deg()) +
                                  " deg holds no disc at the top or bottom; widen it");
    }
  }
  const double lower = bottom + 0.25 * rig.height0_m, upper = bottom + 0.75 * rig.height0_m;
  for (std::uint32_t i = 0; i < p.size(); ++i) {
    if (p.position[2 * i] - p.radius[i] < left + 2 * r_max) rig.left_strip.push_back(i);
    if (p.position[2 * i] + p.radius[i] > right - 2 * r_max) rig.right_strip.push_back(i);
    if (!rig.ucs && !fracture) continue;
    if (rig.ucs && std::abs(p.position[2 * i + 1] - lower) < r_max) rig.lower_gauge.push_back(i);
    if (rig.ucs && std::abs(p.position[2 * i + 1] - upper) < r_max) rig.upper_gauge.push_back(i);
    if (!test.clamp_end_layers() && !fracture) continue;
    if (p.position[2 * i + 1] + p.radius[i] > top - 2 * r_max) top_layer.push_back(i);
    if (p.position[2 * i + 1] - p.radius[i] < bottom + 2 * r_max) bottom_layer.push_back(i);
  }
  rig.strip_width0_m = mean_coordinate(p, rig.right_strip, 0) - mean_coordinate(p, rig.left_strip, 0);
  if (!rig.lower_gauge.empty() && !rig.upper_gauge.empty()) {
    rig.gauge_length0_m =
        mean_coordinate(p, rig.upper_gauge, 1) - mean_coordinate(p, rig.lower_gauge, 1);
  }
  rig.clamped_ends = !top_layer.empty() && !bottom_layer.empty();
  return rig;
}

}  // namespace

DampingChoice damping_choice(const rockcut::Dem& dem) {
  const rockcut::Damping& d = dem.damping();
  const std::string& model = d.model();
  DampingChoice choice;
  if (model == "local" || model == "local+viscous") choice.local_coefficient = d.local_coefficient();
  if (model == "viscous" || model == "local+viscous") {
    if (d.has_restitution() && d.has_damping_ratio()) {
      throw std::invalid_argument(
          "dem.damping: give damping_ratio or restitution, not both (restitution " +
          std::to_string(d.restitution()) + " means damping_ratio " +
          std::to_string(damping_ratio_from_restitution(d.restitution())) + ")");
    }
    choice.damping_ratio =
        d.has_restitution() ? damping_ratio_from_restitution(d.restitution()) : d.damping_ratio();
  }
  return choice;
}

DemSetup build_dem(const rockcut::Dem& dem) {
  DemSetup setup;
  Particles particles = particles_from_scene(dem, setup.specimen_report);
  if (particles.size() == 0) throw std::invalid_argument("dem: the scene makes no particles");
  double ligament_m = 0.0;  // `fracture`: notched before the bonds are installed
  if (dem.has_loading_test() && dem.loading_test().kind() == "fracture") {
    ligament_m = cut_edge_notches(dem.loading_test().notch_depth_ratio(), particles,
                                  setup.specimen_report);
  }
  // On top of each disc's own velocity (a packing file's columns; 0 otherwise).
  const double vx = dem.initial_velocity_m_s().x(), vy = dem.initial_velocity_m_s().y();
  for (std::size_t i = 0; i < particles.size(); ++i) {
    particles.velocity[2 * i] += vx;
    particles.velocity[2 * i + 1] += vy;
  }

  DemSettings settings;
  settings.gravity_x_m_s2 = dem.gravity_m_s2().x();
  settings.gravity_y_m_s2 = dem.gravity_m_s2().y();
  const DampingChoice damping = damping_choice(dem);
  settings.local_damping = damping.local_coefficient;
  settings.skin_m = dem.skin_m();
  settings.threads = static_cast<int>(dem.threads());
  if (dem.has_contact()) {
    settings.contact = {dem.contact().normal_stiffness_pa(), dem.contact().shear_stiffness_pa(),
                        dem.contact().friction(), 0.0, dem.contact().rolling_friction()};
  }
  settings.contact.damping_ratio = damping.damping_ratio;  // the bonds' dashpots too
  if (dem.has_prescribed_motion()) {
    const rockcut::PrescribedMotion& m = dem.prescribed_motion();
    PrescribedMotion motion;
    motion.strain_rate_xx_per_s = m.strain_rate_xx_per_s();
    motion.strain_rate_yy_per_s = m.strain_rate_yy_per_s();
    motion.origin_x_m = m.origin_m().x();
    motion.origin_y_m = m.origin_m().y();
    motion.start_time_s = m.start_time_s();
    if (m.has_end_time_s()) motion.end_time_s = m.end_time_s();
    settings.prescribed_motion = motion;
  }

  BondSet bonds;
  double kn = settings.contact.normal_stiffness_pa, ks = settings.contact.shear_stiffness_pa;
  if (dem.has_bonds()) {
    const rockcut::BondParameters& b = dem.bonds();
    const BondLaw law{b.normal_stiffness_pa(), b.shear_stiffness_pa(),
                      b.tensile_strength_n_per_m(), b.shear_strength_n_per_m(),
                      std::tan(b.friction_angle_deg() * std::numbers::pi / 180.0),
                      b.softening_ratio()};
    CellGrid grid;
    bonds = BondSet::install(particles, law, b.gap_tolerance_m(), grid);
    char line[160];
    std::snprintf(line, sizeof line, "; %zu bonds (%.3f per disc, gap <= %g m)", bonds.size(),
                  2.0 * static_cast<double>(bonds.size()) / static_cast<double>(particles.size()),
                  b.gap_tolerance_m());
    setup.specimen_report += line;
    kn = std::max(kn, law.normal_stiffness_pa);
    ks = std::max(ks, law.shear_stiffness_pa);
  }
  bonds.count_per_particle(particles.size(), setup.initial_bonds);

  WallSet walls;
  for (const rockcut::Wall& w : dem.walls()) {
    if (w.vertex_m_size() < 2) {
      throw std::invalid_argument("dem.walls \"" + w.name() + "\": give at least two vertex_m");
    }
    std::vector<double> vertices;
    for (const rockcut::Vec2& v : w.vertex_m()) vertices.insert(vertices.end(), {v.x(), v.y()});
    walls.add_body(w.name(), vertices, w.closed(), w.velocity_m_s().x(), w.velocity_m_s().y());
  }
  if (dem.has_tool()) {
    if (!dem.has_contact()) {
      throw std::invalid_argument("dem.tool needs dem.contact: the tool pushes discs by contact");
    }
    setup.tool = add_tool(dem.tool(), particles, walls);
  }
  std::vector<std::uint32_t> top_layer, bottom_layer;  // clamp_end_layers: handed to the system
  if (dem.has_loading_test()) {
    if (!dem.has_contact()) {
      throw std::invalid_argument("dem.loading_test needs dem.contact: platens push by contact");
    }
    if (dem.has_tool()) {
      throw std::invalid_argument("dem.loading_test and dem.tool exclude each other");
    }
    setup.rig = add_platens(dem.loading_test(), particles, walls, top_layer, bottom_layer);
    setup.rig.ligament_m = ligament_m;
  }
  if (!walls.empty() && !dem.has_contact()) {
    throw std::invalid_argument("dem.walls need dem.contact: walls push discs by contact");
  }
  setup.critical = critical_step(particles, dem.has_contact() || dem.has_bonds() ? kn : 0.0,
                                 dem.has_contact() || dem.has_bonds() ? ks : 0.0,
                                 damping.damping_ratio, settings.contact.rolling_friction > 0);
  setup.system = std::make_unique<DemSystem>(std::move(particles), settings, std::move(bonds),
                                             std::move(walls));
  if (dem.fixed_base_height_m() > 0) {
    if (!dem.has_specimen()) {
      throw std::invalid_argument("dem.fixed_base_height_m: for a dem.specimen (the block's bottom)");
    }
    const Particles& p = setup.system->particles();
    const double bottom = disc_extent(p).bottom;
    std::vector<std::uint32_t> base;
    for (std::uint32_t i = 0; i < p.size(); ++i) {
      if (p.position[2 * i + 1] - bottom <= dem.fixed_base_height_m()) base.push_back(i);
    }
    if (base.empty()) {
      throw std::invalid_argument("dem.fixed_base_height_m = " +
                                  std::to_string(dem.fixed_base_height_m()) +
                                  " m holds no disc centre; make it at least a disc radius");
    }
    setup.system->add_clamped_group(std::move(base), 0.0, /*fixed=*/true);
  }
  if (setup.rig.biaxial && !setup.rig.side_walls) {
    setup.system->add_membrane_load(
        membrane_load(setup.system->particles(), dem.loading_test().confining_stress_pa()));
  }
  if (setup.rig.side_walls) {
    const Particles& p = setup.system->particles();
    double diameter_sum_m = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i) diameter_sum_m += 2.0 * p.radius[i];
    WallServo servo;
    servo.stress_pa = dem.loading_test().confining_stress_pa();
    servo.top = setup.rig.top;
    servo.bottom = setup.rig.bottom;
    servo.length0_m = setup.rig.height0_m;
    // Every disc along the side touching the wall: L over the mean diameter contacts.
    servo.stiffness_pa = settings.contact.normal_stiffness_pa * setup.rig.height0_m /
                         (diameter_sum_m / static_cast<double>(p.size()));
    servo.max_speed_m_s = dem.loading_test().platen_speed_m_s();
    servo.body = setup.rig.left_wall;
    servo.inward_x = 1.0;
    setup.system->add_wall_servo(servo);
    servo.body = setup.rig.right_wall;
    servo.inward_x = -1.0;
    setup.system->add_wall_servo(servo);
  }
  if (setup.rig.clamped_ends) {
    // Closing (ucs), or pulling apart (fracture).
    const double v = (setup.rig.fracture ? -1.0 : 1.0) * dem.loading_test().platen_speed_m_s();
    setup.rig.top_layer_group = setup.system->add_clamped_group(std::move(top_layer), -v);
    setup.rig.bottom_layer_group = setup.system->add_clamped_group(std::move(bottom_layer), v);
  }

  // With prescribed motion the velocities are imposed: only the NaN guard means anything.
  const bool dynamic = !dem.has_prescribed_motion();
  GuardLimits& guards = setup.guards;
  guards = make_guard_limits(setup.system->particles(), setup.critical.dt_s,
                             dynamic ? dem.guards().max_overlap_ratio() : 0.0,
                             dynamic ? dem.guards().kinetic_energy_factor() : 0.0);
  guards.enabled = dem.guards().enabled();
  // A membrane's dead load is a supply of energy like a wall's push (dry: no Subscribe sets it).
  guards.external_force_supplies_energy = !setup.system->membrane_load().particles.empty();
  if (guards.enabled && guards.max_overlap_ratio > 0) {
    const OverlapExtreme o = largest_overlap(*setup.system);
    if (o.ratio > guards.max_overlap_ratio) {
      const Particles& p = setup.system->particles();
      char message[400];
      std::snprintf(message, sizeof message,
                    "dem.guards.max_overlap_ratio: particle %lld at (%.6g, %.6g) m starts "
                    "overlapping a neighbour or a wall by %.3g of its radius, %.3g times the limit "
                    "%.3g: relax the packing, or raise the limit if the overlaps are meant",
                    static_cast<long long>(o.particle), p.position[2 * o.particle],
                    p.position[2 * o.particle + 1], o.ratio, o.ratio / guards.max_overlap_ratio,
                    guards.max_overlap_ratio);
      throw std::invalid_argument(message);
    }
  }
  setup.initial_energy_j = setup.system->kinetic_energy() + setup.system->strain_energy();
  return setup;
}

rockcut::wire::SolidProperties solid_properties(const rockcut::Dem& dem) {
  rockcut::wire::SolidProperties solid;
  solid.set_grain_density_kg_m3(dem.density_kg_m3());
  const DampingChoice damping = damping_choice(dem);
  solid.set_local_damping(damping.local_coefficient);
  solid.set_viscous_damping_ratio(damping.damping_ratio);
  double kn = dem.has_contact() ? dem.contact().normal_stiffness_pa() : 0.0;
  if (dem.has_bonds()) kn = std::max(kn, dem.bonds().normal_stiffness_pa());
  solid.set_normal_stiffness_pa(kn);
  solid.set_dynamic(!dem.has_prescribed_motion());
  // The walls and the tool the scene writes; a loading test's platens are not counted (no scene
  // puts a pore fluid between platens).
  solid.set_seals_at_walls(dem.walls_size() > 0 || dem.has_tool());
  return solid;
}

}  // namespace rockcut::dem
