#pragma once
// Corrections from the global map (paper section 4.2): an entity's reference scan, taken
// at a pose in its own frame, is matched against a virtual scan ray-cast from the global map
// (localisation::VirtualScanner) at the pose the current alignment predicts. A good match gives a
// new map_from_entity; a poor one leaves the alignment alone (failure is data).

#include <Eigen/Core>
#include <string>
#include <vector>

#include "pena/geometry/pose2.hpp"
#include "pena/geometry/segment2.hpp"
#include "pena/scan_matching/correlation_scan_matcher.hpp"
#include "pena/sensors/laser_scan.hpp"

namespace pena::fusion {

// Options of ComputeCorrection; validated by it (messages name field and unit).
struct CorrectionOptions {
  scan_matching::CorrelationMatcherOptions matcher{0.10, 0.02, 8, 10, true};
  // 1.2 m x 1.2 m x 12 deg around the prediction at 4 cm / 0.5 deg.
  scan_matching::SearchWindow window{1.2, 1.2, 0.20943951023931956, 0.04, 0.008726646259971648};
  double min_score = 0.55;   // eq. 2 fraction of the real points on the virtual scan
  int min_hits = 60;         // and at least this many of them
  int oversample = 3;        // virtual beams per real beam
  double min_range_m = 0.1;  // closer real returns are the carrier's body
  double max_range_m = 15.0; // real and virtual ranges used
};

// A correction the fusion sends back to an entity.
struct FusionCorrection {
  std::string entity_id;
  bool accepted = false;             // false: keep the current alignment
  geometry::Pose2 map_from_entity;   // the new alignment (the old one when not accepted)
  double confidence = 0.0;           // in [0, 1]: score scaled by hit support
  double score = 0.0;                // eq. 2 fraction at the best pose
  int hits = 0;
  int points = 0;
  std::string reason;                // why not accepted
  geometry::Pose2 predicted_map_from_body;  // where the alignment put the body (map frame)
  geometry::Pose2 matched_map_from_body;    // where the match puts it (map frame)
  // J^T J of the match's point-to-line residuals (x_m, y_m, theta_rad) in the predicted body
  // frame: CorrectionFilter turns it into the measurement covariance.
  Eigen::Matrix3d information = Eigen::Matrix3d::Zero();
};

// Matches `scan` (laser at the body origin, taken at entity_from_body) against the virtual scan of
// `map` (map frame) at map_from_entity * entity_from_body.
FusionCorrection ComputeCorrection(const std::string& entity_id, const sensors::LaserScan& scan,
                                   const geometry::Pose2& entity_from_body,
                                   const geometry::Pose2& map_from_entity,
                                   const std::vector<geometry::Segment2>& map,
                                   const CorrectionOptions& options = {});

}  // namespace pena::fusion
