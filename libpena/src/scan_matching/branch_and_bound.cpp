#include "branch_and_bound.hpp"

#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

namespace pena::scan_matching::internal {
namespace {

struct Node {
  int angle, x, y, level;  // covers candidates [x, x + 2^level) x [y, y + 2^level)
  long bound;              // the max-grid sum: no candidate of the node scores more
};

class Search {
 public:
  Search(const HitGrid& hits, const MaxGrids& max_grids, const Points2& scan,
         const geometry::Pose2& prior, const WindowGrid& grid)
      : grid_(grid), max_grids_(max_grids) {
    for (int angle = 0; angle < grid.num_angles; ++angle) {
      cells_.push_back(DiscretizeScan(hits, scan, prior, grid, angle));
    }
  }

  // The node with its bound: the max-grid sum, an upper bound of every candidate's score. A
  // leaf's bound is exactly its score.
  Node MakeNode(int angle, int x, int y, int level) {
    ++scored_;
    long sum = 0;
    const int dx = x * grid_.step_cells;
    const int dy = y * grid_.step_cells;
    for (const auto& cell : cells_[static_cast<std::size_t>(angle)]) {
      sum += max_grids_.At(level, cell.x() + dx, cell.y() + dy);
    }
    return Node{angle, x, y, level, sum};
  }

  // The smallest squared xy and heading index offsets from the prior over the node's candidates.
  std::pair<long, long> MinOffsetsSq(const Node& node) const {
    auto axis = [](int low, int count, int limit, int center) -> long {
      const int high = std::min(low + count, limit) - 1;
      if (center < low) return static_cast<long>(low - center) * (low - center);
      if (center > high) return static_cast<long>(center - high) * (center - high);
      return 0;
    };
    const int size = 1 << node.level;
    const long da = node.angle - grid_.center_angle;
    return {axis(node.x, size, grid_.num_x, grid_.center_x) + axis(node.y, size, grid_.num_y, grid_.center_y),
            da * da};
  }

  long MinDistanceSq(const Node& node) const {
    const auto [xy_sq, theta_sq] = MinOffsetsSq(node);
    return xy_sq + theta_sq;
  }

  void Explore(const Node& node) {
    if (node.bound < best_.score) return;
    if (node.bound == best_.score && MinDistanceSq(node) > best_.distance_sq) return;
    if (node.level == 0) {
      const Candidate candidate = MakeCandidate(grid_, node.angle, node.x, node.y, node.bound);
      if (Better(candidate, best_)) best_ = candidate;
      return;
    }
    const int half = 1 << (node.level - 1);
    std::vector<Node> children;
    for (const auto& [ox, oy] : {std::pair{0, 0}, {half, 0}, {0, half}, {half, half}}) {
      const int x = node.x + ox;
      const int y = node.y + oy;
      if (x >= grid_.num_x || y >= grid_.num_y) continue;
      children.push_back(MakeNode(node.angle, x, y, node.level - 1));
    }
    std::sort(children.begin(), children.end(), [](const Node& a, const Node& b) { return a.bound > b.bound; });
    for (const auto& child : children) Explore(child);
  }

  Candidate best_;
  long scored_ = 0;

 private:
  WindowGrid grid_;
  const MaxGrids& max_grids_;
  std::vector<std::vector<Eigen::Vector2i>> cells_;
};

}  // namespace

int TopLevel(const WindowGrid& grid) {
  int top_level = 0;
  while ((1 << top_level) < std::max(grid.num_x, grid.num_y)) ++top_level;
  return top_level;
}

Candidate BranchAndBound(const HitGrid& hits, const MaxGrids& max_grids, const Points2& scan,
                         const geometry::Pose2& reference_from_prior, const WindowGrid& grid,
                         long& scored) {
  const int top_level = TopLevel(grid);
  Search search(hits, max_grids, scan, reference_from_prior, grid);
  const int size = 1 << top_level;
  std::vector<Node> roots;
  for (int angle = 0; angle < grid.num_angles; ++angle) {
    for (int x = 0; x < grid.num_x; x += size) {
      for (int y = 0; y < grid.num_y; y += size) {
        roots.push_back(search.MakeNode(angle, x, y, top_level));
      }
    }
  }
  std::sort(roots.begin(), roots.end(), [](const Node& a, const Node& b) { return a.bound > b.bound; });
  for (const auto& root : roots) search.Explore(root);
  scored = search.scored_;
  return search.best_;
}

}  // namespace pena::scan_matching::internal
