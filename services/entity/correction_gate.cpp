#include "correction_gate.hpp"

#include <Eigen/Cholesky>

#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

namespace pena::services {
namespace {

// The move from `from` to `to` in the world frame: x, y and the wrapped heading change.
Eigen::Vector3d Move(const geometry::Pose2& from, const geometry::Pose2& to) {
  return {to.x_m - from.x_m, to.y_m - from.y_m, geometry::NormalizeAngle(to.theta_rad - from.theta_rad)};
}

std::string Fixed(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.2f", value);
  return text;
}

std::string Describe(const Eigen::Vector3d& move) {
  char text[96];
  std::snprintf(text, sizeof(text), "(%.3f m, %.3f m, %.4f rad)", move.x(), move.y(), move.z());
  return text;
}

}  // namespace

const char* ToString(GateVerdict verdict) {
  switch (verdict) {
    case GateVerdict::kApply: return "apply";
    case GateVerdict::kOutOfSequence: return "out_of_sequence";
    case GateVerdict::kHeld: return "held";
  }
  return "unknown";
}

CorrectionGate::CorrectionGate(CorrectionGateOptions options) : options_(options) {
  if (!(options_.max_chi2 >= 0.0) || !std::isfinite(options_.max_chi2)) {
    throw std::invalid_argument("corrections.max_chi2 must be >= 0 (0: no bound), got " +
                                Fixed(options_.max_chi2));
  }
  if (!(options_.correction_sd_m >= 0.0) || !(options_.correction_sd_rad >= 0.0)) {
    throw std::invalid_argument("corrections.correction_sd_m and correction_sd_rad must be >= 0 (m, rad)");
  }
  if (options_.remembered_references == 0) {
    throw std::invalid_argument("corrections.remembered_references must be >= 1 scans, got 0");
  }
}

void CorrectionGate::Remember(std::uint64_t seq, const geometry::Pose2& world_from_body,
                              const Eigen::Matrix3d& covariance) {
  estimates_[seq] = {world_from_body, covariance};
  while (estimates_.size() > options_.remembered_references) estimates_.erase(estimates_.begin());
}

GateResult CorrectionGate::CheckPose(std::uint64_t seq, bool from_operator, std::uint64_t reference_seq,
                                     const geometry::Pose2& corrected,
                                     const Eigen::Matrix3d& correction_covariance) {
  const auto found = estimates_.find(reference_seq);
  if (found == estimates_.end() && !from_operator) {
    // Nothing to compare with: the fusion answers reference scans, so this is not its answer
    // (or an answer so late that the estimate was forgotten).
    GateResult result = CheckSequenceOnly(seq);
    if (result.verdict != GateVerdict::kApply) return result;
    ++held_;
    return {GateVerdict::kHeld, 0.0,
            "answers reference scan " + std::to_string(reference_seq) +
                ", which this entity did not publish or no longer remembers"};
  }
  if (found == estimates_.end()) return CheckSequenceOnly(seq);
  return Decide(seq, from_operator, Move(found->second.world_from_body, corrected),
                found->second.covariance + CorrectionCovariance(correction_covariance),
                "reference scan " + std::to_string(reference_seq));
}

GateResult CorrectionGate::CheckFrame(std::uint64_t seq, bool from_operator, const geometry::Pose2& old_frame,
                                      const geometry::Pose2& new_frame, const geometry::Pose2& world_from_body,
                                      const Eigen::Matrix3d& covariance) {
  const geometry::Pose2 moved =
      geometry::Compose(new_frame, geometry::Compose(geometry::Inverse(old_frame), world_from_body));
  return Decide(seq, from_operator, Move(world_from_body, moved),
                covariance + CorrectionCovariance(Eigen::Matrix3d::Zero()), "the current pose");
}

Eigen::Matrix3d CorrectionGate::CorrectionCovariance(const Eigen::Matrix3d& given) const {
  if (given.allFinite() && !given.isZero(0.0)) return given;
  const double sd_m = options_.correction_sd_m, sd_rad = options_.correction_sd_rad;
  return Eigen::Vector3d(sd_m * sd_m, sd_m * sd_m, sd_rad * sd_rad).asDiagonal();
}

GateResult CorrectionGate::CheckSequenceOnly(std::uint64_t seq) {
  if (seq <= last_seq_) {
    ++out_of_sequence_;
    return {GateVerdict::kOutOfSequence, 0.0,
            "seq " + std::to_string(seq) + " is not above the last one seen, " + std::to_string(last_seq_) +
                ": a replay, or a writer that is not the fusion"};
  }
  last_seq_ = seq;
  return {};
}

GateResult CorrectionGate::Decide(std::uint64_t seq, bool from_operator, const Eigen::Vector3d& move,
                                  const Eigen::Matrix3d& innovation_covariance, const std::string& what) {
  GateResult result = CheckSequenceOnly(seq);
  if (result.verdict != GateVerdict::kApply || from_operator || options_.max_chi2 == 0.0) return result;
  // Chi-square of the innovation (a Mahalanobis gate): the entity moves only as far as its own
  // uncertainty and the correction's allow.
  const Eigen::LDLT<Eigen::Matrix3d> ldlt(innovation_covariance);
  const bool usable = move.allFinite() && innovation_covariance.allFinite() &&
                      ldlt.info() == Eigen::Success && ldlt.isPositive() && ldlt.vectorD().minCoeff() > 0.0;
  result.chi2 = usable ? move.dot(ldlt.solve(move)) : std::numeric_limits<double>::infinity();
  if (usable && result.chi2 <= options_.max_chi2) return result;
  ++held_;
  result.verdict = GateVerdict::kHeld;
  char chi2[48];
  std::snprintf(chi2, sizeof(chi2), "%.1f", result.chi2);
  result.message = "moves " + what + " by " + Describe(move) +
                   (usable ? ", chi-square " + std::string(chi2) + " > " + Fixed(options_.max_chi2)
                           : ", and the covariance cannot bound it (not positive definite or not finite)");
  return result;
}

}  // namespace pena::services
