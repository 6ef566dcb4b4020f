#include "fusion_checks.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "pena/line_map/map_delta.hpp"

namespace pena::fusion::detail {

void Require(bool ok, const std::string& what, double value) {
  if (ok) return;
  std::ostringstream text;
  text << what << ", got " << value;
  throw std::invalid_argument(text.str());
}

bool Finite(const geometry::Pose2& pose) {
  return std::isfinite(pose.x_m) && std::isfinite(pose.y_m) && std::isfinite(pose.theta_rad);
}

std::string CheckEntityId(const std::string& entity_id) {
  if (entity_id.empty()) return "entity id is empty";
  if (entity_id.size() > 64) return "entity id " + entity_id.substr(0, 64) + "... exceeds 64 bytes";
  if (entity_id.find(':') != std::string::npos) {
    return "entity id " + entity_id + " contains ':' (it separates provenance keys)";
  }
  if (entity_id == "plan") return "entity id 'plan' is reserved for the a priori plan";
  return {};
}

std::string CheckSegments(const std::vector<line_map::LineSegment>& segments,
                          const std::string& name) {
  for (const line_map::LineSegment& segment : segments) {
    const std::string where = name + ": segment " + std::to_string(segment.id);
    if (segment.id <= 0) return where + ": id must be > 0";
    for (const Eigen::Vector2d& point : {segment.segment.start_m, segment.segment.end_m}) {
      if (!point.allFinite() || point.cwiseAbs().maxCoeff() > line_map::kMaxCoordinateM) {
        return where + ": endpoint not finite or beyond 2000 km";
      }
    }
    for (const double value : {segment.support_cells, segment.observations, segment.rms_error_m}) {
      if (!std::isfinite(value) || value < 0.0) {
        return where + ": support_cells, observations and rms_error_m must be finite and >= 0";
      }
    }
  }
  return {};
}

}  // namespace pena::fusion::detail
