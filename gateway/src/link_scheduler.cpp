#include "pena/gateway/link_scheduler.hpp"

#include <algorithm>
#include <stdexcept>

#include "pena/gateway/link_codec.hpp"

namespace pena::gateway {
namespace {

ClassCounters& Of(std::array<ClassCounters, kItemClassCount>& counters, ItemClass item_class) {
  return counters[static_cast<std::size_t>(item_class)];
}

}  // namespace

// Adds items to the envelope while it keeps within max_bytes; records their bytes in `selection`.
class LinkScheduler::Filler {
 public:
  Filler(link::Envelope* envelope, std::size_t max_bytes, bool oversized_ok, Selection* selection,
         std::uint64_t next_seq)
      : envelope_(envelope), max_bytes_(max_bytes), oversized_ok_(oversized_ok),
        selection_(selection), size_(envelope->ByteSizeLong()), next_seq_(next_seq) {}

  bool Add(const DomainItem& item, std::uint64_t seq, ItemClass item_class) {
    link::Item encoded;
    encoded.set_seq(seq);
    ToProto(item, envelope_->base_stamp_ms(), &encoded);
    return AddEncoded(encoded, item_class, true);
  }
  // Adds `encoded` if it fits; else the envelope is full if `mark_full`. A map update is never
  // oversized (it goes in pieces instead: a frame must stay within the receiver's limit).
  bool AddEncoded(const link::Item& encoded, ItemClass item_class, bool mark_full) {
    if (selection_->full) return false;
    *envelope_->add_items() = encoded;
    const std::size_t size = envelope_->ByteSizeLong();
    const bool oversized_ok = oversized_ok_ && selection_->size() == 0 && item_class != ItemClass::kMap;
    if (size > max_bytes_ && !oversized_ok) {
      envelope_->mutable_items()->RemoveLast();
      if (mark_full) selection_->full = true;
      return false;
    }
    Count(item_class, size);
    return true;
  }
  // Adds a piece of `update` starting at `offset`, up to max_length bytes and as many as the
  // room allows (at least min_length unless the piece is shorter). Returns its length, or
  // nullopt (the envelope is full). A piece shorter than max_length fills the envelope.
  std::optional<std::uint32_t> AddPiece(const OutgoingUpdate& update, std::uint32_t offset,
                                        std::uint32_t max_length, std::size_t min_length) {
    if (selection_->full) return std::nullopt;
    const std::size_t room = max_bytes_ > size_ ? max_bytes_ - size_ : 0;
    std::size_t length = std::min<std::size_t>(max_length, room > 24 ? room - 24 : 0);
    for (int attempt = 0; attempt < 4; ++attempt) {
      if (length == 0 || (length < min_length && length < max_length)) break;
      link::Item* item = envelope_->add_items();
      item->set_seq(next_seq_);
      link::Fragment* fragment = item->mutable_fragment();
      fragment->set_group(update.group());
      fragment->set_total_bytes(static_cast<std::uint32_t>(update.bytes().size()));
      fragment->set_offset(offset);
      fragment->set_data(update.bytes().substr(offset, length));
      const std::size_t size = envelope_->ByteSizeLong();
      const std::size_t overhead = size - size_ - length;
      const std::size_t best = std::min<std::size_t>(max_length, room > overhead ? room - overhead : 0);
      if (size <= max_bytes_ && (best <= length || attempt == 3)) {
        Count(ItemClass::kMap, size);
        ++next_seq_;
        if (length < max_length) selection_->full = true;
        return static_cast<std::uint32_t>(length);
      }
      envelope_->mutable_items()->RemoveLast();
      length = size > max_bytes_ ? length - std::min(length, size - max_bytes_) : best;
    }
    selection_->full = true;
    return std::nullopt;
  }
  std::uint64_t next_seq() const { return next_seq_; }

 private:
  void Count(ItemClass item_class, std::size_t size) {
    ClassCounters& counters = Of(selection_->counters, item_class);
    ++counters.items;
    counters.bytes += size - size_;
    size_ = size;
  }

  link::Envelope* envelope_;
  std::size_t max_bytes_;
  bool oversized_ok_;
  Selection* selection_;
  std::size_t size_;
  std::uint64_t next_seq_;
};


std::size_t Selection::size() const {
  return annotation_seqs.size() + pose_entities.size() + correction_entities.size() +
         snapshot_maps.size() + deltas.size() + pieces.size();
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
  if (options_.min_piece_bytes == 0) {
    throw std::invalid_argument("scheduler.min_piece_bytes must be > 0 bytes, got 0");
  }
  if (!(options_.fragment_stall_s > 0.0)) {
    throw std::invalid_argument("scheduler.fragment_stall_s must be > 0 s, got " +
                                std::to_string(options_.fragment_stall_s));
  }
}

void LinkScheduler::Offer(DomainItem item) {
  if (auto* pose = std::get_if<PoseUpdate>(&item)) {
    PoseSlot& slot = poses_[pose->entity];
    if (slot.pose.entity.empty() || pose->stamp_s >= slot.pose.stamp_s) {
      if (!slot.pose.entity.empty() && !slot.sent) ++replaced_poses_;
      slot = PoseSlot{std::move(*pose), false};
    }
  } else if (std::holds_alternative<Annotation>(item) ||
             std::holds_alternative<OperatorCorrection>(item)) {
    annotations_.emplace(next_seq_++, PendingAnnotation{std::move(item), {}});
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
    QueueSnapshot(change.map_id, map, true);
    return;
  }
  auto& delta = std::get<line_map::MapDelta>(change.change);
  if (delta.empty()) return;
  if (!map.mirror.Apply(delta).ok()) {
    ++rejected_offers_;
    return;
  }
  link::Item encoded;
  ToProto(MapChange{change.map_id, delta, false}, 0, &encoded);
  map.pending.push_back(PendingDelta{delta.from_version, delta.to_version,
                                     OutgoingUpdate(encoded, next_group_++), next_order_++});
}

// Freezes the map as it is now into a snapshot; the deltas it covers are dropped.
void LinkScheduler::QueueSnapshot(const std::string& map_id, OutMap& map, bool reset) {
  map.reset = reset;
  map.snapshot_version = map.mirror.version();
  link::Item encoded;
  ToProto(MapChange{map_id, map.mirror.Snapshot(), reset}, 0, &encoded);
  map.snapshot.emplace(encoded, next_group_++);
  while (!map.pending.empty() && map.pending.front().to_version <= map.snapshot_version) {
    map.pending.pop_front();
  }
}

bool LinkScheduler::AddUpdate(Filler& filler, const OutgoingUpdate& update, PieceRef ref,
                              double now_s, Selection* selection, bool* whole) const {
  *whole = false;
  if (!update.fragmented()) {
    if (!update.whole_timer().Due(now_s)) return true;
    if (filler.AddEncoded(update.item(), ItemClass::kMap, false)) {
      *whole = true;
      return true;
    }
  }
  for (const OutgoingUpdate::Piece& piece : update.DuePieces(now_s)) {
    const std::uint64_t seq = filler.next_seq();
    const std::optional<std::uint32_t> length =
        filler.AddPiece(update, piece.offset, piece.length, options_.min_piece_bytes);
    if (!length) break;
    ref.offset = piece.offset;
    ref.length = *length;
    ref.seq = seq;
    selection->pieces.push_back(ref);
    if (*length < piece.length) break;
  }
  if (!selection->full) return true;
  selection->map_waiting = true;  // this update (or what follows it) has more to send
  return false;
}

Selection LinkScheduler::Fill(link::Envelope* envelope, std::size_t max_bytes, bool oversized_ok,
                              double now_s) {
  Selection selection;
  Filler filler(envelope, max_bytes, oversized_ok, &selection, next_seq_);
  for (const auto& [seq, pending] : annotations_) {
    if (!pending.timer.Due(now_s)) continue;
    if (!filler.Add(pending.item, seq, ItemClass::kAnnotation)) return selection;
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
  bool whole = false;
  for (const auto& [map_id, map] : maps_) {
    if (!map.snapshot) continue;
    PieceRef ref{map_id, true, map.snapshot_version, 0, 0, 0};
    if (!AddUpdate(filler, *map.snapshot, ref, now_s, &selection, &whole)) return selection;
    if (whole) selection.snapshot_maps.push_back(map_id);
  }
  // Deltas in the order they were offered: per map that is version order.
  std::vector<std::pair<const std::string*, const PendingDelta*>> due;
  for (const auto& [map_id, map] : maps_) {
    if (map.snapshot) continue;  // the deltas after it wait until the peer holds it
    for (const PendingDelta& pending : map.pending) due.emplace_back(&map_id, &pending);
  }
  std::sort(due.begin(), due.end(),
            [](const auto& a, const auto& b) { return a.second->order < b.second->order; });
  for (const auto& [map_id, pending] : due) {
    PieceRef ref{*map_id, false, pending->to_version, 0, 0, 0};
    if (!AddUpdate(filler, pending->update, ref, now_s, &selection, &whole)) return selection;
    if (whole) selection.deltas.emplace_back(*map_id, pending->to_version);
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

OutgoingUpdate* LinkScheduler::Find(const PieceRef& ref) {
  const auto found = maps_.find(ref.map_id);
  if (found == maps_.end()) return nullptr;
  OutMap& map = found->second;
  if (ref.snapshot) {
    return map.snapshot && map.snapshot_version == ref.to_version ? &*map.snapshot : nullptr;
  }
  for (PendingDelta& pending : map.pending) {
    if (pending.to_version == ref.to_version) return &pending.update;
  }
  return nullptr;
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
    Sent(maps_.at(map_id).snapshot->whole_timer(), now_s, Of(sent, ItemClass::kMap));
  }
  for (const auto& [map_id, to_version] : selection.deltas) {
    for (PendingDelta& pending : maps_.at(map_id).pending) {
      if (pending.to_version == to_version) Sent(pending.update.whole_timer(), now_s, Of(sent, ItemClass::kMap));
    }
  }
  for (const PieceRef& ref : selection.pieces) {
    next_seq_ = std::max(next_seq_, ref.seq + 1);
    OutgoingUpdate* update = Find(ref);
    if (update == nullptr) continue;
    const Timer before = update->MarkSent(ref.offset, ref.length, ref.seq, now_s,
                                          options_.retransmit_timeout_s, options_.max_retransmit_timeout_s);
    if (before.sends > 0) ++Of(sent, ItemClass::kMap).resent;
  }
  // Updates whose every piece the peer acknowledged but whose version it never confirmed: it
  // dropped them (its buffer limit); send them again.
  for (auto& [map_id, map] : maps_) {
    if (map.snapshot && map.snapshot->Stalled(now_s, options_.fragment_stall_s)) map.snapshot->Restart(next_group_++);
    for (PendingDelta& pending : map.pending) {
      if (pending.update.Stalled(now_s, options_.fragment_stall_s)) pending.update.Restart(next_group_++);
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
  for (auto& [map_id, map] : maps_) {
    if (map.snapshot) map.snapshot->Ack(ack);
    for (PendingDelta& pending : map.pending) pending.update.Ack(ack);
  }
}

void LinkScheduler::OnPeerSummary(const link::ResyncSummary& summary, LinkStats* stats) {
  std::map<std::string, std::uint64_t> versions;
  for (const link::MapVersion& map : summary.maps()) versions[map.map_id()] = map.version();
  for (auto& [map_id, map] : maps_) {
    const auto found = versions.find(map_id);
    map.peer_version = found == versions.end() ? 0 : found->second;
    while (!map.pending.empty() && map.pending.front().to_version <= map.peer_version) {
      map.pending.pop_front();
      ++stats->deltas_pruned;
    }
    CheckPeerMap(map_id, map, stats);
  }
}

void LinkScheduler::CheckPeerMap(const std::string& map_id, OutMap& map, LinkStats* stats) {
  const std::uint64_t version = map.mirror.version();
  if (map.snapshot) {
    // Confirmed once the peer holds its version (a reset snapshot: exactly that version).
    const bool held = map.reset ? map.peer_version == map.snapshot_version
                                : map.peer_version >= map.snapshot_version;
    if (!map.snapshot->SentCompletely() || !held) return;
    map.snapshot.reset();
    map.reset = false;
  }
  const bool ahead = map.peer_version > version;  // the peer holds a map we never made
  const bool gap = map.peer_version < version &&
                   (map.pending.empty() || map.pending.front().from_version > map.peer_version);
  if (!ahead && !gap) return;
  QueueSnapshot(map_id, map, ahead);
  ++stats->snapshots_queued;
}

void LinkScheduler::ResendAllNow() {
  for (auto& [seq, pending] : annotations_) pending.timer.timeout_s = 0.0;
  for (auto& [entity, pending] : corrections_) pending.timer.timeout_s = 0.0;
  for (auto& [map_id, map] : maps_) {
    if (map.snapshot) map.snapshot->DueNow();
    for (PendingDelta& pending : map.pending) pending.update.DueNow();
  }
}

void LinkScheduler::OnPeerRestart() {
  for (auto& [map_id, map] : maps_) {
    if (map.snapshot) map.snapshot->Restart(next_group_++);
    for (PendingDelta& pending : map.pending) pending.update.Restart(next_group_++);
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
