#include "search_window.hpp"

#include <algorithm>
#include <cmath>

namespace pena::odometry::internal {

WindowScale::WindowScale(const LaserOdometryOptions& options)
    : base_(options.window), wide_(options.wide_window), growth_(options.window_growth) {}

double WindowScale::MaxFactor() const {
  return std::max({wide_.size_x_m / base_.size_x_m, wide_.size_y_m / base_.size_y_m,
                   wide_.size_theta_rad / base_.size_theta_rad, 1.0});
}

scan_matching::SearchWindow WindowScale::Current() const {
  if (IsBase()) return base_;
  // Grown windows are searched by branch and bound at the wide window's finer steps.
  scan_matching::SearchWindow window = wide_;
  window.size_x_m = std::clamp(base_.size_x_m * factor_, base_.size_x_m, std::max(wide_.size_x_m, base_.size_x_m));
  window.size_y_m = std::clamp(base_.size_y_m * factor_, base_.size_y_m, std::max(wide_.size_y_m, base_.size_y_m));
  window.size_theta_rad = std::clamp(base_.size_theta_rad * factor_, base_.size_theta_rad,
                                     std::max(wide_.size_theta_rad, base_.size_theta_rad));
  return window;
}

bool WindowScale::Grow() {
  const double max_factor = MaxFactor();
  if (factor_ >= max_factor) return false;
  factor_ = std::min(factor_ * growth_, max_factor);
  return true;
}

void WindowScale::Shrink() { factor_ = std::max(1.0, factor_ / growth_); }

void WindowScale::SetWide() { factor_ = MaxFactor(); }

}  // namespace pena::odometry::internal
