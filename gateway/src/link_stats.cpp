#include "pena/gateway/link_stats.hpp"

namespace pena::gateway {

const char* ToString(ItemClass item_class) {
  switch (item_class) {
    case ItemClass::kControl: return "control";
    case ItemClass::kAnnotation: return "annotation";
    case ItemClass::kPose: return "pose";
    case ItemClass::kCorrection: return "correction";
    case ItemClass::kMap: return "map";
  }
  return "unknown";
}

std::uint64_t LinkStats::rejected_total() const {
  std::uint64_t total = 0;
  for (std::uint64_t count : rejected) total += count;
  return total;
}

}  // namespace pena::gateway
