#pragma once
// Exact nearest reference point for the least-squares refinement (nanoflann k-d tree).

#include <nanoflann.hpp>

#include <cstdint>
#include <memory>
#include <vector>

#include "pena/scan_matching/point_set.hpp"

namespace pena::scan_matching::internal {

// A k-d tree over a point set it owns. Normals are estimated on first use of a point: a
// refinement pairs a few hundred of a local map's thousands of points, and the map is rebuilt at
// every keyframe. So, like the matcher that owns it, not thread-safe.
class NearestNeighbours {
 public:
  explicit NearestNeighbours(Points2 points);
  // Index of the nearest point and the squared distance; false when the set is empty.
  bool Find(const Eigen::Vector2d& query_m, std::uint32_t& index, double& distance_sq_m2) const;
  const Eigen::Vector2d& point(std::uint32_t index) const { return cloud_->points[index]; }
  // Unit normal of the surface at a point (PCA of its neighbours); zero where the neighbourhood
  // is not line-like (a corner, an isolated point).
  const Eigen::Vector2d& normal(std::uint32_t index) const {
    if (!normal_known_[index]) EstimateNormal(index);
    return normals_[index];
  }

 private:
  void EstimateNormal(std::uint32_t index) const;

  struct Cloud {
    Points2 points;
    std::size_t kdtree_get_point_count() const { return points.size(); }
    double kdtree_get_pt(std::size_t index, std::size_t dim) const { return points[index][static_cast<Eigen::Index>(dim)]; }
    template <class Box>
    bool kdtree_get_bbox(Box&) const { return false; }
  };
  using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, Cloud>,
                                                   Cloud, 2, std::uint32_t>;
  // On the heap: the tree keeps a reference to it, which must survive moves of this object.
  std::unique_ptr<Cloud> cloud_;
  std::unique_ptr<Tree> tree_;
  mutable std::vector<Eigen::Vector2d> normals_;
  mutable std::vector<bool> normal_known_;
};

}  // namespace pena::scan_matching::internal
