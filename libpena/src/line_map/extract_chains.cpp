// Skeleton chains: walks between endpoints and junctions of an 8-connected one-pixel skeleton.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "extract_steps.hpp"

namespace pena::line_map::internal {

namespace {

const std::array<cv::Point, 8> kRing = {
    {{0, -1}, {1, -1}, {1, 0}, {1, 1}, {0, 1}, {-1, 1}, {-1, 0}, {-1, -1}}};

class SkeletonWalker {
 public:
  explicit SkeletonWalker(const cv::Mat& skeleton)
      : skeleton_(skeleton), visited_(cv::Mat::zeros(skeleton.size(), CV_8UC1)) {}

  bool Set(const cv::Point& p) const {
    return p.x >= 0 && p.y >= 0 && p.x < skeleton_.cols && p.y < skeleton_.rows &&
           skeleton_.at<std::uint8_t>(p) != 0;
  }
  std::vector<cv::Point> Neighbours(const cv::Point& p) const {
    std::vector<cv::Point> result;
    for (const cv::Point& offset : kRing) {
      if (Set(p + offset)) result.push_back(p + offset);
    }
    return result;
  }
  // Endpoints (one neighbour), junctions (three or more) and isolated pixels end chains.
  bool IsNode(const cv::Point& p) const {
    int degree = 0;
    for (const cv::Point& offset : kRing) degree += Set(p + offset) ? 1 : 0;
    return degree != 2;
  }
  bool Visited(const cv::Point& p) const { return visited_.at<std::uint8_t>(p) != 0; }
  void Visit(const cv::Point& p) { visited_.at<std::uint8_t>(p) = 1; }

  // Appends `current` and the pixels after it (coming from `previous`) up to and including the
  // next node or already visited pixel. Line pixels have exactly two neighbours, so the way on
  // is the one that is not `previous`.
  void Walk(PixelChain& chain, cv::Point previous, cv::Point current) {
    while (true) {
      chain.push_back(current);
      if (IsNode(current) || Visited(current)) return;
      Visit(current);
      const std::vector<cv::Point> next = Neighbours(current);
      const cv::Point ahead = next[0] == previous ? next[1] : next[0];
      previous = current;
      current = ahead;
    }
  }

 private:
  const cv::Mat& skeleton_;
  cv::Mat visited_;  // line (non-node) pixels already on a chain
};

}  // namespace

std::vector<PixelChain> TraceChains(const cv::Mat& skeleton) {
  SkeletonWalker walker(skeleton);
  std::vector<cv::Point> pixels;
  cv::findNonZero(skeleton, pixels);
  std::vector<PixelChain> chains;
  for (const cv::Point& node : pixels) {
    if (!walker.IsNode(node)) continue;
    for (const cv::Point& first : walker.Neighbours(node)) {
      // Node next to node (inside a junction cluster) bounds no line; a visited pixel means the
      // chain was already walked from its other end.
      if (walker.IsNode(first) || walker.Visited(first)) continue;
      PixelChain chain{node};
      walker.Walk(chain, node, first);
      chains.push_back(std::move(chain));
    }
  }
  // What is left are closed loops of line pixels (a pillar, a room without junctions).
  for (const cv::Point& start : pixels) {
    if (walker.IsNode(start) || walker.Visited(start)) continue;
    PixelChain chain{start};
    walker.Visit(start);
    walker.Walk(chain, start, walker.Neighbours(start)[0]);
    chains.push_back(std::move(chain));
  }
  return chains;
}

bool PruneSpurs(cv::Mat& skeleton, double max_spur_px) {
  auto degree = [&skeleton](const cv::Point& p) {
    int count = 0;
    for (const cv::Point& offset : kRing) {
      const cv::Point q = p + offset;
      if (q.x >= 0 && q.y >= 0 && q.x < skeleton.cols && q.y < skeleton.rows &&
          skeleton.at<std::uint8_t>(q) != 0) {
        ++count;
      }
    }
    return count;
  };
  std::vector<PixelChain> spurs;
  for (PixelChain& chain : TraceChains(skeleton)) {
    if (chain.size() < 2) continue;
    if (degree(chain.front()) == 1 && degree(chain.back()) >= 3) {
      std::reverse(chain.begin(), chain.end());
    } else if (!(degree(chain.back()) == 1 && degree(chain.front()) >= 3)) {
      continue;
    }
    // chain.front() is now the junction.
    double length_px = 0.0;
    for (std::size_t k = 1; k < chain.size(); ++k) {
      length_px += std::hypot(chain[k].x - chain[k - 1].x, chain[k].y - chain[k - 1].y);
    }
    if (length_px < max_spur_px) spurs.push_back(std::move(chain));
  }
  // Cleared after all are found, so a junction with two spurs is judged as it was.
  for (const PixelChain& spur : spurs) {
    for (std::size_t k = 1; k < spur.size(); ++k) skeleton.at<std::uint8_t>(spur[k]) = 0;
  }
  return !spurs.empty();
}

}  // namespace pena::line_map::internal
