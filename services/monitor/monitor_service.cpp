#include "monitor_service.hpp"

#include <spdlog/spdlog.h>

#include <cstdio>
#include <stdexcept>

#include "from_dds.hpp"
#include "map_digest.hpp"
#include "pena/io/line_csv.hpp"
#include "signals.hpp"
#include "topics.hpp"

namespace pena::services {
namespace {

// Serialised size of a sample as it travels (the fusion counts traffic the same way).
template <class PubSubType>
long SerializedBytes(const typename PubSubType::type& sample) {
  PubSubType type;
  return static_cast<long>(
      type.getSerializedSizeProvider(const_cast<typename PubSubType::type*>(&sample))());
}

std::ofstream OpenCsv(const std::filesystem::path& path, const char* header) {
  std::ofstream out(path);
  if (!out) throw std::invalid_argument("output_dir: cannot write " + path.string());
  out << header << '\n';
  return out;
}

}  // namespace

void ValidateMonitorOptions(const MonitorOptions& options) {
  if (options.output_dir.empty()) throw std::invalid_argument("output_dir: must be given");
  if (!(options.duration_s >= 0.0)) {
    throw std::invalid_argument("duration_s: must be >= 0 s (0 = until a signal)");
  }
}

MonitorService::MonitorService(MonitorOptions options)
    : options_((ValidateMonitorOptions(options), std::move(options))),
      poses_csv_((std::filesystem::create_directories(options_.output_dir),
                  OpenCsv(options_.output_dir / "poses.csv",
                          "recv_ns,entity,seq,stamp_s,source_ns,age_s,bytes"))),
      map_csv_(OpenCsv(options_.output_dir / "map.csv",
                       "recv_ns,kind,from_version,to_version,status,version,segments,digest,"
                       "bytes")),
      participant_(options_.dds, "pena-monitor"),
      pose_reader_(participant_, topics::kPose,
                   [this](pena_dds::EntityPose&& sample, const SampleMeta& meta) {
                     queue_.Push(PoseEvent{std::move(sample), meta});
                   }),
      delta_reader_(participant_, topics::kGlobalMapDelta,
                    [this](pena_dds::GlobalMapDelta&& sample, const SampleMeta& meta) {
                      queue_.Push(DeltaEvent{std::move(sample), meta});
                    }),
      snapshot_reader_(participant_, topics::kGlobalMapSnapshot,
                       [this](pena_dds::GlobalMapSnapshot&& sample, const SampleMeta& meta) {
                         queue_.Push(SnapshotEvent{std::move(sample), meta});
                       }) {}

MonitorSummary MonitorService::Run() {
  const std::int64_t end_ns = options_.duration_s > 0.0
                                  ? NowNs() + static_cast<std::int64_t>(options_.duration_s * 1e9)
                                  : INT64_MAX;
  std::int64_t next_flush_ns = NowNs();
  while (!StopRequested() && NowNs() < end_ns) {
    std::optional<Event> event = queue_.PopFor(std::chrono::milliseconds(100));
    if (event) std::visit([this](auto& e) { Handle(e); }, *event);
    if (NowNs() >= next_flush_ns) {
      poses_csv_.flush();
      map_csv_.flush();
      next_flush_ns = NowNs() + 1'000'000'000;
    }
  }
  while (std::optional<Event> event = queue_.TryPop()) {
    std::visit([this](auto& e) { Handle(e); }, *event);
  }
  WriteOutputs();
  return summary_;
}

void MonitorService::Handle(PoseEvent& event) {
  const pena_dds::EntityPose& pose = event.sample;
  const long bytes = SerializedBytes<pena_dds::EntityPosePubSubType>(pose);
  summary_.bytes_by_topic[topics::kPose.name] += bytes;
  ++summary_.poses;
  auto [last, inserted] = last_seq_.try_emplace(std::string(pose.entity_id()), pose.seq());
  if (!inserted) {
    if (pose.seq() > last->second + 1) {
      summary_.poses_missing += static_cast<long>(pose.seq() - last->second - 1);
    }
    if (pose.seq() > last->second) last->second = pose.seq();
  }
  const double age_s =
      static_cast<double>(event.meta.reception_time_ns - event.meta.source_time_ns) * 1e-9;
  char line[256];
  std::snprintf(line, sizeof line, "%lld,%s,%llu,%.3f,%lld,%.4f,%ld\n",
                static_cast<long long>(event.meta.reception_time_ns), pose.entity_id().c_str(),
                static_cast<unsigned long long>(pose.seq()), pose.stamp_s(),
                static_cast<long long>(event.meta.source_time_ns), age_s, bytes);
  poses_csv_ << line;
}

bool MonitorService::ExpectedGlobalMap(const std::string& map_id, const char* what) {
  if (map_id == kGlobalMapId) return true;
  if (++summary_.global_maps_refused <= 10) {
    spdlog::warn("{} for map id '{}' refused: the monitor takes the '{}' map only", what, map_id,
                 kGlobalMapId);
  }
  return false;
}

void MonitorService::Handle(DeltaEvent& event) {
  if (!ExpectedGlobalMap(event.sample.map_id().to_string(), "global map delta")) return;
  const long bytes = SerializedBytes<pena_dds::GlobalMapDeltaPubSubType>(event.sample);
  summary_.bytes_by_topic[topics::kGlobalMapDelta.name] += bytes;
  line_map::MapDelta delta;
  try {
    delta = FromDds(event.sample);
  } catch (const std::exception& error) {
    spdlog::warn("global map delta {} rejected: {}", event.sample.to_version(), error.what());
    ++summary_.deltas_invalid;
    return;
  }
  const line_map::ApplyResult result = map_.Apply(delta);
  const char* status = "applied";
  switch (result.status) {
    case line_map::ApplyStatus::kApplied:
      ++summary_.deltas_applied;
      break;
    case line_map::ApplyStatus::kStale:
      ++summary_.deltas_stale;
      status = "stale";
      break;
    case line_map::ApplyStatus::kVersionGap:
      ++summary_.deltas_early;
      status = "early";
      early_.emplace(delta.from_version, std::move(delta));
      break;
    case line_map::ApplyStatus::kInvalid:
      ++summary_.deltas_invalid;
      status = "invalid";
      spdlog::warn("global map delta {} invalid: {}", event.sample.to_version(), result.message);
      break;
  }
  if (result.ok()) ApplyBuffered();
  LogMap(event.meta, "delta", event.sample.from_version(), event.sample.to_version(), status,
         bytes);
}

void MonitorService::Handle(SnapshotEvent& event) {
  if (!ExpectedGlobalMap(event.sample.map_id().to_string(), "global map snapshot")) return;
  const long bytes = SerializedBytes<pena_dds::GlobalMapSnapshotPubSubType>(event.sample);
  summary_.bytes_by_topic[topics::kGlobalMapSnapshot.name] += bytes;
  const char* status = "stale";
  if (event.sample.version() > map_.version()) {
    try {
      map_ = line_map::LineMap::FromSnapshot(FromDds(event.sample));
      ++summary_.snapshots_used;
      status = "applied";
      ApplyBuffered();
    } catch (const std::exception& error) {
      spdlog::warn("global map snapshot {} rejected: {}", event.sample.version(), error.what());
      status = "invalid";
    }
  } else {
    ++summary_.snapshots_stale;
  }
  LogMap(event.meta, "snapshot", 0, event.sample.version(), status, bytes);
}

void MonitorService::ApplyBuffered() {
  while (!early_.empty()) {
    auto first = early_.begin();
    if (first->first > map_.version()) return;  // still a gap before it
    line_map::MapDelta delta = std::move(first->second);
    early_.erase(first);
    if (map_.Apply(delta).ok()) ++summary_.deltas_applied;
  }
}

void MonitorService::LogMap(const SampleMeta& meta, const char* kind, std::uint64_t from_version,
                            std::uint64_t to_version, const char* status, long bytes) {
  char line[256];
  std::snprintf(line, sizeof line, "%lld,%s,%llu,%llu,%s,%llu,%zu,%s,%ld\n",
                static_cast<long long>(meta.reception_time_ns), kind,
                static_cast<unsigned long long>(from_version),
                static_cast<unsigned long long>(to_version), status,
                static_cast<unsigned long long>(map_.version()), map_.size(),
                DigestHex(MapDigest(map_.segments())).c_str(), bytes);
  map_csv_ << line;
}

void MonitorService::WriteOutputs() {
  poses_csv_.flush();
  map_csv_.flush();
  const std::vector<line_map::LineSegment> segments = map_.segments();
  std::vector<io::LineRow> rows;
  for (const line_map::LineSegment& line : segments) {
    std::string sources;
    for (const std::string& key : line.provenance) sources += (sources.empty() ? "" : " ") + key;
    char counts[96];
    std::snprintf(counts, sizeof counts, "%.0f,%.0f,%.4f,", line.observations, line.support_cells,
                  line.rms_error_m);
    rows.push_back({line.id, line.segment, counts + sources});
  }
  io::WriteLineCsv(options_.output_dir / "global_map.csv", rows,
                   ",observations,support_cells,rms_error_m,provenance");
  summary_.map_version = map_.version();
  summary_.map_segments = segments.size();
  summary_.map_digest = MapDigest(segments);
  std::ofstream json(options_.output_dir / "monitor.json");
  json << "{\"poses\": " << summary_.poses << ", \"poses_missing\": " << summary_.poses_missing
       << ", \"deltas_applied\": " << summary_.deltas_applied
       << ", \"deltas_stale\": " << summary_.deltas_stale
       << ", \"deltas_early\": " << summary_.deltas_early
       << ", \"deltas_pending\": " << early_.size()
       << ", \"deltas_invalid\": " << summary_.deltas_invalid
       << ", \"snapshots_used\": " << summary_.snapshots_used
       << ", \"snapshots_stale\": " << summary_.snapshots_stale
       << ", \"global_maps_refused\": " << summary_.global_maps_refused
       << ", \"map_version\": " << summary_.map_version
       << ", \"map_segments\": " << summary_.map_segments << ", \"map_digest\": \""
       << DigestHex(summary_.map_digest) << "\", \"bytes_by_topic\": {";
  const char* separator = "";
  for (const auto& [topic, bytes] : summary_.bytes_by_topic) {
    json << separator << '"' << topic << "\": " << bytes;
    separator = ", ";
  }
  json << "}}\n";
}

}  // namespace pena::services
