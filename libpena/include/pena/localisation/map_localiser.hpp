#pragma once
// Virtual scan matching (paper section 4.2): at every reference-scan change of the laser odometry
// a virtual scan is ray-cast from the a priori plan at the expected pose and the real scan is
// matched against it with the correlation matcher. Above the correlation threshold the pose is
// corrected; below it the entity goes on with its odometry and the window grows for the next
// round, which lets it leave the plan and come back. The correction is kept as a transform
// `map_from_odom` on top of the odometry, so the odometry's own reference is never disturbed.

#include <Eigen/Core>
#include <memory>
#include <optional>
#include <vector>

#include "pena/geometry/pose2.hpp"
#include "pena/geometry/segment2.hpp"
#include "pena/localisation/plan_adaptation.hpp"
#include "pena/localisation/virtual_scanner.hpp"
#include "pena/odometry/laser_odometry.hpp"
#include "pena/scan_matching/correlation_scan_matcher.hpp"
#include "pena/sensors/laser_scan.hpp"

namespace pena::localisation {

// Options of the map localiser; validated by the constructor (messages name field and unit).
struct MapLocaliserOptions {
  // The plan is rough: a wider hit threshold than the odometry's, graded so the nearest wall wins.
  scan_matching::CorrelationMatcherOptions matcher{0.10, 0.02, 8, 10, true};
  // Window after a good match (full extents); it grows by window_growth per failed round.
  scan_matching::SearchWindow window{0.40, 0.40, 0.06981317007977318, 0.04, 0.008726646259971648};
  scan_matching::SearchWindow max_window{3.2, 3.2, 0.3490658503988659, 0.04,
                                         0.008726646259971648};  // 3.2 m x 3.2 m x 20 deg
  double window_growth = 1.4;
  double min_score = 0.55;          // eq. 2 fraction of scan points on the virtual scan
  int min_hits = 100;               // the paper's "number of corresponding pairs"
  double reacquire_min_score = 0.8; // stricter after outside-map rounds (a wide window errs more)
  int outside_after_failures = 2;   // consecutive failed rounds that mean "outside the map"
  int oversample = 3;               // virtual beams per real beam (denser reference points)
  double min_range_m = 0.1;         // closer real returns are the carrier's body
  double max_range_m = 15.0;        // real and virtual ranges used, metres
  double degenerate_eigen_ratio = 0.05;  // J^T J translation eigen ratio below it: corridor
  // Rules beyond the paper; each is explained in docs/localisation.md, "Virtual scan matching".
  double along_probe_m = 0.3;       // a degenerate round probes this far along its weak direction ...
  double along_min_drop = 0.05;     // ... and corrects it too if eq. 2 falls by this much
  double recast_min_m = 0.1;        // corrections this large are judged again from where they lead
  double recast_min_rad = 0.017453292519943295;  // ... or this large in heading (1 deg)
  double along_search_m = 1.0;      // search along a degenerate round's weak direction, m either way (0: off)
  double along_search_step_m = 0.25;  // ... in steps of this
  bool along_search_failed = true;  // search also for degenerate rounds that failed
  bool along_search_unique = true;  // the place found must beat every other place two steps away
  bool reacquire_pinned = true;     // a re-acquisition needs a place pinned in every direction
  bool require_interior = true;     // an optimum on the window's x or y edge fails the round
  bool every_scan = false;          // a round at every scan, not only at reference changes
  VirtualScannerOptions scanner;
  PlanAdaptationOptions plan_adaptation;  // walls measured off the drawing are moved (plan_adaptation.hpp)
};

// Where the entity is judged to be with respect to the plan.
enum class MapStatus {
  kUnknown,     // no match round yet
  kInMap,       // the last round matched
  kOutsideMap,  // outside_after_failures rounds in a row failed: on odometry alone
  kReacquired,  // the first good round after being outside
  kRelocalised, // placed anew on the plan after being lost (pipeline::PlanLocalisationOptions::relocalise_after_rounds)
};

// One match round against the plan (at a reference change of the odometry).
struct MapCorrection {
  double stamp_s = 0.0;
  bool accepted = false;                    // the pose was corrected
  MapStatus status = MapStatus::kUnknown;   // status after this round
  geometry::Pose2 map_from_body_before;     // expected pose the virtual scan was cast from
  geometry::Pose2 map_from_body_after;      // corrected pose (= before when not accepted)
  geometry::Pose2 correction;               // body_before_from_body_after
  double score = 0.0;                       // eq. 2 fraction at the best pose
  int hits = 0;                             // scan points on the virtual scan
  int points = 0;                           // real scan points matched
  int virtual_points = 0;                   // virtual scan returns (the plan seen from there)
  double constraint_ratio = 0.0;            // min / max translation eigenvalue of J^T J
  bool degenerate = false;                  // the weak direction was taken from odometry
  double weak_axis_rad = 0.0;               // weak translation direction, body frame (mod pi)
  double along_drop = 0.0;                  // eq. 2 fall along the weak direction (see options)
  double confidence = 0.0;                  // in [0, 1]: score x hit support x constraint
  double window_xy_m = 0.0;                 // searched window side
  double window_theta_rad = 0.0;
  bool recast = false;        // judged again where a search put it (recast_min_m, along_search_m)
  double first_score = 0.0;   // eq. 2 of the first search (= score when not recast)
  bool ends_corrected = false;  // moved back by what the plan's free wall ends agreed on
};

// Matches keyframes of one entity's laser odometry against an a priori plan. Not thread-safe.
class MapLocaliser {
 public:
  // `plan`: segments in the map frame, metres; `map_from_odom`: where the odometry's world frame
  // sits on the plan (from the known start, or a global localisation).
  MapLocaliser(const MapLocaliserOptions& options, std::vector<geometry::Segment2> plan,
               const geometry::Pose2& map_from_odom);
  ~MapLocaliser();
  MapLocaliser(MapLocaliser&&) noexcept;
  MapLocaliser& operator=(MapLocaliser&&) noexcept;

  // Feeds one scan with its odometry estimate (odometry world frame). Runs a round when the
  // reference changed (or `force`, or every_scan), returns it; nullopt when no round ran.
  std::optional<MapCorrection> Update(const sensors::LaserScan& scan,
                                      const odometry::OdometryEstimate& estimate,
                                      bool force = false);

  // The body pose on the plan for an odometry pose: map_from_odom * odom_from_body.
  geometry::Pose2 MapFromBody(const geometry::Pose2& odom_from_body) const;
  // The body pose on the plan at the last scan fed to Update: MapFromBody of its odometry pose.
  const geometry::Pose2& map_from_body() const;
  const geometry::Pose2& map_from_odom() const;
  // Re-anchors the odometry frame on the plan (after a global localisation); status -> unknown.
  void Reset(const geometry::Pose2& map_from_odom);
  // The same for a lost entity placed anew: the next round reports kRelocalised.
  void Relocalise(const geometry::Pose2& map_from_odom);
  MapStatus status() const;
  // Walked distance in metres since the last accepted correction.
  double distance_since_correction_m() const;
  // The plan as matched now: the a priori one with the walls the rounds moved (plan_adaptation).
  const VirtualScanner& scanner() const;
  const std::vector<SegmentShift>& plan_shifts() const;
  const std::vector<PlanOpening>& plan_openings() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// "unknown", "in_map", "outside_map", "reacquired", "relocalised".
const char* ToString(MapStatus status);

}  // namespace pena::localisation
