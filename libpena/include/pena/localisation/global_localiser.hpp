#pragma once
// Global localisation on an a priori plan (beyond the paper, whose method needs a known start):
// a branch-and-bound search per tile of the plan, fine refinement, and ranking by beam agreement
// with the virtual scan, which counts beams through a plan wall against a place and so separates
// look-alike stretches of a corridor (docs/localisation.md, "Global localisation").

#include <Eigen/Core>
#include <memory>
#include <optional>
#include <vector>

#include "pena/geometry/pose2.hpp"
#include "pena/geometry/segment2.hpp"
#include "pena/scan_matching/correlation_scan_matcher.hpp"
#include "pena/scan_matching/point_set.hpp"
#include "pena/sensors/laser_scan.hpp"

namespace pena::localisation {

// Options; validated by the constructor (messages name field and unit).
struct GlobalLocaliserOptions {
  double sample_spacing_m = 0.05;  // reference points along every plan segment
  // Coarse whole-plan search: a wide threshold so a coarse grid pose still scores.
  scan_matching::CorrelationMatcherOptions coarse{0.15, 0.05, 0, 10, true};
  double coarse_step_xy_m = 0.10;
  double coarse_step_theta_rad = 0.017453292519943295;  // 1 deg
  double tile_size_m = 3.0;    // one hypothesis per tile and heading sector at most
  int heading_sectors = 4;     // heading sectors per tile, each with its own best pose
  int refine_candidates = 60;  // coarse candidates (best coarse score first) refined and ranked
  double margin_m = 1.0;       // the searched area extends this far beyond the plan's box
  int max_hypotheses = 5;      // ranked hypotheses refined and returned
  // Fine refinement around each coarse pose.
  scan_matching::CorrelationMatcherOptions fine{0.08, 0.02, 8, 10, true};
  scan_matching::SearchWindow fine_window{0.24, 0.24, 0.05235987755982988, 0.02,
                                          0.004363323129985824};  // 24 cm x 24 cm x 3 deg
  // Verify (hypothesis tracking): narrow, so a wrong hypothesis cannot slide along with the walk.
  scan_matching::SearchWindow verify_window{0.12, 0.12, 0.02617993877991494, 0.02,
                                            0.004363323129985824};  // 12 cm x 12 cm x 1.5 deg
  // Final fit of a decided hypothesis on several keyframes at once (GlobalTracker's final_keyframes).
  scan_matching::SearchWindow final_window{1.2, 1.2, 0.05235987755982988, 0.04,
                                           0.004363323129985824};  // 1.2 m x 1.2 m x 3 deg
  double max_range_m = 30.0;   // scan points farther than this are dropped
  double min_range_m = 0.1;    // closer returns are the carrier's body
  double agreement_tolerance_m = 0.5;  // a beam agrees within this of the virtual range (walls drawn off)
};

// Headings a whole-plan search may return: within tolerance_rad of heading_rad (map frame), e.g.
// the compass heading of a firefighter. Without one every heading is searched.
struct HeadingBound {
  double heading_rad = 0.0;
  double tolerance_rad = 0.0;  // > 0; pi or more: every heading
};

// Positions a whole-plan search may return: within radius_m of centre_m (map frame), e.g. around
// the last pose a lost entity was known at. Only the tiles that reach into it are searched.
struct SearchRegion {
  Eigen::Vector2d centre_m = Eigen::Vector2d::Zero();
  double radius_m = 0.0;  // > 0
};

// One candidate pose of the body on the plan.
struct PoseHypothesis {
  geometry::Pose2 map_from_body;
  double score = 0.0;         // eq. 2 fraction with the fine threshold, in [0, 1]
  int hits = 0;               // scan points on the plan
  double coarse_score = 0.0;  // eq. 2 fraction of the coarse search
  double agreement = 0.0;     // (agreeing - see-through beams) / returns (whole-scan Localise; else score)
};

// Beam-by-beam comparison of a real scan with the virtual scan from one pose.
struct BeamAgreement {
  int agree = 0;    // real range within agreement_tolerance_m of the virtual one
  int through = 0;  // real range beyond the virtual one: the beam passed where the plan has a wall
  int beyond = 0;   // of `through`, those ending outside the plan's bounding box
  int returns = 0;  // real returns within the range band
  double fraction() const { return returns == 0 ? 0.0 : static_cast<double>(agree - through) / returns; }
};

// Result of one global localisation; failure is data (empty hypotheses).
struct GlobalResult {
  std::vector<PoseHypothesis> hypotheses;  // best first (by agreement, then score)
  double margin = 0.0;        // best agreement minus the second-best's (1 if only one)
  long candidates_scored = 0; // branch-and-bound nodes scored, over all tiles
};

// Global localisation against one plan. Not thread-safe (the matchers cache their max-grids).
class GlobalLocaliser {
 public:
  GlobalLocaliser(std::vector<geometry::Segment2> plan, const GlobalLocaliserOptions& options = {});
  ~GlobalLocaliser();
  GlobalLocaliser(GlobalLocaliser&&) noexcept;
  GlobalLocaliser& operator=(GlobalLocaliser&&) noexcept;

  // Ranked poses of scan points given in the body frame (point score only).
  GlobalResult Localise(const scan_matching::Points2& scan_body) const;
  // Ranked poses of a laser scan (laser at the body origin), verified beam by beam.
  GlobalResult Localise(const sensors::LaserScan& scan) const;
  // The same keeping up to `max_hypotheses` (instead of the option's) for hypothesis tracking.
  GlobalResult Localise(const sensors::LaserScan& scan, int max_hypotheses) const;
  // The same searching only headings within `bound`; nullopt: every heading.
  GlobalResult Localise(const sensors::LaserScan& scan, int max_hypotheses,
                        const std::optional<HeadingBound>& bound) const;
  // The same searching only positions within `region`; nullopt: the whole plan.
  GlobalResult Localise(const sensors::LaserScan& scan, int max_hypotheses, const std::optional<HeadingBound>& bound,
                        const std::optional<SearchRegion>& region) const;
  // True if `region` covers the plan's bounding box (a search in it is a whole-plan search).
  bool Covers(const SearchRegion& region) const;
  // One hypothesis checked at a new scan: fine match in verify_window, then beam agreement.
  PoseHypothesis Verify(const sensors::LaserScan& scan, const geometry::Pose2& map_from_body_guess) const;

  // Fine match in final_window of points merged from several scans (body frame of the latest).
  PoseHypothesis FitMerged(const scan_matching::Points2& points_body, const geometry::Pose2& map_from_body_guess) const;

  // The real scan against the virtual scan from `map_from_body` (laser at the body origin).
  BeamAgreement Agreement(const sensors::LaserScan& scan, const geometry::Pose2& map_from_body) const;

  // True if the position lies inside the plan's bounding box (segment end points).
  bool Inside(const geometry::Pose2& map_from_body) const;
  // True if the straight walk between the two positions crosses a plan wall.
  bool Blocked(const geometry::Pose2& from, const geometry::Pose2& to) const;

  // The plan's reference points (map frame), spaced sample_spacing_m along each segment.
  const scan_matching::Points2& reference() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Points every `spacing_m` along each segment (both ends included), map frame.
// Same place: closer than 0.5 m and 10 deg.
bool SamePlace(const geometry::Pose2& a, const geometry::Pose2& b);

scan_matching::Points2 SampleSegments(const std::vector<geometry::Segment2>& segments,
                                      double spacing_m);

}  // namespace pena::localisation
