#pragma once
// A planar pose graph (Lu and Milios 1997; the back end of Cartographer's global SLAM): keyframe
// poses as nodes, measured relative poses as edges, solved by sparse Gauss-Newton.

#include <Eigen/Core>
#include <vector>

#include "pena/geometry/pose2.hpp"

namespace pena::slam {

// A measured relative pose between two nodes: from_from_to, with its information (inverse
// covariance) in (x_m, y_m, theta_rad) of the `from` node's frame.
struct PoseEdge {
  int from = 0;
  int to = 0;
  geometry::Pose2 from_from_to;
  Eigen::Matrix3d information = Eigen::Matrix3d::Identity();
  bool robust = false;  // loop closures: Cauchy-weighted so a wrong one cannot bend the graph
};

// An absolute heading measured at one node (a compass-bounded heading), with its information
// (1 / sigma^2, rad^-2). Positions stay free: it only keeps the graph from bending.
struct HeadingPrior {
  int node = 0;
  double theta_rad = 0.0;
  double information = 0.0;
};

// What an optimisation did; failure is data.
struct OptimizeResult {
  bool solved = false;       // every linear solve succeeded
  int iterations = 0;
  double initial_chi2 = 0.0;  // sum of squared Mahalanobis edge errors before
  double final_chi2 = 0.0;    // and after
};

// The graph. Node 0 is anchored (it keeps its pose): the map starts at the known start pose.
class PoseGraph {
 public:
  // Adds a node at an initial estimate (world frame); returns its index.
  int AddNode(const geometry::Pose2& world_from_node);
  // Adds an edge; throws std::invalid_argument for an unknown node or equal ends.
  void AddEdge(const PoseEdge& edge);
  // Adds an absolute heading; throws std::invalid_argument for an unknown node or an
  // information that is not finite and > 0.
  void AddHeadingPrior(const HeadingPrior& prior);

  // Gauss-Newton over all nodes but node 0, at most `max_iterations` rounds, stopping when the
  // largest update is below 1e-6 (m or rad).
  OptimizeResult Optimize(int max_iterations = 10);

  // Squared Mahalanobis error of one edge at the current estimate.
  double EdgeChi2(const PoseEdge& edge) const;
  // Of every edge and heading prior.
  double TotalChi2() const;

  const std::vector<geometry::Pose2>& nodes() const { return nodes_; }
  const std::vector<PoseEdge>& edges() const { return edges_; }
  const std::vector<HeadingPrior>& heading_priors() const { return heading_priors_; }
  // Removes the edge at `index` (a rejected loop closure).
  void RemoveEdge(std::size_t index);

 private:
  std::vector<geometry::Pose2> nodes_;
  std::vector<PoseEdge> edges_;
  std::vector<HeadingPrior> heading_priors_;
};

// The error of `edge` between `from` and `to`: Between(from, to) relative to the measurement,
// (x_m, y_m, theta_rad) in the measured frame.
Eigen::Vector3d EdgeError(const geometry::Pose2& from, const geometry::Pose2& to,
                          const geometry::Pose2& from_from_to);

}  // namespace pena::slam
