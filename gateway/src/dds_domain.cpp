// The DDS side of pena-gateway (docs/gateway.md, "DDS domain side"). Reader callbacks convert
// and enqueue only; Drain and Deliver run on the gateway's one worker thread and own all state.
#include "pena/gateway/dds_domain.hpp"

#include <spdlog/spdlog.h>

#include <mutex>
#include <stdexcept>
#include <variant>

#include "dds_domain_impl.hpp"
#include "from_dds.hpp"
#include "to_dds.hpp"

namespace pena::gateway {

namespace topics = services::topics;
using services::SampleMeta;

namespace {

double SourceS(const SampleMeta& meta) { return static_cast<double>(meta.source_time_ns) * 1e-9; }

}  // namespace

DdsDomain::Impl::Impl(DdsDomainOptions domain_options)
    : options(std::move(domain_options)), participant(options.dds, options.name) {
  const auto sends = [this](DdsClass c) { return options.role.send.count(c) > 0; };
  const auto publishes = [this](DdsClass c) { return options.role.publish.count(c) > 0; };
  if (sends(DdsClass::kPose)) {
    pose_reader = MakeReader<pena_dds::EntityPosePubSubType>(
        topics::kPose, [](pena_dds::EntityPose& s, const SampleMeta& m, std::string*) -> std::optional<Event> {
          services::CheckSchemaVersion(s.schema_version(), "EntityPose");
          return PoseFromDds(s, SourceS(m));
        });
  }
  if (sends(DdsClass::kAnnotation)) {
    annotation_reader = MakeReader<pena_dds::AnnotationPubSubType>(
        topics::kAnnotation, [](pena_dds::Annotation& s, const SampleMeta& m, std::string* error) -> std::optional<Event> {
          services::CheckSchemaVersion(s.schema_version(), "Annotation");
          if (auto a = AnnotationFromDds(s, SourceS(m), error)) return *a;
          return std::nullopt;
        });
  }
  if (sends(DdsClass::kCorrection)) {
    correction_reader = MakeReader<pena_dds::CorrectionPubSubType>(
        topics::kCorrection, [](pena_dds::Correction& s, const SampleMeta& m, std::string* error) -> std::optional<Event> {
          services::CheckSchemaVersion(s.schema_version(), "Correction");
          if (auto c = CorrectionFromDds(s, SourceS(m), error)) return *c;
          return std::nullopt;
        });
  }
  if (sends(DdsClass::kOperatorCorrection)) {
    operator_reader = MakeReader<pena_dds::OperatorCorrectionPubSubType>(
        topics::kOperatorCorrection, [](pena_dds::OperatorCorrection& s, const SampleMeta& m, std::string* error) -> std::optional<Event> {
          services::CheckSchemaVersion(s.schema_version(), "OperatorCorrection");
          if (auto c = OperatorCorrectionFromDds(s, SourceS(m), error)) return *c;
          return std::nullopt;
        });
  }
  if (sends(DdsClass::kEntityMap)) {
    entity_delta_reader = MakeReader<pena_dds::LineMapDeltaPubSubType>(
        topics::kLineMapDelta, [](pena_dds::LineMapDelta& s, const SampleMeta&, std::string*) -> std::optional<Event> {
          return MapIn{s.entity_id().to_string(), services::FromDds(s)};
        });
    entity_snapshot_reader = MakeReader<pena_dds::LineMapSnapshotPubSubType>(
        topics::kLineMapSnapshot, [](pena_dds::LineMapSnapshot& s, const SampleMeta&, std::string*) -> std::optional<Event> {
          return MapIn{s.entity_id().to_string(), services::FromDds(s)};
        });
  }
  if (sends(DdsClass::kGlobalMap)) {
    global_delta_reader = MakeReader<pena_dds::GlobalMapDeltaPubSubType>(
        topics::kGlobalMapDelta, [](pena_dds::GlobalMapDelta& s, const SampleMeta&, std::string*) -> std::optional<Event> {
          return MapIn{s.map_id().to_string(), services::FromDds(s)};
        });
    global_snapshot_reader = MakeReader<pena_dds::GlobalMapSnapshotPubSubType>(
        topics::kGlobalMapSnapshot, [](pena_dds::GlobalMapSnapshot& s, const SampleMeta&, std::string*) -> std::optional<Event> {
          return MapIn{s.map_id().to_string(), services::FromDds(s)};
        });
  }
  if (sends(DdsClass::kEntityMap) || sends(DdsClass::kGlobalMap)) {
    sync_writer = std::make_unique<StampedWriter<pena_dds::SyncRequestPubSubType>>(participant, topics::kSyncRequest);
  }
  if (publishes(DdsClass::kEntityMap) || publishes(DdsClass::kGlobalMap)) {
    sync_reader = MakeReader<pena_dds::SyncRequestPubSubType>(
        topics::kSyncRequest, [](pena_dds::SyncRequest& s, const SampleMeta&, std::string*) -> std::optional<Event> {
          return SyncIn{s.target_id().to_string(), s.have_version()};
        });
  }
  CreateWriters(publishes);
}

template <class F>
void DdsDomain::Impl::CreateWriters(const F& publishes) {
  if (publishes(DdsClass::kPose)) pose_writer = MakeWriter<pena_dds::EntityPosePubSubType>(topics::kPose);
  if (publishes(DdsClass::kAnnotation)) {
    annotation_writer = MakeWriter<pena_dds::AnnotationPubSubType>(topics::kAnnotation);
  }
  if (publishes(DdsClass::kCorrection)) {
    correction_writer = MakeWriter<pena_dds::CorrectionPubSubType>(topics::kCorrection);
  }
  if (publishes(DdsClass::kOperatorCorrection)) {
    operator_writer = MakeWriter<pena_dds::OperatorCorrectionPubSubType>(topics::kOperatorCorrection);
  }
  health_writer = std::make_unique<services::Writer<pena_dds::LinkHealthPubSubType>>(participant, topics::kLinkHealth);
  if (publishes(DdsClass::kEntityMap)) {
    entity_delta_writer = MakeWriter<pena_dds::LineMapDeltaPubSubType>(topics::kLineMapDelta);
    entity_snapshot_writer = MakeWriter<pena_dds::LineMapSnapshotPubSubType>(topics::kLineMapSnapshot);
  }
  if (publishes(DdsClass::kGlobalMap)) {
    global_delta_writer = MakeWriter<pena_dds::GlobalMapDeltaPubSubType>(topics::kGlobalMapDelta);
    global_snapshot_writer = MakeWriter<pena_dds::GlobalMapSnapshotPubSubType>(topics::kGlobalMapSnapshot);
  }
}

bool DdsDomain::Impl::FromSelf(const SampleMeta& meta) const {
  const auto& prefix = participant.get()->guid().guidPrefix.value;
  for (std::size_t i = 0; i < 12; ++i) {
    if (meta.publication[i] != prefix[i]) return false;
  }
  return true;
}

void DdsDomain::Impl::Enqueue(const char* topic, std::optional<Event> event, const std::string& error) {
  std::lock_guard<std::mutex> lock(mutex);
  if (event) {
    inbox.push_back(std::move(*event));
    ++stats.samples_read;
    return;
  }
  ++stats.samples_dropped;
  spdlog::warn("{}: {} sample not carried: {}", options.name, topic, error);
}

DdsDomain::DdsDomain(DdsDomainOptions options) {
  if (!(options.snapshot_grace_s >= 0.0)) {
    throw std::invalid_argument("snapshot_grace_s must be >= 0 s, got " + std::to_string(options.snapshot_grace_s));
  }
  if (!(options.sync_request_interval_s > 0.0)) {
    throw std::invalid_argument("sync_request_interval_s must be > 0 s, got " +
                                std::to_string(options.sync_request_interval_s));
  }
  impl_ = std::make_unique<Impl>(std::move(options));
}

DdsDomain::~DdsDomain() = default;

std::vector<DomainItem> DdsDomain::Drain() {
  std::vector<Event> events;
  {
    std::lock_guard<std::mutex> lock(impl_->mutex);
    events.swap(impl_->inbox);
  }
  std::vector<DomainItem> out;
  for (Event& event : events) impl_->Handle(std::move(event), &out);
  impl_->ForwardDueSnapshots(&out);
  return out;
}

void DdsDomain::Deliver(const DomainItem& item) {
  impl_->record.Deliver(item);
  try {
    if (impl_->Publish(item)) {
      std::lock_guard<std::mutex> lock(impl_->mutex);
      ++impl_->stats.samples_published;
    }
  } catch (const std::exception& error) {
    std::lock_guard<std::mutex> lock(impl_->mutex);
    ++impl_->stats.publish_failures;
    spdlog::warn("{}: delivered item not published: {}", impl_->options.name, error.what());
  }
}

void DdsDomain::set_clock(double now_s) {
  impl_->now_s = now_s;
  impl_->record.set_clock(now_s);
}

const InMemoryDomain& DdsDomain::record() const { return impl_->record; }
const std::map<std::string, line_map::LineMap>& DdsDomain::sent_maps() const { return impl_->sent_maps; }
double DdsDomain::last_sent_map_change_s() const { return impl_->last_sent_change_s; }

DdsDomainStats DdsDomain::stats() const {
  std::lock_guard<std::mutex> lock(impl_->mutex);
  DdsDomainStats stats = impl_->stats;
  stats.samples_refused = impl_->participant.refused_samples();
  return stats;
}

void DdsDomain::PublishLinkHealth(const pena_dds::LinkHealth& health) {
  pena_dds::LinkHealth sample = health;
  if (!impl_->health_writer->Write(sample)) {
    spdlog::warn("{}: link health not published", impl_->options.name);
  }
}

int DdsDomain::matched_readers() const { return impl_->MatchedReaders(); }
int DdsDomain::matched_writers() const { return impl_->MatchedWriters(); }

}  // namespace pena::gateway
