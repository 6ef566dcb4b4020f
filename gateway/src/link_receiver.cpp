#include "pena/gateway/link_receiver.hpp"

#include <stdexcept>

namespace pena::gateway {

LinkReceiver::LinkReceiver(ReceiverOptions options)
    : options_(options), assembler_(options.max_partial_bytes) {
  if (options_.max_early_deltas == 0) {
    throw std::invalid_argument("receiver.max_early_deltas must be > 0 deltas, got 0");
  }
  if (!(options_.ack_delay_s >= 0.0)) {
    throw std::invalid_argument("receiver.ack_delay_s must be >= 0 s, got " +
                                std::to_string(options_.ack_delay_s));
  }
  if (options_.max_update_bytes == 0 || options_.max_update_bytes > options_.max_partial_bytes) {
    throw std::invalid_argument("receiver.max_update_bytes must be in [1, max_partial_bytes] bytes, got " +
                                std::to_string(options_.max_update_bytes));
  }
}

std::optional<std::string> LinkReceiver::AcceptFragment(std::uint64_t seq, const link::Fragment& fragment,
                                                        double now_s) {
  if (seq != 0 && !FirstTime(seq, now_s)) return std::nullopt;
  return assembler_.Add(fragment);
}

bool LinkReceiver::FirstTime(std::uint64_t seq, double now_s) {
  Owe(now_s);
  ack_owed_ = true;  // duplicates too: the earlier ack was probably lost
  if (seq <= cumulative_ || beyond_.count(seq) != 0) return false;
  beyond_.insert(seq);
  while (!beyond_.empty() && *beyond_.begin() == cumulative_ + 1) {
    beyond_.erase(beyond_.begin());
    ++cumulative_;
  }
  // A peer that skipped seqs (items it replaced) must not grow this set without bound.
  while (beyond_.size() > 4 * options_.max_selective_acks) {
    cumulative_ = *beyond_.begin();
    beyond_.erase(beyond_.begin());
  }
  return true;
}

std::vector<DomainItem> LinkReceiver::Accept(std::vector<ReceivedItem> items, double now_s) {
  std::vector<DomainItem> out;
  for (ReceivedItem& received : items) {
    if (received.seq != 0 && !FirstTime(received.seq, now_s)) continue;
    if (auto* pose = std::get_if<PoseUpdate>(&received.item)) {
      auto [it, inserted] = pose_stamps_.emplace(pose->entity, pose->stamp_s);
      if (!inserted && pose->stamp_s <= it->second) continue;  // older than one delivered
      it->second = pose->stamp_s;
    } else if (auto* correction = std::get_if<Correction>(&received.item)) {
      auto [it, inserted] = correction_versions_.emplace(correction->entity, correction->version);
      if (!inserted && correction->version <= it->second) continue;
      it->second = correction->version;
    } else if (auto* change = std::get_if<MapChange>(&received.item)) {
      AcceptMap(std::move(*change), now_s, &out);
      continue;
    }
    out.push_back(std::move(received.item));
  }
  return out;
}

void LinkReceiver::Owe(double now_s) {
  if (!ack_owed_ && !summary_owed_) owed_since_s_ = now_s;
}

void LinkReceiver::OweSummary(double now_s) {
  Owe(now_s);
  summary_owed_ = true;
}

void LinkReceiver::AcceptMap(MapChange change, double now_s, std::vector<DomainItem>* out) {
  InMap& map = maps_[change.map_id];
  OweSummary(now_s);  // every map update is acknowledged by versions
  if (auto* snapshot = std::get_if<line_map::MapSnapshot>(&change.change)) {
    if (!change.reset && snapshot->version <= map.version) return;  // already held
    map.version = snapshot->version;
    std::erase_if(map.early, [&map](const auto& entry) { return entry.first < map.version; });
    out->push_back(std::move(change));
  } else {
    const auto& delta = std::get<line_map::MapDelta>(change.change);
    if (delta.to_version <= map.version) return;  // a resend of one held
    if (delta.from_version > map.version) {
      // Early: a predecessor was lost; keep it until the resend arrives.
      if (map.early.size() < options_.max_early_deltas) map.early.emplace(delta.from_version, std::move(change));
      return;
    }
    map.version = delta.to_version;
    out->push_back(std::move(change));
  }
  // Apply the early deltas that now follow.
  for (auto it = map.early.find(map.version); it != map.early.end(); it = map.early.find(map.version)) {
    map.version = std::get<line_map::MapDelta>(it->second.change).to_version;
    out->push_back(std::move(it->second));
    map.early.erase(it);
  }
}

void LinkReceiver::OnPeerRestart(double now_s) {
  cumulative_ = 0;
  beyond_.clear();
  assembler_.Clear();
  OweSummary(now_s);
}

link::Ack LinkReceiver::MakeAck() const {
  link::Ack ack;
  ack.set_cumulative(cumulative_);
  for (std::uint64_t seq : beyond_) {
    if (static_cast<std::size_t>(ack.selective_size()) >= options_.max_selective_acks) break;
    ack.add_selective(seq);
  }
  return ack;
}

link::ResyncSummary LinkReceiver::MakeSummary(std::uint64_t session) const {
  link::ResyncSummary summary;
  summary.set_session(session);
  for (const auto& [map_id, map] : maps_) {
    link::MapVersion* entry = summary.add_maps();
    entry->set_map_id(map_id);
    entry->set_version(map.version);
  }
  return summary;
}

std::uint64_t LinkReceiver::version(const std::string& map_id) const {
  const auto found = maps_.find(map_id);
  return found == maps_.end() ? 0 : found->second.version;
}

}  // namespace pena::gateway
