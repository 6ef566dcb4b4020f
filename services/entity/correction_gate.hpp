#pragma once
// What an entity takes from the DDS domain before it moves its frame (docs/security.md,
// "Defence at the entity"): corrections in increasing sequence only, and only as far as the
// entity's own uncertainty allows, unless an operator sent them. Pure logic: the service feeds it
// what it published and what it received.

#include <Eigen/Core>

#include <cstdint>
#include <map>
#include <string>

#include "pena/geometry/pose2.hpp"

namespace pena::services {

// Validated by CorrectionGate's constructor.
struct CorrectionGateOptions {
  // Bound on the 3-DoF innovation d^T S^-1 d of a correction, S the entity's pose covariance plus
  // the correction's: 16.27 is chi-square's 99.9 % point at 3 degrees of freedom. 0: no bound.
  double max_chi2 = 16.27;
  // The uncertainty assumed for a correction that carries no covariance (the fusion's do not):
  // a scan match is never surer than this (1 sigma).
  double correction_sd_m = 0.05;
  double correction_sd_rad = 0.01;
  std::size_t remembered_references = 512;  // reference scans whose estimate is kept
};

// What to do with a correction.
enum class GateVerdict {
  kApply,
  kOutOfSequence,  // seq not above the last one seen: a replay, or a stale writer; dropped
  kHeld,           // moves the entity further than its uncertainty allows; not applied
};

struct GateResult {
  GateVerdict verdict = GateVerdict::kApply;
  double chi2 = 0.0;    // the innovation's (0 when not bounded)
  std::string message;  // why, for the log (empty for kApply)
};

// "apply", "out_of_sequence", "held".
const char* ToString(GateVerdict verdict);

class CorrectionGate {
 public:
  // Throws std::invalid_argument naming the field for a bad option.
  explicit CorrectionGate(CorrectionGateOptions options = {});

  // The entity's estimate (world frame) and its covariance (x, y, theta) when it published
  // reference scan `seq`: what a pose correction answering that scan is compared with.
  void Remember(std::uint64_t seq, const geometry::Pose2& world_from_body,
                const Eigen::Matrix3d& covariance);

  // A pose correction: the body was at `corrected` when it published reference scan
  // `reference_seq` (0: none). `correction_covariance` zero: unknown (the options' sd instead).
  GateResult CheckPose(std::uint64_t seq, bool from_operator, std::uint64_t reference_seq,
                       const geometry::Pose2& corrected, const Eigen::Matrix3d& correction_covariance);
  // A frame correction: `new_frame` replaces `old_frame` (world_from_frame), moving the entity,
  // now at world_from_body with `covariance`, to new_frame * old_frame^-1 * world_from_body
  // (the correction's uncertainty: the options' sd).
  GateResult CheckFrame(std::uint64_t seq, bool from_operator, const geometry::Pose2& old_frame,
                        const geometry::Pose2& new_frame, const geometry::Pose2& world_from_body,
                        const Eigen::Matrix3d& covariance);
  // A correction whose size is not bounded (an unplaced entity's first frame: it has no world
  // position to keep); only its sequence is checked.
  GateResult CheckSequenceOnly(std::uint64_t seq);

  std::uint64_t last_seq() const { return last_seq_; }
  long out_of_sequence() const { return out_of_sequence_; }
  long held() const { return held_; }

 private:
  struct Estimate {
    geometry::Pose2 world_from_body;
    Eigen::Matrix3d covariance;
  };
  // Sequence first; then the bound on `move` (corrected minus estimate) with covariance S.
  GateResult Decide(std::uint64_t seq, bool from_operator, const Eigen::Vector3d& move,
                    const Eigen::Matrix3d& innovation_covariance, const std::string& what);

  // The correction's covariance, or the options' when it has none.
  Eigen::Matrix3d CorrectionCovariance(const Eigen::Matrix3d& given) const;

  CorrectionGateOptions options_;
  std::uint64_t last_seq_ = 0;
  std::map<std::uint64_t, Estimate> estimates_;  // by reference scan seq
  long out_of_sequence_ = 0;
  long held_ = 0;
};

}  // namespace pena::services
