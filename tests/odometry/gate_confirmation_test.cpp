// The prior gate's confirmation for people: gated matches count
// towards trusting the scans only while their deviations from the prior agree with each other.
#include "../../libpena/src/odometry/gate_confirmation.hpp"

#include <gtest/gtest.h>

#include <numbers>

namespace pena::odometry::internal {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// loop170 seed 3 at 177 s: an aliased match that stuck to one place in the corridor while the
// prior walked on (0.51, 1.24, 1.49 m from the prior). A plain count trusted it at the third.
TEST(GateConfirmation, AliasedMatchesThatDriftApartAreNeverTrusted) {
  GateConfirmation agreeing(0.1, 3.0 * kDeg);
  GateConfirmation count(0.0, 3.0 * kDeg);
  const geometry::Pose2 deviations[] = {{0.51, 0.0, 0.0}, {1.24, 0.0, 0.0}, {1.49, 0.0, 0.0}};
  bool trusted_agreeing = false, trusted_count = false;
  for (const geometry::Pose2& deviation : deviations) {
    trusted_agreeing = agreeing.Outside(deviation, 3) || trusted_agreeing;
    trusted_count = count.Outside(deviation, 3) || trusted_count;
  }
  EXPECT_FALSE(trusted_agreeing);
  EXPECT_EQ(agreeing.in_row(), 1);  // each disagreeing match starts a new run
  EXPECT_TRUE(trusted_count);
}

// A wrong prior (a stride length off, a slipped wheel): the scans agree on the same offset.
TEST(GateConfirmation, AgreeingDeviationsAreTrustedAtTheConfirmCount) {
  GateConfirmation gate(0.1, 3.0 * kDeg);
  EXPECT_FALSE(gate.Outside({0.40, 0.10, 0.0}, 3));
  EXPECT_FALSE(gate.Outside({0.45, 0.12, 0.5 * kDeg}, 3));
  EXPECT_TRUE(gate.Outside({0.50, 0.10, 1.0 * kDeg}, 3));
  EXPECT_EQ(gate.in_row(), 0);  // trusted: the next run starts afresh
}

TEST(GateConfirmation, DisagreementInPositionOrHeadingRestartsTheRun) {
  GateConfirmation gate(0.1, 3.0 * kDeg);
  EXPECT_FALSE(gate.Outside({0.40, 0.0, 0.0}, 3));
  EXPECT_FALSE(gate.Outside({0.40, 0.0, 5.0 * kDeg}, 3));  // heading 5 deg apart: new run
  EXPECT_EQ(gate.in_row(), 1);
  EXPECT_FALSE(gate.Outside({0.40, 0.0, 6.0 * kDeg}, 3));
  EXPECT_FALSE(gate.Outside({0.40, 0.25, 6.0 * kDeg}, 3));  // 0.25 m apart: new run
  EXPECT_EQ(gate.in_row(), 1);
  EXPECT_FALSE(gate.Outside({0.42, 0.27, 6.0 * kDeg}, 3));
  EXPECT_TRUE(gate.Outside({0.44, 0.25, 6.5 * kDeg}, 3));
}

TEST(GateConfirmation, AMatchInsideTheGateEndsTheRun) {
  GateConfirmation gate(0.1, 3.0 * kDeg);
  EXPECT_FALSE(gate.Outside({0.40, 0.0, 0.0}, 3));
  EXPECT_FALSE(gate.Outside({0.40, 0.0, 0.0}, 3));
  gate.Inside();
  EXPECT_EQ(gate.in_row(), 0);
  EXPECT_FALSE(gate.Outside({0.40, 0.0, 0.0}, 3));
  EXPECT_FALSE(gate.Outside({0.40, 0.0, 0.0}, 3));
  EXPECT_TRUE(gate.Outside({0.40, 0.0, 0.0}, 3));
}

// While the compass is being rejected (a magnetic disturbance bends the prior's heading) the
// deviations change scan to scan; they count without having to agree.
TEST(GateConfirmation, DisagreeingMatchesCountWhenAgreementIsNotAsked) {
  GateConfirmation gate(0.1, 3.0 * kDeg);
  EXPECT_FALSE(gate.Outside({0.40, 0.0, 4.0 * kDeg}, 3, false));
  EXPECT_FALSE(gate.Outside({0.60, 0.1, 8.0 * kDeg}, 3, false));
  EXPECT_TRUE(gate.Outside({0.80, 0.2, 12.0 * kDeg}, 3, false));
}

TEST(GateConfirmation, ConfirmOfOneTrustsEveryMatch) {
  GateConfirmation gate(0.1, 3.0 * kDeg);
  EXPECT_TRUE(gate.Outside({2.0, 0.0, 0.0}, 1));
  EXPECT_TRUE(gate.Outside({-2.0, 0.0, 0.0}, 1));
}

}  // namespace
}  // namespace pena::odometry::internal
