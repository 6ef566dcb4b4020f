// Virtual scans per second on a building-like plan of 2,024 segments (22 x 22 rooms of 4 m with a
// door in every wall), 361 beams over 180 deg, 30 m range, from random poses inside the rooms.
// Acceptance: at least 20,000 scans/s on one core. Read "items_per_second".
#include <benchmark/benchmark.h>

#include <numbers>
#include <random>
#include <vector>

#include "building_plan.hpp"
#include "pena/localisation/virtual_scanner.hpp"

namespace {

using pena::geometry::Pose2;

std::vector<Pose2> RandomPoses(int rows, int cols, double room_m, int count) {
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> row(0, rows - 1), col(0, cols - 1);
  std::uniform_real_distribution<double> offset(-0.4 * room_m, 0.4 * room_m);
  std::uniform_real_distribution<double> heading(-std::numbers::pi, std::numbers::pi);
  std::vector<Pose2> poses;
  for (int i = 0; i < count; ++i) {
    const Eigen::Vector2d centre = pena::localisation::testing::RoomCentre(row(rng), col(rng), room_m);
    poses.push_back({centre.x() + offset(rng), centre.y() + offset(rng), heading(rng)});
  }
  return poses;
}

void BM_VirtualScan(benchmark::State& state) {
  const int side = static_cast<int>(state.range(0));
  const double room_m = 4.0;
  const pena::localisation::VirtualScanner scanner(
      pena::localisation::testing::RoomGrid(side, side, room_m));
  const std::vector<Pose2> poses = RandomPoses(side, side, room_m, 1024);
  const pena::sensors::LaserGeometry laser{-std::numbers::pi / 2, std::numbers::pi / 360, 30.0};
  std::vector<float> ranges;
  std::size_t i = 0;
  for (auto _ : state) {
    scanner.CastScan(poses[i++ & 1023], laser, 361, ranges);
    benchmark::DoNotOptimize(ranges.data());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()));
  state.counters["segments"] = static_cast<double>(scanner.segments().size());
}
BENCHMARK(BM_VirtualScan)->Arg(22)->Arg(8);

// Same plan, cell size of the index varied (metres x 10): the default is 1 m.
void BM_VirtualScanCellSize(benchmark::State& state) {
  const double room_m = 4.0;
  const pena::localisation::VirtualScanner scanner(
      pena::localisation::testing::RoomGrid(22, 22, room_m), {static_cast<double>(state.range(0)) / 10.0});
  const std::vector<Pose2> poses = RandomPoses(22, 22, room_m, 1024);
  const pena::sensors::LaserGeometry laser{-std::numbers::pi / 2, std::numbers::pi / 360, 30.0};
  std::vector<float> ranges;
  std::size_t i = 0;
  for (auto _ : state) {
    scanner.CastScan(poses[i++ & 1023], laser, 361, ranges);
    benchmark::DoNotOptimize(ranges.data());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()));
}
BENCHMARK(BM_VirtualScanCellSize)->Arg(5)->Arg(10)->Arg(20)->Arg(40);

}  // namespace

BENCHMARK_MAIN();
