// pena-grid-bandwidth: what the same map costs sent as occupancy grids instead of line-map
// deltas (docs/dds.md, "Bandwidth"). For every entity of a simulated mission it runs pena-entity's
// chain (default options) and, at every line-map update (the moments pena-entity publishes a
// LineMapDelta), measures:
//   - the LineMapDelta's serialised (CDR) size, as on the wire;
//   - the entity's local 20 m window grid (the grid the lines are extracted from), trinary
//     (free / unknown / occupied, as ROS map_server) PNG at compression 9;
//   - the whole map the entity has seen as one occupancy grid (every scan at the corrected pose),
//     trinary PNG, and raw (one byte per cell, like nav_msgs/OccupancyGrid).
// Prints bytes per second of mission time per entity. A benchmark: it reports, it does not judge.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <opencv2/imgcodecs.hpp>
#include <variant>
#include <vector>

#include "load_streams.hpp"
#include "pena/grid/local_grid.hpp"
#include "pena/grid/occupancy_grid.hpp"
#include "pena_dds/line_mapPubSubTypes.h"
#include "to_dds.hpp"

namespace {

using namespace pena;
using namespace pena::services;

// Trinary PNG size of a grid image (ROS map_server thresholds 0.65 / 0.196).
std::size_t TrinaryPngBytes(const grid::GridImage& image) {
  if (image.occupancy.empty()) return 0;
  cv::Mat trinary(image.occupancy.size(), CV_8UC1);
  for (int r = 0; r < trinary.rows; ++r) {
    for (int c = 0; c < trinary.cols; ++c) {
      const unsigned char p = image.occupancy.at<unsigned char>(r, c);
      trinary.at<unsigned char>(r, c) = p > 0.65 * 255 ? 0 : (p < 0.196 * 255 ? 254 : 205);
    }
  }
  std::vector<unsigned char> png;
  cv::imencode(".png", trinary, png, {cv::IMWRITE_PNG_COMPRESSION, 9});
  return png.size();
}

struct Totals {
  long updates = 0;
  double delta_bytes = 0.0, window_png = 0.0, whole_png = 0.0, whole_raw = 0.0;
  double final_snapshot = 0.0, final_whole_png = 0.0;
  double mission_s = 0.0;
};

Totals Measure(const std::filesystem::path& entity_dir, std::string* entity_id) {
  Totals totals;
  const pipeline::EntityPipelineOptions defaults;
  std::optional<grid::LocalGrid> window;
  grid::OccupancyGrid whole(defaults.local_grid.grid);
  const bench::ChainRun run = bench::RunEntityChain(
      entity_dir, 1e9,
      [&](const pipeline::ScanStep& step, const pipeline::EntityPipeline& chain) {
        const sensors::LaserScan& scan = step.scan;
        const geometry::Pose2& pose = step.world_from_body;
        if (!window) window.emplace(defaults.local_grid, Eigen::Vector2d(pose.x_m, pose.y_m));
        whole.Insert(scan, pose);
        window->Insert(scan, pose);
        if (window->NeedsRecentre(pose)) window->Recentre(pose);
        if (!step.map_delta) return;
        ++totals.updates;
        pena_dds::LineMapDelta delta = ToDdsLineMapDelta(*step.map_delta, chain.entity_id(), 0.0);
        totals.delta_bytes += pena_dds::LineMapDeltaPubSubType().getSerializedSizeProvider(&delta)();
        totals.window_png += static_cast<double>(TrinaryPngBytes(window->ToImage()));
        totals.whole_png += static_cast<double>(TrinaryPngBytes(whole.ToImage()));
        totals.whole_raw += static_cast<double>(whole.width()) * whole.height();
        pena_dds::LineMapSnapshot snapshot =
            ToDdsLineMapSnapshot(chain.local_map().Snapshot(), chain.entity_id(), 0.0);
        totals.final_snapshot =
            pena_dds::LineMapSnapshotPubSubType().getSerializedSizeProvider(&snapshot)();
      });
  totals.final_whole_png = static_cast<double>(TrinaryPngBytes(whole.ToImage()));
  totals.mission_s = run.last_stamp_s - run.first_stamp_s;
  *entity_id = run.entity_id;
  return totals;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("pena-grid-bandwidth: line-map deltas vs occupancy grids, bytes per second");
  std::string mission;
  app.add_option("--mission", mission, "Simulated mission directory (pena simulate --out)")
      ->required();
  CLI11_PARSE(app, argc, argv);
  try {
    std::printf("%-8s %7s %8s | %12s %14s %14s %14s | %10s %12s\n", "entity", "mission", "updates",
                "delta B/s", "window PNG B/s", "whole PNG B/s", "whole raw B/s", "map bytes",
                "grid PNG B");
    for (const std::filesystem::path& dir : bench::MissionEntities(mission)) {
      std::string id;
      const Totals t = Measure(dir, &id);
      const double s = std::max(t.mission_s, 1e-9);
      std::printf("%-8s %6.0fs %8ld | %12.1f %14.1f %14.1f %14.1f | %10.0f %12.0f\n", id.c_str(),
                  t.mission_s, t.updates, t.delta_bytes / s, t.window_png / s, t.whole_png / s,
                  t.whole_raw / s, t.final_snapshot, t.final_whole_png);
      std::fflush(stdout);
    }
  } catch (const std::exception& error) {
    std::fprintf(stderr, "pena-grid-bandwidth: %s\n", error.what());
    return 1;
  }
  return 0;
}
