#pragma once
// Summaries of a sample that every error table in eval reports: mean and standard deviation, and
// the order statistics (median, 95th percentile, maximum) that show a rare large error.

#include <vector>

namespace pena::eval {

// Mean and population standard deviation (divides by N) of a sample, in the sample's unit.
struct MeanStd {
  double mean = 0.0;
  double std = 0.0;
};

// Summarises `values`; an empty sample gives {0, 0}.
MeanStd ComputeMeanStd(const std::vector<double>& values);

// Order statistics of a sample, in the sample's unit.
struct Spread {
  double median = 0.0;
  double p95 = 0.0;  // 95th percentile (nearest rank)
  double max = 0.0;
};

// The nearest-rank `fraction` quantile of `values` (fraction in [0, 1]); an empty sample gives 0.
double Quantile(std::vector<double> values, double fraction);

// Median, 95th percentile and maximum of `values`; an empty sample gives zeros.
Spread ComputeSpread(const std::vector<double>& values);

}  // namespace pena::eval
