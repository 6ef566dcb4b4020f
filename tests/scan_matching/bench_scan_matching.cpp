// Matches per second of the correlation matcher on 361-beam scans of a synthetic room, one core.
// Run: build/tests/scan_matching/bench_scan_matching (items_per_second = matches per second).
#include <benchmark/benchmark.h>

#include <numbers>
#include <random>

#include "pena/scan_matching/correlation_scan_matcher.hpp"
#include "synthetic_room.hpp"

namespace pena::scan_matching {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

struct Fixture {
  Points2 reference;
  Points2 scan;
};

Fixture MakeFixture() {
  std::mt19937 rng(5);
  const auto walls = testing::SyntheticRoom();
  return {testing::ScanRoom(walls, {1.5, 2.5, 0.1}, 0.01, rng),
          testing::ScanRoom(walls, {1.75, 2.4, 0.25}, 0.01, rng)};
}

const SearchWindow kPaperWindow{};                                          // 60x36 cm, 3 deg
const SearchWindow kNoGyroWindow{0.80, 0.60, 80.0 * kDeg, 0.02, 0.5 * kDeg};  // the paper's "infeasible"

void Run(benchmark::State& state, const SearchWindow& window, bool branch_and_bound) {
  const Fixture fixture = MakeFixture();
  const CorrelationScanMatcher matcher({}, fixture.reference);
  const geometry::Pose2 prior{0.2, -0.1, 0.15};
  long candidates = 0;
  for (auto _ : state) {
    const MatchResult result = branch_and_bound
                                   ? matcher.MatchBranchAndBound(fixture.scan, prior, window)
                                   : matcher.MatchExhaustive(fixture.scan, prior, window);
    candidates = result.candidates_scored;
    benchmark::DoNotOptimize(result);
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["candidates"] = static_cast<double>(candidates);
}

void BM_PaperWindowExhaustive(benchmark::State& state) { Run(state, kPaperWindow, false); }
void BM_PaperWindowBranchAndBound(benchmark::State& state) { Run(state, kPaperWindow, true); }
void BM_NoGyroWindowExhaustive(benchmark::State& state) { Run(state, kNoGyroWindow, false); }
void BM_NoGyroWindowBranchAndBound(benchmark::State& state) { Run(state, kNoGyroWindow, true); }

void BM_BuildMatcher(benchmark::State& state) {
  const Fixture fixture = MakeFixture();
  for (auto _ : state) benchmark::DoNotOptimize(CorrelationScanMatcher({}, fixture.reference));
  state.SetItemsProcessed(state.iterations());
}

BENCHMARK(BM_PaperWindowExhaustive)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_PaperWindowBranchAndBound)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_NoGyroWindowExhaustive)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_NoGyroWindowBranchAndBound)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_BuildMatcher)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace pena::scan_matching

BENCHMARK_MAIN();
