#include "lockstep_order.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace pena::services {
namespace {

// (stamp, entity) order across entities: equal stamps (simulated entities scan together) go
// by entity id.
bool Before(double stamp_s, const std::string& entity_id, double other_s,
            const std::string& other_id) {
  return stamp_s < other_s || (stamp_s == other_s && entity_id < other_id);
}

}  // namespace

void ValidateLockstepOrderOptions(const LockstepOrderOptions& options) {
  if (!(options.stall_s > 0.0) || !std::isfinite(options.stall_s)) {
    throw std::invalid_argument("lockstep stall_s must be > 0 s, got " +
                                std::to_string(options.stall_s));
  }
  for (const std::string& id : options.expected_entities) {
    if (id.empty()) throw std::invalid_argument("lockstep expected_entities: an empty entity id");
  }
}

LockstepOrder::LockstepOrder(LockstepOrderOptions options) : options_(std::move(options)) {
  ValidateLockstepOrderOptions(options_);
  for (const std::string& id : options_.expected_entities) entities_[id];
}

LockstepOrder::Entity& LockstepOrder::Get(const std::string& entity_id) {
  Entity& entity = entities_[entity_id];
  entity.seen = true;
  return entity;
}

void LockstepOrder::Join(const std::string& entity_id, std::uint64_t base_version, bool fresh) {
  Entity& entity = entities_[entity_id];
  if (entity.seen) return;
  entity.seen = true;
  entity.released_version = base_version;
  entity.received_version = base_version;
  entity.scans_known = fresh;
  Advance(entity);
}

void LockstepOrder::LearnScans(Entity& entity, std::uint64_t scans_before) {
  if (entity.scans_known) return;
  entity.scans_known = true;
  entity.released_scans = std::max(entity.released_scans, scans_before);
  entity.received_scans = std::max(entity.received_scans, entity.released_scans);
}

void LockstepOrder::Insert(Entity& entity, LocalKey key, const Item& item, std::int64_t now_ns) {
  if (held() == 0) waiting_since_ns_ = now_ns;
  // The same sample twice (durable samples after a restart) keeps both, in arrival order: the
  // store refuses the stale one.
  while (entity.items.count(key) > 0) ++std::get<3>(key);
  entity.items.emplace(key, item);
}

void LockstepOrder::AddDelta(const std::string& entity_id, double stamp_s,
                             std::uint64_t from_version, std::uint64_t to_version,
                             std::uint64_t scans_before, std::uint64_t token,
                             std::int64_t now_ns) {
  Entity& entity = Get(entity_id);
  LearnScans(entity, scans_before);
  Insert(entity, {to_version, 0, 0, 0}, Item{stamp_s, from_version, scans_before, false, token},
         now_ns);
  Advance(entity);
}

void LockstepOrder::AddScan(const std::string& entity_id, double stamp_s,
                            std::uint64_t local_map_version, std::uint64_t seq,
                            std::uint64_t token, std::int64_t now_ns) {
  Entity& entity = Get(entity_id);
  const std::uint64_t before = seq > 0 ? seq - 1 : 0;
  LearnScans(entity, before);
  Insert(entity, {local_map_version, 1, seq, 0}, Item{stamp_s, 0, before, true, token}, now_ns);
  entity.held_scans.insert(seq);
  Progress(entity_id, stamp_s, local_map_version, seq);
}

void LockstepOrder::Progress(const std::string& entity_id, double stamp_s,
                             std::uint64_t local_map_version, std::uint64_t scans_sent) {
  Entity& entity = Get(entity_id);
  LearnScans(entity, scans_sent);
  entity.progress.push_back(Mark{local_map_version, scans_sent, stamp_s});
  Advance(entity);
}

void LockstepOrder::Finished(const std::string& entity_id, std::uint64_t final_version,
                             std::uint64_t scans_sent) {
  Entity& entity = Get(entity_id);
  LearnScans(entity, scans_sent);
  entity.finished = Mark{final_version, scans_sent, 0.0};
  Advance(entity);
}

void LockstepOrder::StatusHeard(const std::string& entity_id) {
  // Not Get(): whether the entity was seen is Join's to decide (base version after a restart).
  entities_[entity_id].status_heard = true;
}

void LockstepOrder::Drop(const std::string& entity_id) { Get(entity_id).done = true; }

void LockstepOrder::Advance(Entity& entity) {
  // Deltas are contiguous (to = from + 1), but a gap must stop the count, not be skipped.
  for (const auto& [key, item] : entity.items) {
    const std::uint64_t to_version = std::get<0>(key);
    if (item.scan || to_version <= entity.received_version) continue;
    if (item.from_version > entity.received_version) break;
    entity.received_version = to_version;
  }
  while (entity.held_scans.count(entity.received_scans + 1) > 0) ++entity.received_scans;
  const auto covered = [&entity](const Mark& mark) {
    return mark.version <= entity.received_version && mark.scans <= entity.received_scans;
  };
  for (const Mark& mark : entity.progress) {
    if (covered(mark)) entity.frontier_s = std::max(entity.frontier_s, mark.stamp_s);
  }
  entity.progress.erase(std::remove_if(entity.progress.begin(), entity.progress.end(), covered),
                        entity.progress.end());
  if (entity.finished && covered(*entity.finished)) entity.done = true;
  if (entity.skipped && entity.frontier_s >= released_s_) entity.skipped = false;
}

const LockstepOrder::Item* LockstepOrder::Ready(const Entity& entity) const {
  if (entity.items.empty() || !entity.status_heard) return nullptr;
  const auto& [key, item] = *entity.items.begin();
  // Everything the entity sent before it was handled: a delta applies on top of the released
  // versions, a scan waits for the deltas its map holds; both wait for the scans before them.
  const bool deltas_before = item.scan ? std::get<0>(key) <= entity.released_version
                                       : item.from_version <= entity.released_version;
  return deltas_before && item.scans_before <= entity.released_scans ? &item : nullptr;
}

bool LockstepOrder::Safe(const std::string& entity_id, double stamp_s) const {
  return Blocker(entity_id, stamp_s).empty();
}

std::string LockstepOrder::Blocker(const std::string& entity_id, double stamp_s) const {
  for (const auto& [id, other] : entities_) {
    if (id == entity_id || other.skipped) continue;
    // Items it holds wait for its status (even once it is done): nothing after them goes.
    if (!other.status_heard) {
      for (const auto& [key, item] : other.items) {
        if (!Before(stamp_s, entity_id, item.stamp_s, id)) return id;
      }
    }
    if (other.done) continue;
    // Its later items come at or after (frontier_s, id).
    if (!Before(stamp_s, entity_id, other.frontier_s, id)) return id;
  }
  return "";
}

std::optional<LockstepRelease> LockstepOrder::Next(std::int64_t now_ns) {
  // The first item in (stamp, entity) order among the entities whose own turn it is.
  const std::string* first_id = nullptr;
  const Item* first = nullptr;
  for (const auto& [id, entity] : entities_) {
    const Item* item = Ready(entity);
    if (item != nullptr && (first == nullptr || Before(item->stamp_s, id, first->stamp_s, *first_id))) {
      first = item;
      first_id = &id;
    }
  }
  if (first != nullptr && Safe(*first_id, first->stamp_s)) {
    return Release(*first_id, entities_.at(*first_id), false, "", now_ns);
  }
  if (held() == 0 || now_ns - waiting_since_ns_ < static_cast<std::int64_t>(options_.stall_s * 1e9)) {
    return std::nullopt;
  }
  // Stalled: an entity makes no progress (or a delta never came). Release the first ready item,
  // or the first held one if none is ready (a lost delta: the store sees the gap and asks for
  // the entity's snapshot).
  if (first == nullptr) {
    for (const auto& [id, entity] : entities_) {
      if (entity.items.empty()) continue;
      const Item& item = entity.items.begin()->second;
      if (first == nullptr || Before(item.stamp_s, id, first->stamp_s, *first_id)) {
        first = &item;
        first_id = &id;
      }
    }
  }
  const std::string blocker = Blocker(*first_id, first->stamp_s);
  if (!blocker.empty()) entities_.at(blocker).skipped = true;
  ++forced_;
  return Release(*first_id, entities_.at(*first_id), true, blocker, now_ns);
}

LockstepRelease LockstepOrder::Release(const std::string& entity_id, Entity& entity, bool forced,
                                       const std::string& waited_for, std::int64_t now_ns) {
  // Forced out: its status is not waited for any longer either (a stall per item would crawl).
  if (forced) entity.status_heard = true;
  const auto it = entity.items.begin();
  const std::uint64_t to_version = std::get<0>(it->first);
  const Item item = it->second;
  entity.items.erase(it);
  if (item.scan) {
    const std::uint64_t seq = item.scans_before + 1;
    entity.held_scans.erase(seq);
    entity.released_scans = std::max(entity.released_scans, seq);
    entity.received_scans = std::max(entity.received_scans, entity.released_scans);
  } else {
    entity.released_version = std::max(entity.released_version, to_version);
    entity.received_version = std::max(entity.received_version, entity.released_version);
  }
  released_s_ = std::max(released_s_, item.stamp_s);
  waiting_since_ns_ = held() == 0 ? -1 : now_ns;
  Advance(entity);
  return LockstepRelease{item.token, entity_id, forced, waited_for};
}

std::size_t LockstepOrder::held() const {
  std::size_t count = 0;
  for (const auto& [id, entity] : entities_) count += entity.items.size();
  return count;
}

std::string LockstepOrder::Describe() const {
  std::ostringstream out;
  for (const auto& [id, entity] : entities_) {
    out << id << ": " << (entity.seen ? "" : "not seen, ")
        << (entity.status_heard ? "" : "no status yet, ") << (entity.done ? "done, " : "")
        << (entity.skipped ? "skipped, " : "") << "at " << entity.frontier_s << " s, versions "
        << entity.released_version << " released / " << entity.received_version
        << " received, " << entity.items.size() << " held";
    int shown = 0;
    for (const auto& [key, item] : entity.items) {
      if (++shown > 4) break;
      out << (shown == 1 ? " (" : ", ") << (item.scan ? "scan " : "delta ")
          << std::get<2>(key) << " at " << item.stamp_s << " s, version " << std::get<0>(key);
    }
    if (shown > 0) out << ")";
    out << ", scans " << entity.released_scans << " released / " << entity.received_scans
        << " received";
    if (!entity.progress.empty()) {
      out << ", progress waiting for version " << entity.progress.front().version << " scan "
          << entity.progress.front().scans;
    }
    out << "; ";
  }
  return out.str();
}

}  // namespace pena::services
