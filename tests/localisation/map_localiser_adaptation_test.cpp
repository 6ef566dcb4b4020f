// Plan adaptation inside the map localiser, on the office scenario's own a priori plan: the
// corridor wall in front of the archive (plan segments 10 and 11) is drawn 0.4 m north of the
// real one (y 15.4 instead of 15).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "office_plan.hpp"
#include "pena/localisation/map_localiser.hpp"

namespace pena::localisation {
namespace {

// Walks the corridor east from x = 20 to 33 with a perfect odometry, a round every 0.5 m.
MapLocaliser WalkPastTheArchive(const MapLocaliserOptions& options, double* worst_error_m) {
  const sim::Scenario office = testing::OfficeScenario();
  const VirtualScanner truth(office.walls);
  MapLocaliser localiser(options, *office.apriori, {});
  *worst_error_m = 0.0;
  double stamp_s = 0.0;
  for (double x = 20.0; x <= 33.0; x += 0.5) {
    testing::PerfectRound(localiser, truth, {x, 14.0, 0.0}, stamp_s += 0.5);
    const geometry::Pose2 got = localiser.map_from_body();
    *worst_error_m = std::max(*worst_error_m, std::hypot(got.x_m - x, got.y_m - 14.0));
  }
  return localiser;
}

TEST(MapLocaliserPlanAdaptation, TheArchiveWallIsMovedWhereTheScansSeeIt) {
  double worst_m = 0.0;
  const MapLocaliser localiser = WalkPastTheArchive({}, &worst_m);
  ASSERT_EQ(localiser.plan_shifts().size(), 2u);
  for (const SegmentShift& shift : localiser.plan_shifts()) {
    EXPECT_TRUE(shift.index == 10 || shift.index == 11) << shift.index;
    // Segments 10 and 11 run west to east: their left normal points north.
    EXPECT_NEAR(shift.offset_m, -0.4, 0.03) << shift.index;
    const geometry::Segment2& moved = localiser.scanner().segments()[static_cast<std::size_t>(shift.index)];
    EXPECT_NEAR(moved.start_m.y(), 15.0, 0.03);
    EXPECT_NEAR(moved.end_m.y(), 15.0, 0.03);
  }
  EXPECT_LT(worst_m, 0.05);
}

TEST(MapLocaliserPlanAdaptation, OffKeepsThePlanAsDrawn) {
  MapLocaliserOptions options;
  options.plan_adaptation.enabled = false;
  double worst_m = 0.0;
  const MapLocaliser localiser = WalkPastTheArchive(options, &worst_m);
  EXPECT_TRUE(localiser.plan_shifts().empty());
  EXPECT_NEAR(localiser.scanner().segments()[10].start_m.y(), 15.4, 1e-9);
}

}  // namespace
}  // namespace pena::localisation
