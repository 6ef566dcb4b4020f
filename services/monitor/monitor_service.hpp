#pragma once
// pena-monitor: a passive DDS subscriber for the command post (docs/link-experiments.md). It
// logs every pose it receives with its age (this machine's clock at the take minus the writer's
// source timestamp: both ends of a link experiment share one clock), follows the global map from
// pena-fusion's deltas and snapshots and logs its state (version, segments, digest) after each
// change, and at the end writes the final global map as a line CSV and a JSON summary.

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <variant>

#include "dds_endpoints.hpp"
#include "dds_participant.hpp"
#include "pena/line_map/line_map.hpp"
#include "pena_dds/entityPubSubTypes.h"
#include "pena_dds/global_mapPubSubTypes.h"
#include "work_queue.hpp"

namespace pena::services {

// pena-monitor's options.
struct MonitorOptions {
  DdsOptions dds;
  std::filesystem::path output_dir;  // poses.csv, map.csv, global_map.csv, monitor.json
  double duration_s = 0.0;           // wall seconds to run; 0 = until SIGINT/SIGTERM
};

// Throws std::invalid_argument naming the field.
void ValidateMonitorOptions(const MonitorOptions& options);

// Counts per run (also written to monitor.json).
struct MonitorSummary {
  long poses = 0;
  long poses_missing = 0;  // seq gaps per entity (best-effort samples that never arrived)
  long deltas_applied = 0;
  long deltas_stale = 0;
  long deltas_early = 0;  // arrived before a predecessor (buffered)
  long deltas_invalid = 0;
  long snapshots_used = 0;
  long snapshots_stale = 0;
  long global_maps_refused = 0;  // deltas and snapshots of another map id than "global"
  std::uint64_t map_version = 0;
  std::size_t map_segments = 0;
  std::uint64_t map_digest = 0;
  std::map<std::string, long> bytes_by_topic;  // serialised payload bytes received
};

// The monitor: one participant, three readers, one worker (Run) that owns the map and the files.
class MonitorService {
 public:
  // Creates the participant and readers; throws DdsError or std::invalid_argument.
  explicit MonitorService(MonitorOptions options);
  // Processes samples until the duration passed or a stop signal; then writes the outputs.
  MonitorSummary Run();

 private:
  struct PoseEvent {
    pena_dds::EntityPose sample;
    SampleMeta meta;
  };
  struct DeltaEvent {
    pena_dds::GlobalMapDelta sample;
    SampleMeta meta;
  };
  struct SnapshotEvent {
    pena_dds::GlobalMapSnapshot sample;
    SampleMeta meta;
  };
  using Event = std::variant<PoseEvent, DeltaEvent, SnapshotEvent>;

  void Handle(PoseEvent& event);
  void Handle(DeltaEvent& event);
  void Handle(SnapshotEvent& event);
  // Whether a global map sample is for the map this monitor follows; counts and logs the rest.
  bool ExpectedGlobalMap(const std::string& map_id, const char* what);
  void ApplyBuffered();
  void LogMap(const SampleMeta& meta, const char* kind, std::uint64_t from_version,
              std::uint64_t to_version, const char* status, long bytes);
  void WriteOutputs();

  MonitorOptions options_;
  std::ofstream poses_csv_;
  std::ofstream map_csv_;
  WorkQueue<Event> queue_;
  line_map::LineMap map_;
  std::map<std::uint64_t, line_map::MapDelta> early_;  // by from_version
  std::map<std::string, std::uint64_t> last_seq_;
  MonitorSummary summary_;
  Participant participant_;
  Reader<pena_dds::EntityPosePubSubType> pose_reader_;
  Reader<pena_dds::GlobalMapDeltaPubSubType> delta_reader_;
  Reader<pena_dds::GlobalMapSnapshotPubSubType> snapshot_reader_;
};

}  // namespace pena::services
