// The plan's free wall ends as references (PlanAdaptation::ErrorAtEnds and the internal
// FreeEnds): a corridor with a door, scanned by ray casting the true walls.
#include "pena/localisation/internal/plan_ends.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "pena/localisation/plan_adaptation.hpp"
#include "pena/localisation/virtual_scanner.hpp"

namespace pena::localisation {
namespace {

using geometry::Segment2;

Segment2 Wall(double x1, double y1, double x2, double y2) { return {{x1, y1}, {x2, y2}}; }

// A corridor along x (y 0 to 2) with a 1 m door in its south wall at x 5-6 into a room
// (y -4 to 0, x 3-9).
std::vector<Segment2> Corridor() {
  return {Wall(0, 0, 5, 0),  Wall(6, 0, 20, 0), Wall(0, 2, 20, 2),
          Wall(3, 0, 3, -4), Wall(9, 0, 9, -4), Wall(3, -4, 9, -4)};
}

// The returns of a 361-beam scan of `walls` taken at `truth` facing east, put on the map at
// `estimate` (what the localiser would do with a pose that is off).
scan_matching::Points2 OnMap(const std::vector<Segment2>& walls, const geometry::Pose2& truth,
                             const geometry::Pose2& estimate) {
  const VirtualScanner scanner(walls);
  const sensors::LaserGeometry laser{-std::numbers::pi / 2, std::numbers::pi / 360, 30.0};
  std::vector<float> ranges;
  scanner.CastScan(truth, laser, 361, ranges);
  scan_matching::Points2 points;
  for (std::size_t i = 0; i < ranges.size(); ++i) {
    if (!std::isfinite(ranges[i]) || ranges[i] >= laser.max_range_m) continue;
    const double bearing = laser.angle_min_rad + static_cast<double>(i) * laser.angle_increment_rad;
    points.push_back(geometry::TransformPoint(estimate, Eigen::Vector2d(ranges[i] * std::cos(bearing),
                                                                         ranges[i] * std::sin(bearing))));
  }
  return points;
}

std::optional<Eigen::Vector2d> ErrorAt(const std::vector<Segment2>& plan, const std::vector<Segment2>& truth_walls,
                                       const geometry::Pose2& truth, const geometry::Pose2& estimate,
                                       const PlanAdaptationOptions& options = {}) {
  const PlanAdaptation adaptation(options, plan);
  return adaptation.ErrorAtEnds(OnMap(truth_walls, truth, estimate), Eigen::Vector2d(estimate.x_m, estimate.y_m),
                                estimate.theta_rad);
}

TEST(PlanEnds, OnlyEndsAwayFromOtherSegmentsAreReferences) {
  const std::vector<SegmentEnds> ends = internal::FreeEnds(Corridor(), 0.1);
  // The door's jambs are free; the corridor's west and east ends are too (nothing drawn there).
  EXPECT_TRUE(ends[0].end);
  EXPECT_TRUE(ends[1].start);
  EXPECT_TRUE(ends[0].start);
  // The room's walls meet at corners and on the corridor wall (a T): none of their ends is.
  for (std::size_t i : {3u, 4u, 5u}) {
    EXPECT_FALSE(ends[i].start) << i;
    EXPECT_FALSE(ends[i].end) << i;
  }
}

TEST(PlanEnds, TheDoorJambsMeasureAPoseOffAlongTheCorridor) {
  const geometry::Pose2 truth{4.0, 1.0, 0.0};
  // Right: the jambs agree with the pose.
  const std::optional<Eigen::Vector2d> none = ErrorAt(Corridor(), Corridor(), truth, truth);
  ASSERT_TRUE(none.has_value());
  EXPECT_NEAR(none->x(), 0.0, 0.03);
  EXPECT_NEAR(none->y(), 0.0, 1e-9);  // the jambs say nothing across the corridor
  // 0.25 m too far east, and 0.25 m too far west.
  for (const double off_m : {0.25, -0.25}) {
    const std::optional<Eigen::Vector2d> error =
        ErrorAt(Corridor(), Corridor(), truth, {truth.x_m + off_m, truth.y_m, 0.0});
    ASSERT_TRUE(error.has_value()) << off_m;
    EXPECT_NEAR(error->x(), off_m, 0.03) << off_m;
  }
}

// The ends MeasureEnds takes from a scan of `walls` at `truth` (pose right), by segment and side.
std::vector<std::pair<int, bool>> Measured(const std::vector<Segment2>& plan, const std::vector<Segment2>& walls,
                                           const geometry::Pose2& truth) {
  std::vector<std::pair<int, bool>> out;
  for (const internal::EndMeasurement& m :
       internal::MeasureEnds(plan, internal::FreeEnds(plan, 0.1), OnMap(walls, truth, truth),
                             Eigen::Vector2d(truth.x_m, truth.y_m), truth.theta_rad, PlanEndOptions{})) {
    const Eigen::Vector2d along = plan[static_cast<std::size_t>(m.segment)].end_m - plan[static_cast<std::size_t>(m.segment)].start_m;
    out.emplace_back(m.segment, m.outward.dot(along) > 0.0);  // true: the segment's end, false: its start
  }
  return out;
}

TEST(PlanEnds, AnEndWhoseViewBeyondIsBlockedIsNotMeasured) {
  const geometry::Pose2 truth{4.0, 1.0, 0.0};
  const std::pair<int, bool> near_jamb{0, true}, far_jamb{1, false};
  const auto open = Measured(Corridor(), Corridor(), truth);
  EXPECT_NE(std::find(open.begin(), open.end(), near_jamb), open.end());
  EXPECT_NE(std::find(open.begin(), open.end(), far_jamb), open.end());
  // A post in front of the door just past the near jamb (bearings -45 to -40 deg from the
  // laser): the wall may go on behind it, so the run's last return there says nothing.
  std::vector<Segment2> walls = Corridor();
  walls.push_back(Wall(4.65, 0.45, 4.75, 0.25));
  const auto hidden = Measured(Corridor(), walls, truth);
  EXPECT_EQ(std::find(hidden.begin(), hidden.end(), near_jamb), hidden.end());
  EXPECT_NE(std::find(hidden.begin(), hidden.end(), far_jamb), hidden.end());
}

TEST(PlanEnds, AWallThatGoesOnPastItsDrawnEndIsNotMeasured) {
  // The plan stops the south wall at 5 m (and starts it again at 8 m), but the real wall goes on:
  // its returns run past the drawn end and the laser never sees beyond them.
  const std::vector<Segment2> plan{Wall(0, 0, 5, 0), Wall(8, 0, 20, 0), Wall(0, 2, 20, 2)};
  const std::vector<Segment2> walls{Wall(0, 0, 20, 0), Wall(0, 2, 20, 2)};
  EXPECT_TRUE(Measured(plan, walls, {4.0, 1.0, 0.0}).empty());
  EXPECT_FALSE(ErrorAt(plan, walls, {4.0, 1.0, 0.0}, {4.0, 1.0, 0.0}).has_value());
}

TEST(PlanEnds, EndsThatDisagreeSayNothing) {
  // The plan draws the door 0.3 m wider on its east side: one jamb says 0, the other -0.3.
  const std::vector<Segment2> plan{Wall(0, 0, 5, 0),  Wall(6.3, 0, 20, 0), Wall(0, 2, 20, 2),
                                   Wall(3, 0, 3, -4), Wall(9, 0, 9, -4),   Wall(3, -4, 9, -4)};
  EXPECT_FALSE(ErrorAt(plan, Corridor(), {2.0, 1.0, 0.0}, {2.0, 1.0, 0.0}).has_value());
}

TEST(PlanEnds, OffMeasuresNothing) {
  PlanAdaptationOptions options;
  options.ends.enabled = false;
  EXPECT_FALSE(ErrorAt(Corridor(), Corridor(), {2.0, 1.0, 0.0}, {2.25, 1.0, 0.0}, options).has_value());
}

TEST(PlanEnds, RefusesBadOptionsNamingTheField) {
  const auto refused = [](const std::string& field, auto change) {
    PlanAdaptationOptions options;
    change(options.ends);
    try {
      ValidatePlanAdaptationOptions(options);
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("plan_adaptation.ends." + field), std::string::npos) << e.what();
      return;
    }
    ADD_FAILURE() << field << " was accepted";
  };
  refused("across_m", [](PlanEndOptions& o) { o.across_m = 0.0; });
  refused("window_m", [](PlanEndOptions& o) { o.window_m = -1.0; });
  refused("min_points", [](PlanEndOptions& o) { o.min_points = 1; });
  refused("max_gap_m", [](PlanEndOptions& o) { o.max_gap_m = 0.0; });
  refused("past_rad", [](PlanEndOptions& o) { o.past_rad = 0.0; });
  refused("min_ends", [](PlanEndOptions& o) { o.min_ends = 0; });
  refused("min_error_m", [](PlanEndOptions& o) { o.min_error_m = -0.1; });
}

}  // namespace
}  // namespace pena::localisation
