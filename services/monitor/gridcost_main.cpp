// pena-link-gridcost: what one entity's map would cost on the link as compressed occupancy grids
// instead of line-map deltas (docs/link-experiments.md, "Line maps against grids"). Rebuilds the
// entity's grid from its sensor log at the poses it published (its trajectory.tum of a run) and,
// every --period-s of mission time, PNG-encodes (a) the whole grid and (b) the bounding box of the
// cells that changed since the last update (the smallest grid "delta" a sender could send as an
// image). Prints one JSON line; --csv writes every update. Exits 1 on bad input.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <opencv2/imgcodecs.hpp>
#include <variant>
#include <vector>

#include "pena/grid/occupancy_grid.hpp"
#include "pena/io/log_source.hpp"
#include "pena/io/trajectory_io.hpp"

namespace {

using pena::geometry::Pose2;

struct Snapshot {
  cv::Mat occupancy;
  Eigen::Vector2i min_cell = Eigen::Vector2i::Zero();
};

std::size_t PngBytes(const cv::Mat& image) {
  if (image.empty()) return 0;
  std::vector<unsigned char> png;
  if (!cv::imencode(".png", image, png)) throw std::runtime_error("cannot PNG-encode a grid");
  return png.size();
}

// The bounding box (pixels of `now`) of the cells that differ from `before` or are new.
cv::Rect ChangedBox(const Snapshot& before, const Snapshot& now) {
  int min_col = now.occupancy.cols, min_row = now.occupancy.rows, max_col = -1, max_row = -1;
  for (int row = 0; row < now.occupancy.rows; ++row) {
    const int cell_y = now.min_cell.y() + now.occupancy.rows - 1 - row;
    const int before_row = before.occupancy.rows - 1 - (cell_y - before.min_cell.y());
    for (int col = 0; col < now.occupancy.cols; ++col) {
      const int before_col = now.min_cell.x() + col - before.min_cell.x();
      const bool inside = before_row >= 0 && before_row < before.occupancy.rows &&
                          before_col >= 0 && before_col < before.occupancy.cols;
      const std::uint8_t value = now.occupancy.at<std::uint8_t>(row, col);
      const bool changed = inside
                               ? before.occupancy.at<std::uint8_t>(before_row, before_col) != value
                               : value != 128;
      if (!changed) continue;
      min_col = std::min(min_col, col);
      max_col = std::max(max_col, col);
      min_row = std::min(min_row, row);
      max_row = std::max(max_row, row);
    }
  }
  if (max_col < 0) return {};
  return {min_col, min_row, max_col - min_col + 1, max_row - min_row + 1};
}

// The published pose nearest in time to `stamp_s` (poses are published per scan).
const Pose2* PoseAt(const pena::geometry::Trajectory& trajectory, double stamp_s) {
  auto it = std::lower_bound(trajectory.begin(), trajectory.end(), stamp_s,
                             [](const auto& pose, double t) { return pose.stamp_s < t; });
  const pena::geometry::StampedPose2* best = nullptr;
  if (it != trajectory.end()) best = &*it;
  if (it != trajectory.begin() &&
      (best == nullptr || stamp_s - std::prev(it)->stamp_s < best->stamp_s - stamp_s)) {
    best = &*std::prev(it);
  }
  return best != nullptr && std::abs(best->stamp_s - stamp_s) < 0.05 ? &best->pose : nullptr;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("pena-link-gridcost: grid PNG bytes per map update for one entity");
  std::string log_path, trajectory_path, csv_path;
  double period_s = 1.0;
  app.add_option("--log", log_path, "The entity's sensors.penalog")->required();
  app.add_option("--trajectory", trajectory_path, "Its published poses (trajectory.tum)")
      ->required();
  app.add_option("--period-s", period_s, "Mission seconds between grid updates")
      ->capture_default_str();
  app.add_option("--csv", csv_path, "Write stamp_s,full_png_bytes,changed_png_bytes per update");
  CLI11_PARSE(app, argc, argv);
  try {
    if (!(period_s > 0.0)) throw std::invalid_argument("--period-s: must be > 0 s");
    const pena::geometry::Trajectory trajectory = pena::io::ReadTum(trajectory_path);
    auto log = pena::io::OpenLog(log_path);
    pena::grid::OccupancyGrid grid;
    Snapshot last;
    std::ofstream csv;
    if (!csv_path.empty()) {
      csv.open(csv_path);
      csv << "stamp_s,full_png_bytes,changed_png_bytes,width,height\n";
    }
    double next_update_s = -1.0;
    std::size_t updates = 0, full_total = 0, changed_total = 0, final_full = 0, scans = 0;
    auto update = [&](double stamp_s) {
      Snapshot now{grid.ToImage().occupancy.clone(), grid.min_cell()};
      const cv::Rect box = ChangedBox(last, now);
      const std::size_t full = PngBytes(now.occupancy);
      const std::size_t changed = box.area() > 0 ? PngBytes(now.occupancy(box).clone()) : 0;
      if (box.area() == 0) return;  // nothing new: no update sent
      ++updates;
      full_total += full;
      changed_total += changed;
      final_full = full;
      if (csv.is_open()) {
        csv << stamp_s << ',' << full << ',' << changed << ',' << now.occupancy.cols << ','
            << now.occupancy.rows << '\n';
      }
      last = std::move(now);
    };
    double stamp_s = 0.0;
    while (auto record = log->Next()) {
      const auto* scan = std::get_if<pena::sensors::LaserScan>(&*record);
      if (scan == nullptr) continue;
      stamp_s = scan->stamp_s;
      if (next_update_s < 0.0) next_update_s = stamp_s + period_s;
      if (stamp_s >= next_update_s) {
        update(stamp_s);
        next_update_s += period_s * std::ceil((stamp_s - next_update_s) / period_s + 1e-9);
        if (next_update_s <= stamp_s) next_update_s += period_s;
      }
      const Pose2* pose = PoseAt(trajectory, scan->stamp_s);
      if (pose != nullptr && grid.Insert(*scan, *pose)) ++scans;
    }
    update(stamp_s);
    std::printf(
        "{\"scans\": %zu, \"updates\": %zu, \"full_png_bytes_total\": %zu, "
        "\"changed_png_bytes_total\": %zu, \"final_full_png_bytes\": %zu}\n",
        scans, updates, full_total, changed_total, final_full);
  } catch (const std::exception& error) {
    std::cerr << "pena-link-gridcost: " << error.what() << '\n';
    return 1;
  }
  return 0;
}
