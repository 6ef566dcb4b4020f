#include "load_streams.hpp"

#include <algorithm>
#include <stdexcept>
#include <variant>

#include "pena/io/log_source.hpp"
#include "pena/pipeline/entity_pipeline.hpp"
#include "pena/pipeline/start_pose.hpp"
#include "to_dds.hpp"

namespace pena::services::bench {
namespace {

// pena-entity's default reference-scan range resolution (EntityConfig.range_quantum_m).
constexpr double kRangeQuantumM = 0.01;

void Shift(pena_dds::Pose2& pose, long dx_mm, long dy_mm) {
  pose.x_m(pose.x_m() + static_cast<double>(dx_mm) * 1e-3);
  pose.y_m(pose.y_m() + static_cast<double>(dy_mm) * 1e-3);
}

void Shift(pena_dds::Segment& segment, long dx_mm, long dy_mm) {
  segment.start_x_mm(segment.start_x_mm() + static_cast<std::int32_t>(dx_mm));
  segment.start_y_mm(segment.start_y_mm() + static_cast<std::int32_t>(dy_mm));
  segment.end_x_mm(segment.end_x_mm() + static_cast<std::int32_t>(dx_mm));
  segment.end_y_mm(segment.end_y_mm() + static_cast<std::int32_t>(dy_mm));
}

}  // namespace

std::vector<std::filesystem::path> MissionEntities(const std::filesystem::path& mission_dir) {
  std::vector<std::filesystem::path> entities;
  std::error_code error;
  for (const auto& entry : std::filesystem::directory_iterator(mission_dir, error)) {
    if (entry.is_directory() && std::filesystem::exists(entry.path() / "sensors.penalog")) {
      entities.push_back(entry.path());
    }
  }
  if (entities.empty()) {
    throw std::runtime_error(mission_dir.string() +
                             ": no entity directory with sensors.penalog (run pena simulate)");
  }
  std::sort(entities.begin(), entities.end());
  return entities;
}

ChainRun RunEntityChain(const std::filesystem::path& entity_dir, double duration_s,
                        const StepCallback& on_step) {
  std::unique_ptr<io::LogSource> source = io::OpenLog(entity_dir / "sensors.penalog");
  std::vector<sensors::SensorRecord> read_ahead;
  while (auto record = source->Next()) {
    read_ahead.push_back(std::move(*record));
    if (std::holds_alternative<sensors::LaserScan>(read_ahead.back())) break;
  }
  if (read_ahead.empty()) throw std::runtime_error(entity_dir.string() + ": empty log");
  const io::LogDescription& description = source->description();
  ChainRun run;
  run.entity_id = description.entity_id.empty() ? entity_dir.filename().string()
                                                : description.entity_id;
  run.kind = description.kind.value_or(sensors::EntityKind::kRobot);
  run.world_from_start = pipeline::StartPoseOf(read_ahead, true).world_from_body;
  run.first_stamp_s = sensors::StampOf(read_ahead.front());
  pipeline::EntityPipeline chain({}, run.kind, run.entity_id, run.world_from_start,
                                 run.first_stamp_s);
  std::size_t ahead = 0;
  while (true) {
    std::optional<sensors::SensorRecord> record;
    if (ahead < read_ahead.size()) {
      record = std::move(read_ahead[ahead++]);
    } else {
      record = source->Next();
    }
    if (!record || sensors::StampOf(*record) - run.first_stamp_s > duration_s) break;
    run.last_stamp_s = std::max(run.last_stamp_s, sensors::StampOf(*record));
    for (const pipeline::ScanStep& step : chain.Add(*record)) on_step(step, chain);
  }
  chain.EndOfInput();  // what the stride spreading still holds
  while (const std::optional<pipeline::ScanStep> step = chain.Next()) on_step(*step, chain);
  return run;
}

SourceStream ComputeSourceStream(const std::filesystem::path& entity_dir, double duration_s) {
  SourceStream stream;
  std::uint64_t pose_seq = 0, scan_seq = 0;
  double first_s = -1.0;
  const ChainRun run = RunEntityChain(
      entity_dir, duration_s,
      [&](const pipeline::ScanStep& step, const pipeline::EntityPipeline& chain) {
        if (first_s < 0.0) first_s = step.odometry.stamp_s;
        ScanSamples samples;
        samples.offset_s = step.odometry.stamp_s - first_s;
        const std::uint64_t version = chain.local_map().version();
        samples.pose = ToDdsPose(step, chain.entity_id(), ++pose_seq, version, 0);
        if (step.odometry.reference_changed) {
          samples.reference_scan =
              ToDdsReferenceScan(step.scan, step, chain.entity_id(),
                                 ++scan_seq, version, kRangeQuantumM);
          ++stream.reference_scans;
        }
        if (step.map_delta) {
          samples.delta = ToDdsLineMapDelta(*step.map_delta, chain.entity_id(), step.odometry.stamp_s);
          ++stream.deltas;
        }
        stream.scans.push_back(std::move(samples));
      });
  stream.entity_id = run.entity_id;
  stream.kind = ToDds(run.kind);
  return stream;
}

void Relabel(ScanSamples& samples, const std::string& entity_id, long dx_mm, long dy_mm) {
  SetBounded(samples.pose.entity_id(), entity_id, "entity_id");
  Shift(samples.pose.world_from_body(), dx_mm, dy_mm);
  Shift(samples.pose.odom_from_body(), dx_mm, dy_mm);
  if (samples.reference_scan) {
    SetBounded(samples.reference_scan->entity_id(), entity_id, "entity_id");
    Shift(samples.reference_scan->world_from_body(), dx_mm, dy_mm);
    Shift(samples.reference_scan->odom_from_body(), dx_mm, dy_mm);
  }
  if (samples.delta) {
    SetBounded(samples.delta->entity_id(), entity_id, "entity_id");
    for (pena_dds::Segment& segment : samples.delta->added()) Shift(segment, dx_mm, dy_mm);
    for (pena_dds::Segment& segment : samples.delta->changed()) Shift(segment, dx_mm, dy_mm);
  }
}

}  // namespace pena::services::bench
