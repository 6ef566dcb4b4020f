// The entity's correction gate (services/entity/correction_gate.hpp): corrections apply in
// increasing sequence only, and only as far as the entity's own uncertainty allows, unless an
// operator sent them.
#include <gtest/gtest.h>

#include <cmath>

#include "correction_gate.hpp"

namespace pena::services {
namespace {

// A pose covariance with position sd `sd_m` and heading sd `sd_rad`.
Eigen::Matrix3d Sd(double sd_m, double sd_rad) {
  return Eigen::Vector3d(sd_m * sd_m, sd_m * sd_m, sd_rad * sd_rad).asDiagonal();
}

const Eigen::Matrix3d kUnknown = Eigen::Matrix3d::Zero();

// A gate that assumes no uncertainty for corrections without a covariance, so the figures below
// are the entity's covariance alone.
CorrectionGateOptions Exact() {
  CorrectionGateOptions options;
  options.correction_sd_m = 0.0;
  options.correction_sd_rad = 0.0;
  return options;
}

TEST(CorrectionGate, DropsASeqThatDoesNotIncrease) {
  CorrectionGate gate;
  EXPECT_EQ(gate.CheckSequenceOnly(5).verdict, GateVerdict::kApply);
  const GateResult again = gate.CheckSequenceOnly(5);
  EXPECT_EQ(again.verdict, GateVerdict::kOutOfSequence);
  EXPECT_NE(again.message.find("not above the last one seen, 5"), std::string::npos) << again.message;
  EXPECT_EQ(gate.CheckSequenceOnly(3).verdict, GateVerdict::kOutOfSequence);
  EXPECT_EQ(gate.CheckSequenceOnly(6).verdict, GateVerdict::kApply);
  EXPECT_EQ(gate.out_of_sequence(), 2);
  EXPECT_EQ(gate.last_seq(), 6U);
  // An operator's correction is bounded by nothing, but its sequence still counts.
  EXPECT_EQ(gate.CheckPose(6, true, 0, {50.0, 50.0, 1.0}, kUnknown).verdict, GateVerdict::kOutOfSequence);
}

TEST(CorrectionGate, HoldsAPoseCorrectionBeyondTheEntitysUncertainty) {
  CorrectionGate gate(Exact());
  gate.Remember(7, {10.0, 5.0, 0.0}, Sd(0.1, 0.05));
  // 2 sigma along x: chi-square 4, applied.
  GateResult small = gate.CheckPose(1, false, 7, {10.2, 5.0, 0.0}, kUnknown);
  EXPECT_EQ(small.verdict, GateVerdict::kApply);
  EXPECT_NEAR(small.chi2, 4.0, 1e-9);
  // 10 sigma: chi-square 100, held.
  const GateResult large = gate.CheckPose(2, false, 7, {11.0, 5.0, 0.0}, kUnknown);
  EXPECT_EQ(large.verdict, GateVerdict::kHeld);
  EXPECT_NEAR(large.chi2, 100.0, 1e-9);
  EXPECT_NE(large.message.find("chi-square 100.0 > 16.27"), std::string::npos) << large.message;
  EXPECT_NE(large.message.find("reference scan 7"), std::string::npos) << large.message;
  // The correction's own covariance widens the bound: sd 0.3 m more makes 1 m 3.2 sigma.
  EXPECT_EQ(gate.CheckPose(3, false, 7, {11.0, 5.0, 0.0}, Sd(0.3, 0.05)).verdict, GateVerdict::kApply);
  // A heading across +-pi is a small turn.
  gate.Remember(8, {0.0, 0.0, 3.10}, Sd(0.1, 0.05));
  EXPECT_EQ(gate.CheckPose(4, false, 8, {0.0, 0.0, -3.10}, kUnknown).verdict, GateVerdict::kApply);
  EXPECT_EQ(gate.held(), 1);
}

TEST(CorrectionGate, AppliesAnOperatorsCorrectionBeyondTheBound) {
  CorrectionGate gate;
  gate.Remember(1, {0.0, 0.0, 0.0}, Sd(0.05, 0.01));
  EXPECT_EQ(gate.CheckPose(1, true, 0, {30.0, -4.0, 2.0}, kUnknown).verdict, GateVerdict::kApply);
  EXPECT_EQ(gate.CheckPose(2, true, 1, {30.0, -4.0, 2.0}, kUnknown).verdict, GateVerdict::kApply);
  EXPECT_EQ(gate.CheckFrame(3, true, {}, {5.0, 5.0, 1.0}, {1.0, 0.0, 0.0}, kUnknown).verdict,
            GateVerdict::kApply);
  EXPECT_EQ(gate.held(), 0);
}

TEST(CorrectionGate, HoldsAnAnswerToAReferenceScanItDidNotPublish) {
  CorrectionGateOptions options;
  options.remembered_references = 2;
  CorrectionGate gate(options);
  gate.Remember(1, {0.0, 0.0, 0.0}, Sd(1.0, 1.0));
  gate.Remember(2, {0.0, 0.0, 0.0}, Sd(1.0, 1.0));
  gate.Remember(3, {0.0, 0.0, 0.0}, Sd(1.0, 1.0));
  const GateResult forgotten = gate.CheckPose(10, false, 1, {0.0, 0.0, 0.0}, kUnknown);
  EXPECT_EQ(forgotten.verdict, GateVerdict::kHeld);
  EXPECT_NE(forgotten.message.find("did not publish or no longer remembers"), std::string::npos);
  EXPECT_EQ(gate.CheckPose(11, false, 0, {0.0, 0.0, 0.0}, kUnknown).verdict, GateVerdict::kHeld);
  EXPECT_EQ(gate.CheckPose(12, false, 3, {0.0, 0.0, 0.0}, kUnknown).verdict, GateVerdict::kApply);
}

TEST(CorrectionGate, BoundsAFrameCorrectionByTheMoveOfTheCurrentPose) {
  CorrectionGate gate(Exact());
  const geometry::Pose2 now{10.0, 0.0, 0.0};
  // 5 cm shift of the frame, sd 0.1 m: applied.
  EXPECT_EQ(gate.CheckFrame(1, false, {}, {0.05, 0.0, 0.0}, now, Sd(0.1, 0.05)).verdict, GateVerdict::kApply);
  // 0.05 rad about the frame's origin moves the entity 10 m away by 0.5 m (and 1 heading sigma).
  const GateResult turned = gate.CheckFrame(2, false, {}, {0.0, 0.0, 0.05}, now, Sd(0.1, 0.05));
  EXPECT_EQ(turned.verdict, GateVerdict::kHeld);
  EXPECT_NEAR(turned.chi2, std::pow(10.0 * std::sin(0.05) / 0.1, 2) + std::pow((10.0 * std::cos(0.05) - 10.0) / 0.1, 2) + 1.0,
              1e-6);
  // Relative to the current frame, not to the identity.
  EXPECT_EQ(gate.CheckFrame(3, false, {3.0, 0.0, 0.0}, {3.05, 0.0, 0.0}, now, Sd(0.1, 0.05)).verdict,
            GateVerdict::kApply);
}

TEST(CorrectionGate, AssumesAScanMatchsUncertaintyForACorrectionWithoutOne) {
  // The entity is certain (a known start, no step yet): the correction's assumed 5 cm and 0.01
  // rad bound it alone. 1 cm is 0.2 sigma; 30 cm is 6 sigma (chi-square 36).
  CorrectionGate gate;
  gate.Remember(1, {0.0, 0.0, 0.0}, kUnknown);
  EXPECT_EQ(gate.CheckPose(1, false, 1, {0.01, 0.0, 0.0}, kUnknown).verdict, GateVerdict::kApply);
  const GateResult far = gate.CheckPose(2, false, 1, {0.3, 0.0, 0.0}, kUnknown);
  EXPECT_EQ(far.verdict, GateVerdict::kHeld);
  EXPECT_NEAR(far.chi2, 36.0, 1e-9);
  EXPECT_EQ(gate.CheckFrame(3, false, {}, {0.02, 0.0, 0.0}, {}, kUnknown).verdict, GateVerdict::kApply);
}

TEST(CorrectionGate, HoldsWhatNoCovarianceCanBound) {
  CorrectionGate gate(Exact());
  gate.Remember(1, {0.0, 0.0, 0.0}, kUnknown);
  const GateResult result = gate.CheckPose(1, false, 1, {0.01, 0.0, 0.0}, kUnknown);
  EXPECT_EQ(result.verdict, GateVerdict::kHeld);
  EXPECT_NE(result.message.find("cannot bound"), std::string::npos) << result.message;
  EXPECT_EQ(gate.CheckFrame(2, false, {}, {NAN, 0.0, 0.0}, {}, Sd(0.1, 0.1)).verdict, GateVerdict::kHeld);
  // With the bound off, only the sequence decides.
  CorrectionGateOptions off = Exact();
  off.max_chi2 = 0.0;
  CorrectionGate open(off);
  open.Remember(1, {0.0, 0.0, 0.0}, kUnknown);
  EXPECT_EQ(open.CheckPose(1, false, 1, {100.0, 0.0, 0.0}, kUnknown).verdict, GateVerdict::kApply);
}

TEST(CorrectionGate, RejectsBadOptions) {
  CorrectionGateOptions options;
  options.max_chi2 = -1.0;
  EXPECT_THROW(CorrectionGate{options}, std::invalid_argument);
  options = {};
  options.remembered_references = 0;
  EXPECT_THROW(CorrectionGate{options}, std::invalid_argument);
  options = {};
  options.correction_sd_m = -0.1;
  EXPECT_THROW(CorrectionGate{options}, std::invalid_argument);
}

}  // namespace
}  // namespace pena::services
