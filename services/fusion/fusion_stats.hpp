#pragma once
// What pena-fusion counts for the demo report: samples and serialised bytes per topic and entity
// (received and sent), pose latency (writer's source timestamp to this process's take), and the
// poses it received (both the corrected world_from_body and the entity's own odom_from_body, i.e.
// the trajectory without fusion corrections). Written as JSON and TUM files at a clean stop.

#include <cstdint>
#include <filesystem>
#include <map>
#include <mutex>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "pena/geometry/trajectory.hpp"

namespace pena::services {

// Samples and bytes of one (direction, topic, entity).
struct TrafficCount {
  std::uint64_t samples = 0;
  std::uint64_t bytes = 0;  // serialised CDR size (payload as sent on the wire, without RTPS headers)
};

// Thread-safe: the fusion worker and the correction worker both count.
class FusionStats {
 public:
  // Counts one sample; `direction` "received" or "sent"; entity "" for broadcast topics.
  void Count(const std::string& direction, const std::string& topic, const std::string& entity,
             std::uint32_t bytes);
  // One pose: its latency and both poses at its stamp.
  void Pose(const std::string& entity, double latency_s, double stamp_s,
            const geometry::Pose2& world_from_body, const geometry::Pose2& odom_from_body);
  // Free counters ("corrections_sent", "corrections_rejected", ...).
  void Add(const std::string& counter, long value = 1) {
    const std::lock_guard<std::mutex> lock(mutex_);
    counters_[counter] += value;
  }

  // Writes `dir`/fusion_stats.json and `dir`/poses/<entity>_{world,odom}.tum.
  // Also writes traffic.csv (direction,topic,entity,samples,bytes) and pose_latency.csv
  // (entity,samples,p50_ms,p99_ms; last row "all").
  void Write(const std::filesystem::path& dir, double wall_s) const;

 private:
  void WriteCsvs(const std::filesystem::path& dir) const;

  mutable std::mutex mutex_;
  std::map<std::tuple<std::string, std::string, std::string>, TrafficCount> traffic_;
  std::map<std::string, std::vector<double>> latency_s_;
  std::map<std::string, geometry::Trajectory> world_;
  std::map<std::string, geometry::Trajectory> odom_;
  std::map<std::string, long> counters_;
};

// The q-quantile (0..1) of `values` (nearest rank); 0 for none.
double Quantile(std::vector<double> values, double q);

}  // namespace pena::services
