// fusion_rebuild_eval: rebuilds the global map of a finished pena-fusion run from its state
// directory (the entities' local maps and alignments, as the journal left them) with the global
// map options given here, and scores it against the mission's observed walls like `pena report`
// (docs/fusion.md, "Measuring the global map offline"). The state directory is copied first and
// never written. Not a test: a tool to compare GlobalMapOptions on the same inputs.
//
// MISSION_DIR may also be a line CSV of reference walls (e.g. a single-run SLAM's line map of a
// real log, scripts/fusion-split-log.py).
//
//   fusion_rebuild_eval STATE_DIR MISSION_DIR|WALLS.csv [--min-lone-support CELLS_PER_M]
//       [--lone-duplicate-m M] [--max-lone-error-m M] [--error-radius-m M]
//       [--prior-evidence-m M] [--list-imprecise]
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "pena/eval/line_map_error.hpp"
#include "pena/fusion/fusion_store.hpp"
#include "pena/io/line_csv.hpp"

namespace fs = std::filesystem;
using namespace pena;

namespace {

struct Args {
  fs::path state, mission;
  fusion::GlobalMapOptions global;
  bool list_imprecise = false;
};

Args Parse(int argc, char** argv) {
  if (argc < 3) {
    throw std::invalid_argument(
        "usage: fusion_rebuild_eval STATE_DIR MISSION_DIR [--min-lone-support CELLS_PER_M] "
        "[--lone-duplicate-m M] [--max-lone-error-m M] [--error-radius-m M] "
        "[--prior-evidence-m M] [--list-imprecise]");
  }
  Args args;
  args.state = argv[1];
  args.mission = argv[2];
  for (int i = 3; i < argc; ++i) {
    const std::string flag = argv[i];
    const auto value = [&]() -> double {
      if (i + 1 >= argc) throw std::invalid_argument(flag + " needs a value");
      return std::stod(argv[++i]);
    };
    if (flag == "--min-lone-support") args.global.min_lone_support_per_m = value();
    else if (flag == "--lone-duplicate-m") args.global.lone_duplicate_distance_m = value();
    else if (flag == "--max-lone-error-m") args.global.max_lone_error_m = value();
    else if (flag == "--error-radius-m") args.global.error_radius_m = value();
    else if (flag == "--prior-evidence-m") args.global.prior_evidence_m = value();
    else if (flag == "--list-imprecise") args.list_imprecise = true;
    else throw std::invalid_argument("unknown option " + flag);
  }
  return args;
}

std::vector<geometry::Segment2> ReadSegments(const fs::path& path) {
  std::vector<geometry::Segment2> segments;
  for (const io::LineRow& row : io::ReadLineCsv(path)) segments.push_back(row.segment);
  return segments;
}

// "plan", "ff1 alone", "2+ entities" and "+plan" for a segment's provenance.
std::string ClassOf(const line_map::LineSegment& segment) {
  std::set<std::string> entities;
  bool plan = false;
  for (const std::string& key : segment.provenance) {
    const std::string source = key.substr(0, key.rfind(':'));
    if (source == "plan") plan = true;
    else entities.insert(source);
  }
  if (entities.empty()) return "plan only";
  const std::string who = entities.size() == 1 ? *entities.begin() + " alone" : "2+ entities";
  return who + (plan ? " +plan" : "");
}

void Print(const std::string& name, const eval::LineMapErrorSummary& s) {
  std::printf("%-28s segments %4zu  length %7.1f m  imprecise %6.1f m  coverage %5.1f%%  "
              "precision %5.1f%%  segments/wall %.2f\n",
              name.c_str(), s.map_segments, s.map_length_m, s.map_length_m - s.precise_length_m,
              100.0 * s.coverage, 100.0 * s.precision, s.fragmentation);
}

}  // namespace

int main(int argc, char** argv) try {
  const Args args = Parse(argc, argv);
  const fs::path copy = fs::temp_directory_path() / ("fusion_rebuild_eval_" + std::to_string(::getpid()));
  fs::remove_all(copy);
  fs::copy(args.state, copy, fs::copy_options::recursive);
  fusion::FusionCheckpoint checkpoint;
  {
    const fusion::FusionStore store(copy);
    checkpoint = store.state().Checkpoint();
  }
  fs::remove_all(copy);

  std::vector<fusion::MergeSource> sources;
  sources.push_back({"plan", checkpoint.plan, true});
  for (const auto& entity : checkpoint.entities) {
    if (!entity.status.map_from_entity) continue;
    fusion::MergeSource source{entity.status.entity_id, entity.local.segments};
    const geometry::Pose2 map_from_entity = *entity.status.map_from_entity;
    for (line_map::LineSegment& s : source.segments) {
      s.segment.start_m = geometry::TransformPoint(map_from_entity, s.segment.start_m);
      s.segment.end_m = geometry::TransformPoint(map_from_entity, s.segment.end_m);
    }
    sources.push_back(std::move(source));
  }
  fusion::GlobalMap global(args.global);
  global.Rebuild(sources);
  const std::vector<geometry::Segment2> walls = ReadSegments(
      fs::is_directory(args.mission) ? args.mission / "observed.csv" : args.mission);

  std::vector<geometry::Segment2> observed;
  std::map<std::string, std::vector<geometry::Segment2>> classes;
  for (const line_map::LineSegment& s : global.Snapshot().segments) {
    const std::string name = ClassOf(s);
    classes[name].push_back(s.segment);
    if (name == "plan only") continue;
    observed.push_back(s.segment);
    if (args.list_imprecise) {
      const eval::LineMapErrorSummary one = eval::EvaluateLineMap({s.segment}, walls);
      if (one.precision < 0.999) {
        std::string keys;
        for (const std::string& key : s.provenance) keys += " " + key;
        std::printf("  imprecise %5.2f of %5.2f m  (%6.2f,%6.2f)-(%6.2f,%6.2f) cells/m %5.1f rms "
                    "%.3f:%s\n",
                    one.map_length_m - one.precise_length_m, one.map_length_m,
                    s.segment.start_m.x(), s.segment.start_m.y(), s.segment.end_m.x(),
                    s.segment.end_m.y(), s.support_cells / std::max(1e-9, one.map_length_m),
                    s.rms_error_m, keys.c_str());
      }
    }
  }
  for (const auto& entity : checkpoint.entities) {
    std::vector<geometry::Segment2> local;
    for (const line_map::LineSegment& s : entity.local.segments) local.push_back(s.segment);
    Print("local " + entity.status.entity_id, eval::EvaluateLineMap(local, walls));
  }
  for (const auto& [entity, a] : global.agreement()) {
    std::printf("agreement %-8s %6.1f m merged into corroborated walls, %6.1f m drifted copies: "
                "%.3f, RMS offset %.3f m\n",
                entity.c_str(), a.agree_m, a.disagree_m, a.ratio(), a.rms_offset_m());
  }
  for (const auto& [name, segments] : classes) Print("  " + name, eval::EvaluateLineMap(segments, walls));
  Print("global map (observed)", eval::EvaluateLineMap(observed, walls));
  return 0;
} catch (const std::exception& error) {
  std::cerr << "fusion_rebuild_eval: " << error.what() << "\n";
  return 1;
}
