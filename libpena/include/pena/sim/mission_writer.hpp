#pragma once
// Writes a simulated mission as a directory (layout in docs/simulator.md):
//   DIR/floorplan.csv, DIR/floorplan.svg, DIR/observed.csv, DIR/apriori.csv (if the scenario has a plan),
//   DIR/<entity>/sensors.penalog, DIR/<entity>/truth.tum, DIR/<entity>/truth.relations.
// The picture DIR/mission.png is rendered by RenderMission (mission_picture.hpp) and encoded by
// the caller, so libpena stays free of image codecs.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "pena/sim/scenario.hpp"
#include "pena/sim/simulator.hpp"
#include "pena/sim/truth_relations.hpp"

namespace pena::sim {

// The files of one entity.
struct EntityFiles {
  std::string id;
  std::filesystem::path log;
  std::filesystem::path truth_tum;
  std::filesystem::path truth_relations;
};

// Every file written.
struct MissionFiles {
  std::filesystem::path floorplan;
  std::filesystem::path observed;
  std::filesystem::path floorplan_svg;  // true walls, observed parts, a priori plan
  std::optional<std::filesystem::path> apriori;
  std::vector<EntityFiles> entities;
};

// Writes the mission under `dir` (created if missing); `producer` goes into each log header.
// Throws std::runtime_error (from the io writers) naming the path on I/O failure.
MissionFiles WriteMission(const Scenario& scenario, const SimulationResult& result,
                          const std::filesystem::path& dir, const std::string& producer,
                          const TruthRelationOptions& relations = {});

}  // namespace pena::sim
