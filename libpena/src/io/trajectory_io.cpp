// TUM trajectories and Freiburg relations as text (docs/formats.md).
#include "pena/io/trajectory_io.hpp"

#include <cmath>
#include <string>

#include "gz_line_reader.hpp"
#include "pena/io/input_error.hpp"
#include "text_fields.hpp"
#include "text_writer.hpp"

namespace pena::io {
namespace {

// Six decimals: scan stamps of CARMEN logs have microseconds, so they come back unchanged.
constexpr int kStampDecimals = 6;

// Reads numeric rows of exactly `columns` fields, skipping blank lines and '#' comments, and
// calls `row(values, line_number)` for each. Throws InputError naming the line of a bad row.
template <typename RowFunction>
void ReadRows(const std::filesystem::path& path, std::size_t columns, RowFunction row) {
  detail::GzLineReader reader(path);
  std::string line;
  std::vector<double> values(columns);
  while (reader.ReadLine(line)) {
    const std::vector<std::string_view> fields = detail::SplitWhitespace(line);
    if (fields.empty() || fields[0].front() == '#') continue;
    if (fields.size() != columns) {
      throw InputError(path, reader.line_number(),
                       "expected " + std::to_string(columns) + " fields, found " +
                           std::to_string(fields.size()));
    }
    for (std::size_t i = 0; i < columns; ++i) {
      const std::optional<double> value = detail::ParseDouble(fields[i]);
      if (!value || !std::isfinite(*value)) {
        throw InputError(path, reader.line_number(),
                         "field " + std::to_string(i + 1) + " '" + std::string(fields[i]) +
                             "' is not a finite number");
      }
      values[i] = *value;
    }
    row(values, reader.line_number());
  }
}

std::string Joined(std::initializer_list<std::string> parts) {
  std::string line;
  for (const std::string& part : parts) {
    if (!line.empty()) line += ' ';
    line += part;
  }
  return line + '\n';
}

}  // namespace

void WriteTum(const std::filesystem::path& path, const geometry::Trajectory& trajectory) {
  detail::TextWriter out(path);
  out.Put("# timestamp x y z qx qy qz qw\n");
  for (const geometry::StampedPose2& stamped : trajectory) {
    const double half_yaw = 0.5 * stamped.pose.theta_rad;
    out.Put(Joined({detail::FormatFixed(stamped.stamp_s, kStampDecimals),
                    detail::FormatExact(stamped.pose.x_m), detail::FormatExact(stamped.pose.y_m),
                    "0", "0", "0", detail::FormatExact(std::sin(half_yaw)),
                    detail::FormatExact(std::cos(half_yaw))}));
  }
  out.Close();
}

geometry::Trajectory ReadTum(const std::filesystem::path& path) {
  geometry::Trajectory trajectory;
  ReadRows(path, 8, [&](const std::vector<double>& v, std::size_t line) {
    const double qx = v[4], qy = v[5], qz = v[6], qw = v[7];
    const double norm = std::sqrt(qx * qx + qy * qy + qz * qz + qw * qw);
    if (norm < 1e-9) throw InputError(path, line, "quaternion has zero norm");
    if (!trajectory.empty() && !(v[0] > trajectory.back().stamp_s)) {
      throw InputError(path, line,
                       "timestamp " + detail::FormatFixed(v[0], kStampDecimals) +
                           " is not after the previous pose at " +
                           detail::FormatFixed(trajectory.back().stamp_s, kStampDecimals));
    }
    // Yaw about +z of the (possibly not unit) quaternion; roll and pitch are dropped.
    const double yaw_rad = std::atan2(2.0 * (qw * qz + qx * qy), qw * qw + qx * qx - qy * qy - qz * qz);
    trajectory.push_back({v[0], {v[1], v[2], yaw_rad}});
  });
  return trajectory;
}

void WriteRelations(const std::filesystem::path& path,
                    const std::vector<geometry::Relation>& relations) {
  detail::TextWriter out(path);
  for (const geometry::Relation& relation : relations) {
    out.Put(Joined({detail::FormatFixed(relation.t1_s, kStampDecimals),
                    detail::FormatFixed(relation.t2_s, kStampDecimals),
                    detail::FormatExact(relation.motion.x_m), detail::FormatExact(relation.motion.y_m),
                    "0", "0", "0", detail::FormatExact(relation.motion.theta_rad)}));
  }
  out.Close();
}

std::vector<geometry::Relation> ReadRelations(const std::filesystem::path& path) {
  std::vector<geometry::Relation> relations;
  ReadRows(path, 8, [&](const std::vector<double>& v, std::size_t /*line*/) {
    relations.push_back({v[0], v[1], {v[2], v[3], v[7]}});
  });
  return relations;
}

}  // namespace pena::io
