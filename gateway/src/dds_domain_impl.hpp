#pragma once
// DdsDomain's state (private to gateway/src): the participant, the readers and writers of the
// configured classes, the inbox the reader callbacks fill, and the worker thread's map mirrors.

#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "dds_endpoints.hpp"
#include "dds_endpoints_stamped.hpp"
#include "pena/gateway/dds_convert.hpp"
#include "pena/gateway/dds_domain.hpp"
#include "pena_dds/correctionPubSubTypes.h"
#include "pena_dds/entityPubSubTypes.h"
#include "pena_dds/global_mapPubSubTypes.h"
#include "pena_dds/line_mapPubSubTypes.h"
#include "pena_dds/operatorPubSubTypes.h"

namespace pena::gateway {

// A map change read from DDS (entity or global map).
struct MapIn {
  std::string map_id;
  std::variant<line_map::MapDelta, line_map::MapSnapshot> change;
};
// A SyncRequest read from DDS: someone wants the whole map `target`.
struct SyncIn {
  std::string target;
  std::uint64_t have_version = 0;
};
using Event = std::variant<PoseUpdate, Annotation, Correction, MapIn, SyncIn, OperatorCorrection>;

struct DdsDomain::Impl {
  explicit Impl(DdsDomainOptions domain_options);

  // A reader whose callback converts (may throw or return nullopt with an error) and enqueues.
  template <class PubSubType, class Convert>
  std::unique_ptr<services::Reader<PubSubType>> MakeReader(const services::TopicSpec& spec, Convert convert) {
    return std::make_unique<services::Reader<PubSubType>>(
        participant, spec, [this, spec, convert](typename PubSubType::type&& sample, const services::SampleMeta& meta) {
          if (FromSelf(meta)) return;  // our own publication: never echo it back to the link
          std::string error;
          std::optional<Event> event;
          try {
            event = convert(sample, meta, &error);
          } catch (const std::exception& exception) {
            error = exception.what();
          }
          Enqueue(spec.name, std::move(event), error);
        });
  }
  template <class PubSubType>
  std::unique_ptr<StampedWriter<PubSubType>> MakeWriter(const services::TopicSpec& spec) {
    return std::make_unique<StampedWriter<PubSubType>>(participant, spec);
  }
  template <class F>
  void CreateWriters(const F& publishes);

  bool FromSelf(const services::SampleMeta& meta) const;
  void Enqueue(const char* topic, std::optional<Event> event, const std::string& error);
  // Worker thread: one read sample into link items.
  void Handle(Event event, std::vector<DomainItem>* out);
  void HandleMap(MapIn map_in, std::vector<DomainItem>* out);
  void HandleDelta(const std::string& map_id, line_map::MapDelta delta, std::vector<DomainItem>* out);
  void HandleSync(const SyncIn& sync);
  void RequestSync(const std::string& map_id, std::uint64_t have_version);
  void ForwardDueSnapshots(std::vector<DomainItem>* out);
  // Worker thread: one delivered item into DDS; false if its class is not published here.
  bool Publish(const DomainItem& item);
  bool PublishMap(const MapChange& change);
  bool PublishSnapshot(const std::string& map_id, const line_map::MapSnapshot& snapshot);
  int MatchedReaders() const;
  int MatchedWriters() const;

  DdsDomainOptions options;
  services::Participant participant;

  mutable std::mutex mutex;   // guards inbox and stats
  std::vector<Event> inbox;
  DdsDomainStats stats;

  // Worker thread only.
  double now_s = 0.0;
  InMemoryDomain record;
  std::map<std::string, line_map::LineMap> sent_maps;
  struct PendingSnapshot {
    line_map::MapSnapshot snapshot;
    double since_s = 0.0;
  };
  std::map<std::string, PendingSnapshot> pending_snapshots;
  std::map<std::string, double> last_sync_request_s;
  std::map<std::string, std::string> annotations_seen;  // link id text -> content sent/received
  std::map<std::string, std::string> operator_seen;     // correction_id -> content sent/received
  std::map<std::string, std::uint64_t> pose_seq;
  double last_sent_change_s = 0.0;

  // Endpoints (destroyed before the participant: declared after it).
  std::unique_ptr<services::Reader<pena_dds::EntityPosePubSubType>> pose_reader;
  std::unique_ptr<services::Reader<pena_dds::AnnotationPubSubType>> annotation_reader;
  std::unique_ptr<services::Reader<pena_dds::CorrectionPubSubType>> correction_reader;
  std::unique_ptr<services::Reader<pena_dds::OperatorCorrectionPubSubType>> operator_reader;
  std::unique_ptr<services::Reader<pena_dds::LineMapDeltaPubSubType>> entity_delta_reader;
  std::unique_ptr<services::Reader<pena_dds::LineMapSnapshotPubSubType>> entity_snapshot_reader;
  std::unique_ptr<services::Reader<pena_dds::GlobalMapDeltaPubSubType>> global_delta_reader;
  std::unique_ptr<services::Reader<pena_dds::GlobalMapSnapshotPubSubType>> global_snapshot_reader;
  std::unique_ptr<services::Reader<pena_dds::SyncRequestPubSubType>> sync_reader;
  std::unique_ptr<StampedWriter<pena_dds::EntityPosePubSubType>> pose_writer;
  std::unique_ptr<StampedWriter<pena_dds::AnnotationPubSubType>> annotation_writer;
  std::unique_ptr<StampedWriter<pena_dds::CorrectionPubSubType>> correction_writer;
  std::unique_ptr<StampedWriter<pena_dds::OperatorCorrectionPubSubType>> operator_writer;
  std::unique_ptr<services::Writer<pena_dds::LinkHealthPubSubType>> health_writer;
  std::unique_ptr<StampedWriter<pena_dds::LineMapDeltaPubSubType>> entity_delta_writer;
  std::unique_ptr<StampedWriter<pena_dds::LineMapSnapshotPubSubType>> entity_snapshot_writer;
  std::unique_ptr<StampedWriter<pena_dds::GlobalMapDeltaPubSubType>> global_delta_writer;
  std::unique_ptr<StampedWriter<pena_dds::GlobalMapSnapshotPubSubType>> global_snapshot_writer;
  std::unique_ptr<StampedWriter<pena_dds::SyncRequestPubSubType>> sync_writer;
};

}  // namespace pena::gateway
