#pragma once
// Shared between the files of `pena map` (cmd_map.cpp: the passes over the log; cmd_map_slam.cpp:
// the odometry + SLAM pass; cmd_map_output.cpp: files, picture and summary).

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "pena/geometry/trajectory.hpp"
#include "pena/grid/grid_image.hpp"
#include "pena/grid/local_grid.hpp"
#include "pena/grid/occupancy_grid.hpp"
#include "pena/io/log_source.hpp"
#include "pena/line_map/line_map.hpp"
#include "pena/line_map/line_segment.hpp"
#include "pena/odometry/laser_odometry.hpp"
#include "pena/pipeline/entity_pipeline.hpp"
#include "pena/slam/keyframe_slam.hpp"

namespace pena::cli::map {

struct MapArgs {
  std::string log;
  std::string trajectory;
  std::string out;
  double resolution_m = 0.05;
  double min_length_m = 0.35;  // shortest segment kept (extraction's min_length_m, library: 0.30)
  double refit_band_m = 0.0;       // LineMap bounded drift (0 = off), docs/line-map.md
  double absorb_distance_m = 0.0;  // LineMap absorption of near-duplicates (with the band)
  std::string bent_scans = "off";   // "level" / "drop": two passes, bent scans levelled / left out
  bool online = false;
  bool slam = true;            // without a trajectory and logged poses: odometry + keyframe SLAM
  bool ignore_logged = false;  // run the odometry (+ SLAM) even when the scans carry poses
  bool quiet = false;
  std::vector<std::string> odometry_settings;  // --set NAME=VALUE, as `pena odometry --set`
  io::ReadOptions read;
};

// The odometry options of the chain that gives the poses (defaults changed by --set).
odometry::LaserOdometryOptions OdometryOptionsOf(const MapArgs& args);
// The entity's chain that gives the poses: those odometry options, without its line map.
pipeline::EntityPipelineOptions ChainOptionsOf(const MapArgs& args);
// The SLAM's options (--set slam.NAME=VALUE applied, validated); throws std::runtime_error or
// std::invalid_argument naming a bad setting.
slam::SlamOptions SlamOptionsOf(const MapArgs& args);

// What the pass over the log produced.
struct MapRun {
  explicit MapRun(const grid::GridOptions& options) : grid(options) {}
  grid::OccupancyGrid grid;
  // The entity pipeline's stages after the odometry, fed each scan at its pose before `grid`
  // takes it: the bent-scan stage (--bent-scans) and, with --online, the local grid that moves
  // with the entity, its lines merged into the entity's line map.
  std::optional<pipeline::EntityPipeline> stages;
  bool online = false;                   // --online: the line map comes from `stages`
  line_map::LineMap map;                 // the merged line map
  std::string source = "map";            // provenance of its segments: the log's entity id
  long extractions = 0;
  std::string pose_source;  // "trajectory", "logged poses", "odometry", "odometry + SLAM"
  std::optional<slam::SlamCounts> slam;  // when the SLAM pass ran
  double slam_wall_s = 0.0;
  // Where the time went in the chain that gave the poses (SLAM pass or odometry), when one ran.
  std::optional<pipeline::PipelineStageTimes> pipeline_stages;
  std::optional<odometry::OdometryStageTimes> odometry_stages;
  std::optional<slam::SlamStageTimes> slam_stages;
  std::optional<double> first_stamp_s;  // of the records read (the log's span)
  double last_stamp_s = 0.0;
  long scans = 0;
  long used = 0;
  long skipped_no_pose = 0;
  long refused = 0;  // Insert said no: pose not finite or grid too large
  // --bent-scans, second pass: the first pass's grid, handed to `stages` when it starts.
  std::optional<grid::OccupancyGrid> reference;
  bool second_pass = false;
  long bent_scans = 0;  // --bent-scans: scans the second pass found bent
  double wall_s = 0.0;
};

// Sizes of the map in bytes: the CSV file, the line map as the services send it (a snapshot in
// the line-map codec), as the gateway packs it for the radio link, and the grid as a PNG.
struct MapBytes {
  std::size_t csv = 0;
  std::size_t codec = 0;
  std::size_t packed = 0;
  std::size_t png = 0;
};

// The SLAM pass: odometry chain and KeyframeSlam over the whole log. nullopt when the log's
// scans carry logged poses (they are used as they are). Fills run.slam and run.slam_wall_s.
std::optional<geometry::Trajectory> RunSlamPass(const MapArgs& args, MapRun& run);

// DIR/lines.csv, lines.svg, lines.dxf.
void WriteLines(const std::filesystem::path& out_dir,
                const std::vector<line_map::LineSegment>& lines);
// DIR/map.png: the grid in grey levels with the lines over it, scale bar and legend.
void WriteMapPicture(const std::filesystem::path& path, const grid::GridImage& image,
                     const std::vector<line_map::LineSegment>& lines);
// The byte sizes of the written map.
MapBytes MeasureBytes(const std::filesystem::path& out_dir, const line_map::LineMap& map,
                      const grid::GridImage& image);
// DIR/summary.json: counts, times (per stage of the chain that gave the poses), peak memory.
void WriteSummaryJson(const std::filesystem::path& path, const MapArgs& args, const MapRun& run,
                      const grid::GridImage& image, const std::vector<line_map::LineSegment>& lines,
                      double extract_s, double write_s, double total_wall_s);
// The summary on stdout.
void PrintSummary(const MapRun& run, const grid::GridImage& image,
                  const std::vector<line_map::LineSegment>& lines, const MapBytes& bytes,
                  double extract_s, double write_s);

}  // namespace pena::cli::map
