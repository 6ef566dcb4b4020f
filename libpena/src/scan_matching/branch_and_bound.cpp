#include "branch_and_bound.hpp"

#include <algorithm>
#include <cstdint>
#include <vector>

namespace pena::scan_matching::internal {
namespace {

// Max-grids L_h(q) = max over i, j < h of hits(q + (i, j) * step), for h = 1, 2, 4, ..., top.
// Stored with a low-side pad so queries below the hit grid that can still reach it are valid.
class MaxGrids {
 public:
  MaxGrids(const HitGrid& hits, int step_cells, int top_h)
      : pad_((top_h - 1) * step_cells),
        width_(hits.width() + pad_),
        height_(hits.height() + pad_) {
    std::vector<std::uint8_t> level(static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_));
    for (int y = 0; y < height_; ++y) {
      for (int x = 0; x < width_; ++x) level[Index(x, y)] = hits.At(x - pad_, y - pad_);
    }
    levels_.push_back(level);
    for (int h = 1; h < top_h; h *= 2) {
      const int shift = h * step_cells;  // L_2h(q) = max of L_h at q and three shifted copies
      std::vector<std::uint8_t> next(level.size());
      for (int y = 0; y < height_; ++y) {
        for (int x = 0; x < width_; ++x) {
          next[Index(x, y)] = std::max({Get(level, x, y), Get(level, x + shift, y),
                                        Get(level, x, y + shift), Get(level, x + shift, y + shift)});
        }
      }
      levels_.push_back(next);
      level = std::move(next);
    }
  }

  // Level index k holds h = 2^k; cell coordinates are those of the hit grid.
  std::uint8_t At(int k, int cell_x, int cell_y) const {
    return Get(levels_[static_cast<std::size_t>(k)], cell_x + pad_, cell_y + pad_);
  }

 private:
  std::size_t Index(int x, int y) const {
    return static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(x);
  }
  std::uint8_t Get(const std::vector<std::uint8_t>& level, int x, int y) const {
    if (x < 0 || y < 0 || x >= width_ || y >= height_) return 0;
    return level[Index(x, y)];
  }

  int pad_;
  int width_;
  int height_;
  std::vector<std::vector<std::uint8_t>> levels_;
};

struct Node {
  int angle, x, y, level;  // covers candidates [x, x + 2^level) x [y, y + 2^level)
  int bound;
};

class Search {
 public:
  Search(const HitGrid& hits, const Points2& scan, const geometry::Pose2& prior,
         const WindowGrid& grid, int top_level)
      : grid_(grid), max_grids_(hits, grid.step_cells, 1 << top_level) {
    for (int angle = 0; angle < grid.num_angles; ++angle) {
      cells_.push_back(DiscretizeScan(hits, scan, prior, grid, angle));
    }
  }

  int Bound(int angle, int x, int y, int level) {
    ++scored_;
    int sum = 0;
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
  MaxGrids max_grids_;
  std::vector<std::vector<Eigen::Vector2i>> cells_;
};

}  // namespace

Candidate BranchAndBound(const HitGrid& hits, const Points2& scan,
                         const geometry::Pose2& reference_from_prior, const WindowGrid& grid,
                         long& scored) {
  int top_level = 0;
  while ((1 << top_level) < std::max(grid.num_x, grid.num_y)) ++top_level;
  Search search(hits, scan, reference_from_prior, grid, top_level);
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
