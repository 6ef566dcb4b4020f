#include "pena/slam/pose_graph.hpp"

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <cmath>
#include <stdexcept>
#include <string>

namespace pena::slam {
namespace {

using geometry::Pose2;

// Cauchy kernel scale in Mahalanobis units: a loop closure 3 sigma off keeps half its weight.
constexpr double kCauchyScale2 = 9.0;
// Weight that pins node 0 (the known start) in the normal equations.
constexpr double kAnchorWeight = 1e10;

Eigen::Matrix2d Rotation(double theta_rad) {
  const double c = std::cos(theta_rad);
  const double s = std::sin(theta_rad);
  return (Eigen::Matrix2d() << c, -s, s, c).finished();
}

// Jacobians of EdgeError with respect to (x, y, theta) of `from` and of `to`.
void EdgeJacobians(const Pose2& from, const Pose2& to, const Pose2& z, Eigen::Matrix3d& j_from,
                   Eigen::Matrix3d& j_to) {
  const Eigen::Matrix2d rz_t = Rotation(z.theta_rad).transpose();
  const Eigen::Matrix2d ri_t = Rotation(from.theta_rad).transpose();
  const double c = std::cos(from.theta_rad);
  const double s = std::sin(from.theta_rad);
  const Eigen::Matrix2d dri_t = (Eigen::Matrix2d() << -s, c, -c, -s).finished();
  const Eigen::Vector2d dt(to.x_m - from.x_m, to.y_m - from.y_m);
  j_from.setZero();
  j_to.setZero();
  j_from.block<2, 2>(0, 0) = -rz_t * ri_t;
  j_from.block<2, 1>(0, 2) = rz_t * dri_t * dt;
  j_from(2, 2) = -1.0;
  j_to.block<2, 2>(0, 0) = rz_t * ri_t;
  j_to(2, 2) = 1.0;
}

double HeadingError(const std::vector<Pose2>& nodes, const HeadingPrior& prior) {
  return geometry::NormalizeAngle(nodes[static_cast<std::size_t>(prior.node)].theta_rad -
                                  prior.theta_rad);
}

// The normal equations H dx = -b of all edges and heading priors at the current estimate, node 0
// pinned.
void Linearize(const std::vector<Pose2>& nodes, const std::vector<PoseEdge>& edges,
               const std::vector<HeadingPrior>& heading_priors, Eigen::SparseMatrix<double>& h,
               Eigen::VectorXd& b) {
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(edges.size() * 36 + 3);
  for (const PoseEdge& edge : edges) {
    const Pose2& from = nodes[static_cast<std::size_t>(edge.from)];
    const Pose2& to = nodes[static_cast<std::size_t>(edge.to)];
    const Eigen::Vector3d e = EdgeError(from, to, edge.from_from_to);
    const double chi2 = e.dot(edge.information * e);
    const double weight = edge.robust ? 1.0 / (1.0 + chi2 / kCauchyScale2) : 1.0;
    Eigen::Matrix3d jacobians[2];
    EdgeJacobians(from, to, edge.from_from_to, jacobians[0], jacobians[1]);
    const int index[2] = {edge.from, edge.to};
    for (int a = 0; a < 2; ++a) {
      b.segment<3>(3 * index[a]) += weight * jacobians[a].transpose() * edge.information * e;
      for (int c = 0; c < 2; ++c) {
        const Eigen::Matrix3d block =
            weight * jacobians[a].transpose() * edge.information * jacobians[c];
        for (int r = 0; r < 3; ++r) {
          for (int k = 0; k < 3; ++k) {
            triplets.emplace_back(3 * index[a] + r, 3 * index[c] + k, block(r, k));
          }
        }
      }
    }
  }
  for (const HeadingPrior& prior : heading_priors) {
    const int row = 3 * prior.node + 2;  // d error / d theta = 1
    b(row) += prior.information * HeadingError(nodes, prior);
    triplets.emplace_back(row, row, prior.information);
  }
  for (int r = 0; r < 3; ++r) triplets.emplace_back(r, r, kAnchorWeight);
  h.setFromTriplets(triplets.begin(), triplets.end());
}

}  // namespace

Eigen::Vector3d EdgeError(const Pose2& from, const Pose2& to, const Pose2& from_from_to) {
  const Eigen::Vector2d dt(to.x_m - from.x_m, to.y_m - from.y_m);
  const Eigen::Vector2d t_local = Rotation(from.theta_rad).transpose() * dt;
  const Eigen::Vector2d t_error =
      Rotation(from_from_to.theta_rad).transpose() *
      (t_local - Eigen::Vector2d(from_from_to.x_m, from_from_to.y_m));
  return {t_error.x(), t_error.y(),
          geometry::NormalizeAngle(to.theta_rad - from.theta_rad - from_from_to.theta_rad)};
}

int PoseGraph::AddNode(const Pose2& world_from_node) {
  nodes_.push_back(world_from_node);
  return static_cast<int>(nodes_.size()) - 1;
}

void PoseGraph::AddEdge(const PoseEdge& edge) {
  const int count = static_cast<int>(nodes_.size());
  if (edge.from < 0 || edge.to < 0 || edge.from >= count || edge.to >= count ||
      edge.from == edge.to) {
    throw std::invalid_argument("pose graph: edge " + std::to_string(edge.from) + " -> " +
                                std::to_string(edge.to) + " needs two different existing nodes");
  }
  edges_.push_back(edge);
}

void PoseGraph::AddHeadingPrior(const HeadingPrior& prior) {
  if (prior.node < 0 || prior.node >= static_cast<int>(nodes_.size())) {
    throw std::invalid_argument("pose graph: heading prior on node " + std::to_string(prior.node) +
                                ", which does not exist");
  }
  if (!std::isfinite(prior.information) || !(prior.information > 0.0) ||
      !std::isfinite(prior.theta_rad)) {
    throw std::invalid_argument("pose graph: heading prior on node " + std::to_string(prior.node) +
                                " needs a finite heading and an information > 0");
  }
  heading_priors_.push_back(prior);
}

void PoseGraph::RemoveEdge(std::size_t index) {
  if (index < edges_.size()) edges_.erase(edges_.begin() + static_cast<std::ptrdiff_t>(index));
}

double PoseGraph::TotalChi2() const {
  double chi2 = 0.0;
  for (const PoseEdge& edge : edges_) chi2 += EdgeChi2(edge);
  for (const HeadingPrior& prior : heading_priors_) {
    const double e = HeadingError(nodes_, prior);
    chi2 += prior.information * e * e;
  }
  return chi2;
}

double PoseGraph::EdgeChi2(const PoseEdge& edge) const {
  const Eigen::Vector3d e = EdgeError(nodes_[static_cast<std::size_t>(edge.from)],
                                      nodes_[static_cast<std::size_t>(edge.to)], edge.from_from_to);
  return e.dot(edge.information * e);
}

OptimizeResult PoseGraph::Optimize(int max_iterations) {
  OptimizeResult result;
  const int n = static_cast<int>(nodes_.size());
  result.initial_chi2 = TotalChi2();
  result.final_chi2 = result.initial_chi2;
  if (n < 2 || edges_.empty()) {
    result.solved = true;
    return result;
  }
  for (int iteration = 0; iteration < max_iterations; ++iteration) {
    Eigen::SparseMatrix<double> h(3 * n, 3 * n);
    Eigen::VectorXd b = Eigen::VectorXd::Zero(3 * n);
    Linearize(nodes_, edges_, heading_priors_, h, b);
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(h);
    if (solver.info() != Eigen::Success) return result;
    const Eigen::VectorXd dx = solver.solve(-b);
    if (solver.info() != Eigen::Success || !dx.allFinite()) return result;
    for (int i = 1; i < n; ++i) {
      Pose2& node = nodes_[static_cast<std::size_t>(i)];
      node.x_m += dx(3 * i);
      node.y_m += dx(3 * i + 1);
      node.theta_rad = geometry::NormalizeAngle(node.theta_rad + dx(3 * i + 2));
    }
    result.iterations = iteration + 1;
    if (dx.lpNorm<Eigen::Infinity>() < 1e-6) break;
  }
  result.solved = true;
  result.final_chi2 = TotalChi2();
  return result;
}

}  // namespace pena::slam
