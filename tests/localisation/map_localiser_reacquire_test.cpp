// A re-acquisition needs a place the scan pins down (MapLocaliserOptions::reacquire_pinned).
#include <gtest/gtest.h>

#include <optional>
#include <vector>

#include "office_plan.hpp"
#include "pena/localisation/map_localiser.hpp"

namespace pena::localisation {
namespace {

// Rounds in a featureless corridor after the entity was judged outside the plan: the grown window
// can place it anywhere along the corridor, so a re-acquisition there is refused
// (MapLocaliserOptions::reacquire_pinned) and the entity stays outside on its odometry.
std::optional<MapCorrection> ReacquireInFeaturelessCorridor(const MapLocaliserOptions& options) {
  const std::vector<geometry::Segment2> plan{{{0.0, 0.0}, {40.0, 0.0}}, {{0.0, 2.0}, {40.0, 2.0}}};
  MapLocaliser localiser(options, plan, {});
  const geometry::Pose2 truth{20.0, 1.0, 0.0};
  // A closet, not on the plan: its scans match nothing there.
  const VirtualScanner closet(std::vector<geometry::Segment2>{
      {{19.6, 0.6}, {20.4, 0.6}}, {{20.4, 0.6}, {20.4, 1.4}}, {{20.4, 1.4}, {19.6, 1.4}}, {{19.6, 1.4}, {19.6, 0.6}}});
  const VirtualScanner corridor(plan);
  odometry::OdometryEstimate estimate;
  estimate.world_from_body = {20.3, 1.2, 0.0};  // 0.3 m along, 0.2 m across
  estimate.reference_changed = true;
  for (int i = 0; i < 2; ++i) {
    estimate.stamp_s = 1.0 + i;
    const auto failed = localiser.Update(closet.Scan(truth, testing::OfficeLaser(), 361, estimate.stamp_s), estimate);
    EXPECT_FALSE(failed && failed->accepted);
  }
  EXPECT_EQ(localiser.status(), MapStatus::kOutsideMap);
  estimate.stamp_s = 3.0;
  return localiser.Update(corridor.Scan(truth, testing::OfficeLaser(), 361, estimate.stamp_s), estimate);
}

TEST(MapLocaliserReacquire, NotInAPlaceFreeAlongOneDirection) {
  const auto round = ReacquireInFeaturelessCorridor({});
  ASSERT_TRUE(round.has_value());
  EXPECT_TRUE(round->degenerate);
  EXPECT_FALSE(round->accepted);
  EXPECT_EQ(round->status, MapStatus::kOutsideMap);
  MapLocaliserOptions off;
  off.reacquire_pinned = false;
  const auto taken = ReacquireInFeaturelessCorridor(off);
  ASSERT_TRUE(taken.has_value());
  EXPECT_TRUE(taken->accepted);
  EXPECT_EQ(taken->status, MapStatus::kReacquired);
}

}  // namespace
}  // namespace pena::localisation
