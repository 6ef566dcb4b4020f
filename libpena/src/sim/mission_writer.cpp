#include "pena/sim/mission_writer.hpp"

#include <stdexcept>
#include <string>

#include "pena/io/line_csv.hpp"
#include "pena/io/line_svg.hpp"
#include "pena/io/mission_log.hpp"
#include "pena/io/trajectory_io.hpp"

namespace pena::sim {
namespace {

std::vector<io::LineRow> Rows(const std::vector<geometry::Segment2>& segments) {
  std::vector<io::LineRow> rows;
  rows.reserve(segments.size());
  for (std::size_t i = 0; i < segments.size(); ++i) {
    rows.push_back({static_cast<std::int64_t>(i), segments[i], ""});
  }
  return rows;
}

// Entity ids become directory names: keep them to one plain path component.
void CheckEntityId(const std::string& id) {
  const bool plain = !id.empty() && id != "." && id != ".." &&
                     id.find_first_not_of(
                         "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                         "0123456789_-.") == std::string::npos;
  if (!plain)
    throw std::invalid_argument("mission_writer: entity id '" + id + "' is not a plain name");
}

EntityFiles WriteEntity(const EntityRecording& entity, const std::string& mission,
                        const std::filesystem::path& dir, const std::string& producer,
                        const TruthRelationOptions& relation_options) {
  CheckEntityId(entity.id);
  EntityFiles files{entity.id, dir / "sensors.penalog", dir / "truth.tum", dir / "truth.relations"};
  std::filesystem::create_directories(dir);
  io::MissionLogHeader header;
  header.mission = mission;
  header.entity_id = entity.id;
  header.kind = entity.kind;
  header.laser = entity.laser;
  header.laser_height_m = entity.laser_height_m;
  header.producer = producer;
  io::MissionLogWriter writer(files.log, header);
  for (const sensors::SensorRecord& record : entity.records) writer.Write(record);
  writer.Close();
  geometry::Trajectory truth;
  truth.reserve(entity.truth.size());
  for (const sensors::GroundTruth& pose : entity.truth) {
    truth.push_back({pose.stamp_s, pose.world_from_body});
  }
  io::WriteTum(files.truth_tum, truth);
  io::WriteRelations(files.truth_relations, TruthRelations(truth, relation_options));
  return files;
}

// The plan for people: true walls, the parts the lasers saw, and the a priori plan if any.
std::vector<io::SvgLayer> PlanLayers(const Scenario& scenario, const SimulationResult& result) {
  std::vector<io::SvgLayer> layers{{"true walls", "#9e9e9e", 0.12, scenario.walls}};
  io::SvgLayer observed{"observed by the lasers", "#1565c0", 0.06, {}};
  for (const ObservedSegment& segment : result.observed) observed.segments.push_back(segment.segment);
  layers.push_back(std::move(observed));
  if (scenario.apriori) layers.push_back({"a priori plan", "#ef6c00", 0.04, *scenario.apriori});
  return layers;
}

}  // namespace

MissionFiles WriteMission(const Scenario& scenario, const SimulationResult& result,
                          const std::filesystem::path& dir, const std::string& producer,
                          const TruthRelationOptions& relations) {
  std::filesystem::create_directories(dir);
  MissionFiles files;
  files.floorplan = dir / "floorplan.csv";
  io::WriteLineCsv(files.floorplan, Rows(scenario.walls));
  files.observed = dir / "observed.csv";
  std::vector<io::LineRow> observed;
  for (const ObservedSegment& segment : result.observed) {
    observed.push_back({static_cast<std::int64_t>(observed.size()), segment.segment,
                        std::to_string(segment.wall_index)});
  }
  io::WriteLineCsv(files.observed, observed, ",wall_id");
  if (scenario.apriori) {
    files.apriori = dir / "apriori.csv";
    io::WriteLineCsv(*files.apriori, Rows(*scenario.apriori));
  }
  files.floorplan_svg = dir / "floorplan.svg";
  io::WriteLineSvg(files.floorplan_svg, PlanLayers(scenario, result));
  for (const EntityRecording& entity : result.entities) {
    files.entities.push_back(
        WriteEntity(entity, result.mission, dir / entity.id, producer, relations));
  }
  return files;
}

}  // namespace pena::sim
