#pragma once
// Mean and standard deviation of a sample, the summary every error table in eval reports.

#include <vector>

namespace pena::eval {

// Mean and population standard deviation (divides by N) of a sample, in the sample's unit.
struct MeanStd {
  double mean = 0.0;
  double std = 0.0;
};

// Summarises `values`; an empty sample gives {0, 0}.
MeanStd ComputeMeanStd(const std::vector<double>& values);

}  // namespace pena::eval
