// Edge topology of a disc whose centre vertex has valence N, faces listed in decreasing order (issue 20:
// an insertion sort per vertex made it quadratic, 3.5 s at 50K and 48.7 s at 200K). Prints the time per
// size with a fitted complexity, and the 200K / 50K ratio measured in one run: about 4 (4.3 for
// N log N) when the bucket sort is O(N log N), 16 when quadratic.
#include "iarap/core/threads.h"
#include "iarap/mesh/edge_topology.h"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>

namespace {

Eigen::MatrixXi decreasing_disc(int valence) {
  Eigen::MatrixXi F(valence, 3);
  for (int i = 0; i < valence; ++i) {
    const int ring = valence - 1 - i;
    F.row(i) << 0, 1 + ring, 1 + (ring + 1) % valence;
  }
  return F;
}

double seconds_for(const Eigen::MatrixXi& F) {
  const auto start = std::chrono::steady_clock::now();
  benchmark::DoNotOptimize(iarap::edge_topology(F, static_cast<int>(F.rows()) + 1));
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void BM_HighValenceDisc(benchmark::State& state) {
  iarap::set_thread_count(1);
  const Eigen::MatrixXi F = decreasing_disc(static_cast<int>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(iarap::edge_topology(F, static_cast<int>(F.rows()) + 1));
  state.SetComplexityN(state.range(0));
}
BENCHMARK(BM_HighValenceDisc)
    ->Arg(50000)
    ->Arg(100000)
    ->Arg(200000)
    ->Unit(benchmark::kMillisecond)
    ->Complexity();

// 50K and 200K alternately in every iteration, so that other load on the machine hits both alike.
void BM_ValenceRatio200KOver50K(benchmark::State& state) {
  iarap::set_thread_count(1);
  const Eigen::MatrixXi small = decreasing_disc(50000), large = decreasing_disc(200000);
  // Fastest of each: a burst of other load or a page-fault storm inflates single runs, not the minimum.
  double t_small = 1e300, t_large = 1e300;
  for (auto _ : state) {
    t_small = std::min(t_small, seconds_for(small));
    t_large = std::min(t_large, seconds_for(large));
  }
  state.counters["ratio"] = t_large / t_small;
}
BENCHMARK(BM_ValenceRatio200KOver50K)->Unit(benchmark::kMillisecond);

} // namespace

BENCHMARK_MAIN();
