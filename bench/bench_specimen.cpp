// bench_specimen: generate_packing (advancing front, core/specimen_generator.hpp) for the paper's
// rock block, 0.2 m x 0.1 m with radii uniform in [0.2, 0.4] mm (~55,000 discs), plus a 0.1 m
// Brazilian test disc and a block 4 times larger to show the O(N log N) scaling.
//
// Counters: discs = discs returned; discs/s = discs per second of real time; phi = packing fraction;
// coordination = mean number of neighbours within a 0.2 um gap (r_min * 1e-3, the bond tolerance).
#include <benchmark/benchmark.h>

#include "core/specimen_generator.hpp"

namespace {

using rockcut::dem::Packing;
using rockcut::dem::PackingRegion;
using rockcut::dem::PackingSpec;

PackingSpec spec(PackingRegion::Shape shape, double size_m) {
  PackingSpec s;
  s.region.shape = shape;
  s.region.width_m = size_m;
  s.region.height_m = 0.5 * size_m;
  s.region.radius_m = 0.5 * size_m;
  s.radius_min_m = 0.2e-3;
  s.radius_max_m = 0.4e-3;
  return s;
}

void run(benchmark::State& state, const PackingSpec& base) {
  PackingSpec s = base;
  std::size_t n = 0;
  for (auto _ : state) {
    ++s.seed;  // a new specimen each time; the cost does not depend on the seed
    Packing p = rockcut::dem::generate_packing(s);
    n = p.size();
    benchmark::DoNotOptimize(p.x_m.data());
  }
  const auto st = rockcut::dem::packing_stats(rockcut::dem::generate_packing(s), s.region,
                                              1e-3 * s.radius_min_m);
  state.counters["discs"] = static_cast<double>(n);
  state.counters["discs/s"] = benchmark::Counter(static_cast<double>(n) * state.iterations(),
                                                 benchmark::Counter::kIsRate);
  state.counters["phi"] = st.packing_fraction;
  state.counters["coordination"] = st.mean_coordination;
}

void BM_PackBlock_0_2x0_1m(benchmark::State& state) {
  run(state, spec(PackingRegion::Shape::rectangle, 0.2));
}
void BM_PackBlock_0_4x0_2m(benchmark::State& state) {
  run(state, spec(PackingRegion::Shape::rectangle, 0.4));
}
void BM_PackBrazilianDisc_0_1m(benchmark::State& state) {
  run(state, spec(PackingRegion::Shape::circle, 0.1));
}

}  // namespace

BENCHMARK(BM_PackBlock_0_2x0_1m)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_PackBlock_0_4x0_2m)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_PackBrazilianDisc_0_1m)->Unit(benchmark::kMillisecond)->UseRealTime();

BENCHMARK_MAIN();
