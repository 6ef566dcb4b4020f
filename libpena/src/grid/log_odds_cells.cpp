#include "pena/grid/log_odds_cells.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace pena::grid {
namespace {

constexpr std::uint8_t kUnknownPixel = 128;

std::uint8_t PixelOf(float log_odds) {
  if (log_odds == 0.0f) return kUnknownPixel;
  const double probability = ProbabilityFromLogOdds(log_odds);
  return static_cast<std::uint8_t>(std::clamp(std::lround(255.0 * probability), 0L, 255L));
}

}  // namespace

LogOddsCells::LogOddsCells(const Eigen::Vector2i& min_cell, int width, int height)
    : min_cell_(min_cell), width_(width), height_(height) {
  if (width < 0 || height < 0) throw std::invalid_argument("grid cells: negative size");
  const std::size_t count = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  log_odds_.assign(count, 0.0f);
  stamps_.assign(count, 0);
  hit_counts_.assign(count, 0);
  first_hit_scans_.assign(count, 0);
  last_hit_scans_.assign(count, 0);
}

std::size_t LogOddsCells::Index(int local_x, int local_y) const {
  return static_cast<std::size_t>(local_y) * static_cast<std::size_t>(width_) +
         static_cast<std::size_t>(local_x);
}

double LogOddsCells::LogOdds(const Eigen::Vector2i& cell) const {
  if (!Contains(cell)) return 0.0;
  return log_odds_[Index(cell.x() - min_cell_.x(), cell.y() - min_cell_.y())];
}

void LogOddsCells::Reframe(const Eigen::Vector2i& min_cell, int width, int height) {
  LogOddsCells moved(min_cell, width, height);
  // Copy the overlap row by row; stamps need not survive because no scan is in progress.
  const Eigen::Vector2i low = min_cell_.cwiseMax(min_cell);
  const Eigen::Vector2i high = (min_cell_ + Eigen::Vector2i(width_, height_))
                                   .cwiseMin(min_cell + Eigen::Vector2i(width, height));
  const auto copy_row = [&](const auto& from_cells, auto& to_cells, int y) {
    const auto from = from_cells.begin() + static_cast<std::ptrdiff_t>(
                                               Index(low.x() - min_cell_.x(), y - min_cell_.y()));
    const auto to = to_cells.begin() + static_cast<std::ptrdiff_t>(
                                           moved.Index(low.x() - min_cell.x(), y - min_cell.y()));
    std::copy(from, from + (high.x() - low.x()), to);
  };
  for (int y = low.y(); y < high.y(); ++y) {
    copy_row(log_odds_, moved.log_odds_, y);
    copy_row(hit_counts_, moved.hit_counts_, y);
    copy_row(first_hit_scans_, moved.first_hit_scans_, y);
    copy_row(last_hit_scans_, moved.last_hit_scans_, y);
  }
  moved.scan_ = scan_;
  *this = std::move(moved);
}

void LogOddsCells::AdvanceStamp() {
  // Stamps compare against 2 * scan_; restart all of them before that would overflow.
  // (2^31 scans: years of scanning; the last-hit numbers then restart too, as int32 needs.)
  if (scan_ >= std::numeric_limits<std::uint32_t>::max() / 2 - 1) {
    std::fill(stamps_.begin(), stamps_.end(), 0u);
    std::fill(first_hit_scans_.begin(), first_hit_scans_.end(), 0);
    std::fill(last_hit_scans_.begin(), last_hit_scans_.end(), 0);
    scan_ = 0;
  }
  ++scan_;
}

void LogOddsCells::Insert(const ScanRays& rays, const GridOptions& options) {
  if (width_ == 0 || height_ == 0) return;
  AdvanceStamp();
  const auto hit = static_cast<float>(options.hit_log_odds);
  const auto miss = static_cast<float>(options.miss_log_odds);
  // Hits first, so the rays of other beams do not clear a cell this scan saw occupied.
  ApplyHits(rays, hit, static_cast<float>(options.max_log_odds));
  const auto min_value = static_cast<float>(options.min_log_odds);
  // Each return clears up to its free end (before its hit cell, or earlier for a grazing beam).
  for (const Eigen::Vector2i& end : rays.free_end_cells) {
    CastFree(rays.origin_cell, end, false, miss, min_value);
  }
  for (const Eigen::Vector2i& end : rays.clear_cells) {
    CastFree(rays.origin_cell, end, true, miss, min_value);
  }
}

void LogOddsCells::ApplyHits(const ScanRays& rays, float hit, float max_value) {
  const std::uint32_t hit_stamp = 2 * scan_ + 1;
  for (const Eigen::Vector2i& cell : rays.hit_cells) {
    if (!Contains(cell)) continue;
    const std::size_t index = Index(cell.x() - min_cell_.x(), cell.y() - min_cell_.y());
    if (stamps_[index] == hit_stamp) continue;  // several beams on one cell count once
    stamps_[index] = hit_stamp;
    log_odds_[index] = std::min(log_odds_[index] + hit, max_value);
    if (hit_counts_[index] < std::numeric_limits<std::uint16_t>::max()) ++hit_counts_[index];
    if (first_hit_scans_[index] == 0) first_hit_scans_[index] = static_cast<std::int32_t>(scan_);
    last_hit_scans_[index] = static_cast<std::int32_t>(scan_);
  }
}

// Bresenham's line in integer arithmetic, in cells relative to the bounds.
void LogOddsCells::CastFree(const Eigen::Vector2i& from, const Eigen::Vector2i& to,
                            bool include_end, float miss, float min_value) {
  const std::uint32_t miss_stamp = 2 * scan_;
  int x = from.x() - min_cell_.x();
  int y = from.y() - min_cell_.y();
  const int end_x = to.x() - min_cell_.x();
  const int end_y = to.y() - min_cell_.y();
  const int dx = std::abs(end_x - x);
  const int dy = -std::abs(end_y - y);
  const int step_x = x < end_x ? 1 : -1;
  const int step_y = y < end_y ? 1 : -1;
  int error = dx + dy;
  while (true) {
    const bool at_end = x == end_x && y == end_y;
    if (at_end && !include_end) return;
    if (x >= 0 && y >= 0 && x < width_ && y < height_) {
      const std::size_t index = Index(x, y);
      if (stamps_[index] < miss_stamp) {  // neither hit nor cleared by this scan yet
        stamps_[index] = miss_stamp;
        log_odds_[index] = std::max(log_odds_[index] + miss, min_value);
      }
    }
    if (at_end) return;
    const int twice_error = 2 * error;
    if (twice_error >= dy) {
      error += dy;
      x += step_x;
    }
    if (twice_error <= dx) {
      error += dx;
      y += step_y;
    }
  }
}

GridImage LogOddsCells::ToImage(double resolution_m) const {
  GridImage image;
  image.resolution_m = resolution_m;
  image.origin_m = min_cell_.cast<double>() * resolution_m;
  image.occupancy = cv::Mat(height_, width_, CV_8UC1);
  image.hit_counts = cv::Mat(height_, width_, CV_16UC1);
  image.first_hit_scans = cv::Mat(height_, width_, CV_32SC1);
  image.last_hit_scans = cv::Mat(height_, width_, CV_32SC1);
  // Image row 0 is the top of the grid (largest y), see grid_image.hpp.
  for (int row = 0; row < height_; ++row) {
    auto* pixels = image.occupancy.ptr<std::uint8_t>(row);
    const std::size_t offset = Index(0, height_ - 1 - row);
    for (int col = 0; col < width_; ++col) {
      pixels[col] = PixelOf(log_odds_[offset + static_cast<std::size_t>(col)]);
    }
    std::copy_n(hit_counts_.begin() + static_cast<std::ptrdiff_t>(offset), width_,
                image.hit_counts.ptr<std::uint16_t>(row));
    std::copy_n(first_hit_scans_.begin() + static_cast<std::ptrdiff_t>(offset), width_,
                image.first_hit_scans.ptr<std::int32_t>(row));
    std::copy_n(last_hit_scans_.begin() + static_cast<std::ptrdiff_t>(offset), width_,
                image.last_hit_scans.ptr<std::int32_t>(row));
  }
  return image;
}

}  // namespace pena::grid
