// FusionState: annotations, read access and checkpoints (the handlers of map inputs are in
// fusion_state.cpp).
#include <cmath>
#include <stdexcept>

#include "fusion_checks.hpp"
#include "pena/fusion/fusion_state.hpp"

namespace pena::fusion {
namespace {

constexpr std::size_t kMaxAnnotationText = 4096;
constexpr std::size_t kMaxOutlineCorners = 64;  // OUTLINE_MAX_POINTS on the wire

std::string CheckAnnotation(const Annotation& annotation) {
  const std::string name = "annotation " + std::to_string(annotation.id);
  if (!annotation.position_m.allFinite()) return name + ": position_m is not finite";
  if (!std::isfinite(annotation.radius_m) || annotation.radius_m < 0.0) {
    return name + ": radius_m must be finite and >= 0 (metres)";
  }
  if (static_cast<unsigned>(annotation.kind) > static_cast<unsigned>(AnnotationKind::kNote)) {
    return name + ": unknown kind " + std::to_string(static_cast<unsigned>(annotation.kind));
  }
  if (annotation.text.size() > kMaxAnnotationText || annotation.author.size() > 256) {
    return name + ": text over 4096 bytes or author over 256 bytes";
  }
  if (annotation.author.empty()) return name + ": author is empty";
  if (annotation.outline_m.size() > kMaxOutlineCorners) {
    return name + ": outline of " + std::to_string(annotation.outline_m.size()) +
           " corners (at most 64)";
  }
  for (std::size_t i = 0; i < annotation.outline_m.size(); ++i) {
    if (!annotation.outline_m[i].allFinite()) {
      return name + ": outline corner " + std::to_string(i) + " is not finite";
    }
  }
  return {};
}

}  // namespace

FusionOutput FusionState::OnPut(const PutAnnotation& input) {
  FusionOutput output;
  Annotation annotation = input.annotation;
  if (output.problem = CheckAnnotation(annotation); !output.problem.empty()) return output;
  if (annotation.id < 0 || (annotation.id > 0 && !annotations_.contains(annotation.id))) {
    output.problem = "annotation " + std::to_string(annotation.id) + " is unknown (use id 0 to add)";
    return output;
  }
  if (annotation.id == 0) annotation.id = next_annotation_id_++;
  annotations_[annotation.id] = annotation;
  output.annotation = AnnotationChange{++annotation_version_, annotation, false};
  output.changed = true;
  return output;
}

FusionOutput FusionState::OnRemove(const RemoveAnnotation& input) {
  FusionOutput output;
  const auto it = annotations_.find(input.annotation_id);
  if (it == annotations_.end()) {
    output.problem = "annotation " + std::to_string(input.annotation_id) + " is unknown";
    return output;
  }
  output.annotation = AnnotationChange{++annotation_version_, it->second, true};
  annotations_.erase(it);
  output.changed = true;
  return output;
}

const EntityStatus* FusionState::entity(const std::string& entity_id) const {
  const auto it = entities_.find(entity_id);
  return it == entities_.end() ? nullptr : &it->second.status;
}

std::vector<std::string> FusionState::entity_ids() const {
  std::vector<std::string> ids;
  for (const auto& entry : entities_) ids.push_back(entry.first);
  return ids;
}

const line_map::LineMap& FusionState::local_map(const std::string& entity_id) const {
  const auto it = entities_.find(entity_id);
  if (it == entities_.end()) throw std::out_of_range("fusion: unknown entity " + entity_id);
  return it->second.local;
}

std::vector<Annotation> FusionState::annotations() const {
  std::vector<Annotation> all;
  for (const auto& entry : annotations_) all.push_back(entry.second);
  return all;
}

std::vector<geometry::Segment2> FusionState::CorrectionMap(const std::string& entity_id) const {
  const std::string own = entity_id + ":";
  std::vector<geometry::Segment2> walls;
  for (const line_map::LineSegment& segment : global_.Snapshot().segments) {
    for (const std::string& key : segment.provenance) {
      if (key.compare(0, own.size(), own) != 0) {
        walls.push_back(segment.segment);
        break;
      }
    }
  }
  return walls;
}

FusionCheckpoint FusionState::Checkpoint() const {
  FusionCheckpoint checkpoint;
  checkpoint.plan = plan_;
  checkpoint.global = global_.Snapshot();
  for (const auto& [id, entity] : entities_) {
    checkpoint.entities.push_back({entity.status, entity.local.Snapshot()});
  }
  checkpoint.annotations = annotations();
  checkpoint.annotation_version = annotation_version_;
  checkpoint.next_annotation_id = next_annotation_id_;
  checkpoint.rebuild_pending = rebuild_pending_;
  return checkpoint;
}

FusionState FusionState::FromCheckpoint(const FusionCheckpoint& checkpoint,
                                        FusionOptions options) {
  FusionState state(options);
  state.plan_ = checkpoint.plan;
  state.global_ = GlobalMap::FromSnapshot(checkpoint.global, options.global);
  for (const FusionCheckpoint::Entity& entity : checkpoint.entities) {
    if (const std::string problem = detail::CheckEntityId(entity.status.entity_id);
        !problem.empty()) {
      throw std::invalid_argument("fusion checkpoint: " + problem);
    }
    Entity restored{entity.status, line_map::LineMap::FromSnapshot(entity.local)};
    if (!state.entities_.emplace(entity.status.entity_id, std::move(restored)).second) {
      throw std::invalid_argument("fusion checkpoint: entity " + entity.status.entity_id +
                                  " twice");
    }
  }
  for (const Annotation& annotation : checkpoint.annotations) {
    if (annotation.id <= 0 || annotation.id >= checkpoint.next_annotation_id ||
        !state.annotations_.emplace(annotation.id, annotation).second) {
      throw std::invalid_argument("fusion checkpoint: bad or repeated annotation id " +
                                  std::to_string(annotation.id));
    }
  }
  state.annotation_version_ = checkpoint.annotation_version;
  state.next_annotation_id_ = checkpoint.next_annotation_id;
  state.rebuild_pending_ = checkpoint.rebuild_pending;
  return state;
}

double StampOf(const FusionInput& input) {
  return std::visit([](const auto& value) { return value.stamp_s; }, input);
}

const char* ToString(AnnotationKind kind) {
  switch (kind) {
    case AnnotationKind::kDangerousArea: return "dangerous_area";
    case AnnotationKind::kVictimFound: return "victim_found";
    case AnnotationKind::kCorridorCrossing: return "corridor_crossing";
    case AnnotationKind::kElevator: return "elevator";
    case AnnotationKind::kLandmark: return "landmark";
    case AnnotationKind::kNote: return "note";
  }
  return "unknown";
}

}  // namespace pena::fusion
