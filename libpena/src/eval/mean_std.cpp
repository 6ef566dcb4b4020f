#include "pena/eval/mean_std.hpp"

#include <cmath>

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

}  // namespace pena::eval
