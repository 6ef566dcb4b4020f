// Censi's CSM laser_data as JSON, one object per line, in the field order of CSM's ld_to_json
// (sm/csm/laser_data_json.c) so that CSM's ld_from_json_stream, sm1 and sm2 read it unchanged.
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "pena/io/carmen.hpp"
#include "text_fields.hpp"
#include "text_writer.hpp"

namespace pena::io {
namespace {

// CSM's json-c reads a number as a double only if it has '.' or 'e' ("0" would be an int and
// read back as NaN for min_theta); NaN is written as null, as jo_double_or_null does.
std::string JsonDouble(double value) {
  if (!std::isfinite(value)) return "null";
  std::string text = detail::FormatExact(value);
  if (text.find_first_of(".e") == std::string::npos) text += ".0";
  return text;
}

std::string JsonFloat(float value) {
  if (!std::isfinite(value)) return "null";
  std::string text = detail::FormatExact(value);  // shortest text of the float, not its double
  if (text.find_first_of(".e") == std::string::npos) text += ".0";
  return text;
}

void AppendKey(std::string& json, const char* key) {
  if (json.size() > 1) json += ", ";
  json += '"';
  json += key;
  json += "\": ";
}

template <typename Range, typename Format>
void AppendArray(std::string& json, const char* key, const Range& values, Format format) {
  AppendKey(json, key);
  json += '[';
  bool first = true;
  for (const auto& value : values) {
    if (!first) json += ", ";
    json += format(value);
    first = false;
  }
  json += ']';
}

void AppendPose(std::string& json, const char* key, const std::optional<geometry::Pose2>& pose) {
  const double nan = std::nan("");
  const double values[3] = {pose ? pose->x_m : nan, pose ? pose->y_m : nan,
                            pose ? pose->theta_rad : nan};
  AppendArray(json, key, values, JsonDouble);
}

// {sec, usec} as CSM's struct timeval, rounded to the microsecond.
void AppendTimestamp(std::string& json, double stamp_s) {
  const auto total_us = static_cast<std::int64_t>(std::llround(stamp_s * 1e6));
  const std::int64_t sec = total_us >= 0 ? total_us / 1000000 : -((-total_us + 999999) / 1000000);
  const std::int64_t usec = total_us - sec * 1000000;
  AppendKey(json, "timestamp");
  json += '[' + std::to_string(sec) + ", " + std::to_string(usec) + ']';
}

std::string ScanToJson(const sensors::LaserScan& scan) {
  const std::size_t n = scan.ranges_m.size();
  std::vector<double> theta(n);
  std::vector<float> readings(n);
  std::vector<int> valid(n);
  for (std::size_t i = 0; i < n; ++i) {
    theta[i] = scan.BeamAngle(i);
    valid[i] = scan.IsReturn(i) ? 1 : 0;
    readings[i] = valid[i] ? scan.ranges_m[i] : std::nanf("");
  }
  std::string json = "{";
  AppendKey(json, "nrays");
  json += std::to_string(n);
  AppendKey(json, "min_theta");
  json += JsonDouble(n > 0 ? theta.front() : scan.geometry.angle_min_rad);
  AppendKey(json, "max_theta");
  json += JsonDouble(n > 0 ? theta.back() : scan.geometry.angle_min_rad);
  // CSM's odometry seeds sm1/sm2; fall back to the logged pose where the source has no odometry.
  AppendPose(json, "odometry", scan.odometry_pose ? scan.odometry_pose : scan.logged_pose);
  AppendPose(json, "estimate", scan.logged_pose);
  AppendPose(json, "true_pose", std::nullopt);
  AppendArray(json, "theta", theta, JsonDouble);
  AppendArray(json, "readings", readings, JsonFloat);
  AppendArray(json, "valid", valid, [](int v) { return std::to_string(v); });
  AppendTimestamp(json, scan.stamp_s);
  json += "}\n";
  return json;
}

}  // namespace

struct CsmJsonWriter::Impl {
  explicit Impl(const std::filesystem::path& path) : out(path) {}
  detail::TextWriter out;
};

CsmJsonWriter::CsmJsonWriter(const std::filesystem::path& path)
    : impl_(std::make_unique<Impl>(path)) {}

CsmJsonWriter::~CsmJsonWriter() = default;

void CsmJsonWriter::Write(const sensors::LaserScan& scan) { impl_->out.Put(ScanToJson(scan)); }

}  // namespace pena::io
