#pragma once
// The gateway core's view of its local domain (docs/gateway.md): DDS in pena-gateway, an
// in-memory domain in tests and in the synthetic link experiments.

#include <map>
#include <string>
#include <vector>

#include "pena/gateway/link_items.hpp"
#include "pena/line_map/line_map.hpp"

namespace pena::gateway {

// One side of the gateway: items its domain produced, and items the link delivers into it.
class DomainSide {
 public:
  virtual ~DomainSide() = default;
  // Items produced since the last call, oldest first (moved out).
  virtual std::vector<DomainItem> Drain() = 0;
  // Hands an item received over the link to the domain (maps: in version order, no gaps).
  virtual void Deliver(const DomainItem& item) = 0;
};

// A domain held in memory: Offer() queues items for the link; delivered items are recorded and
// map changes applied to one LineMap per map id (the far side's picture).
class InMemoryDomain : public DomainSide {
 public:
  // Queues an item for the link.
  void Offer(DomainItem item) { outbound_.push_back(std::move(item)); }
  std::vector<DomainItem> Drain() override;
  void Deliver(const DomainItem& item) override;

  // Sets the time recorded with each delivery from now on (seconds, the items' clock).
  void set_clock(double now_s) { now_s_ = now_s; }
  // Every item delivered so far, in order, and when (by set_clock).
  const std::vector<DomainItem>& delivered() const { return delivered_; }
  const std::vector<double>& delivered_at_s() const { return delivered_at_s_; }
  // The maps built from delivered changes, by map id.
  const std::map<std::string, line_map::LineMap>& maps() const { return maps_; }
  // Map changes that did not apply (a bug if ever non-zero: the link delivers in order).
  std::size_t failed_applies() const { return failed_applies_; }

 private:
  std::vector<DomainItem> outbound_;
  std::vector<DomainItem> delivered_;
  std::vector<double> delivered_at_s_;
  double now_s_ = 0.0;
  std::map<std::string, line_map::LineMap> maps_;
  std::size_t failed_applies_ = 0;
};

}  // namespace pena::gateway
