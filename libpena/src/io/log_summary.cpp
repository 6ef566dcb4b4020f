#include "pena/io/log_summary.hpp"

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <numbers>
#include <type_traits>
#include <vector>

namespace pena::io {
namespace {

// printf into a std::string (GCC 12 has no std::format).
__attribute__((format(printf, 1, 2))) std::string Printf(const char* format, ...) {
  std::va_list args;
  va_start(args, format);
  std::vector<char> text(256);
  std::va_list copy;
  va_copy(copy, args);
  const int needed = std::vsnprintf(text.data(), text.size(), format, copy);
  va_end(copy);
  if (needed >= static_cast<int>(text.size())) {
    text.resize(static_cast<std::size_t>(needed) + 1);
    std::vsnprintf(text.data(), text.size(), format, args);
  }
  va_end(args);
  return needed < 0 ? std::string() : std::string(text.data());
}

void AddStamp(StreamSummary& stream, double stamp_s) {
  if (stream.count == 0) {
    stream.first_stamp_s = stamp_s;
    stream.last_stamp_s = stamp_s;
  }
  // Streams are interleaved, so the overall range needs min / max, not first / last.
  stream.first_stamp_s = std::min(stream.first_stamp_s, stamp_s);
  stream.last_stamp_s = std::max(stream.last_stamp_s, stamp_s);
  ++stream.count;
}

void AddScan(LaserSummary& laser, const sensors::LaserScan& scan, bool first) {
  const std::size_t beams = scan.ranges_m.size();
  const double last_angle_rad = scan.BeamAngle(beams > 0 ? beams - 1 : 0);
  if (first) {
    laser.min_beams = beams;
    laser.max_beams = beams;
    laser.angle_min_rad = scan.geometry.angle_min_rad;
    laser.angle_max_rad = last_angle_rad;
  }
  laser.min_beams = std::min(laser.min_beams, beams);
  laser.max_beams = std::max(laser.max_beams, beams);
  laser.angle_min_rad = std::min(laser.angle_min_rad, scan.geometry.angle_min_rad);
  laser.angle_max_rad = std::max(laser.angle_max_rad, last_angle_rad);
  laser.max_range_m = std::max(laser.max_range_m, scan.geometry.max_range_m);
  for (std::size_t i = 0; i < beams; ++i) {
    if (scan.IsReturn(i)) {
      laser.longest_return_m = std::max(laser.longest_return_m, double{scan.ranges_m[i]});
    } else {
      ++laser.no_returns;
    }
  }
  laser.beams += beams;
}

// Mean rate over the stream, Hz; 0 when it cannot be told.
double RateHz(const StreamSummary& stream) {
  return stream.count > 1 && stream.duration_s() > 0.0
             ? static_cast<double>(stream.count - 1) / stream.duration_s()
             : 0.0;
}

std::string OrDash(const std::string& text) { return text.empty() ? "-" : text; }

std::string FormatLaser(const LaserSummary& laser) {
  constexpr double kDegPerRad = 180.0 / std::numbers::pi;
  const std::string beams =
      laser.min_beams == laser.max_beams
          ? Printf("%zu beams per scan", laser.max_beams)
          : Printf("%zu..%zu beams per scan", laser.min_beams, laser.max_beams);
  return Printf("Laser:         %s, span %.2f .. %.2f deg, max range %.2f m\n", beams.c_str(),
                laser.angle_min_rad * kDegPerRad, laser.angle_max_rad * kDegPerRad,
                laser.max_range_m) +
         Printf("               longest return %.3f m, no-returns %.1f %% of %zu beams\n",
                laser.longest_return_m, 100.0 * laser.no_return_fraction(), laser.beams);
}

}  // namespace

std::string_view SensorName(std::size_t index) {
  static_assert(
      std::is_same_v<std::variant_alternative_t<0, sensors::SensorRecord>, sensors::LaserScan> &&
          std::is_same_v<std::variant_alternative_t<5, sensors::SensorRecord>,
                         sensors::GroundTruth>,
      "names follow the order of sensors::SensorRecord");
  static constexpr std::array<std::string_view, kSensorKindCount> kNames = {
      "laser", "gyro", "compass", "stride", "wheel_odometry", "ground_truth"};
  return index < kNames.size() ? kNames[index] : "unknown";
}

double LaserSummary::no_return_fraction() const {
  return beams == 0 ? 0.0 : static_cast<double>(no_returns) / static_cast<double>(beams);
}

LogSummary SummarizeLog(LogSource& source) {
  LogSummary summary;
  while (const std::optional<sensors::SensorRecord> record = source.Next()) {
    const double stamp_s = sensors::StampOf(*record);
    if (const auto* scan = std::get_if<sensors::LaserScan>(&*record)) {
      AddScan(summary.laser, *scan, summary.sensors[record->index()].count == 0);
    }
    AddStamp(summary.sensors[record->index()], stamp_s);
    AddStamp(summary.overall, stamp_s);
  }
  // Taken after the pass: the source only knows its path and header fields once opened, and its
  // skip count once read.
  summary.description = source.description();
  summary.skipped_lines = source.skipped();
  return summary;
}

std::string FormatSummary(const LogSummary& summary) {
  const LogDescription& d = summary.description;
  const StreamSummary& all = summary.overall;
  std::string text;
  text += Printf("File:          %s\n", d.path.string().c_str());
  text += Printf("Format:        %s\n", OrDash(d.format).c_str());
  text += Printf("Entity:        %s (%s)\n", OrDash(d.entity_id).c_str(),
                 d.kind ? std::string(sensors::ToString(*d.kind)).c_str() : "kind unknown");
  text += Printf("Mission:       %s\n", OrDash(d.mission).c_str());
  text += Printf("Records:       %zu (malformed lines skipped: %zu)\n", all.count,
                 summary.skipped_lines);
  if (all.count == 0) return text;
  text += Printf("Duration:      %.3f s (stamps %.6f .. %.6f s)\n", all.duration_s(),
                 all.first_stamp_s, all.last_stamp_s);
  text += Printf("Sensors:       %-15s %9s %9s %12s %18s %18s\n", "stream", "count", "rate Hz",
                 "duration s", "first s", "last s");
  for (std::size_t i = 0; i < kSensorKindCount; ++i) {
    const StreamSummary& stream = summary.sensors[i];
    if (stream.count == 0) continue;
    text += Printf("               %-15s %9zu %9.2f %12.3f %18.6f %18.6f\n",
                   std::string(SensorName(i)).c_str(), stream.count, RateHz(stream),
                   stream.duration_s(), stream.first_stamp_s, stream.last_stamp_s);
  }
  if (summary.sensors[0].count > 0) text += FormatLaser(summary.laser);
  return text;
}

}  // namespace pena::io
