#include "branch_and_bound.hpp"

#include <algorithm>
#include <cstdint>
#include <vector>

namespace pena::scan_matching::internal {
namespace {

struct Node {
  int angle, x, y, level;  // covers candidates [x, x + 2^level) x [y, y + 2^level)
  long bound;
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

  long Bound(int angle, int x, int y, int level) {
    ++scored_;
    long sum = 0;
    const int dx = x * grid_.step_cells;
    const int dy = y * grid_.step_cells;
    for (const auto& cell : cells_[static_cast<std::size_t>(angle)]) {
      sum += max_grids_.At(level, cell.x() + dx, cell.y() + dy);
    }
    return sum;
  }

  long MinDistanceSq(const Node& node) const {
    auto axis = [](int low, int count, int limit, int center) -> long {
      const int high = std::min(low + count, limit) - 1;
      if (center < low) return static_cast<long>(low - center) * (low - center);
      if (center > high) return static_cast<long>(center - high) * (center - high);
      return 0;
    };
    const int size = 1 << node.level;
    const long da = node.angle - grid_.center_angle;
    return da * da + axis(node.x, size, grid_.num_x, grid_.center_x) +
           axis(node.y, size, grid_.num_y, grid_.center_y);
  }

  void Explore(const Node& node) {
    if (node.bound < best_.score) return;
    if (node.bound == best_.score && MinDistanceSq(node) > best_.distance_sq) return;
    if (node.level == 0) {
      const Candidate candidate{node.angle, node.x, node.y, node.bound,
                                DistanceSq(grid_, node.angle, node.x, node.y)};
      if (Better(candidate, best_)) best_ = candidate;
      return;
    }
    const int half = 1 << (node.level - 1);
    std::vector<Node> children;
    for (const auto& [ox, oy] : {std::pair{0, 0}, {half, 0}, {0, half}, {half, half}}) {
      const int x = node.x + ox;
      const int y = node.y + oy;
      if (x >= grid_.num_x || y >= grid_.num_y) continue;
      children.push_back({node.angle, x, y, node.level - 1, Bound(node.angle, x, y, node.level - 1)});
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
        roots.push_back({angle, x, y, top_level, search.Bound(angle, x, y, top_level)});
      }
    }
  }
  std::sort(roots.begin(), roots.end(), [](const Node& a, const Node& b) { return a.bound > b.bound; });
  for (const auto& root : roots) search.Explore(root);
  scored = search.scored_;
  return search.best_;
}

}  // namespace pena::scan_matching::internal
