// pena-fusion: what the worker does with the samples its listeners queued (reference scans:
// fusion_corrections.cpp). Part of FusionService (fusion_service.hpp).
#include <spdlog/spdlog.h>

#include <chrono>
#include <cmath>

#include "from_dds.hpp"
#include "fusion_service.hpp"
#include "pena/localisation/operator_corrections.hpp"
#include "to_dds.hpp"

namespace pena::services {
namespace {

// The participant part (GUID prefix, 12 bytes) of a publication handle.
std::string ParticipantOf(const Handle& publication) {
  return std::string(reinterpret_cast<const char*>(publication.data()), 12);
}

template <class PubSubType>
std::uint32_t SizeOf(const typename PubSubType::type& sample) {
  PubSubType type;
  return type.getSerializedSizeProvider(const_cast<typename PubSubType::type*>(&sample))();
}

fusion::AnnotationKind FromDds(pena_dds::AnnotationKind kind) {
  switch (kind) {
    case pena_dds::ANNOTATION_DANGEROUS_AREA: return fusion::AnnotationKind::kDangerousArea;
    case pena_dds::ANNOTATION_VICTIM_FOUND: return fusion::AnnotationKind::kVictimFound;
    case pena_dds::ANNOTATION_CORRIDOR_CROSSING: return fusion::AnnotationKind::kCorridorCrossing;
    case pena_dds::ANNOTATION_ELEVATOR: return fusion::AnnotationKind::kElevator;
    case pena_dds::ANNOTATION_STAIRS:
    case pena_dds::ANNOTATION_EXIT: return fusion::AnnotationKind::kLandmark;
    case pena_dds::ANNOTATION_FREE_TEXT: break;
  }
  return fusion::AnnotationKind::kNote;
}

}  // namespace

bool FusionService::FromSelf(const SampleMeta& meta) const {
  const auto& prefix = participant_.get()->guid().guidPrefix.value;
  for (std::size_t i = 0; i < 12; ++i) {
    if (meta.publication[i] != prefix[i]) return false;
  }
  return true;
}

void FusionService::Dispatch(const Event& event) {
  try {
    std::visit([&](const auto& sample) { Handle(sample, event.meta); }, event.sample);
  } catch (const std::logic_error& error) {
    // Another schema version, a malformed or oversized sample: dropped, the service goes on.
    stats_.Add("samples_dropped");
    spdlog::warn("sample dropped: {}", error.what());
  }
}

void FusionService::EnsureJoined(const std::string& entity_id, const SampleMeta& meta,
                                 bool start_unknown) {
  entity_of_participant_[ParticipantOf(meta.publication)] = entity_id;
  if (store_->state().entity(entity_id) != nullptr) return;
  if (start_unknown) {
    // Its local map is in its own frame: placement (PlaceLocalMap) finds map_from_entity.
    spdlog::info("{}: start unknown; placed by matching its local map to the global map",
                 entity_id);
    Apply(fusion::EntityJoin{NowS(), entity_id, std::nullopt});
    return;
  }
  // The entity's local map is in the mission frame its known start gives: map_from_entity = I.
  Apply(fusion::EntityJoin{NowS(), entity_id, geometry::Pose2{}});
}

void FusionService::Handle(const pena_dds::EntityPose& sample, const SampleMeta& meta) {
  const std::string entity_id = sample.entity_id().to_string();
  entity_of_participant_[ParticipantOf(meta.publication)] = entity_id;
  stats_.Count("received", topics::kPose.name, entity_id,
               SizeOf<pena_dds::EntityPosePubSubType>(sample));
  latest_pose_[entity_id] = {sample.stamp_s(), FromDds(sample.world_from_body()),
                             FromDds(sample.odom_from_body())};
  if (wall_moves_.contains(entity_id)) {
    const LatestPose& pose = latest_pose_[entity_id];
    FollowWallMove(entity_id, pose.stamp_s,
                   geometry::Compose(pose.world_from_body, geometry::Inverse(pose.odom_from_body)));
  }
  stats_.Pose(entity_id, static_cast<double>(meta.reception_time_ns - meta.source_time_ns) * 1e-9,
              sample.stamp_s(), FromDds(sample.world_from_body()),
              FromDds(sample.odom_from_body()));
}

void FusionService::Handle(const pena_dds::EntityStatus& sample, const SampleMeta& meta) {
  CheckSchemaVersion(sample.schema_version(), "EntityStatus");
  const std::string entity_id = sample.entity_id().to_string();
  stats_.Count("received", topics::kStatus.name, entity_id,
               SizeOf<pena_dds::EntityStatusPubSubType>(sample));
  const bool start_unknown = sample.start_unknown();
  EnsureJoined(entity_id, meta, start_unknown);
  start_unknown_[entity_id] = start_unknown;
  if (corrections_) {
    corrections_->SetEntity(entity_id, sample.kind() == pena_dds::ENTITY_ROBOT, start_unknown);
  }
  // A placement made before a restart of the fusion (or before the entity listened): told once
  // per run.
  if (start_unknown && !placement_sent_[entity_id]) SendPlacement(entity_id, 1.0, 0);
  const fusion::EntityStatus* status = store_->state().entity(entity_id);
  const bool left = status != nullptr && status->lifecycle == fusion::EntityLifecycle::kLeft;
  if (sample.state() == pena_dds::ENTITY_FINISHED || sample.state() == pena_dds::ENTITY_FAILED) {
    if (!left) {
      spdlog::info("{} is leaving ({}{})", entity_id,
                   sample.state() == pena_dds::ENTITY_FAILED ? "failed" : "finished",
                   sample.message().size() == 0 ? "" : ": " + sample.message().to_string());
      Apply(fusion::EntityLeave{NowS(), entity_id});
    }
  } else if (sample.state() == pena_dds::ENTITY_RUNNING) {
    Apply(fusion::EntityHeartbeat{NowS(), entity_id});
  }
}

void FusionService::Handle(const pena_dds::LineMapDelta& sample, const SampleMeta& meta) {
  const std::string entity_id = sample.entity_id().to_string();
  stats_.Count("received", topics::kLineMapDelta.name, entity_id,
               SizeOf<pena_dds::LineMapDeltaPubSubType>(sample));
  line_map::MapDelta delta = services::FromDds(sample);
  EnsureJoined(entity_id, meta);
  // Journalled before the delta: a restarted fusion knows when each wall it holds was mapped.
  RecordWallStamps(entity_id, delta.added, sample.stamp_s());
  const std::uint64_t version_before = store_->state().local_map(entity_id).version();
  AfterPlacement(entity_id, Apply(fusion::LocalDelta{NowS(), entity_id, delta}));
  if (store_->state().local_map(entity_id).version() == version_before) return;  // not applied
  std::map<std::int64_t, double>& stamps = wall_stamp_s_[entity_id];
  for (const std::int64_t id : delta.removed) stamps.erase(id);
  std::vector<std::int64_t> added_ids;
  for (const line_map::LineSegment& segment : delta.added) added_ids.push_back(segment.id);
  FollowWallMove(entity_id, sample.stamp_s(), added_ids);
}

void FusionService::Handle(const pena_dds::LineMapSnapshot& sample, const SampleMeta& meta) {
  const std::string entity_id = sample.entity_id().to_string();
  stats_.Count("received", topics::kLineMapSnapshot.name, entity_id,
               SizeOf<pena_dds::LineMapSnapshotPubSubType>(sample));
  line_map::MapSnapshot snapshot = services::FromDds(sample);
  EnsureJoined(entity_id, meta);
  // Already held (the entity's final snapshot after every delta arrived): nothing to journal.
  const line_map::LineMap& local = store_->state().local_map(entity_id);
  if (local.version() == snapshot.version && line_map::SameMap(local.Snapshot(), snapshot)) return;
  // A wall not heard before dates from the snapshot (journalled before it is applied).
  RecordWallStamps(entity_id, snapshot.segments, sample.stamp_s());
  std::map<std::int64_t, double> stamps;
  const std::map<std::int64_t, double>& known = wall_stamp_s_[entity_id];
  for (const line_map::LineSegment& segment : snapshot.segments) {
    stamps[segment.id] = known.at(segment.id);
  }
  wall_stamp_s_[entity_id] = std::move(stamps);
  AfterPlacement(entity_id, Apply(fusion::LocalSnapshot{NowS(), entity_id, std::move(snapshot)}));
}

namespace {

// The move an operator's rotation, translation or undo makes (paper section 4.1): the transform
// corrected_from_wrong, from when, and its kind, filled into `record`; a problem (refused) or "".
// An undo takes back the last move of its entity still in force, from that move's stamp on.
std::string OperatorMove(const pena_dds::OperatorCorrection& sample, const OperatorLog& log,
                         OperatorLogRecord* record) {
  if (sample.kind() == pena_dds::OPERATOR_UNDO) {
    const std::string undoes = sample.undoes_id().to_string();
    const OperatorLogRecord* undone = log.Find(undoes);
    if (undone == nullptr || undone->entity_id != record->entity_id || undone->kind == "undo") {
      return "nothing to undo: '" + undoes + "' is no correction of " + record->entity_id +
             " applied here";
    }
    if (log.LastInForce(record->entity_id) != undoes) {
      return "'" + undoes + "' is not the last correction of " + record->entity_id +
             " in force (undo goes from the last one)";
    }
    record->kind = "undo";
    record->undoes = undoes;
    record->from_stamp_s = undone->from_stamp_s;
    record->corrected_from_wrong = geometry::Inverse(undone->corrected_from_wrong);
    return "";
  }
  const auto point = [](const pena_dds::Point2& p) { return Eigen::Vector2d(p.x_m(), p.y_m()); };
  localisation::OperatorCorrection move;
  if (sample.kind() == pena_dds::OPERATOR_ROTATE) {
    move = localisation::RotationCorrection{sample.stamp_s(), point(sample.rotation_origin()),
                                            point(sample.wrong_point()),
                                            point(sample.correct_point())};
    record->kind = "rotate";
  } else {
    move = localisation::TranslationCorrection{sample.stamp_s(), point(sample.wrong_point()),
                                               point(sample.correct_point())};
    record->kind = "translate";
  }
  try {
    record->corrected_from_wrong = localisation::CorrectionTransform(move);  // section 4.1
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  const geometry::Pose2& t = record->corrected_from_wrong;
  if (!std::isfinite(sample.stamp_s()) || !std::isfinite(t.x_m) || !std::isfinite(t.y_m) ||
      !std::isfinite(t.theta_rad)) {
    return "not finite";
  }
  return "";
}

}  // namespace

void FusionService::Handle(const pena_dds::OperatorCorrection& sample, const SampleMeta& meta) {
  if (FromSelf(meta)) return;
  CheckSchemaVersion(sample.schema_version(), "OperatorCorrection");
  if (sample.applied() || !sample.refusal().to_string().empty()) return;  // an answer, ours or another's
  stats_.Count("received", topics::kOperatorCorrection.name, sample.operator_id().to_string(),
               SizeOf<pena_dds::OperatorCorrectionPubSubType>(sample));
  const std::string entity_id = sample.target_entity_id().to_string();
  if (sample.kind() == pena_dds::OPERATOR_ROTATE || sample.kind() == pena_dds::OPERATOR_TRANSLATE ||
      sample.kind() == pena_dds::OPERATOR_UNDO) {
    HandleOperatorMove(sample);
    return;
  }
  if (sample.kind() != pena_dds::OPERATOR_SET_POSE) {
    spdlog::warn("operator correction {}: segment edits are not supported; ignored",
                 sample.correction_id().to_string());
    AnswerOperator(sample, "segment edits are not supported");
    return;
  }
  // Relayed to the entity, which moves its own frame (its later walls arrive corrected).
  pipeline::Correction correction;
  correction.kind = pipeline::Correction::Kind::kPose;
  correction.stamp_s = sample.stamp_s();
  correction.world_from_body = services::FromDds(sample.world_from_body());
  correction.confidence = 1.0;
  SendCorrection(entity_id, correction, 0, store_->state().global_version(),
                 sample.operator_id().to_string());
  if (corrections_) corrections_->Forget(entity_id);  // the entity's frame is the operator's now
  spdlog::info("operator {} set {}'s pose at {:.3f} s; relayed as a correction",
               sample.operator_id().to_string(), entity_id, sample.stamp_s());
  AnswerOperator(sample, "");
}

void FusionService::AnswerOperator(const pena_dds::OperatorCorrection& sample,
                                   const std::string& refusal) {
  if (!operator_answer_writer_) return;
  pena_dds::OperatorCorrection answer = sample;
  answer.applied(refusal.empty());
  SetBounded(answer.refusal(), refusal.substr(0, 160), "operator correction refusal");
  if (!operator_answer_writer_->Write(answer)) {
    spdlog::warn("operator correction {}: answer not written", sample.correction_id().to_string());
  }
}

void FusionService::HandleOperatorMove(const pena_dds::OperatorCorrection& sample) {
  const std::string id = sample.correction_id().to_string();
  const std::string entity_id = sample.target_entity_id().to_string();
  const std::string author = sample.operator_id().to_string();
  if (operator_log_->Contains(id)) {  // applied before (a durable sample comes again)
    AnswerOperator(sample, "");
    return;
  }
  OperatorLogRecord record{id, entity_id, author, "", sample.stamp_s(), {}, ""};
  if (const std::string problem = OperatorMove(sample, *operator_log_, &record); !problem.empty()) {
    spdlog::warn("operator correction {} of {} dropped: {}", id, entity_id, problem);
    AnswerOperator(sample, problem);
    return;
  }
  const geometry::Pose2 corrected_from_wrong = record.corrected_from_wrong;
  const double angle_deg = corrected_from_wrong.theta_rad * 180.0 / M_PI;
  const bool placed_entity = start_unknown_[entity_id];
  const auto latest = latest_pose_.find(entity_id);
  if (!placed_entity && latest == latest_pose_.end()) {
    spdlog::warn("operator correction {} of {} dropped: no pose of it heard yet", id, entity_id);
    AnswerOperator(sample, "no pose of " + entity_id + " heard yet");
    return;
  }
  // Recorded (and synced) before it is applied: a restart neither loses nor repeats it.
  try {
    operator_log_->Append(record);
  } catch (const std::runtime_error& error) {
    spdlog::error("operator correction {} of {} NOT applied: {}", id, entity_id, error.what());
    AnswerOperator(sample, std::string("not journalled: ") + error.what());
    return;
  }
  if (placed_entity) {
    // A placed entity keeps its own frame: its walls move with its alignment (journaled), and
    // it is told its new frame. The walls it mapped up to the origin were right: they are moved
    // back (journaled too), so that only its data from the origin on moves, as for an entity
    // with a known start.
    const fusion::FusionOutput output =
        Apply(fusion::OperatorCorrection{NowS(), entity_id, corrected_from_wrong, author});
    if (!output.problem.empty()) {
      spdlog::warn("operator correction {} dropped: {}", id, output.problem);
      AnswerOperator(sample, output.problem);
      return;
    }
    KeepWallsBefore(entity_id, record);
    SendPlacement(entity_id, 1.0, 0);
  } else {
    // An entity with a known start moves its own frame: map_from_odom <- T * map_from_odom, from
    // its latest pose (world_from_body = map_from_odom * odom_from_body). Its later poses and
    // walls arrive corrected.
    const LatestPose& latest_pose = latest->second;
    {
      const std::lock_guard<std::mutex> lock(send_mutex_);
      operator_barrier_s_[entity_id] = latest_pose.stamp_s;
    }
    pipeline::Correction correction;
    correction.kind = pipeline::Correction::Kind::kMapFromOdom;
    correction.map_from_odom = geometry::Compose(
        corrected_from_wrong, geometry::Compose(latest_pose.world_from_body,
                                                geometry::Inverse(latest_pose.odom_from_body)));
    correction.confidence = 1.0;
    // An operator's correction: the entity applies it whatever its size (correction_gate).
    SendCorrection(entity_id, correction, 0, store_->state().global_version(), author);
    StartWallMove(entity_id, record, correction.map_from_odom);
  }
  if (corrections_) corrections_->Forget(entity_id);  // the entity's frame is the operator's now
  stats_.Add("operator_corrections");
  spdlog::info("operator {}: {} of {} by ({:.3f} m, {:.3f} m, {:.2f} deg) from {:.3f} s sent",
               author, id, entity_id, corrected_from_wrong.x_m, corrected_from_wrong.y_m,
               angle_deg, record.from_stamp_s);
  AnswerOperator(sample, "");
}

void FusionService::KeepWallsBefore(const std::string& entity_id, const OperatorLogRecord& record) {
  fusion::MoveEntityWalls keep{NowS(), entity_id, geometry::Inverse(record.corrected_from_wrong),
                               {}, record.operator_id};
  for (const auto& [id, stamp_s] : wall_stamp_s_[entity_id]) {
    if (stamp_s <= record.from_stamp_s) keep.segment_ids.push_back(id);
  }
  if (keep.segment_ids.empty()) return;
  const std::size_t count = keep.segment_ids.size();
  if (const fusion::FusionOutput output = Apply(std::move(keep)); !output.problem.empty()) {
    spdlog::warn("operator correction {}: walls of {} mapped before {:.3f} s moved with the "
                 "rest: {}",
                 record.correction_id, entity_id, record.from_stamp_s, output.problem);
    return;
  }
  spdlog::info("operator correction {}: {} wall(s) {} mapped up to {:.3f} s kept where they were",
               record.correction_id, count, entity_id, record.from_stamp_s);
}

void FusionService::StartWallMove(const std::string& entity_id, const OperatorLogRecord& record,
                                  const geometry::Pose2& corrected_map_from_odom) {
  WallMove move;
  move.correction_id = record.correction_id;
  move.author = record.operator_id;
  move.corrected_from_wrong = record.corrected_from_wrong;
  move.from_stamp_s = record.from_stamp_s;
  move.corrected_map_from_odom = corrected_map_from_odom;
  wall_moves_[entity_id] = std::move(move);
  // The walls it began after the origin until now; those still on the way follow as they come.
  std::vector<std::int64_t> so_far;
  for (const auto& [id, stamp_s] : wall_stamp_s_[entity_id]) {
    if (stamp_s > record.from_stamp_s) so_far.push_back(id);
  }
  FollowWallMove(entity_id, std::nextafter(record.from_stamp_s, 1e300), so_far);
}

void FusionService::FollowWallMove(const std::string& entity_id, double delta_stamp_s,
                                   const std::vector<std::int64_t>& added_ids) {
  const auto it = wall_moves_.find(entity_id);
  if (it == wall_moves_.end()) return;
  WallMove& move = it->second;
  // Data up to the origin was right; data from the entity's first pose in the new frame on
  // arrives corrected (the walls its grid held at the correction are stamped before that). A
  // wall begun before the origin and extended after it stays: its askew pieces, too far off to
  // merge with it, are walls of their own.
  if (delta_stamp_s <= move.from_stamp_s) return;
  if (move.applied_stamp_s > 0.0 && delta_stamp_s >= move.applied_stamp_s) return;
  fusion::MoveEntityWalls walls{NowS(), entity_id, move.corrected_from_wrong, {}, move.author};
  for (const std::int64_t id : added_ids) {
    if (move.moved.insert(id).second) walls.segment_ids.push_back(id);
  }
  if (walls.segment_ids.empty()) return;
  const fusion::FusionOutput output = Apply(walls);
  if (!output.problem.empty()) {
    spdlog::warn("operator correction {}: walls of {} not moved: {}", move.correction_id,
                 entity_id, output.problem);
    return;
  }
  stats_.Add("operator_moved_walls", static_cast<long>(walls.segment_ids.size()));
  spdlog::info("operator correction {}: {} wall(s) {} mapped from {:.3f} s moved", move.correction_id,
               walls.segment_ids.size(), entity_id, move.from_stamp_s);
}

void FusionService::FollowWallMove(const std::string& entity_id, double pose_stamp_s,
                                   const geometry::Pose2& map_from_odom) {
  const auto it = wall_moves_.find(entity_id);
  if (it == wall_moves_.end() || it->second.applied_stamp_s > 0.0) return;
  const geometry::Pose2& told = it->second.corrected_map_from_odom;
  // The frame it was told (the entity sets it exactly; its poses carry it to 1e-9 m or so).
  if (std::hypot(map_from_odom.x_m - told.x_m, map_from_odom.y_m - told.y_m) < 0.01 &&
      std::abs(geometry::NormalizeAngle(map_from_odom.theta_rad - told.theta_rad)) < 0.005) {
    it->second.applied_stamp_s = pose_stamp_s;
    spdlog::info("operator correction {}: {} in its corrected frame from {:.3f} s",
                 it->second.correction_id, entity_id, pose_stamp_s);
  }
}

void FusionService::Handle(const pena_dds::Annotation& sample, const SampleMeta& meta) {
  if (FromSelf(meta)) return;
  CheckSchemaVersion(sample.schema_version(), "Annotation");
  const std::string key = sample.annotation_id().to_string();
  stats_.Count("received", topics::kAnnotation.name, sample.author_id().to_string(),
               SizeOf<pena_dds::AnnotationPubSubType>(sample));
  std::int64_t id = 0;
  if (const auto it = annotation_ids_.find(key); it != annotation_ids_.end()) id = it->second;
  for (const fusion::Annotation& known : store_->state().annotations()) {
    // After a restart the operator's durable samples come again: the same author and stamp is
    // the same mark.
    if (id == 0 && known.author == sample.author_id().to_string() &&
        known.stamp_s == sample.stamp_s()) {
      id = known.id;
    }
  }
  if (sample.retracted()) {
    if (id != 0) Apply(fusion::RemoveAnnotation{NowS(), id, sample.author_id().to_string()});
    annotation_ids_.erase(key);
  } else {
    fusion::Annotation annotation;
    annotation.id = id;
    annotation.kind = FromDds(sample.kind());
    annotation.position_m = {sample.position().x_m(), sample.position().y_m()};
    annotation.radius_m = sample.radius_m();
    for (const pena_dds::Point2& corner : sample.outline()) {
      annotation.outline_m.emplace_back(corner.x_m(), corner.y_m());
    }
    annotation.text = sample.text().to_string();
    annotation.author = sample.author_id().to_string();
    annotation.stamp_s = sample.stamp_s();
    const fusion::FusionOutput output = Apply(fusion::PutAnnotation{NowS(), annotation});
    if (output.annotation) annotation_ids_[key] = output.annotation->annotation.id;
  }
  // Journalled, then relayed so that late joiners get it after the operator left (same key:
  // readers replace), and after a restart of this fusion too (Startup).
  try {
    annotation_log_->Append(sample);
  } catch (const std::runtime_error& error) {
    spdlog::error("annotation {}: not journalled (a restarted fusion will not publish it): {}",
                  key, error.what());
  }
  pena_dds::Annotation relay = sample;
  if (annotation_writer_) annotation_writer_->Write(relay);
}

void FusionService::Handle(const pena_dds::SyncRequest& sample, const SampleMeta& meta) {
  if (FromSelf(meta) || sample.target_id().to_string() != kGlobalMapId) return;
  spdlog::info("{} asked for the global map (it holds version {})",
               sample.requester_id().to_string(), sample.have_version());
  PublishSnapshot();
}

void FusionService::Handle(const LivelinessChange& change, const SampleMeta& /*meta*/) {
  const auto it = entity_of_participant_.find(ParticipantOf(change.publication));
  const std::string who = it != entity_of_participant_.end() ? it->second : "an unknown writer";
  if (change.not_alive_change > 0) {
    spdlog::warn("{} went silent (liveliness lost); marked lost after {} s without data", who,
                 options_.store.fusion.silent_after_s);
  } else if (change.alive_change > 0) {
    spdlog::info("{} is alive (liveliness)", who);
  }
}

}  // namespace pena::services
