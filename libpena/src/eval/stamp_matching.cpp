#include "pena/eval/stamp_matching.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace pena::eval {

namespace {

bool IsFinite(const geometry::StampedPose2& stamped) {
  return std::isfinite(stamped.stamp_s) && std::isfinite(stamped.pose.x_m) &&
         std::isfinite(stamped.pose.y_m) && std::isfinite(stamped.pose.theta_rad);
}

}  // namespace

void ValidateTrajectory(const geometry::Trajectory& trajectory, std::string_view what) {
  const std::string name(what);
  if (trajectory.empty()) throw std::invalid_argument(name + " is empty");
  for (std::size_t i = 0; i < trajectory.size(); ++i) {
    if (!IsFinite(trajectory[i])) {
      throw std::invalid_argument(name + ": pose " + std::to_string(i) + " is not finite");
    }
    // Binary search needs sorted stamps, and two poses at one stamp make a lookup ambiguous.
    if (i > 0 && trajectory[i].stamp_s <= trajectory[i - 1].stamp_s) {
      std::ostringstream message;
      message.precision(17);
      message << name << ": stamps must be strictly increasing, pose " << i << " has stamp_s "
              << trajectory[i].stamp_s << " after " << trajectory[i - 1].stamp_s;
      throw std::invalid_argument(message.str());
    }
  }
}

std::optional<std::size_t> FindStamp(const geometry::Trajectory& trajectory, double stamp_s,
                                     double tolerance_s) {
  const auto after = std::lower_bound(
      trajectory.begin(), trajectory.end(), stamp_s,
      [](const geometry::StampedPose2& pose, double stamp) { return pose.stamp_s < stamp; });
  std::optional<std::size_t> best;
  double best_gap_s = tolerance_s;
  // The closest stamp is either the first at or after stamp_s, or the one before it.
  for (auto it = after == trajectory.begin() ? after : after - 1;
       it != trajectory.end() && it <= after; ++it) {
    const double gap_s = std::abs(it->stamp_s - stamp_s);
    if (gap_s <= best_gap_s) {
      best_gap_s = gap_s;
      best = static_cast<std::size_t>(it - trajectory.begin());
    }
  }
  return best;
}

}  // namespace pena::eval
