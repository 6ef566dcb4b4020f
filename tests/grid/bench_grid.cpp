// Scans per second of the occupancy grid update on 361-beam scans (180 deg at 0.5 deg), one core.
// Synthetic rooms of 10, 20 and 40 m, and the real seattle log of data/radish-corrected.
// Run: build/tests/grid/bench_grid (scans_per_s = items_per_second = scans per second).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "pena/grid/local_grid.hpp"
#include "pena/grid/occupancy_grid.hpp"
#include "radish_scans.hpp"

namespace pena::grid {
namespace {

constexpr int kBeams = 361;
constexpr int kScans = 200;

struct Walk {
  std::vector<sensors::LaserScan> scans;
  std::vector<geometry::Pose2> poses;
};

// Distance from `origin` along `angle_rad` to the walls of the room [0, width] x [0, depth].
float RangeInRoom(const geometry::Pose2& origin, double angle_rad, double width_m, double depth_m) {
  const double dx = std::cos(angle_rad);
  const double dy = std::sin(angle_rad);
  const double tx = dx > 0 ? (width_m - origin.x_m) / dx : dx < 0 ? -origin.x_m / dx : 1e9;
  const double ty = dy > 0 ? (depth_m - origin.y_m) / dy : dy < 0 ? -origin.y_m / dy : 1e9;
  return static_cast<float>(std::min(tx, ty));
}

// A walk around a rectangular room, the laser looking ahead; beams beyond 30 m are no-returns.
Walk MakeWalk(double width_m, double depth_m) {
  Walk walk;
  for (int k = 0; k < kScans; ++k) {
    const double phase = 2.0 * std::numbers::pi * k / kScans;
    const geometry::Pose2 pose{width_m / 2 + 0.3 * width_m * std::cos(phase),
                               depth_m / 2 + 0.3 * depth_m * std::sin(phase),
                               phase + std::numbers::pi / 2};
    sensors::LaserScan scan;
    scan.geometry = {-std::numbers::pi / 2, std::numbers::pi / (kBeams - 1), 30.0};
    for (int i = 0; i < kBeams; ++i) {
      const float range = RangeInRoom(
          pose, pose.theta_rad + scan.BeamAngle(static_cast<std::size_t>(i)), width_m, depth_m);
      scan.ranges_m.push_back(range < 30.0f ? range : sensors::LaserScan::kNoReturn);
    }
    walk.scans.push_back(std::move(scan));
    walk.poses.push_back(pose);
  }
  return walk;
}

template <typename Grid>
void RunInsert(benchmark::State& state, Grid& grid, const Walk& walk) {
  std::size_t k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(grid.Insert(walk.scans[k], walk.poses[k]));
    k = (k + 1) % walk.scans.size();
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["scans_per_s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

// Room side in metres from the benchmark argument (beams of a few metres up to ~30 m).
void BM_GlobalGridInsert(benchmark::State& state) {
  const double side_m = static_cast<double>(state.range(0));
  const Walk walk = MakeWalk(side_m, 0.6 * side_m);
  OccupancyGrid grid;
  RunInsert(state, grid, walk);
}

void BM_LocalGridInsert(benchmark::State& state) {
  const double side_m = static_cast<double>(state.range(0));
  const Walk walk = MakeWalk(side_m, 0.6 * side_m);
  LocalGrid grid({}, {side_m / 2, 0.3 * side_m});
  RunInsert(state, grid, walk);
}

// The real 361-beam scans of the radish-corrected seattle log at their corrected poses.
void BM_SeattleGlobalGridInsert(benchmark::State& state) {
  const testing::PosedScans data = testing::ReadRadish("seattle");
  if (data.scans.empty()) {
    state.SkipWithError("data/radish-corrected/seattle has no posed scans");
    return;
  }
  const Walk walk{data.scans, data.poses};
  OccupancyGrid grid;
  RunInsert(state, grid, walk);
  state.counters["grid_cells"] = static_cast<double>(grid.width()) * grid.height();
}

BENCHMARK(BM_GlobalGridInsert)->Arg(10)->Arg(20)->Arg(40)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_LocalGridInsert)->Arg(10)->Arg(20)->Arg(40)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_SeattleGlobalGridInsert)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace pena::grid

BENCHMARK_MAIN();
