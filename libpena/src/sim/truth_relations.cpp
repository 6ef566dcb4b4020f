#include "pena/sim/truth_relations.hpp"

#include <algorithm>
#include <stdexcept>

namespace pena::sim {
namespace {

constexpr double kStampSlack_s = 1e-6;  // stamps are multiples of the scan period, up to rounding

geometry::Relation Make(const geometry::StampedPose2& a, const geometry::StampedPose2& b) {
  return {a.stamp_s, b.stamp_s, geometry::Between(a.pose, b.pose)};
}

}  // namespace

std::vector<geometry::Relation> TruthRelations(const geometry::Trajectory& truth,
                                               const TruthRelationOptions& options) {
  if (!(options.anchor_every_s > 0.0)) {
    throw std::invalid_argument("truth_relations.anchor_every_s must be > 0 s");
  }
  std::vector<geometry::Relation> relations;
  double next_anchor_s = truth.empty() ? 0.0 : truth.front().stamp_s;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    const double t1 = truth[i].stamp_s;
    if (options.consecutive && i + 1 < truth.size())
      relations.push_back(Make(truth[i], truth[i + 1]));
    if (t1 + kStampSlack_s < next_anchor_s) continue;
    next_anchor_s = t1 + options.anchor_every_s;
    for (const double offset_s : options.offsets_s) {
      const auto later = std::lower_bound(truth.begin() + static_cast<std::ptrdiff_t>(i),
                                          truth.end(), t1 + offset_s - kStampSlack_s,
                                          [](const geometry::StampedPose2& pose, double stamp_s) {
                                            return pose.stamp_s < stamp_s;
                                          });
      if (later == truth.end() || later->stamp_s > t1 + offset_s + 0.5) continue;
      if (options.consecutive && later == truth.begin() + static_cast<std::ptrdiff_t>(i + 1))
        continue;
      relations.push_back(Make(truth[i], *later));
    }
  }
  std::sort(relations.begin(), relations.end(), [](const auto& a, const auto& b) {
    return a.t1_s != b.t1_s ? a.t1_s < b.t1_s : a.t2_s < b.t2_s;
  });
  return relations;
}

}  // namespace pena::sim
