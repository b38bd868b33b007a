// DEM step throughput on the benchmark packing (bench/data/pack57k.txt, 57,636 discs): the
// bonded block being cut by the chisel, with bond shear springs and break checks on, for 1, 2 and
// more threads, up to the machine's. Reports particle-steps per second, the figure
// bench/data/README.md gives for LAMMPS, LIGGGHTS and YADE on the same packing (k_n 1e10, k_t
// 2.5e10 Pa, friction 1, dt 2e-8 s).
//
// Run: build/bin/bench_dem [--packing PATH]   (default: bench/data/pack57k.txt)
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <memory>
#include <string>
#include <thread>

#include "core/dem_system.hpp"
#include "core/packing_file.hpp"

namespace {

std::string g_packing = ROCKCUT_BENCH_DATA_DIR "/pack57k.txt";

// The file lists the discs in random order; like LAMMPS (atom_modify sort) and the specimen
// generator, the bench numbers them in cell order. Read once; each benchmark copies it.
const rockcut::dem::Packing& packing() {
  static const rockcut::dem::Packing p =
      rockcut::dem::in_cell_order(rockcut::dem::read_packing_file(g_packing));
  return p;
}

// The damping of the run: 0 the paper's local damping (alpha_d 0.7), 1 dashpots (zeta 0.1), 2
// dashpots and rolling springs (mu_r 0.1): what each pair-loop variant costs. softening_ratio:
// the bonds' lambda (core/bond_softening.hpp), 0 the paper's brittle bond.
std::unique_ptr<rockcut::dem::DemSystem> bonded_block_with_tool(int threads, int damping = 0,
                                                                double softening_ratio = 0.0) {
  using namespace rockcut::dem;
  const Packing& pk = packing();
  Particles p;
  double left = 1e300, top = -1e300;
  for (std::size_t i = 0; i < pk.x_m.size(); ++i) {
    p.add(pk.x_m[i], pk.y_m[i], pk.radius_m[i], 2800);
    left = std::min(left, pk.x_m[i] - pk.radius_m[i]);
    top = std::max(top, pk.y_m[i] + pk.radius_m[i]);
  }
  CellGrid grid;
  // The README's bonding rule: every pair with a surface gap up to 10 um.
  BondSet bonds = BondSet::install(p, {1e10, 2.5e10, 1e4, 2e4, 0.0, softening_ratio}, 10e-6, grid);
  DemSettings s;
  s.contact = {1e10, 2.5e10, 1.0, damping > 0 ? 0.1 : 0.0, damping > 1 ? 0.1 : 0.0};
  s.local_damping = damping == 0 ? 0.7 : 0.0;
  s.threads = threads;
  WallSet walls;
  // The chisel touching the block's left edge, 20 mm deep, moving at 1 m/s (60 deg cutting angle).
  const double tip_x = left, tip_y = top - 0.02;
  walls.add_body("tool", {tip_x, tip_y, tip_x - 0.03, tip_y + 0.052, tip_x - 0.06, tip_y + 0.005},
                 true, 1.0, 0.0);
  walls.add_body("floor", {-1.0, 0.0, 1.0, 0.0}, false, 0.0, 0.0);
  return std::make_unique<DemSystem>(std::move(p), s, std::move(bonds), std::move(walls));
}

// Steps `system` through the benchmark's iterations (after a warm-up: first rebuilds, caches) and
// sets its counters.
void time_steps(benchmark::State& state, rockcut::dem::DemSystem& system) {
  const double dt = 2e-8;
  for (int k = 0; k < 200; ++k) system.step(dt);
  const std::size_t n = system.particles().size();
  std::uint64_t steps = 0;
  for (auto _ : state) {
    for (int k = 0; k < 100; ++k) system.step(dt);
    steps += 100;
  }
  state.counters["particle_steps_per_s"] =
      benchmark::Counter(static_cast<double>(steps) * n, benchmark::Counter::kIsRate);
  state.counters["particles"] = static_cast<double>(n);
  state.counters["bonds"] = static_cast<double>(system.bonds().size());
  state.counters["breaks"] = static_cast<double>(system.breaks().size());
  std::size_t damaged = 0;
  for (std::size_t k = 0; k < system.bonds().size(); ++k) damaged += system.bonds().damage(k) > 0;
  state.counters["damaged"] = static_cast<double>(damaged);
  state.counters["rebuilds"] = static_cast<double>(system.neighbour_rebuilds());
}

// 1, 2 and the powers of two up to this machine's hardware threads, and that count itself: the
// scaling measured where the cores are (bench/scaling_model.py's model predicts it from 1 and 2).
void thread_counts(benchmark::internal::Benchmark* b) {
  const int cores = static_cast<int>(std::max(2u, std::thread::hardware_concurrency()));
  for (int t = 1; t < cores; t *= 2) b->Arg(t);
  b->Arg(cores);
}

void BM_BondedBlockCutting(benchmark::State& state) {
  time_steps(state, *bonded_block_with_tool(static_cast<int>(state.range(0))));
}
BENCHMARK(BM_BondedBlockCutting)->Apply(thread_counts)->UseRealTime()
    ->Unit(benchmark::kMillisecond)->MinTime(3.0);

// The dynamic scenes' model, dashpots of zeta 0.1, on 1, 2, ... threads (thread_counts): what
// bench_whole_cut.py holds a dry dynamic cut's whole-run rate against.
void BM_BondedBlockCuttingViscous(benchmark::State& state) {
  time_steps(state, *bonded_block_with_tool(static_cast<int>(state.range(0)), 1));
}
BENCHMARK(BM_BondedBlockCuttingViscous)->Apply(thread_counts)->UseRealTime()
    ->Unit(benchmark::kMillisecond)->MinTime(3.0);

// One thread, per damping model (argument as bonded_block_with_tool's `damping`).
void BM_BondedBlockCuttingDamping(benchmark::State& state) {
  time_steps(state, *bonded_block_with_tool(1, static_cast<int>(state.range(0))));
}
BENCHMARK(BM_BondedBlockCuttingDamping)->Arg(0)->Arg(1)->Arg(2)->UseRealTime()
    ->Unit(benchmark::kMillisecond)->MinTime(3.0);

// One thread under dashpots, brittle bonds (0) against softening ones (lambda 9): what the
// damage check costs every bond, and the damaged bonds' own path once the tool has loaded some.
void BM_BondedBlockCuttingSoftening(benchmark::State& state) {
  time_steps(state, *bonded_block_with_tool(1, 1, static_cast<double>(state.range(0))));
}
BENCHMARK(BM_BondedBlockCuttingSoftening)->Arg(0)->Arg(9)->UseRealTime()
    ->Unit(benchmark::kMillisecond)->MinTime(3.0);

}  // namespace

int main(int argc, char** argv) {
  for (int i = 1; i + 1 < argc; ++i) {
    if (std::strcmp(argv[i], "--packing") == 0) g_packing = argv[i + 1];
  }
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  return 0;
}
