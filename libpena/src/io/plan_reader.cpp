// A priori plans: picks the reader by extension, then scales drawing units to metres and places
// the plan in the mission frame.
#include "pena/io/plan_reader.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <stdexcept>
#include <string>

#include "dxf_plan_reader.hpp"
#include "pena/io/input_error.hpp"
#include "pena/io/line_csv.hpp"
#include "svg_plan_reader.hpp"

namespace pena::io {
namespace {

std::string LowerName(const std::filesystem::path& path) {
  std::string name = path.filename().string();
  std::transform(name.begin(), name.end(), name.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return name;
}

std::vector<geometry::Segment2> ReadDrawing(const std::filesystem::path& path) {
  const std::string name = LowerName(path);
  if (name.ends_with(".csv") || name.ends_with(".csv.gz")) {
    std::vector<geometry::Segment2> segments;
    for (const LineRow& row : ReadLineCsv(path)) segments.push_back(row.segment);
    return segments;
  }
  if (name.ends_with(".svg") || name.ends_with(".svgz")) return detail::ReadSvgPlan(path);
  if (name.ends_with(".dxf")) return detail::ReadDxfPlan(path);
  throw InputError(path, 0, "unknown plan format: expected .csv, .svg or .dxf");
}

}  // namespace

void ValidatePlanOptions(const PlanOptions& options) {
  if (!(options.unit_scale_m > 0.0) || !std::isfinite(options.unit_scale_m)) {
    throw std::invalid_argument(
        "plan.unit_scale_m must be > 0 and finite (m per drawing unit), got " +
        std::to_string(options.unit_scale_m));
  }
  const geometry::Pose2& pose = options.mission_from_plan;
  if (!std::isfinite(pose.x_m) || !std::isfinite(pose.y_m) || !std::isfinite(pose.theta_rad)) {
    throw std::invalid_argument("plan.mission_from_plan must be finite (m, m, rad)");
  }
}

std::vector<geometry::Segment2> ReadPlan(const std::filesystem::path& path,
                                         const PlanOptions& options) {
  ValidatePlanOptions(options);
  std::vector<geometry::Segment2> segments;
  for (const geometry::Segment2& drawn : ReadDrawing(path)) {
    const geometry::Segment2 placed{
        geometry::TransformPoint(options.mission_from_plan, drawn.start_m * options.unit_scale_m),
        geometry::TransformPoint(options.mission_from_plan, drawn.end_m * options.unit_scale_m)};
    if (geometry::Length(placed) > 0.0) segments.push_back(placed);
  }
  return segments;
}

}  // namespace pena::io
