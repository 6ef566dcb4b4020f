#include "pena/gateway/link_scheduler.hpp"

#include <algorithm>
#include <stdexcept>

#include "pena/gateway/link_codec.hpp"

namespace pena::gateway {
namespace {

ClassCounters& Of(std::array<ClassCounters, kItemClassCount>& counters, ItemClass item_class) {
  return counters[static_cast<std::size_t>(item_class)];
}

// Adds `item` to the envelope if it keeps within max_bytes; records its bytes in `selection`.
class EnvelopeFiller {
 public:
  EnvelopeFiller(link::Envelope* envelope, std::size_t max_bytes, bool oversized_ok,
                 Selection* selection)
      : envelope_(envelope), max_bytes_(max_bytes), oversized_ok_(oversized_ok),
        selection_(selection), size_(envelope->ByteSizeLong()) {}

  bool Add(const DomainItem& item, std::uint64_t seq, ItemClass item_class) {
    link::Item encoded;
    encoded.set_seq(seq);
    ToProto(item, envelope_->base_stamp_ms(), &encoded);
    return AddEncoded(encoded, item_class);
  }
  bool AddEncoded(const link::Item& encoded, ItemClass item_class) {
    if (selection_->full) return false;
    *envelope_->add_items() = encoded;
    const std::size_t size = envelope_->ByteSizeLong();
    if (size > max_bytes_ && !(oversized_ok_ && selection_->size() == 0)) {
      envelope_->mutable_items()->RemoveLast();
      selection_->full = true;
      return false;
    }
    ClassCounters& counters = Of(selection_->counters, item_class);
    ++counters.items;
    counters.bytes += size - size_;
    size_ = size;
    return true;
  }

 private:
  link::Envelope* envelope_;
  std::size_t max_bytes_;
  bool oversized_ok_;
  Selection* selection_;
  std::size_t size_;
};

}  // namespace

std::size_t Selection::size() const {
  return annotation_seqs.size() + pose_entities.size() + correction_entities.size() +
         snapshot_maps.size() + deltas.size();
}

LinkScheduler::LinkScheduler(SchedulerOptions options) : options_(options) {
  if (!(options_.retransmit_timeout_s > 0.0)) {
    throw std::invalid_argument("scheduler.retransmit_timeout_s must be > 0 s, got " +
                                std::to_string(options_.retransmit_timeout_s));
  }
  if (!(options_.max_retransmit_timeout_s >= options_.retransmit_timeout_s)) {
    throw std::invalid_argument(
        "scheduler.max_retransmit_timeout_s must be >= retransmit_timeout_s s, got " +
        std::to_string(options_.max_retransmit_timeout_s));
  }
}

void LinkScheduler::Offer(DomainItem item) {
  if (auto* pose = std::get_if<PoseUpdate>(&item)) {
    PoseSlot& slot = poses_[pose->entity];
    if (slot.pose.entity.empty() || pose->stamp_s >= slot.pose.stamp_s) {
      if (!slot.pose.entity.empty() && !slot.sent) ++replaced_poses_;
      slot = PoseSlot{std::move(*pose), false};
    }
  } else if (auto* annotation = std::get_if<Annotation>(&item)) {
    annotations_.emplace(next_seq_++, PendingAnnotation{std::move(*annotation), {}});
  } else if (auto* correction = std::get_if<Correction>(&item)) {
    auto found = corrections_.find(correction->entity);
    if (found != corrections_.end() && correction->version <= found->second.correction.version) return;
    const std::string entity = correction->entity;
    corrections_[entity] = PendingCorrection{std::move(*correction), next_seq_++, false, {}};
  } else {
    OfferMap(std::get<MapChange>(std::move(item)));
  }
}

void LinkScheduler::OfferMap(MapChange change) {
  OutMap& map = maps_[change.map_id];
  if (auto* snapshot = std::get_if<line_map::MapSnapshot>(&change.change)) {
    // The producer's whole map replaces ours; the peer gets it whole (reset: it is authoritative).
    map.mirror = line_map::LineMap::FromSnapshot(*snapshot, map.mirror.options());
    map.pending.clear();
    map.snapshot_due = true;
    map.reset = true;
    map.snapshot_timer = {};
    return;
  }
  auto& delta = std::get<line_map::MapDelta>(change.change);
  if (delta.empty()) return;
  if (!map.mirror.Apply(delta).ok()) {
    ++rejected_offers_;
    return;
  }
  PendingDelta pending{std::move(delta), {}, next_order_++, {}};
  ToProto(MapChange{change.map_id, pending.delta, false}, 0, &pending.encoded);
  map.pending.push_back(std::move(pending));
}

Selection LinkScheduler::Fill(link::Envelope* envelope, std::size_t max_bytes, bool oversized_ok,
                              double now_s) {
  Selection selection;
  EnvelopeFiller filler(envelope, max_bytes, oversized_ok, &selection);
  for (const auto& [seq, pending] : annotations_) {
    if (!pending.timer.Due(now_s)) continue;
    if (!filler.Add(pending.annotation, seq, ItemClass::kAnnotation)) return selection;
    selection.annotation_seqs.push_back(seq);
  }
  // Oldest pose first, so no entity's pose waits behind the others twice.
  std::vector<const PoseSlot*> poses;
  for (const auto& [entity, slot] : poses_) if (!slot.sent) poses.push_back(&slot);
  std::sort(poses.begin(), poses.end(),
            [](const PoseSlot* a, const PoseSlot* b) { return a->pose.stamp_s < b->pose.stamp_s; });
  for (const PoseSlot* slot : poses) {
    if (!filler.Add(slot->pose, 0, ItemClass::kPose)) return selection;
    selection.pose_entities.push_back(slot->pose.entity);
  }
  for (const auto& [entity, pending] : corrections_) {
    if (pending.acked || !pending.timer.Due(now_s)) continue;
    if (!filler.Add(pending.correction, pending.seq, ItemClass::kCorrection)) return selection;
    selection.correction_entities.push_back(entity);
  }
  for (const auto& [map_id, map] : maps_) {
    if (!map.snapshot_due || !map.snapshot_timer.Due(now_s)) continue;
    if (!filler.Add(MapChange{map_id, map.mirror.Snapshot(), map.reset}, 0, ItemClass::kMap)) {
      return selection;
    }
    selection.snapshot_maps.push_back(map_id);
  }
  // Deltas in the order they were offered: per map that is version order.
  std::vector<std::pair<const std::string*, const PendingDelta*>> due;
  for (const auto& [map_id, map] : maps_) {
    if (map.snapshot_due) continue;  // the snapshot carries them
    for (const PendingDelta& pending : map.pending) {
      if (pending.timer.Due(now_s)) due.emplace_back(&map_id, &pending);
    }
  }
  std::sort(due.begin(), due.end(),
            [](const auto& a, const auto& b) { return a.second->order < b.second->order; });
  for (const auto& [map_id, pending] : due) {
    if (!filler.AddEncoded(pending->encoded, ItemClass::kMap)) return selection;
    selection.deltas.emplace_back(*map_id, pending->delta.to_version);
  }
  return selection;
}

void LinkScheduler::Sent(Timer& timer, double now_s, ClassCounters& counters) const {
  if (timer.sends > 0) ++counters.resent;
  timer.timeout_s = timer.sends == 0 ? options_.retransmit_timeout_s
                                     : std::clamp(2.0 * timer.timeout_s,
                                                  options_.retransmit_timeout_s,
                                                  options_.max_retransmit_timeout_s);
  ++timer.sends;
  timer.last_sent_s = now_s;
}

void LinkScheduler::Commit(const Selection& selection, double now_s, LinkStats* stats) {
  auto& sent = stats->sent;
  for (std::size_t i = 0; i < kItemClassCount; ++i) {
    sent[i].items += selection.counters[i].items;
    sent[i].bytes += selection.counters[i].bytes;
  }
  for (std::uint64_t seq : selection.annotation_seqs) {
    Sent(annotations_.at(seq).timer, now_s, Of(sent, ItemClass::kAnnotation));
  }
  for (const std::string& entity : selection.pose_entities) poses_.at(entity).sent = true;
  for (const std::string& entity : selection.correction_entities) {
    Sent(corrections_.at(entity).timer, now_s, Of(sent, ItemClass::kCorrection));
  }
  for (const std::string& map_id : selection.snapshot_maps) {
    OutMap& map = maps_.at(map_id);
    Sent(map.snapshot_timer, now_s, Of(sent, ItemClass::kMap));
    // The snapshot holds every change up to its version.
    map.snapshot_version = map.mirror.version();
    while (!map.pending.empty() && map.pending.front().delta.to_version <= map.snapshot_version) {
      map.pending.pop_front();
    }
  }
  for (const auto& [map_id, to_version] : selection.deltas) {
    for (PendingDelta& pending : maps_.at(map_id).pending) {
      if (pending.delta.to_version == to_version) Sent(pending.timer, now_s, Of(sent, ItemClass::kMap));
    }
  }
}

void LinkScheduler::OnAck(const link::Ack& ack) {
  auto acked = [&ack](std::uint64_t seq) {
    return seq <= ack.cumulative() ||
           std::find(ack.selective().begin(), ack.selective().end(), seq) != ack.selective().end();
  };
  std::erase_if(annotations_, [&](const auto& entry) { return acked(entry.first); });
  for (auto& [entity, pending] : corrections_) {
    if (acked(pending.seq)) pending.acked = true;
  }
}

void LinkScheduler::OnPeerSummary(const link::ResyncSummary& summary, LinkStats* stats) {
  std::map<std::string, std::uint64_t> versions;
  for (const link::MapVersion& map : summary.maps()) versions[map.map_id()] = map.version();
  for (auto& [map_id, map] : maps_) {
    const auto found = versions.find(map_id);
    map.peer_version = found == versions.end() ? 0 : found->second;
    while (!map.pending.empty() && map.pending.front().delta.to_version <= map.peer_version) {
      map.pending.pop_front();
      ++stats->deltas_pruned;
    }
    CheckPeerMap(map, stats);
  }
}

void LinkScheduler::CheckPeerMap(OutMap& map, LinkStats* stats) {
  const std::uint64_t version = map.mirror.version();
  if (map.snapshot_due) {
    // Confirmed once the peer holds its version (a reset snapshot: exactly that version).
    const bool held = map.reset ? map.peer_version == map.snapshot_version
                                : map.peer_version >= map.snapshot_version;
    if (map.snapshot_timer.sends == 0 || !held) return;
    map.snapshot_due = map.reset = false;
  }
  const bool ahead = map.peer_version > version;  // the peer holds a map we never made
  const bool gap = map.peer_version < version &&
                   (map.pending.empty() || map.pending.front().delta.from_version > map.peer_version);
  if (!ahead && !gap) return;
  map.snapshot_due = true;
  map.reset = ahead;
  map.snapshot_timer = {};
  ++stats->snapshots_queued;
}

void LinkScheduler::ResendAllNow() {
  for (auto& [seq, pending] : annotations_) pending.timer.timeout_s = 0.0;
  for (auto& [entity, pending] : corrections_) pending.timer.timeout_s = 0.0;
  for (auto& [map_id, map] : maps_) {
    map.snapshot_timer.timeout_s = 0.0;
    for (PendingDelta& pending : map.pending) pending.timer.timeout_s = 0.0;
  }
}

std::size_t LinkScheduler::pending_corrections() const {
  return static_cast<std::size_t>(std::count_if(
      corrections_.begin(), corrections_.end(), [](const auto& entry) { return !entry.second.acked; }));
}

std::size_t LinkScheduler::pending_deltas() const {
  std::size_t count = 0;
  for (const auto& [map_id, map] : maps_) count += map.pending.size();
  return count;
}

}  // namespace pena::gateway
