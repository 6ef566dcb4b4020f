// DdsDomain's worker-thread half: read samples become link items (map mirrors, snapshot grace,
// SyncRequests on gaps, annotation de-duplication), delivered items become DDS samples.
#include <spdlog/spdlog.h>

#include <sstream>

#include "dds_domain_impl.hpp"
#include "from_dds.hpp"
#include "to_dds.hpp"

namespace pena::gateway {
namespace {

template <class... F>
struct Overloaded : F... {
  using F::operator()...;
};
template <class... F>
Overloaded(F...) -> Overloaded<F...>;

// What identifies an annotation's content on the link: relays of it (fusion re-publishes every
// annotation) are not sent again.
std::string ContentKey(const Annotation& annotation) {
  std::ostringstream key;
  key.precision(17);
  key << annotation.id << ' ' << annotation.x_m << ' ' << annotation.y_m << ' ' << annotation.text;
  return key.str();
}

// An operator correction's content: pena-fusion's answer (applied, refusal) differs from the
// operator's sample and crosses; a relay of the same content does not.
std::string ContentKey(const OperatorCorrection& c) {
  std::ostringstream key;
  key.precision(17);
  key << c.kind << ' ' << c.entity << ' ' << c.mission_stamp_s << ' ' << c.origin_x_m << ' '
      << c.origin_y_m << ' ' << c.wrong_x_m << ' ' << c.wrong_y_m << ' ' << c.correct_x_m << ' '
      << c.correct_y_m << ' ' << c.applied << ' ' << c.refusal << ' ' << c.undoes_id;
  return key.str();
}

std::string AnnotationKey(const Annotation& annotation) {
  return annotation.entity + "/" + std::to_string(annotation.id >> kAnnotationIdShift);
}

}  // namespace

std::optional<DdsClass> ParseDdsClass(const std::string& name) {
  for (DdsClass c : {DdsClass::kPose, DdsClass::kEntityMap, DdsClass::kGlobalMap,
                     DdsClass::kAnnotation, DdsClass::kCorrection, DdsClass::kOperatorCorrection}) {
    if (name == ToString(c)) return c;
  }
  return std::nullopt;
}

const char* ToString(DdsClass dds_class) {
  switch (dds_class) {
    case DdsClass::kPose: return "pose";
    case DdsClass::kEntityMap: return "entity_map";
    case DdsClass::kGlobalMap: return "global_map";
    case DdsClass::kAnnotation: return "annotation";
    case DdsClass::kCorrection: return "correction";
    case DdsClass::kOperatorCorrection: return "operator_correction";
  }
  return "?";
}

std::optional<DdsRole> ParseDdsRole(const std::string& name) {
  using C = DdsClass;
  // Operator corrections go in from the command post; pena-fusion's answers come back out.
  if (name == "building") {
    return DdsRole{{C::kPose, C::kGlobalMap, C::kAnnotation, C::kOperatorCorrection},
                   {C::kAnnotation, C::kOperatorCorrection}};
  }
  if (name == "command-post") {
    return DdsRole{{C::kAnnotation, C::kOperatorCorrection},
                   {C::kPose, C::kGlobalMap, C::kAnnotation, C::kOperatorCorrection}};
  }
  if (name == "entities") {
    return DdsRole{{C::kPose, C::kEntityMap, C::kAnnotation}, {C::kAnnotation, C::kCorrection}};
  }
  if (name == "fusion-post") {
    return DdsRole{{C::kAnnotation, C::kCorrection}, {C::kPose, C::kEntityMap, C::kAnnotation}};
  }
  return std::nullopt;
}

void DdsDomain::Impl::Handle(Event event, std::vector<DomainItem>* out) {
  std::visit(Overloaded{
                 [&](PoseUpdate& pose) { out->push_back(std::move(pose)); },
                 [&](Correction& correction) { out->push_back(std::move(correction)); },
                 [&](Annotation& annotation) {
                   std::string& seen = annotations_seen[AnnotationKey(annotation)];
                   const std::string content = ContentKey(annotation);
                   if (seen == content) return;  // a relay of what already crossed
                   seen = content;
                   out->push_back(std::move(annotation));
                 },
                 [&](OperatorCorrection& correction) {
                   std::string& seen = operator_seen[correction.correction_id];
                   const std::string content = ContentKey(correction);
                   if (seen == content) return;  // a relay of what already crossed
                   seen = content;
                   out->push_back(std::move(correction));
                 },
                 [&](MapIn& map_in) { HandleMap(std::move(map_in), out); },
                 [&](SyncIn& sync) { HandleSync(sync); },
             },
             event);
}

void DdsDomain::Impl::HandleMap(MapIn map_in, std::vector<DomainItem>* out) {
  if (auto* delta = std::get_if<line_map::MapDelta>(&map_in.change)) {
    HandleDelta(map_in.map_id, std::move(*delta), out);
    return;
  }
  auto& snapshot = std::get<line_map::MapSnapshot>(map_in.change);
  if (snapshot.version <= sent_maps[map_in.map_id].version()) return;  // deltas already gave it
  // Wait: the deltas up to it are usually in flight (fusion republishes its snapshot while the
  // map changes); forward it only if they do not arrive within the grace time.
  auto [it, inserted] = pending_snapshots.try_emplace(map_in.map_id, PendingSnapshot{{}, now_s});
  if (inserted || it->second.snapshot.version < snapshot.version) it->second.snapshot = std::move(snapshot);
}

void DdsDomain::Impl::HandleDelta(const std::string& map_id, line_map::MapDelta delta,
                                  std::vector<DomainItem>* out) {
  line_map::LineMap& map = sent_maps[map_id];
  if (delta.to_version <= map.version()) {
    std::lock_guard<std::mutex> lock(mutex);
    ++stats.stale_deltas;  // transient-local history replayed, or a snapshot already covered it
    return;
  }
  const line_map::ApplyResult result = map.Apply(delta);
  if (!result.ok()) {
    spdlog::info("{}: map {}: {}; asking for a snapshot", options.name, map_id, result.message);
    RequestSync(map_id, map.version());
    return;
  }
  last_sent_change_s = now_s;
  const auto pending = pending_snapshots.find(map_id);
  if (pending != pending_snapshots.end() && pending->second.snapshot.version <= map.version()) {
    pending_snapshots.erase(pending);
  }
  out->push_back(MapChange{map_id, std::move(delta), false});
}

void DdsDomain::Impl::RequestSync(const std::string& map_id, std::uint64_t have_version) {
  if (!sync_writer) return;
  const auto last = last_sync_request_s.find(map_id);
  if (last != last_sync_request_s.end() && now_s - last->second < options.sync_request_interval_s) return;
  last_sync_request_s[map_id] = now_s;
  pena_dds::SyncRequest request;
  services::SetBounded(request.requester_id(), options.name, "gateway name (SyncRequest requester_id)");
  request.schema_version(pena_dds::SCHEMA_VERSION);
  services::SetBounded(request.target_id(), map_id, "SyncRequest target_id");
  request.have_version(have_version);
  sync_writer->Write(request, now_s);
  std::lock_guard<std::mutex> lock(mutex);
  ++stats.sync_requests_sent;
}

void DdsDomain::Impl::ForwardDueSnapshots(std::vector<DomainItem>* out) {
  for (auto it = pending_snapshots.begin(); it != pending_snapshots.end();) {
    line_map::LineMap& map = sent_maps[it->first];
    if (it->second.snapshot.version <= map.version()) {
      it = pending_snapshots.erase(it);
      continue;
    }
    if (now_s - it->second.since_s < options.snapshot_grace_s) {
      ++it;
      continue;
    }
    map = line_map::LineMap::FromSnapshot(it->second.snapshot);
    last_sent_change_s = now_s;
    out->push_back(MapChange{it->first, std::move(it->second.snapshot), true});
    {
      std::lock_guard<std::mutex> lock(mutex);
      ++stats.snapshots_forwarded;
    }
    it = pending_snapshots.erase(it);
  }
}

void DdsDomain::Impl::HandleSync(const SyncIn& sync) {
  const auto it = record.maps().find(sync.target);
  if (it == record.maps().end()) return;  // not a map this side publishes
  if (PublishSnapshot(sync.target, it->second.Snapshot())) {
    std::lock_guard<std::mutex> lock(mutex);
    ++stats.sync_requests_answered;
  }
}

bool DdsDomain::Impl::Publish(const DomainItem& item) {
  return std::visit(
      Overloaded{
          [&](const PoseUpdate& pose) {
            if (!pose_writer) return false;
            pena_dds::EntityPose sample = PoseToDds(pose, ++pose_seq[pose.entity]);
            return pose_writer->Write(sample, pose.stamp_s);
          },
          [&](const Annotation& annotation) {
            if (!annotation_writer) return false;
            pena_dds::Annotation sample = AnnotationToDds(annotation);
            annotations_seen[AnnotationKey(annotation)] = ContentKey(annotation);
            return annotation_writer->Write(sample, annotation.stamp_s);
          },
          [&](const Correction& correction) {
            if (!correction_writer) return false;
            pena_dds::Correction sample = CorrectionToDds(correction);
            return correction_writer->Write(sample, correction.stamp_s);
          },
          [&](const OperatorCorrection& correction) {
            if (!operator_writer) return false;
            pena_dds::OperatorCorrection sample = OperatorCorrectionToDds(correction);
            operator_seen[correction.correction_id] = ContentKey(correction);
            return operator_writer->Write(sample, correction.stamp_s);
          },
          [&](const MapChange& change) { return PublishMap(change); },
      },
      item);
}

bool DdsDomain::Impl::PublishMap(const MapChange& change) {
  const auto* delta = std::get_if<line_map::MapDelta>(&change.change);
  if (delta == nullptr) return PublishSnapshot(change.map_id, std::get<line_map::MapSnapshot>(change.change));
  if (change.map_id == services::kGlobalMapId) {
    if (!global_delta_writer) return false;
    pena_dds::GlobalMapDelta sample = services::ToDdsGlobalMapDelta(*delta, change.map_id, now_s);
    return global_delta_writer->Write(sample, now_s);
  }
  if (!entity_delta_writer) return false;
  pena_dds::LineMapDelta sample = services::ToDdsLineMapDelta(*delta, change.map_id, now_s);
  return entity_delta_writer->Write(sample, now_s);
}

bool DdsDomain::Impl::PublishSnapshot(const std::string& map_id, const line_map::MapSnapshot& snapshot) {
  if (map_id == services::kGlobalMapId) {
    if (!global_snapshot_writer) return false;
    pena_dds::GlobalMapSnapshot sample = services::ToDdsGlobalMapSnapshot(snapshot, map_id, now_s);
    return global_snapshot_writer->Write(sample, now_s);
  }
  if (!entity_snapshot_writer) return false;
  pena_dds::LineMapSnapshot sample = services::ToDdsLineMapSnapshot(snapshot, map_id, now_s);
  return entity_snapshot_writer->Write(sample, now_s);
}

int DdsDomain::Impl::MatchedReaders() const {
  int matched = 0;
  if (pose_reader) matched += pose_reader->matched();
  if (annotation_reader) matched += annotation_reader->matched();
  if (correction_reader) matched += correction_reader->matched();
  if (operator_reader) matched += operator_reader->matched();
  if (entity_delta_reader) matched += entity_delta_reader->matched();
  if (global_delta_reader) matched += global_delta_reader->matched();
  return matched;
}

int DdsDomain::Impl::MatchedWriters() const {
  int matched = 0;
  if (pose_writer) matched += pose_writer->matched();
  if (annotation_writer) matched += annotation_writer->matched();
  if (correction_writer) matched += correction_writer->matched();
  if (operator_writer) matched += operator_writer->matched();
  if (entity_delta_writer) matched += entity_delta_writer->matched();
  if (global_delta_writer) matched += global_delta_writer->matched();
  return matched;
}

}  // namespace pena::gateway
