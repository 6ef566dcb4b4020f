#pragma once
// The estimate of plan localisation at one scan: what the entity pipeline's plan stage reports
// and what the offline smoother takes.

#include <optional>

#include "pena/geometry/pose2.hpp"
#include "pena/localisation/global_localiser.hpp"
#include "pena/localisation/map_localiser.hpp"
#include "pena/odometry/laser_odometry.hpp"

namespace pena::localisation {

struct LocalisedPose {
  double stamp_s = 0.0;
  geometry::Pose2 map_from_body;          // on the plan
  odometry::OdometryEstimate odometry;    // the odometry's own estimate (its world frame)
  MapStatus status = MapStatus::kUnknown; // after this scan
  std::optional<MapCorrection> correction;     // a match round ran at this scan
  std::optional<GlobalResult> global;          // the followed global hypotheses at this scan
  bool global_searched = false;                // a whole-plan search ran at this scan
  bool anchored = false;                  // the odometry frame is placed on the plan
  bool relocalising = false;              // lost: global hypotheses are followed (relocalise_after_rounds)
  bool lost = false;                      // judged lost (LostAndFound) after this scan
  bool found = false;                     // found again at this scan (placed anew or by a plan round)
  std::optional<double> lost_search_radius_m;  // a lost search ran at this scan (0: whole plan)
};

}  // namespace pena::localisation
