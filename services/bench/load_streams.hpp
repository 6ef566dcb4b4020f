#pragma once
// pena-load's input: what one entity publishes, computed before the timed run. Each source
// entity of a simulated mission goes through the real per-entity chain (pipeline::EntityPipeline,
// the same calls as pena-entity) once; the DDS samples it would publish (pose per scan, reference
// scan at reference changes, line-map delta when the map changed) are kept with their mission
// time, so the timed run only replays them and the load generator's CPU stays small.

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "pena_dds/entity.h"
#include "pena_dds/line_map.h"
#include "pena_dds/scan.h"
#include "pena/pipeline/entity_pipeline.hpp"

namespace pena::services::bench {

// The samples of one laser scan, at offset_s mission seconds after the entity's first scan.
struct ScanSamples {
  double offset_s = 0.0;
  pena_dds::EntityPose pose;
  std::optional<pena_dds::ReferenceScan> reference_scan;
  std::optional<pena_dds::LineMapDelta> delta;
};

// One source entity's stream.
struct SourceStream {
  std::string entity_id;
  pena_dds::EntityKind kind = pena_dds::ENTITY_HUMAN;
  std::vector<ScanSamples> scans;
  long reference_scans = 0;
  long deltas = 0;
};

// One scan of the chain: its step (with the scan) and the chain after it.
using StepCallback =
    std::function<void(const pipeline::ScanStep& step, const pipeline::EntityPipeline& chain)>;

// What RunEntityChain saw of the log.
struct ChainRun {
  std::string entity_id;
  sensors::EntityKind kind = sensors::EntityKind::kRobot;
  geometry::Pose2 world_from_start;
  double first_stamp_s = 0.0;
  double last_stamp_s = 0.0;
};

// Runs pena-entity's chain (default options, start pose as pena-entity takes it) over the first
// `duration_s` mission seconds of `entity_dir`/sensors.penalog, calling `on_step` per scan.
ChainRun RunEntityChain(const std::filesystem::path& entity_dir, double duration_s,
                        const StepCallback& on_step);

// Runs the entity chain on `entity_dir` (a simulated entity: sensors.penalog + truth.tum) for
// the first `duration_s` mission seconds. Throws io::InputError for a bad log.
SourceStream ComputeSourceStream(const std::filesystem::path& entity_dir, double duration_s);

// The entity directories of a simulated mission (sub-directories holding sensors.penalog),
// sorted by name. Throws std::runtime_error naming the directory if there are none.
std::vector<std::filesystem::path> MissionEntities(const std::filesystem::path& mission_dir);

// Renames a stream's samples to `entity_id` and moves everything by (dx_mm, dy_mm) in the
// world frame (whole millimetres, so the line-map quantisation stays exact).
void Relabel(ScanSamples& samples, const std::string& entity_id, long dx_mm, long dy_mm);

}  // namespace pena::services::bench
