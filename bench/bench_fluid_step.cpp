// bench_fluid_step: one fluid step of the SP pore-pressure models (fluid_module/sp/) on the
// 58,000-disc benchmark packing bench/data/pack57k.txt (0.2 m x 0.1 m, radii 0.2-0.4 mm,
// Table 1's h = 1.5 mm: ~23 listed neighbours per particle), on one thread (fluid.threads 1, the
// default) unless a benchmark says otherwise.
//
//   explicit/static    forward Euler at its stability limit, particles at rest
//   explicit/moving    the same while the block deforms (isochoric shear at 10 1/s): the
//                      neighbour lists are rebuilt whenever a particle has moved half the skin
//   explicit/reused    particles at rest with the scene default fluid.geometry_refresh_distance
//                      (0.002 h): the geometry is computed once, so this is the step alone
//                      (divergence with the Laplacian, update, adjoint force), on 1 and 2 threads
//   step_passes        the two passes over the pairs of that step alone, on 1 and 2 threads
//   points/reused      explicit/reused on fewer points than grains (fluid.point_spacing 1.5, 2,
//                      3; 1 is the model on every grain): the step with the grains' motion
//                      restricted to the points and the force spread back
//   point_restriction  those two products alone (positions in, forces out), 2 values per grain
//   implicit           backward Euler at 1, 20 and 100 times the explicit limit
//   neighbour_build    the cell-list rebuild alone;  geometry  the per-step SP geometry alone
//   geometry_refresh   a geometry update with the step's coefficients, full (patch_mm:0) or local
//                      around a moved disc of particles (patch_mm:5, 10, 20)
// each with the particles numbered cell by cell (cell_ordered:1, as the specimen generator numbers
// them) and in pack57k's own random order (cell_ordered:0).
//
// Counters: time/particle = wall time of one step per particle; particle-steps/s; for the
// implicit model cg_iterations = conjugate-gradient iterations per step.
#include <benchmark/benchmark.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "models/explicit_model.hpp"
#include "models/fluid_points_model.hpp"
#include "models/implicit_model.hpp"
#include "sp/step_operator.hpp"

namespace {

using namespace rockcut::fluid;

struct Packing {
  std::vector<double> position, radius;
};

// pack57k.txt (bench/data/), or where it is missing a jittered lattice of the
// same size and density. pack57k lists its discs in random order; `cell_ordered` renumbers them
// row by row of 0.8 mm cells, the order in which the DEM's specimen generator numbers its discs.
Packing read_packing() {
  {
    Packing out;
    std::ifstream in(std::string(ROCKCUT_BENCH_DATA_DIR) + "/pack57k.txt");
    std::string line;
    while (in && std::getline(in, line)) {
      if (line.empty() || line[0] == '#') continue;
      std::istringstream s(line);
      double x, y, r;
      if (s >> x >> y >> r) {
        out.position.insert(out.position.end(), {x, y});
        out.radius.push_back(r);
      }
    }
    if (out.radius.empty()) {
      std::mt19937_64 rng(1);
      const double s = 0.000589;  // mean spacing of pack57k
      for (int j = 0; j < 170; ++j) {
        for (int i = 0; i < 340; ++i) {
          const double jx = (static_cast<double>(rng() >> 11) * 0x1.0p-53 - 0.5) * 0.6 * s;
          const double jy = (static_cast<double>(rng() >> 11) * 0x1.0p-53 - 0.5) * 0.6 * s;
          out.position.insert(out.position.end(), {i * s + jx, j * s + jy});
          out.radius.push_back(0.0003);
        }
      }
    }
    return out;
  }
}

Packing cell_ordered(const Packing& in) {
  const std::size_t n = in.radius.size();
  std::vector<std::size_t> idx(n);
  for (std::size_t i = 0; i < n; ++i) idx[i] = i;
  auto key = [&](std::size_t i) {
    return std::make_pair(static_cast<long>(in.position[2 * i + 1] / 0.0008), in.position[2 * i]);
  };
  std::stable_sort(idx.begin(), idx.end(), [&](auto a, auto b) { return key(a) < key(b); });
  Packing out;
  for (std::size_t i : idx) {
    out.position.insert(out.position.end(), {in.position[2 * i], in.position[2 * i + 1]});
    out.radius.push_back(in.radius[i]);
  }
  return out;
}

const Packing& packing(bool ordered) {
  static const Packing random = read_packing();
  static const Packing cells = cell_ordered(random);
  return ordered ? cells : random;
}

sp::SpParams params() {
  sp::SpParams p;  // Table 1
  p.pulse_amplitude_pa = 1e5;
  p.pulse_x_m = 0.1;
  p.pulse_y_m = 0.05;
  p.pulse_sigma_m = 0.01;
  p.sealed = {true, true, true, false};  // the specimen in its box, open at the top
  return p;
}

// Counters common to every benchmark: the particle count and the cost per particle.
void per_particle(benchmark::State& state, std::size_t n) {
  state.counters["particles"] = static_cast<double>(n);
  state.counters["time/particle"] = benchmark::Counter(
      static_cast<double>(n),
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["particle-steps/s"] =
      benchmark::Counter(static_cast<double>(n), benchmark::Counter::kIsIterationInvariantRate);
}

// state.range(0): 1 for the cell-ordered numbering, 0 for pack57k's own (random) order.
// `threads`: the OpenMP threads of the model's loops (fluid.threads).
void run(benchmark::State& state, sp::PorePressureModel& model, double dt, double strain_rate,
         int threads = 1) {
  omp_set_num_threads(threads);
  const Packing& p = packing(state.range(0) != 0);
  const std::size_t n = p.radius.size();
  std::vector<double> x = p.position, d(2 * n, 0.0), v(2 * n, 0.0), force(2 * n);
  model.initialise({p.radius, p.position});
  model.step(0.0, 0.0, {x, v, d, {}}, force);
  double t = 0.0;
  const std::uint64_t builds0 = model.neighbour_list().builds();
  for (auto _ : state) {
    if (strain_rate != 0.0) {
      for (std::size_t i = 0; i < n; ++i) {  // v = diag(e, -e) (x - centre): isochoric shear
        d[2 * i] = dt * strain_rate * (x[2 * i] - 0.1);
        d[2 * i + 1] = -dt * strain_rate * (x[2 * i + 1] - 0.05);
        x[2 * i] += d[2 * i];
        x[2 * i + 1] += d[2 * i + 1];
      }
    }
    t += dt;
    model.step(dt, t, {x, v, d, {}}, force);
    benchmark::DoNotOptimize(force.data());
  }
  per_particle(state, n);
  state.counters["rebuilds/step"] =
      static_cast<double>(model.neighbour_list().builds() - builds0) / state.iterations();
  state.counters["pairs/particle"] =
      static_cast<double>(model.neighbour_list().pairs()) / static_cast<double>(n);
}

void explicit_static(benchmark::State& state) {
  sp::ExplicitModel m(params());
  run(state, m, m.dt_max_s(), 0.0);
}

void explicit_moving(benchmark::State& state) {
  sp::ExplicitModel m(params());
  run(state, m, m.dt_max_s(), 10.0);
}

// state.range(1): OpenMP threads (fluid.threads).
void explicit_reused(benchmark::State& state) {
  sp::SpParams p = params();
  p.geometry_refresh = 0.002;
  sp::ExplicitModel m(p);
  run(state, m, m.dt_max_s(), 0.0, static_cast<int>(state.range(1)));
  state.counters["geometry_updates/step"] =
      static_cast<double>(m.geometry_updates()) / static_cast<double>(state.iterations());
}

// state.range(0): fluid.point_spacing x 10; particles at rest, the geometry reused, one thread.
void points_reused(benchmark::State& state) {
  sp::SpParams p = params();
  p.geometry_refresh = 0.002;
  p.point_spacing = static_cast<double>(state.range(0)) / 10.0;
  const auto model = sp::pore_pressure_model(p, [](const sp::SpParams& q) {
    return std::unique_ptr<sp::PorePressureModel>(std::make_unique<sp::ExplicitModel>(q));
  });
  omp_set_num_threads(1);
  const Packing& pack = packing(true);
  const std::size_t n = pack.radius.size();
  std::vector<double> x = pack.position, d(2 * n, 0.0), v(2 * n, 0.0), force(2 * n);
  model->initialise({pack.radius, pack.position});
  model->step(0.0, 0.0, {x, v, d, {}}, force);
  const double dt = sp::ExplicitModel(p).dt_max_s();
  double t = 0.0;
  for (auto _ : state) {
    t += dt;
    model->step(dt, t, {x, v, d, {}}, force);
    benchmark::DoNotOptimize(force.data());
  }
  per_particle(state, n);
}

// state.range(0): fluid.point_spacing x 10. The restriction of the positions and the spread of
// the forces alone, one thread.
void point_restriction(benchmark::State& state) {
  const Packing& pack = packing(true);
  const std::size_t n = pack.radius.size();
  const double spacing_grains = static_cast<double>(state.range(0)) / 10.0;
  const sp::PointRestriction r(pack.position, pack.radius, spacing_grains);
  omp_set_num_threads(1);
  std::vector<double> xp(2 * r.points()), force(2 * n);
  for (auto _ : state) {
    r.restrict_to_points(pack.position, xp, 2);
    r.spread_to_grains(xp, force, 2);
    benchmark::DoNotOptimize(force.data());
  }
  per_particle(state, n);
  state.counters["grains/point"] = static_cast<double>(n) / static_cast<double>(r.points());
}

// state.range(1): the step in multiples of the explicit limit.
void implicit_step(benchmark::State& state) {
  sp::ImplicitModel m(params());
  const double dt = static_cast<double>(state.range(1)) * sp::ExplicitModel(params()).dt_max_s();
  run(state, m, dt, 0.0);
  state.counters["cg_iterations"] = m.last_solve().iterations;
}

void neighbour_build(benchmark::State& state) {
  const Packing& p = packing(state.range(0) != 0);
  sp::NeighbourList list(0.0015, 0.1);
  omp_set_num_threads(1);
  for (auto _ : state) list.build(p.position);
  per_particle(state, p.radius.size());
}

void geometry(benchmark::State& state) {
  const Packing& p = packing(state.range(0) != 0);
  sp::NeighbourList list(0.0015, 0.1);
  list.build(p.position);
  sp::Geometry geo;
  const std::vector<double> lucy(p.radius.size(), 3e-7);
  const sp::WendlandC2 kernel(0.0015);
  omp_set_num_threads(1);
  for (auto _ : state) sp::update_geometry(list, kernel, p.position, lucy, 3, geo);
  per_particle(state, p.radius.size());
}

// The cell-ordered packing with its neighbour lists, geometry (h = 1.5 mm, Lucy length 3e-7 m)
// and the step's coefficients: what the benchmarks of StepOperator start from.
struct OperatorSetup {
  const Packing& p = packing(true);
  const std::size_t n = p.radius.size();
  sp::NeighbourList list{0.0015, 0.1};
  const std::vector<double> lucy = std::vector<double>(n, 3e-7);
  const sp::WendlandC2 kernel{0.0015};
  sp::Geometry geo;
  sp::StepOperator op;

  OperatorSetup() {
    list.build(p.position);
    sp::update_geometry(list, kernel, p.position, lucy, 3, geo);
    op.build(geo);
  }
};

// A geometry update with the step's coefficients after the particles in a disc of patch_mm
// around the packing's centre moved (the region around a tool and its chip): the local refresh
// (sp::refresh_geometry, StepOperator::rebuild_rows); patch_mm 0 is the full update of every row.
// rows = the fraction of the rows recomputed.
void geometry_refresh(benchmark::State& state) {
  OperatorSetup setup;
  auto& [p, n, list, lucy, kernel, geo, op] = setup;
  const double patch_m = 1e-3 * static_cast<double>(state.range(0));
  double cx = 0.0, cy = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    cx += p.position[2 * i] / static_cast<double>(n);
    cy += p.position[2 * i + 1] / static_cast<double>(n);
  }
  std::vector<int> moved;
  for (std::size_t i = 0; i < n; ++i) {
    if (std::hypot(p.position[2 * i] - cx, p.position[2 * i + 1] - cy) < patch_m) {
      moved.push_back(static_cast<int>(i));
    }
  }
  // The patch moves 3 um (0.002 h) and back, so the list stays valid.
  std::vector<double> x = p.position, shifted = p.position;
  for (int i : moved) shifted[2 * i] += 3e-6;
  sp::LocalRefresh scratch;
  omp_set_num_threads(1);
  bool flip = false;
  for (auto _ : state) {
    flip = !flip;
    const std::vector<double>& now = flip ? shifted : x;
    if (moved.empty()) {
      sp::update_geometry(list, kernel, now, lucy, 3, geo);
      op.build(geo);
    } else {
      sp::refresh_geometry(list, kernel, now, moved, lucy, 3, 1.0, scratch, geo);
      op.rebuild_rows(geo, scratch.coefficient_rows);
    }
  }
  per_particle(state, n);
  state.counters["moved"] = static_cast<double>(moved.size());
  state.counters["rows"] =
      moved.empty() ? 1.0 : static_cast<double>(scratch.coefficient_rows.size()) / n;
}

// The explicit step's two passes over the pairs alone (StepOperator::divergence_laplacian and
// adjoint_force), fixed inputs, on 1 or 2 threads: what explicit/reused spends outside the update.
void step_passes(benchmark::State& state) {
  OperatorSetup setup;
  auto& [p, n, list, lucy, kernel, geo, op] = setup;
  std::vector<double> vel(2 * n), a(n), div(n), lap(n), force(2 * n);
  std::mt19937_64 rng(3);
  for (double& v : vel) v = static_cast<double>(rng() >> 11) * 0x1.0p-53 - 0.5;
  for (double& v : a) v = static_cast<double>(rng() >> 11) * 0x1.0p-53;
  omp_set_num_threads(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    op.divergence_laplacian(geo, vel, a, div, lap);
    op.adjoint_force(geo, a, force);
    benchmark::DoNotOptimize(force.data());
  }
  omp_set_num_threads(1);
  per_particle(state, n);
}

BENCHMARK(explicit_static)->Name("explicit/static")->ArgName("cell_ordered")->Arg(1)->Arg(0)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(explicit_moving)->Name("explicit/moving")->ArgName("cell_ordered")->Arg(1)->Arg(0)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(explicit_reused)->Name("explicit/reused")->ArgNames({"cell_ordered", "threads"})
    ->Args({1, 1})->Args({1, 2})->Unit(benchmark::kMillisecond);
BENCHMARK(step_passes)->ArgName("threads")->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(points_reused)->Name("points/reused")->ArgName("spacing_x10")->Arg(10)->Arg(15)->Arg(20)
    ->Arg(30)->Unit(benchmark::kMillisecond);
BENCHMARK(point_restriction)->ArgName("spacing_x10")->Arg(15)->Arg(20)->Arg(30)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(implicit_step)->Name("implicit")->ArgNames({"cell_ordered", "dt_x_explicit"})
    ->Args({1, 1})->Args({1, 20})->Args({1, 100})->Args({0, 1})->Unit(benchmark::kMillisecond);
BENCHMARK(neighbour_build)->ArgName("cell_ordered")->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond);
BENCHMARK(geometry)->ArgName("cell_ordered")->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond);
BENCHMARK(geometry_refresh)->ArgName("patch_mm")->Arg(0)->Arg(5)->Arg(10)->Arg(20)
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
