// Issue 4 acceptance: line extraction from a 60 m x 60 m grid at 5 cm in under 200 ms on one core.
#include <benchmark/benchmark.h>

#include <cstdint>
#include <random>

#include "pena/line_map/line_extractor.hpp"
#include "synthetic_grid.hpp"

namespace {

// 6 x 6 rooms of 9.8 m with doors (about 60 m x 60 m with the margin), walls 2 cells thick, plus
// speckle and weak reflections so every step has work.
pena::grid::GridImage BenchmarkGrid() {
  pena::grid::GridImage grid = pena::line_map::testing::Building(6, 6, 9.8, 0.9, 0.05, 2, nullptr);
  std::mt19937 random(1);
  std::uniform_int_distribution<int> col(0, grid.occupancy.cols - 1);
  std::uniform_int_distribution<int> row(0, grid.occupancy.rows - 1);
  for (int k = 0; k < 5000; ++k) {
    grid.occupancy.at<std::uint8_t>(row(random), col(random)) = k % 2 == 0 ? 255 : 150;
  }
  return grid;
}

void BM_ExtractLines60m(benchmark::State& state) {
  const pena::grid::GridImage grid = BenchmarkGrid();
  std::size_t segments = 0;
  for (auto _ : state) {
    const auto lines = pena::line_map::ExtractLines(grid);
    segments = lines.size();
    benchmark::DoNotOptimize(segments);
  }
  state.counters["segments"] = static_cast<double>(segments);
  state.counters["cells"] = static_cast<double>(grid.occupancy.total());
}
BENCHMARK(BM_ExtractLines60m)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
