#include "pena/gateway/domain_side.hpp"

namespace pena::gateway {

std::vector<DomainItem> InMemoryDomain::Drain() {
  std::vector<DomainItem> items;
  items.swap(outbound_);
  return items;
}

void InMemoryDomain::Deliver(const DomainItem& item) {
  delivered_.push_back(item);
  delivered_at_s_.push_back(now_s_);
  const auto* map_change = std::get_if<MapChange>(&item);
  if (map_change == nullptr) return;
  line_map::LineMap& map = maps_[map_change->map_id];
  if (const auto* delta = std::get_if<line_map::MapDelta>(&map_change->change)) {
    if (!map.Apply(*delta).ok()) ++failed_applies_;
    return;
  }
  map = line_map::LineMap::FromSnapshot(std::get<line_map::MapSnapshot>(map_change->change));
}

}  // namespace pena::gateway
