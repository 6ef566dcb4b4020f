#include "skeleton.hpp"

#include <array>
#include <bit>
#include <cstdint>
#include <stdexcept>
#include <vector>

namespace pena::line_map::internal {

namespace {

// Neighbour bits in ring order N, NE, E, SE, S, SW, W, NW (Zhang-Suen's P2..P9).
constexpr int kN = 0, kE = 2, kS = 4, kW = 6;

bool Bit(unsigned mask, int i) { return ((mask >> i) & 1U) != 0U; }

// 0 -> 1 transitions around the ring (Zhang-Suen's A(P1)).
int Transitions(unsigned mask) {
  int count = 0;
  for (int i = 0; i < 8; ++i) count += (!Bit(mask, i) && Bit(mask, (i + 1) % 8)) ? 1 : 0;
  return count;
}

// Number of 8-connected groups among the set neighbours: ring neighbours touch, and so do two
// 4-neighbours around a corner (N and E are diagonal to each other).
int Groups(unsigned mask) {
  std::array<int, 8> parent{0, 1, 2, 3, 4, 5, 6, 7};
  auto find = [&parent](int i) {
    while (parent[static_cast<std::size_t>(i)] != i) i = parent[static_cast<std::size_t>(i)];
    return i;
  };
  auto join = [&](int a, int b) {
    if (Bit(mask, a) && Bit(mask, b)) parent[static_cast<std::size_t>(find(a))] = find(b);
  };
  for (int i = 0; i < 8; ++i) join(i, (i + 1) % 8);
  for (int i = 0; i < 8; i += 2) join(i, (i + 2) % 8);
  int groups = 0;
  for (int i = 0; i < 8; ++i) groups += (Bit(mask, i) && find(i) == i) ? 1 : 0;
  return groups;
}

// Per neighbour mask: may the pixel go in Zhang-Suen's first / second sub-iteration, and is it a
// staircase corner whose removal keeps its neighbours connected.
struct Tables {
  std::array<bool, 256> first{};
  std::array<bool, 256> second{};
  std::array<bool, 256> corner{};
};

Tables BuildTables() {
  Tables t;
  for (unsigned m = 0; m < 256; ++m) {
    const int count = std::popcount(m);
    const bool p2 = Bit(m, kN), p4 = Bit(m, kE), p6 = Bit(m, kS), p8 = Bit(m, kW);
    const bool thin_able = count >= 2 && count <= 6 && Transitions(m) == 1;
    t.first[m] = thin_able && !(p2 && p4 && p6) && !(p4 && p6 && p8);
    t.second[m] = thin_able && !(p2 && p4 && p8) && !(p2 && p6 && p8);
    const bool has_corner = (p2 && p4) || (p4 && p6) || (p6 && p8) || (p8 && p2);
    t.corner[m] = count >= 2 && has_corner && Groups(m) == 1;
  }
  return t;
}

const Tables& GetTables() {
  static const Tables tables = BuildTables();
  return tables;
}

// A 0/1 image with a one-pixel zero border, so neighbour reads need no bounds checks.
class PaddedImage {
 public:
  explicit PaddedImage(const cv::Mat& binary)
      : stride_(binary.cols + 2), pixels_(static_cast<std::size_t>((binary.rows + 2) * stride_)) {
    for (int r = 0; r < binary.rows; ++r) {
      const std::uint8_t* row = binary.ptr<std::uint8_t>(r);
      for (int c = 0; c < binary.cols; ++c) {
        if (row[c] == 0) continue;
        const int index = (r + 1) * stride_ + c + 1;
        pixels_[static_cast<std::size_t>(index)] = 1;
        foreground_.push_back(index);
      }
    }
    const int s = stride_;
    offsets_ = {-s, -s + 1, 1, s + 1, s, s - 1, -1, -s - 1};
  }

  unsigned Mask(int index) const {
    unsigned mask = 0;
    for (int i = 0; i < 8; ++i) mask |= static_cast<unsigned>(At(index + offsets_[i])) << i;
    return mask;
  }
  std::uint8_t At(int index) const { return pixels_[static_cast<std::size_t>(index)]; }
  void Clear(int index) { pixels_[static_cast<std::size_t>(index)] = 0; }
  std::vector<int>& Foreground() { return foreground_; }
  int Stride() const { return stride_; }

 private:
  int stride_;
  std::vector<std::uint8_t> pixels_;
  std::vector<int> foreground_;  // indices of pixels still set, raster order
  std::array<int, 8> offsets_{};
};

// One Zhang-Suen sub-iteration: marks against the current image, then deletes all at once.
bool SubIteration(PaddedImage& image, const std::array<bool, 256>& deletable) {
  std::vector<int>& pixels = image.Foreground();
  std::vector<int> doomed;
  for (const int index : pixels) {
    if (deletable[image.Mask(index)]) doomed.push_back(index);
  }
  for (const int index : doomed) image.Clear(index);
  std::erase_if(pixels, [&image](int index) { return image.At(index) == 0; });
  return !doomed.empty();
}

// Sequential (not parallel) so two touching corners are never removed together.
void RemoveStaircaseCorners(PaddedImage& image, const std::array<bool, 256>& corner) {
  for (const int index : image.Foreground()) {
    if (corner[image.Mask(index)]) image.Clear(index);
  }
  std::erase_if(image.Foreground(), [&image](int index) { return image.At(index) == 0; });
}

}  // namespace

cv::Mat Skeletonize(const cv::Mat& binary) {
  if (binary.type() != CV_8UC1) throw std::invalid_argument("Skeletonize needs a CV_8UC1 image");
  const Tables& tables = GetTables();
  PaddedImage image(binary);
  // Only the pixels still set are visited, so the cost follows the walls, not the image area.
  bool changed = true;
  while (changed) {
    const bool first = SubIteration(image, tables.first);
    const bool second = SubIteration(image, tables.second);
    changed = first || second;
  }
  RemoveStaircaseCorners(image, tables.corner);
  cv::Mat skeleton = cv::Mat::zeros(binary.size(), CV_8UC1);
  for (const int index : image.Foreground()) {
    skeleton.at<std::uint8_t>(index / image.Stride() - 1, index % image.Stride() - 1) = 1;
  }
  return skeleton;
}

}  // namespace pena::line_map::internal
