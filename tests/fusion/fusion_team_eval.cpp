// fusion_team_eval: feeds a simulated mission (`pena simulate`) into the fusion as the services
// would, and scores the global map (docs/fusion.md). Each entity builds a `pena map`-style local
// map from its truth poses (one occupancy grid, lines extracted every --chunk-s seconds and merged
// into its LineMap); its deltas go, interleaved in time, into a FusionStore journaled in OUT.
// With --restart-every N the store is dropped without a checkpoint and reopened every N inputs
// (a kill -9), and the final map is compared with an uninterrupted run.
//
//   fusion_team_eval MISSION_DIR OUT_DIR [--chunk-s S] [--no-plan] [--unknown-start ID]
//                    [--restart-every N] [--min-lone-support CELLS_PER_M] [--replicate K]
//                    [--batched]
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "pena/eval/line_map_error.hpp"
#include "pena/fusion/fusion_codec.hpp"
#include "pena/fusion/fusion_store.hpp"
#include "pena/grid/occupancy_grid.hpp"
#include "pena/io/line_csv.hpp"
#include "pena/io/line_svg.hpp"
#include "pena/io/log_source.hpp"
#include "pena/io/trajectory_io.hpp"
#include "pena/line_map/line_extractor.hpp"

namespace fs = std::filesystem;
using namespace pena;

namespace {

struct Args {
  fs::path mission, out;
  double chunk_s = 10.0;
  bool plan = true;
  std::string unknown_start;
  std::size_t restart_every = 0;
  double min_lone_support_per_m = fusion::GlobalMapOptions{}.min_lone_support_per_m;
  int replicate = 1;     // each entity sent this many times under other ids (load test)
  bool batched = false;  // rebuild once per round (a Publish input) instead of per delta
};

// One entity: its scans with truth poses, its grid and line map, its frame.
struct EntityRun {
  std::string id;
  std::vector<std::pair<sensors::LaserScan, geometry::Pose2>> scans;  // map frame truth poses
  std::size_t next = 0;
  grid::OccupancyGrid grid;
  line_map::LineMap local;
  geometry::Pose2 entity_from_map;  // identity unless its start is "unknown"
};

std::vector<EntityRun> LoadEntities(const fs::path& mission) {
  std::vector<EntityRun> entities;
  std::vector<fs::path> dirs;
  for (const auto& entry : fs::directory_iterator(mission)) {
    if (fs::exists(entry.path() / "sensors.penalog")) dirs.push_back(entry.path());
  }
  std::sort(dirs.begin(), dirs.end());
  for (const fs::path& dir : dirs) {
    EntityRun run{dir.filename().string(), {}, 0, grid::OccupancyGrid{}, line_map::LineMap{}, {}};
    const geometry::Trajectory truth = io::ReadTum(dir / "truth.tum");
    auto log = io::OpenLog(dir / "sensors.penalog");
    std::size_t at = 0;
    while (auto record = log->Next()) {
      const auto* scan = std::get_if<sensors::LaserScan>(&*record);
      if (scan == nullptr) continue;
      while (at < truth.size() && truth[at].stamp_s < scan->stamp_s - 1e-3) ++at;
      if (at < truth.size() && std::abs(truth[at].stamp_s - scan->stamp_s) <= 1e-3) {
        run.scans.emplace_back(*scan, truth[at].pose);
      }
    }
    entities.push_back(std::move(run));
  }
  return entities;
}

std::vector<line_map::LineSegment> ReadPlan(const fs::path& path) {
  std::vector<line_map::LineSegment> plan;
  for (const io::LineRow& row : io::ReadLineCsv(path)) {
    line_map::LineSegment wall;
    wall.id = static_cast<std::int64_t>(plan.size() + 1);
    wall.segment = row.segment;
    plan.push_back(wall);
  }
  return plan;
}

// The inputs the services would send, in time order.
std::vector<fusion::FusionInput> MissionInputs(const Args& args, std::vector<EntityRun>& entities) {
  std::vector<fusion::FusionInput> inputs;
  if (args.plan) inputs.push_back(fusion::SetPlan{0.0, ReadPlan(args.mission / "apriori.csv")});
  double end_s = 0.0;
  for (EntityRun& e : entities) {
    if (e.id == args.unknown_start) e.entity_from_map = geometry::Inverse(e.scans.front().second);
    std::optional<geometry::Pose2> start;
    if (e.id != args.unknown_start) start = geometry::Pose2{};
    inputs.push_back(fusion::EntityJoin{0.0, e.id, start});
    end_s = std::max(end_s, e.scans.back().first.stamp_s);
  }
  for (double t = args.chunk_s; t < end_s + args.chunk_s; t += args.chunk_s) {
    for (EntityRun& e : entities) {
      bool inserted = false;
      for (; e.next < e.scans.size() && e.scans[e.next].first.stamp_s < t; ++e.next) {
        const auto& [scan, pose] = e.scans[e.next];
        inserted |= e.grid.Insert(scan, geometry::Compose(e.entity_from_map, pose));
      }
      if (!inserted) continue;
      line_map::MapDelta delta = e.local.Integrate(line_map::ExtractLines(e.grid.ToImage()), e.id);
      if (!delta.empty()) inputs.push_back(fusion::LocalDelta{t, e.id, std::move(delta)});
    }
    inputs.push_back(fusion::Tick{t});
  }
  return inputs;
}

// K copies of every entity's join and deltas (ids "<id>_<k>" for k > 0), and a Publish after each
// round when batched: the load of a larger team seeing the same building.
std::vector<fusion::FusionInput> Scaled(const Args& args, const std::vector<fusion::FusionInput>& inputs) {
  std::vector<fusion::FusionInput> scaled;
  for (const fusion::FusionInput& input : inputs) {
    for (int k = 0; k < args.replicate; ++k) {
      const std::string suffix = k == 0 ? "" : "_" + std::to_string(k);
      if (const auto* join = std::get_if<fusion::EntityJoin>(&input)) {
        fusion::EntityJoin copy = *join;
        copy.entity_id += suffix;
        scaled.push_back(copy);
      } else if (const auto* delta = std::get_if<fusion::LocalDelta>(&input)) {
        fusion::LocalDelta copy = *delta;
        copy.entity_id += suffix;
        scaled.push_back(copy);
      } else if (k == 0) {
        scaled.push_back(input);
      }
    }
    if (args.batched && std::holds_alternative<fusion::Tick>(input)) {
      scaled.push_back(fusion::Publish{fusion::StampOf(input)});
    }
  }
  return scaled;
}

std::vector<geometry::Segment2> Walls(const std::vector<line_map::LineSegment>& lines,
                                      bool observed_only) {
  std::vector<geometry::Segment2> walls;
  for (const line_map::LineSegment& line : lines) {
    const bool observed = std::any_of(line.provenance.begin(), line.provenance.end(),
                                      [](const std::string& key) { return key.rfind("plan:", 0) != 0; });
    if (!observed_only || observed) walls.push_back(line.segment);
  }
  return walls;
}

void WriteCsv(const fs::path& path, const std::vector<line_map::LineSegment>& lines, bool observed_only) {
  std::vector<io::LineRow> rows;
  for (const line_map::LineSegment& line : lines) {
    const auto walls = Walls({line}, observed_only);
    if (walls.empty()) continue;
    std::string sources;
    for (const std::string& key : line.provenance) sources += (sources.empty() ? "" : " ") + key;
    char counts[96];
    std::snprintf(counts, sizeof counts, "%.0f,%.0f,%.4f,", line.observations, line.support_cells,
                  line.rms_error_m);
    rows.push_back({line.id, line.segment, counts + sources});
  }
  io::WriteLineCsv(path, rows, ",observations,support_cells,rms_error_m,provenance");
}

void Score(const std::string& name, const std::vector<geometry::Segment2>& map,
           const std::vector<geometry::Segment2>& observed) {
  const eval::LineMapErrorSummary s = eval::EvaluateLineMap(map, observed);
  std::printf("%-34s segments %4zu  coverage %5.1f%%  precision %5.1f%%  segments/wall %.2f\n",
              name.c_str(), s.map_segments, 100.0 * s.coverage, 100.0 * s.precision,
              s.fragmentation);
}

Args Parse(int argc, char** argv) {
  if (argc < 3) {
    throw std::invalid_argument("usage: fusion_team_eval MISSION_DIR OUT_DIR [--chunk-s S] "
                                "[--no-plan] [--unknown-start ID] [--restart-every N] "
                                "[--min-lone-support CELLS_PER_M] [--replicate K] [--batched]");
  }
  Args args;
  args.mission = argv[1];
  args.out = argv[2];
  for (int i = 3; i < argc; ++i) {
    const std::string flag = argv[i];
    const auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw std::invalid_argument(flag + " needs a value");
      return argv[++i];
    };
    if (flag == "--chunk-s") args.chunk_s = std::stod(value());
    else if (flag == "--no-plan") args.plan = false;
    else if (flag == "--unknown-start") args.unknown_start = value();
    else if (flag == "--restart-every") args.restart_every = std::stoul(value());
    else if (flag == "--min-lone-support") args.min_lone_support_per_m = std::stod(value());
    else if (flag == "--replicate") args.replicate = std::stoi(value());
    else if (flag == "--batched") args.batched = true;
    else throw std::invalid_argument("unknown option " + flag);
  }
  if (!(args.chunk_s > 0.0)) throw std::invalid_argument("--chunk-s must be > 0 seconds");
  return args;
}

}  // namespace

int main(int argc, char** argv) try {
  const Args args = Parse(argc, argv);
  std::vector<EntityRun> entities = LoadEntities(args.mission);
  const auto started = std::chrono::steady_clock::now();
  const std::vector<fusion::FusionInput> inputs = Scaled(args, MissionInputs(args, entities));
  const double mapping_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();

  // Uninterrupted, in memory, timed.
  fusion::FusionStoreOptions options;
  options.fusion.global.min_lone_support_per_m = args.min_lone_support_per_m;
  options.fusion.rebuild_on_publish = args.batched;
  fusion::FusionState reference(options.fusion);
  double fusion_s = 0.0, worst_s = 0.0;
  std::vector<double> took;
  for (const fusion::FusionInput& input : inputs) {
    const auto t0 = std::chrono::steady_clock::now();
    const fusion::FusionOutput out = reference.Handle(input);
    const double took_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    fusion_s += took_s;
    took.push_back(took_s);
    worst_s = std::max(worst_s, took_s);
    if (!out.problem.empty()) std::cerr << "refused: " << out.problem << "\n";
    if (out.placement) {
      std::printf("placement attempt at %.0f s: %s, %zu hypotheses, margin %.1f m%s%s\n",
                  fusion::StampOf(input), out.placement->placed ? "placed" : "pending",
                  out.placement->hypotheses.size(), out.placement->margin_m,
                  out.placement->reason.empty() ? "" : ": ", out.placement->reason.c_str());
    }
  }

  // Journaled, with simulated kill -9 and restart.
  fs::remove_all(args.out / "journal");
  std::optional<fusion::FusionStore> store;
  store.emplace(args.out / "journal", options);
  std::size_t restarts = 0;
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    if (args.restart_every > 0 && i > 0 && i % args.restart_every == 0) {
      store.reset();
      store.emplace(args.out / "journal", options);
      ++restarts;
    }
    store->Handle(inputs[i]);
  }
  const bool same = fusion::EncodeCheckpoint(store->state().Checkpoint()) ==
                    fusion::EncodeCheckpoint(reference.Checkpoint());
  std::uintmax_t journal_bytes = 0;
  for (const auto& entry : fs::directory_iterator(args.out / "journal")) journal_bytes += entry.file_size();

  const line_map::MapSnapshot global = reference.GlobalSnapshot();
  WriteCsv(args.out / "global_map.csv", global.segments, false);
  WriteCsv(args.out / "global_map_observed.csv", global.segments, true);
  std::vector<geometry::Segment2> observed;
  for (const io::LineRow& row : io::ReadLineCsv(args.mission / "observed.csv")) observed.push_back(row.segment);
  std::vector<geometry::Segment2> plan, raw_union;
  if (args.plan) plan = Walls(ReadPlan(args.mission / "apriori.csv"), false);
  io::WriteLineSvg(args.out / "global_map.svg",
                   {{"a priori plan", "#999999", 0.15, plan},
                    {"global map", "#d62728", 0.06, Walls(global.segments, false)}});

  std::sort(took.begin(), took.end());
  std::printf("%zu inputs (%zu entities x %d), local mapping %.1f s, fusion %.3f s total, per input "
              "mean %.1f ms, p99 %.1f ms, worst %.1f ms\n",
              inputs.size(), entities.size(), args.replicate, mapping_s, fusion_s,
              1e3 * fusion_s / static_cast<double>(took.size()),
              1e3 * took[std::min(took.size() - 1, took.size() * 99 / 100)], 1e3 * worst_s);
  std::printf("global map version %llu; journal %zu restarts, %ju bytes; state after restarts %s\n",
              static_cast<unsigned long long>(global.version), restarts, journal_bytes,
              same ? "identical to the uninterrupted run" : "DIFFERS from the uninterrupted run");
  for (EntityRun& e : entities) {
    const fusion::EntityStatus* status = reference.entity(e.id);
    if (e.id == args.unknown_start && status != nullptr && status->map_from_entity) {
      const geometry::Pose2 error = geometry::Between(geometry::Inverse(e.entity_from_map),
                                                      *status->map_from_entity);
      std::printf("%s placed with error %.3f m, %.2f deg\n", e.id.c_str(),
                  std::hypot(error.x_m, error.y_m), error.theta_rad * 180.0 / M_PI);
    }
    std::vector<geometry::Segment2> local;
    const geometry::Pose2 map_from_entity = geometry::Inverse(e.entity_from_map);
    for (const line_map::LineSegment& s : e.local.segments()) {
      local.push_back({geometry::TransformPoint(map_from_entity, s.segment.start_m),
                       geometry::TransformPoint(map_from_entity, s.segment.end_m)});
      raw_union.push_back(local.back());
    }
    Score("local map " + e.id + " (vs all walls)", local, observed);
  }
  Score("union of local maps (no merging)", raw_union, observed);
  Score("global map, observed segments", Walls(global.segments, true), observed);
  Score("global map, with plan-only walls", Walls(global.segments, false), observed);
  std::vector<geometry::Segment2> building;
  for (const io::LineRow& row : io::ReadLineCsv(args.mission / "floorplan.csv")) building.push_back(row.segment);
  Score("  the same against floorplan.csv", Walls(global.segments, false), building);
  std::printf("wrote %s/global_map.csv, global_map_observed.csv, global_map.svg, journal/\n",
              args.out.c_str());
  return same ? 0 : 1;
} catch (const std::exception& error) {
  std::cerr << "fusion_team_eval: " << error.what() << "\n";
  return 2;
}
