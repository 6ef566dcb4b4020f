#include "weak_direction.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>

namespace pena::odometry::internal {

std::optional<Eigen::Vector2d> WeakDirection::Apply(const Eigen::Matrix3d& information,
                                                    const geometry::Pose2& prior,
                                                    const Eigen::Vector2d& travel_m, geometry::Pose2& pose) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> solver(information.topLeftCorner<2, 2>());
  const double weak = solver.eigenvalues()(0);
  const double strong = solver.eigenvalues()(1);
  if (!(strong > 0.0)) return std::nullopt;
  const Eigen::Vector2d direction = solver.eigenvectors().col(0);
  const Eigen::Vector2d offset(prior.x_m - pose.x_m, prior.y_m - pose.y_m);  // from the match to the prior
  const bool weakly_constrained = weak < options_.slide_ratio * strong;
  if (!weakly_constrained) {
    // A match that pins the position down checks the prior: after a step back or a stop, which
    // the stride model reads as steps forward, the prior is off until a keyframe re-anchors it.
    prior_held_lately_ = options_.prior_agreed_m <= 0.0 || offset.norm() <= options_.prior_agreed_m;
  }
  const bool degenerate = weak < options_.degenerate_ratio * strong;
  const Eigen::Vector2d shift = direction * direction.dot(offset);
  // Returns that move with the person (floor hits, a bend's floor line ahead) pull a match back
  // against the walk, never ahead; a genuine correction of the prior can go either way.
  const bool backward = shift.dot(travel_m) > 0.0;
  // A prior off across the weak direction (a side step read as a step forward) is off along it too.
  const double across_m = std::abs(solver.eigenvectors().col(1).dot(offset));
  const bool slid = weakly_constrained && shift.norm() > options_.max_slide_m &&
                    (!options_.backward_only || backward) &&
                    (options_.max_across_m <= 0.0 || across_m <= options_.max_across_m) &&
                    prior_held_lately_;
  if (!degenerate && !slid) return std::nullopt;
  pose.x_m += shift.x();
  pose.y_m += shift.y();
  return direction;
}

}  // namespace pena::odometry::internal
