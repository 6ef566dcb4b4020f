#include "pena/eval/mean_std.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace pena::eval {

MeanStd ComputeMeanStd(const std::vector<double>& values) {
  if (values.empty()) return {};
  const double n = static_cast<double>(values.size());
  double sum = 0.0;
  for (const double value : values) sum += value;
  const double mean = sum / n;
  // Two-pass variance: the squared errors of raw odometry reach 1e5 m^2, where the one-pass
  // formula loses digits.
  double squares = 0.0;
  for (const double value : values) squares += (value - mean) * (value - mean);
  return {mean, std::sqrt(squares / n)};
}

double Quantile(std::vector<double> values, double fraction) {
  if (!(fraction >= 0.0 && fraction <= 1.0)) {
    throw std::invalid_argument("quantile fraction must be in [0, 1], got " +
                                std::to_string(fraction));
  }
  if (values.empty()) return 0.0;
  // Nearest rank: the smallest value with at least `fraction` of the sample at or below it.
  const auto rank = static_cast<std::size_t>(
      std::max(1.0, std::ceil(fraction * static_cast<double>(values.size()))));
  const auto nth = values.begin() + static_cast<std::ptrdiff_t>(rank - 1);
  std::nth_element(values.begin(), nth, values.end());
  return *nth;
}

Spread ComputeSpread(const std::vector<double>& values) {
  if (values.empty()) return {};
  return {Quantile(values, 0.5), Quantile(values, 0.95),
          *std::max_element(values.begin(), values.end())};
}

}  // namespace pena::eval
