#include "console_picture.hpp"

#include <algorithm>
#include <cmath>
#include <type_traits>
#include <string>
#include <utility>
#include <vector>

namespace pena::services {
namespace {

using nlohmann::json;

double Ms(std::int64_t ns) { return static_cast<double>(ns / 1'000'000); }

// The entities among a global wall's provenance keys ("ff1:12" -> "ff1"), sorted, once each.
std::vector<std::string> MappedBy(const line_map::LineSegment& s) {
  std::vector<std::string> names;
  for (const std::string& key : s.provenance) {
    const std::size_t colon = key.rfind(':');
    if (key.empty() || key[0] == '#' || colon == std::string::npos || colon == 0) continue;
    if (std::string name = key.substr(0, colon); name != "plan") names.push_back(std::move(name));
  }
  std::sort(names.begin(), names.end());
  names.erase(std::unique(names.begin(), names.end()), names.end());
  return names;
}

// [id, x0, y0, x1, y1, observed, seen_by_entities, error_sd_m, [entities whose walls are in it]]:
// metres, map frame; the support as pena-fusion published it (0, 0 when it has none).
json SegmentJson(const line_map::LineSegment& s) {
  return json::array({s.id, s.segment.start_m.x(), s.segment.start_m.y(), s.segment.end_m.x(),
                      s.segment.end_m.y(), IsObserved(s) ? 1 : 0, s.seen_by_entities,
                      s.error_sd_m, MappedBy(s)});
}

bool SameDrawing(const line_map::LineSegment& a, const line_map::LineSegment& b) {
  return a.segment.start_m == b.segment.start_m && a.segment.end_m == b.segment.end_m &&
         IsObserved(a) == IsObserved(b) && a.seen_by_entities == b.seen_by_entities &&
         a.error_sd_m == b.error_sd_m && MappedBy(a) == MappedBy(b);
}

json TrailJson(const geometry::Trajectory& trail, std::size_t from) {
  json points = json::array();
  for (std::size_t i = from; i < trail.size(); ++i) {
    points.push_back(json::array({trail[i].stamp_s, trail[i].pose.x_m, trail[i].pose.y_m}));
  }
  return points;
}

json AnnotationJson(const AnnotationRecord& a) {
  json outline = json::array();
  for (const auto& [x, y] : a.outline) outline.push_back(json::array({x, y}));
  return {{"id", a.annotation_id}, {"author", a.author_id}, {"kind", a.kind},
          {"stamp_s", a.stamp_s},  {"x", a.x_m},            {"y", a.y_m},
          {"radius_m", a.radius_m}, {"outline", outline},    {"text", a.text},
          {"retracted", a.retracted}};
}

json CorrectionJson(const CorrectionRecord& c) {
  json out = {{"id", c.correction_id}, {"operator", c.operator_id}, {"kind", c.kind},
              {"entity", c.entity_id}, {"stamp_s", c.stamp_s},
              {"state", c.applied ? "applied" : c.refusal.empty() ? "sent" : "refused"},
              {"refusal", c.refusal}, {"undone", c.undone}, {"undoes", c.undoes}};
  if (c.geometry) {
    const geometry::Pose2 t = localisation::CorrectionTransform(*c.geometry);
    out["transform"] = json::array({t.x_m, t.y_m, t.theta_rad});
  }
  return out;
}

json LinkJson(const LinkRecord& l, std::int64_t now_ns) {
  return {{"id", l.gateway_id},
          {"peer_alive", l.peer_alive},
          {"peer_heard_age_s", l.peer_heard_age_s},
          {"budget_bit_s", l.budget_bit_s},
          {"sent_bit_s", l.sent_bit_s},
          {"received_frames_s", l.received_frames_s},
          {"pending_reliable", l.pending_reliable},
          {"pending_map_updates", l.pending_map_updates},
          {"frames_rejected", l.frames_rejected},
          {"resyncs", l.resyncs},
          {"report_age_s", static_cast<double>(now_ns - l.heard_ns) * 1e-9}};
}

}  // namespace

bool IsObserved(const line_map::LineSegment& segment) {
  return std::any_of(segment.provenance.begin(), segment.provenance.end(),
                     [](const std::string& key) {
                       return !key.empty() && key[0] != '#' && key.rfind("plan:", 0) != 0;
                     });
}

ConsolePicture::ConsolePicture(PictureOptions options) : options_(options) {}

void ConsolePicture::OnPose(const PoseUpdate& pose) {
  Entity& entity = entities_[pose.entity_id];
  // Best-effort samples may arrive out of order: an older one changes nothing.
  if (entity.pose && pose.seq != 0 && pose.seq <= entity.pose->seq &&
      pose.stamp_s <= entity.pose->stamp_s) {
    return;
  }
  entity.pose = pose;
  entity.dirty = true;
  latest_stamp_s_ = std::max(latest_stamp_s_, pose.stamp_s);
  const geometry::Pose2& p = pose.world_from_body;
  if (!entity.trail.empty()) {
    const geometry::Pose2& last = entity.trail.back().pose;
    if (std::hypot(p.x_m - last.x_m, p.y_m - last.y_m) < options_.trail_step_m) return;
  }
  entity.trail.push_back({pose.stamp_s, p});
  if (entity.trail.size() > options_.trail_points) {
    const std::size_t drop = entity.trail.size() - options_.trail_points;
    entity.trail.erase(entity.trail.begin(), entity.trail.begin() + static_cast<long>(drop));
    entity.trail_replaced = true;  // the page's copy starts earlier: send it whole
  }
}

void ConsolePicture::OnStatus(const StatusUpdate& status) {
  Entity& entity = entities_[status.entity_id];
  entity.status = status;
  entity.dirty = true;
}

void ConsolePicture::OnMapDelta(line_map::MapDelta delta) {
  if (delta.to_version <= map_.version()) return;
  if (delta.from_version > map_.version()) {
    early_.emplace(delta.from_version, std::move(delta));
    return;
  }
  if (map_.Apply(delta).ok()) ApplyEarly();
}

void ConsolePicture::OnMapSnapshot(const line_map::MapSnapshot& snapshot) {
  if (snapshot.version <= map_.version()) return;
  map_ = line_map::LineMap::FromSnapshot(snapshot);
  ApplyEarly();
}

void ConsolePicture::ApplyEarly() {
  while (!early_.empty() && early_.begin()->first <= map_.version()) {
    line_map::MapDelta delta = std::move(early_.begin()->second);
    early_.erase(early_.begin());
    map_.Apply(delta);
  }
}

void ConsolePicture::OnAnnotation(const AnnotationRecord& annotation) {
  annotations_[annotation.annotation_id] = annotation;
  dirty_annotations_.push_back(annotation.annotation_id);
}

void ConsolePicture::OnCorrection(const CorrectionRecord& given) {
  CorrectionRecord correction = given;
  if (correction.kind == "undo") {
    // The inverse of what it takes back: the same points with wrong and correct swapped.
    const CorrectionRecord* undone = FindCorrection(correction.undoes);
    if (undone != nullptr && undone->geometry) {
      correction.geometry = std::visit(
          [](auto g) -> localisation::OperatorCorrection {
            if constexpr (std::is_same_v<decltype(g), localisation::RotationCorrection>) {
              std::swap(g.wrong_m, g.correct_m);
            } else {
              std::swap(g.point_m, g.correct_m);
            }
            return g;
          },
          *undone->geometry);
    }
  }
  const bool answer = correction.applied || !correction.refusal.empty();
  for (std::size_t i = 0; i < corrections_.size(); ++i) {
    CorrectionRecord& known = corrections_[i];
    if (known.correction_id != correction.correction_id) continue;
    const bool known_answered = known.applied || !known.refusal.empty();
    if (!answer || known_answered) return;  // a durable sample again
    known.applied = correction.applied;
    known.refusal = correction.refusal;
    if (!known.applied) {
      MoveTrail(known, /*inverse=*/true);
      MarkUndone(known.undoes, false);
    }
    if (i < corrections_sent_) changed_corrections_.push_back(i);
    return;
  }
  corrections_.push_back(correction);
  if (correction.refusal.empty()) {
    MoveTrail(correction, /*inverse=*/false);
    MarkUndone(correction.undoes, true);
  }
}

void ConsolePicture::MarkUndone(const std::string& correction_id, bool undone) {
  if (correction_id.empty()) return;
  for (std::size_t i = 0; i < corrections_.size(); ++i) {
    if (corrections_[i].correction_id != correction_id) continue;
    corrections_[i].undone = undone;
    if (i < corrections_sent_) changed_corrections_.push_back(i);
  }
}

const CorrectionRecord* ConsolePicture::FindCorrection(const std::string& correction_id) const {
  for (const CorrectionRecord& c : corrections_) {
    if (c.correction_id == correction_id) return &c;
  }
  return nullptr;
}

const CorrectionRecord* ConsolePicture::LastInForce(const std::string& entity_id) const {
  for (auto it = corrections_.rbegin(); it != corrections_.rend(); ++it) {
    if (it->entity_id == entity_id && it->geometry && it->kind != "undo" && !it->undone &&
        it->refusal.empty()) {
      return &*it;
    }
  }
  return nullptr;
}

void ConsolePicture::MoveTrail(const CorrectionRecord& correction, bool inverse) {
  const auto it = entities_.find(correction.entity_id);
  if (!correction.geometry || it == entities_.end()) return;
  // The trajectory from the correction's stamp on, as the operator asked it to be (section 4.1).
  geometry::Pose2 transform = localisation::CorrectionTransform(*correction.geometry);
  if (inverse) transform = geometry::Inverse(transform);
  const double from_s = localisation::FromStamp(*correction.geometry);
  for (auto& point : it->second.trail) {
    if (point.stamp_s >= from_s) point.pose = geometry::Compose(transform, point.pose);
  }
  it->second.trail_replaced = true;
  it->second.dirty = true;
}

void ConsolePicture::OnLinkHealth(const LinkRecord& link) {
  links_[link.gateway_id] = link;
  links_dirty_ = true;
}

std::string ConsolePicture::StateOf(const Entity& entity, std::int64_t now_ns) const {
  if (entity.status && entity.status->state == "finished") return "finished";
  if (entity.status && entity.status->state == "failed") return "lost";
  const std::int64_t heard_ns = std::max(entity.pose ? entity.pose->heard_ns : 0,
                                         entity.status ? entity.status->heard_ns : 0);
  if (static_cast<double>(now_ns - heard_ns) * 1e-9 > options_.stale_after_s) return "stale";
  if (!entity.pose) return "starting";
  const std::string& status = entity.pose->status;
  if (status == "failed") return "lost";
  if (status == "first" || status == "matched") return "tracking";
  return "degraded";
}

nlohmann::json ConsolePicture::EntityJson(const std::string& id, const Entity& entity,
                                          std::int64_t now_ns, bool whole_trail) const {
  json out = {{"id", id}, {"state", StateOf(entity, now_ns)}};
  if (entity.status) {
    out["kind"] = entity.status->kind;
    out["lifecycle"] = entity.status->state;
    out["message"] = entity.status->message;
    out["corrections_applied"] = entity.status->corrections_applied;
  }
  std::int64_t heard_ns = entity.status ? entity.status->heard_ns : 0;
  if (entity.pose) {
    const PoseUpdate& p = *entity.pose;
    heard_ns = std::max(heard_ns, p.heard_ns);
    out["pose"] = {{"seq", p.seq},
                   {"stamp_s", p.stamp_s},
                   {"x", p.world_from_body.x_m},
                   {"y", p.world_from_body.y_m},
                   {"theta", p.world_from_body.theta_rad},
                   // The entity's own odometry frame: world * inverse(odom) is the frame the
                   // corrections put it in (a check of a correction compares frames with it).
                   {"odom", json::array({p.odom_from_body.x_m, p.odom_from_body.y_m,
                                         p.odom_from_body.theta_rad})},
                   {"cov", json::array({p.covariance[0], p.covariance[1], p.covariance[4]})},
                   {"status", p.status},
                   // Writer's clock, ms (fractional): a browser on this machine measures the
                   // pose's age when it arrives.
                   {"src_ms", static_cast<double>(p.source_ns) * 1e-6},
                   {"rx_ms", static_cast<double>(p.heard_ns) * 1e-6}};
  }
  out["heard_ms"] = Ms(heard_ns);
  if (whole_trail) {
    out["trail"] = TrailJson(entity.trail, 0);
  } else {
    out["trail_add"] = TrailJson(entity.trail, entity.trail_sent);
  }
  return out;
}

nlohmann::json ConsolePicture::Snapshot(std::int64_t now_ns) const {
  json entities = json::array();
  for (const auto& [id, entity] : entities_) {
    entities.push_back(EntityJson(id, entity, now_ns, true));
  }
  json segments = json::array();
  for (const line_map::LineSegment& s : map_.segments()) segments.push_back(SegmentJson(s));
  json annotations = json::array();
  for (const auto& [id, a] : annotations_) annotations.push_back(AnnotationJson(a));
  json corrections = json::array();
  for (const CorrectionRecord& c : corrections_) corrections.push_back(CorrectionJson(c));
  json links = json::array();
  for (const auto& [id, link] : links_) links.push_back(LinkJson(link, now_ns));
  return {{"type", "snapshot"},
          {"links", links},
          {"now_ms", Ms(now_ns)},
          {"entities", entities},
          {"map", {{"version", map_.version()}, {"segments", segments}}},
          {"annotations", annotations},
          {"corrections", corrections}};
}

std::optional<nlohmann::json> ConsolePicture::TakeDelta(std::int64_t now_ns) {
  json out = {{"type", "delta"}, {"now_ms", Ms(now_ns)}};
  bool any = false;
  json entities = json::array();
  for (auto& [id, entity] : entities_) {
    const std::string state = StateOf(entity, now_ns);
    if (!entity.dirty && state == entity.shown_state) continue;
    entities.push_back(EntityJson(id, entity, now_ns, entity.trail_replaced));
    entity.trail_sent = entity.trail.size();
    entity.trail_replaced = false;
    entity.dirty = false;
    entity.shown_state = state;
  }
  if (!entities.empty()) {
    out["entities"] = std::move(entities);
    any = true;
  }
  if (map_.version() != shown_version_) {
    // The difference to what the browsers hold, by id: a snapshot may replace many deltas.
    std::map<std::int64_t, line_map::LineSegment> now;
    for (line_map::LineSegment& s : map_.segments()) now.emplace(s.id, std::move(s));
    json upsert = json::array(), removed = json::array();
    for (const auto& [id, s] : now) {
      const auto old = shown_segments_.find(id);
      if (old == shown_segments_.end() || !SameDrawing(old->second, s)) {
        upsert.push_back(SegmentJson(s));
      }
    }
    for (const auto& [id, s] : shown_segments_) {
      if (now.count(id) == 0) removed.push_back(id);
    }
    out["map"] = {{"version", map_.version()}, {"upsert", upsert}, {"remove", removed}};
    shown_segments_ = std::move(now);
    shown_version_ = map_.version();
    any = true;
  }
  if (!dirty_annotations_.empty()) {
    json annotations = json::array();
    std::sort(dirty_annotations_.begin(), dirty_annotations_.end());
    dirty_annotations_.erase(std::unique(dirty_annotations_.begin(), dirty_annotations_.end()),
                             dirty_annotations_.end());
    for (const std::string& id : dirty_annotations_) {
      annotations.push_back(AnnotationJson(annotations_.at(id)));
    }
    dirty_annotations_.clear();
    out["annotations"] = std::move(annotations);
    any = true;
  }
  if (corrections_sent_ < corrections_.size() || !changed_corrections_.empty()) {
    // New ones and answered ones; the page replaces a listed id.
    json corrections = json::array();
    for (std::size_t i : changed_corrections_) corrections.push_back(CorrectionJson(corrections_[i]));
    for (std::size_t i = corrections_sent_; i < corrections_.size(); ++i) {
      corrections.push_back(CorrectionJson(corrections_[i]));
    }
    changed_corrections_.clear();
    corrections_sent_ = corrections_.size();
    out["corrections"] = std::move(corrections);
    any = true;
  }
  if (links_dirty_) {
    json links = json::array();
    for (const auto& [id, link] : links_) links.push_back(LinkJson(link, now_ns));
    out["links"] = std::move(links);
    links_dirty_ = false;
    any = true;
  }
  if (!any) return std::nullopt;
  return out;
}

const AnnotationRecord* ConsolePicture::FindAnnotation(const std::string& annotation_id) const {
  const auto it = annotations_.find(annotation_id);
  return it == annotations_.end() ? nullptr : &it->second;
}

std::optional<ConsolePicture::Nearest> ConsolePicture::NearestTrailPose(
    const std::string& entity_id, const Eigen::Vector2d& point_m) const {
  const auto it = entities_.find(entity_id);
  if (it == entities_.end() || it->second.trail.empty()) return std::nullopt;
  Nearest best{0.0, INFINITY};
  for (const geometry::StampedPose2& pose : it->second.trail) {
    const double d = std::hypot(pose.pose.x_m - point_m.x(), pose.pose.y_m - point_m.y());
    if (d < best.distance_m) best = {pose.stamp_s, d};
  }
  return best;
}

}  // namespace pena::services
