#include "pena/fusion/fusion_state.hpp"

#include <cmath>
#include <stdexcept>

#include "fusion_checks.hpp"

namespace pena::fusion {
namespace {

using line_map::LineSegment;

// A segment of the entity's map moved into the map frame.
LineSegment Aligned(const LineSegment& segment, const geometry::Pose2& map_from_entity) {
  LineSegment moved = segment;
  moved.segment.start_m = geometry::TransformPoint(map_from_entity, segment.segment.start_m);
  moved.segment.end_m = geometry::TransformPoint(map_from_entity, segment.segment.end_m);
  return moved;
}

double WallLength(const line_map::LineMap& map) {
  double length_m = 0.0;
  for (const LineSegment& segment : map.segments()) length_m += geometry::Length(segment.segment);
  return length_m;
}

}  // namespace

const char* ToString(EntityLifecycle lifecycle) {
  switch (lifecycle) {
    case EntityLifecycle::kJoined: return "joined";
    case EntityLifecycle::kActive: return "active";
    case EntityLifecycle::kLost: return "lost";
    case EntityLifecycle::kLeft: return "left";
  }
  return "unknown";
}

void ValidateFusionOptions(const FusionOptions& options) {
  GlobalMap check(options.global);  // throws naming the field
  ValidatePlacementOptions(options.placement);
  detail::Require(std::isfinite(options.silent_after_s) && options.silent_after_s > 0.0,
                  "fusion.silent_after_s must be > 0 (seconds)", options.silent_after_s);
  detail::Require(std::isfinite(options.placement_every_m) && options.placement_every_m >= 0.0,
                  "fusion.placement_every_m must be >= 0 (metres)", options.placement_every_m);
}

FusionState::FusionState(FusionOptions options) : options_(options), global_(options.global) {
  ValidateFusionOptions(options_);
}

FusionOutput FusionState::Handle(const FusionInput& input) {
  return std::visit(
      [this](const auto& value) -> FusionOutput {
        using T = std::decay_t<decltype(value)>;
        if constexpr (std::is_same_v<T, SetPlan>) return OnPlan(value);
        if constexpr (std::is_same_v<T, EntityJoin>) return OnJoin(value);
        if constexpr (std::is_same_v<T, EntityLeave>) return OnLeave(value);
        if constexpr (std::is_same_v<T, EntityHeartbeat>) return OnHeartbeat(value);
        if constexpr (std::is_same_v<T, LocalDelta>) return OnDelta(value);
        if constexpr (std::is_same_v<T, LocalSnapshot>) return OnSnapshot(value);
        if constexpr (std::is_same_v<T, AlignmentCorrection>) return OnAlignment(value);
        if constexpr (std::is_same_v<T, OperatorCorrection>) return OnOperator(value);
        if constexpr (std::is_same_v<T, PutAnnotation>) return OnPut(value);
        if constexpr (std::is_same_v<T, RemoveAnnotation>) return OnRemove(value);
        if constexpr (std::is_same_v<T, Tick>) return OnTick(value);
        if constexpr (std::is_same_v<T, Publish>) return OnPublish(value);
        if constexpr (std::is_same_v<T, MoveEntityWalls>) return OnMoveWalls(value);
      },
      input);
}

FusionOutput FusionState::OnPlan(const SetPlan& input) {
  FusionOutput output;
  if (output.problem = detail::CheckSegments(input.segments, "plan"); !output.problem.empty()) {
    return output;
  }
  plan_ = input.segments;
  output.changed = true;
  Changed(output);
  return output;
}

FusionState::Entity& FusionState::Create(const std::string& entity_id, double stamp_s,
                                         FusionOutput& output) {
  Entity entity{{}, line_map::LineMap(line_map::LineMapOptions{})};
  entity.status.entity_id = entity_id;
  entity.status.last_data_s = stamp_s;
  output.lifecycle.push_back({entity_id, EntityLifecycle::kJoined, EntityLifecycle::kJoined, true});
  output.changed = true;
  return entities_.emplace(entity_id, std::move(entity)).first->second;
}

FusionState::Entity& FusionState::Touch(const std::string& entity_id, double stamp_s,
                                        FusionOutput& output) {
  const auto it = entities_.find(entity_id);
  // Data from an entity we never heard join (its join was lost): it is placed by matching.
  Entity& entity = it == entities_.end() ? Create(entity_id, stamp_s, output) : it->second;
  EntityStatus& status = entity.status;
  status.last_data_s = std::max(status.last_data_s, stamp_s);
  if (status.lifecycle != EntityLifecycle::kActive) {
    output.lifecycle.push_back({entity_id, status.lifecycle, EntityLifecycle::kActive, false});
    status.lifecycle = EntityLifecycle::kActive;
  }
  output.changed = true;
  return entity;
}

FusionOutput FusionState::OnJoin(const EntityJoin& input) {
  FusionOutput output;
  if (output.problem = detail::CheckEntityId(input.entity_id); !output.problem.empty()) return output;
  if (input.map_from_entity && !detail::Finite(*input.map_from_entity)) {
    output.problem = "join of " + input.entity_id + ": map_from_entity is not finite";
    return output;
  }
  // A rejoin (entity or fusion restarted) counts as data and keeps the fusion's alignment, so
  // corrections survive; a new entity stays "joined" until its first data.
  const auto it = entities_.find(input.entity_id);
  Entity& entity = it == entities_.end() ? Create(input.entity_id, input.stamp_s, output)
                                         : Touch(input.entity_id, input.stamp_s, output);
  if (!entity.status.map_from_entity && input.map_from_entity) {
    entity.status.map_from_entity = input.map_from_entity;
    if (entity.local.size() > 0) Changed(output);
  }
  return output;
}

FusionOutput FusionState::OnLeave(const EntityLeave& input) {
  FusionOutput output;
  const auto it = entities_.find(input.entity_id);
  if (it == entities_.end()) {
    output.problem = "leave of unknown entity " + input.entity_id;
    return output;
  }
  EntityStatus& status = it->second.status;
  if (status.lifecycle != EntityLifecycle::kLeft) {
    output.lifecycle.push_back({input.entity_id, status.lifecycle, EntityLifecycle::kLeft, false});
    status.lifecycle = EntityLifecycle::kLeft;
    output.changed = true;
  }
  return output;
}

FusionOutput FusionState::OnHeartbeat(const EntityHeartbeat& input) {
  FusionOutput output;
  if (output.problem = detail::CheckEntityId(input.entity_id); !output.problem.empty()) return output;
  Touch(input.entity_id, input.stamp_s, output);
  return output;
}

FusionOutput FusionState::OnDelta(const LocalDelta& input) {
  FusionOutput output;
  if (output.problem = detail::CheckEntityId(input.entity_id); !output.problem.empty()) return output;
  const std::string name = "delta of " + input.entity_id;
  for (const auto* list : {&input.delta.added, &input.delta.changed}) {
    if (output.problem = detail::CheckSegments(*list, name); !output.problem.empty()) return output;
  }
  Entity& entity = Touch(input.entity_id, input.stamp_s, output);
  const line_map::ApplyResult result = entity.local.Apply(input.delta);
  switch (result.status) {
    case line_map::ApplyStatus::kApplied:
      entity.status.awaiting_snapshot = false;
      for (const std::int64_t id : input.delta.removed) entity.status.moved_walls.erase(id);
      AfterLocalChange(entity, output);
      break;
    case line_map::ApplyStatus::kStale:
      break;
    case line_map::ApplyStatus::kVersionGap:
      entity.status.awaiting_snapshot = true;
      output.snapshot_request = input.entity_id;
      break;
    case line_map::ApplyStatus::kInvalid:
      output.problem = name + ": " + result.message;
      break;
  }
  return output;
}

FusionOutput FusionState::OnSnapshot(const LocalSnapshot& input) {
  FusionOutput output;
  if (output.problem = detail::CheckEntityId(input.entity_id); !output.problem.empty()) return output;
  const std::string name = "snapshot of " + input.entity_id;
  if (output.problem = detail::CheckSegments(input.snapshot.segments, name);
      !output.problem.empty()) {
    return output;
  }
  std::optional<line_map::LineMap> local;
  try {
    local = line_map::LineMap::FromSnapshot(input.snapshot);
  } catch (const std::invalid_argument& error) {
    output.problem = name + ": " + error.what();
    return output;
  }
  Entity& entity = Touch(input.entity_id, input.stamp_s, output);
  // The sender's map is authoritative (it may have restarted from scratch); later deltas follow it.
  entity.local = std::move(*local);
  entity.status.awaiting_snapshot = false;
  std::erase_if(entity.status.moved_walls,
                [&entity](const auto& move) { return !entity.local.HasSegment(move.first); });
  AfterLocalChange(entity, output);
  return output;
}

FusionOutput FusionState::OnAlignment(const AlignmentCorrection& input) {
  FusionOutput output;
  const auto it = entities_.find(input.entity_id);
  if (it == entities_.end()) {
    output.problem = "correction of unknown entity " + input.entity_id;
  } else if (!detail::Finite(input.map_from_entity) || !(input.confidence >= 0.0) ||
             !(input.confidence <= 1.0)) {
    output.problem = "correction of " + input.entity_id +
                     ": map_from_entity not finite or confidence outside [0, 1]";
  } else {
    it->second.status.map_from_entity = input.map_from_entity;
    output.changed = true;
    Changed(output);
  }
  return output;
}

FusionOutput FusionState::OnOperator(const OperatorCorrection& input) {
  FusionOutput output;
  const auto it = entities_.find(input.entity_id);
  if (it == entities_.end() || !it->second.status.map_from_entity) {
    output.problem = "operator correction of " + input.entity_id + " by " + input.author +
                     ": entity unknown or not placed";
  } else if (!detail::Finite(input.corrected_from_wrong)) {
    output.problem = "operator correction of " + input.entity_id + ": transform not finite";
  } else {
    auto& alignment = it->second.status.map_from_entity;
    alignment = geometry::Compose(input.corrected_from_wrong, *alignment);
    output.changed = true;
    Changed(output);
  }
  return output;
}

FusionOutput FusionState::OnMoveWalls(const MoveEntityWalls& input) {
  FusionOutput output;
  const auto it = entities_.find(input.entity_id);
  if (it == entities_.end() || !it->second.status.map_from_entity) {
    output.problem = "operator move of " + input.entity_id + "'s walls by " + input.author +
                     ": entity unknown or not placed";
  } else if (!detail::Finite(input.corrected_from_wrong)) {
    output.problem = "operator move of " + input.entity_id + "'s walls: transform not finite";
  } else {
    Entity& entity = it->second;
    for (const std::int64_t id : input.segment_ids) {
      if (!entity.local.HasSegment(id)) continue;  // merged away since: nothing left to move
      const auto [move, added] = entity.status.moved_walls.try_emplace(id, geometry::Pose2{});
      move->second = geometry::Compose(input.corrected_from_wrong, move->second);
    }
    output.changed = true;
    Changed(output);
  }
  return output;
}

void FusionState::AfterLocalChange(Entity& entity, FusionOutput& output) {
  EntityStatus& status = entity.status;
  if (!status.map_from_entity) {
    const double length_m = WallLength(entity.local);
    if (length_m < status.placement_length_m + options_.placement_every_m) return;
    status.placement_length_m = length_m;
    status.placement = PlaceLocalMap(entity.local.segments(), global_.Snapshot().segments,
                                     status.placement.hypotheses, options_.placement);
    output.placement = status.placement;
    if (!status.placement.placed) return;
    status.map_from_entity = status.placement.map_from_entity;
  }
  Changed(output);
}

void FusionState::Changed(FusionOutput& output) {
  if (options_.rebuild_on_publish) {
    rebuild_pending_ = true;
  } else {
    Rebuild(output);
  }
}

FusionOutput FusionState::OnPublish(const Publish&) {
  FusionOutput output;
  if (rebuild_pending_) {
    Rebuild(output);
    rebuild_pending_ = false;
    output.changed = true;
  }
  return output;
}

void FusionState::Rebuild(FusionOutput& output) {
  std::vector<MergeSource> sources;
  sources.push_back({"plan", plan_, true});
  for (const auto& [id, entity] : entities_) {
    if (!entity.status.map_from_entity) continue;
    MergeSource source{id, entity.local.segments()};
    const std::map<std::int64_t, geometry::Pose2>& moved = entity.status.moved_walls;
    for (LineSegment& segment : source.segments) {
      const auto move = moved.find(segment.id);
      segment = Aligned(segment, move == moved.end()
                                     ? *entity.status.map_from_entity
                                     : geometry::Compose(move->second, *entity.status.map_from_entity));
    }
    sources.push_back(std::move(source));
  }
  line_map::MapDelta delta = global_.Rebuild(sources);
  if (!delta.empty()) output.global_delta = std::move(delta);
}

FusionOutput FusionState::OnTick(const Tick& input) {
  FusionOutput output;
  for (auto& [id, entity] : entities_) {
    EntityStatus& status = entity.status;
    const bool watched = status.lifecycle == EntityLifecycle::kActive ||
                         status.lifecycle == EntityLifecycle::kJoined;
    if (watched && input.stamp_s - status.last_data_s > options_.silent_after_s) {
      output.lifecycle.push_back({id, status.lifecycle, EntityLifecycle::kLost, false});
      status.lifecycle = EntityLifecycle::kLost;
      output.changed = true;
    }
  }
  return output;
}

}  // namespace pena::fusion
