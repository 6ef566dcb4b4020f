#pragma once
// The gateway's DDS side (docs/gateway.md, "DDS domain side"): a DomainSide that reads the PeNa
// topics of one DDS domain and hands them to the link (send classes), and publishes what the link
// delivers into that domain on the same topics and types (publish classes), so unmodified DDS
// subscribers (fusion, a coordinator's screen) see it. Samples this participant wrote itself are
// never read back, so two gateways never echo each other's data.

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "dds_participant.hpp"
#include "pena/gateway/domain_side.hpp"
#include "pena_dds/operator.h"

namespace pena::gateway {

// What a DdsDomain carries; each class may be sent, published, both (annotations) or neither.
enum class DdsClass {
  kPose,        // pena/entity/pose
  kEntityMap,   // pena/entity/line_map_delta and _snapshot (map id = entity id)
  kGlobalMap,   // pena/fusion/global_map_delta and _snapshot (map id "global")
  kAnnotation,  // pena/annotation (alarms: victim found, dangerous area)
  kCorrection,  // pena/fusion/correction (CORRECTION_MAP_FROM_ODOM only)
  kOperatorCorrection,  // pena/operator/correction (a console's, and pena-fusion's answers)
};

// "pose", "entity_map", "global_map", "annotation", "correction", "operator_correction"; nullopt
// for anything else.
std::optional<DdsClass> ParseDdsClass(const std::string& name);
const char* ToString(DdsClass dds_class);

// A topology preset (docs/gateway.md): the send and publish classes of one side.
struct DdsRole {
  std::set<DdsClass> send;
  std::set<DdsClass> publish;
};
// "building" (entities + fusion inside), "command-post" (coordinator subscribers), "entities"
// (entities inside, fusion outside), "fusion-post" (the command post of "entities"); nullopt
// for anything else.
std::optional<DdsRole> ParseDdsRole(const std::string& name);

// Participant, classes and map handling; validated by DdsDomain's constructor.
struct DdsDomainOptions {
  services::DdsOptions dds;              // profile files, participant profile, domain id
  std::string name = "pena-gateway";     // participant name, SyncRequest requester id
  DdsRole role;                          // what is sent and published
  double snapshot_grace_s = 2.0;         // a newer snapshot is forwarded only if deltas do not
                                         // reach its version within this (wall seconds)
  double sync_request_interval_s = 2.0;  // at most one SyncRequest per map per this (s)
};

// Counters of what the DDS side did (for the summary and tests).
struct DdsDomainStats {
  std::uint64_t samples_read = 0;       // accepted samples from the DDS readers
  std::uint64_t samples_dropped = 0;    // samples the link cannot carry (logged)
  std::uint64_t samples_published = 0;  // delivered items written to DDS
  std::uint64_t publish_failures = 0;   // items that could not be written (logged)
  std::uint64_t stale_deltas = 0;       // deltas at or below the version already sent
  std::uint64_t snapshots_forwarded = 0;
  std::uint64_t sync_requests_sent = 0;
  std::uint64_t sync_requests_answered = 0;
  std::uint64_t samples_refused = 0;    // secured: samples about an entity from a writer outside
                                        // its partition (services::Participant::AcceptsEntitySample)
};

class DdsDomain : public DomainSide {
 public:
  // Creates the participant, readers and writers; throws services::DdsError or
  // std::invalid_argument (naming the option) on failure.
  explicit DdsDomain(DdsDomainOptions options);
  ~DdsDomain() override;
  DdsDomain(const DdsDomain&) = delete;
  DdsDomain& operator=(const DdsDomain&) = delete;

  std::vector<DomainItem> Drain() override;
  void Deliver(const DomainItem& item) override;

  // Wall-clock seconds now (grace timers, delivery times, stamps of published map samples).
  void set_clock(double now_s);
  // Every item delivered from the link, with its time, and the maps it built.
  const InMemoryDomain& record() const;
  // The maps as sent to the link (the mirrors of the local DDS maps), by map id.
  const std::map<std::string, line_map::LineMap>& sent_maps() const;
  // When a sent map last changed (wall seconds; 0: never).
  double last_sent_map_change_s() const;
  DdsDomainStats stats() const;
  // Readers and writers matched with remote endpoints (for "wait until discovered").
  int matched_readers() const;
  int matched_writers() const;
  // Publishes the link's health for the operator's console (pena/gateway/link_health).
  void PublishLinkHealth(const pena_dds::LinkHealth& health);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace pena::gateway
