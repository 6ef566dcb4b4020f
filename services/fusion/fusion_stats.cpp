#include "fusion_stats.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <tuple>

#include "pena/io/trajectory_io.hpp"

namespace pena::services {
namespace {

std::string Quote(const std::string& text) {
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + '"';
}

std::string Number(double value) {
  std::ostringstream out;
  out.precision(9);
  out << (std::isfinite(value) ? value : 0.0);
  return out.str();
}

}  // namespace

double Quantile(std::vector<double> values, double q) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const double rank = std::ceil(q * static_cast<double>(values.size()));
  const std::size_t index = static_cast<std::size_t>(std::max(rank, 1.0)) - 1;
  return values[std::min(index, values.size() - 1)];
}

void FusionStats::Count(const std::string& direction, const std::string& topic,
                        const std::string& entity, std::uint32_t bytes) {
  const std::lock_guard<std::mutex> lock(mutex_);
  TrafficCount& count = traffic_[{direction, topic, entity}];
  ++count.samples;
  count.bytes += bytes;
}

void FusionStats::Pose(const std::string& entity, double latency_s, double stamp_s,
                       const geometry::Pose2& world_from_body,
                       const geometry::Pose2& odom_from_body) {
  const std::lock_guard<std::mutex> lock(mutex_);
  latency_s_[entity].push_back(latency_s);
  geometry::Trajectory& world = world_[entity];
  // Best effort poses arrive in order; a repeated stamp (a restarted entity) is skipped.
  if (!world.empty() && stamp_s <= world.back().stamp_s) return;
  world.push_back({stamp_s, world_from_body});
  odom_[entity].push_back({stamp_s, odom_from_body});
}

void FusionStats::Write(const std::filesystem::path& dir, double wall_s) const {
  const std::lock_guard<std::mutex> lock(mutex_);
  std::filesystem::create_directories(dir / "poses");
  for (const auto& [entity, trajectory] : world_) {
    io::WriteTum(dir / "poses" / (entity + "_world.tum"), trajectory);
    io::WriteTum(dir / "poses" / (entity + "_odom.tum"), odom_.at(entity));
  }
  std::ostringstream json;
  json << "{\n  \"wall_s\": " << Number(wall_s) << ",\n  \"traffic\": [";
  bool first = true;
  for (const auto& [key, count] : traffic_) {
    const auto& [direction, topic, entity] = key;
    json << (first ? "\n" : ",\n") << "    {\"direction\": " << Quote(direction)
         << ", \"topic\": " << Quote(topic) << ", \"entity\": " << Quote(entity)
         << ", \"samples\": " << count.samples << ", \"bytes\": " << count.bytes << "}";
    first = false;
  }
  json << "\n  ],\n  \"pose_latency\": {";
  first = true;
  std::vector<double> all;
  for (const auto& [entity, values] : latency_s_) {
    all.insert(all.end(), values.begin(), values.end());
    json << (first ? "\n" : ",\n") << "    " << Quote(entity) << ": {\"samples\": "
         << values.size() << ", \"p50_ms\": " << Number(1e3 * Quantile(values, 0.5))
         << ", \"p99_ms\": " << Number(1e3 * Quantile(values, 0.99)) << "}";
    first = false;
  }
  json << (first ? "\n" : ",\n") << "    \"all\": {\"samples\": " << all.size()
       << ", \"p50_ms\": " << Number(1e3 * Quantile(all, 0.5))
       << ", \"p99_ms\": " << Number(1e3 * Quantile(all, 0.99)) << "}\n  },\n  \"counters\": {";
  first = true;
  for (const auto& [name, value] : counters_) {
    json << (first ? "\n" : ",\n") << "    " << Quote(name) << ": " << value;
    first = false;
  }
  json << "\n  }\n}\n";
  std::ofstream(dir / "fusion_stats.json") << json.str();
  WriteCsvs(dir);
}

void FusionStats::WriteCsvs(const std::filesystem::path& dir) const {
  std::ofstream traffic(dir / "traffic.csv");
  traffic << "direction,topic,entity,samples,bytes\n";
  for (const auto& [key, count] : traffic_) {
    const auto& [direction, topic, entity] = key;
    traffic << direction << ',' << topic << ',' << entity << ',' << count.samples << ','
            << count.bytes << '\n';
  }
  std::ofstream latency(dir / "pose_latency.csv");
  latency << "entity,samples,p50_ms,p99_ms\n";
  std::vector<double> all;
  for (const auto& [entity, values] : latency_s_) {
    all.insert(all.end(), values.begin(), values.end());
    latency << entity << ',' << values.size() << ',' << Number(1e3 * Quantile(values, 0.5)) << ','
            << Number(1e3 * Quantile(values, 0.99)) << '\n';
  }
  latency << "all," << all.size() << ',' << Number(1e3 * Quantile(all, 0.5)) << ','
          << Number(1e3 * Quantile(all, 0.99)) << '\n';
}

}  // namespace pena::services
