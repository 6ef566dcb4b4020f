#pragma once
// pena-fusion --lockstep: one mission-time order for every entity's line-map deltas and
// reference scans (docs/fusion-service.md, "Lockstep"). The entities run concurrently and their
// samples arrive in whatever order the machine's load gives, but the global map is built
// incrementally (a merge depends on what is already there) and a correction depends on the
// global map it was matched against. So in lockstep the fusion applies deltas and attempts
// scans in the order of (mission stamp, entity id, the entity's own publication order), and
// releases an item only when no entity can still send one that comes before it. Then the global
// map and every answer are the same on every run, however loaded the machine.
//
// An entity's own order comes from what each sample says came before it on the other topic:
// a reference scan carries the local-map version (every delta up to it came first), a delta
// the number of reference scans published before it; versions and scan seqs are contiguous,
// so a missing sample is noticed (pena-entity publishes a scan's delta, its reference scan, its
// pose, then any correction's delta). An entity is known to have sent everything before mission
// time t once it reported progress (a pose, a scan or a status: stamp, local-map version and
// reference scans sent) at t and all of that arrived; its later samples then have stamps >= t
// (a correction's delta keeps the scan's stamp).
//
// Pure bookkeeping, no DDS: the service keeps the payloads under the tokens it hands in.

#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <tuple>
#include <vector>

namespace pena::services {

struct LockstepOrderOptions {
  // Entities to wait for before releasing anything (their first samples may come after
  // another entity's first scan). Empty: only the entities seen so far are waited for.
  std::vector<std::string> expected_entities;
  // An item held this long (wall seconds) while an entity makes no progress is released anyway
  // and that entity is no longer waited for until it catches up (a crashed or frozen entity
  // must not stop the others; they give an answer up after 5 s). > 0.
  double stall_s = 10.0;
};

// Throws std::invalid_argument naming the field.
void ValidateLockstepOrderOptions(const LockstepOrderOptions& options);

// What Next() hands back: the token given with the item, and why it was released.
struct LockstepRelease {
  std::uint64_t token = 0;
  std::string entity_id;
  bool forced = false;   // released after stall_s although an entity might still precede it
  std::string waited_for;  // forced: the entity that did not make progress
};

class LockstepOrder {
 public:
  explicit LockstepOrder(LockstepOrderOptions options);

  // An entity seen for the first time (call before anything else of it): a new one starts at
  // version 0 and no scans; after a restart of the fusion `base_version` is what the store
  // holds and `fresh` is false: the scans it sent before are taken from its first sample.
  void Join(const std::string& entity_id, std::uint64_t base_version, bool fresh);
  // A line-map delta from_version -> to_version made at mission time stamp_s, after
  // scans_before reference scans.
  void AddDelta(const std::string& entity_id, double stamp_s, std::uint64_t from_version,
                std::uint64_t to_version, std::uint64_t scans_before, std::uint64_t token,
                std::int64_t now_ns);
  // Reference scan `seq` (1, 2, ...) taken at stamp_s with the entity's local map at
  // local_map_version (also progress: the entity reached stamp_s).
  void AddScan(const std::string& entity_id, double stamp_s, std::uint64_t local_map_version,
               std::uint64_t seq, std::uint64_t token, std::int64_t now_ns);
  // A pose or status: the entity reached stamp_s with its local map at local_map_version and
  // scans_sent reference scans published.
  void Progress(const std::string& entity_id, double stamp_s, std::uint64_t local_map_version,
                std::uint64_t scans_sent);
  // The entity's status was handled: its kind and whether its start is known, which the
  // correction filter and the placement depend on. Until then none of its items is its turn
  // (the status is published first but travels on its own topic, so it may arrive after the
  // first reference scan; a stall releases them anyway).
  void StatusHeard(const std::string& entity_id);
  // The entity finished: once what it sent has arrived it is not waited for any more.
  void Finished(const std::string& entity_id, std::uint64_t final_version,
                std::uint64_t scans_sent);
  // The entity left or was lost: no longer waited for; what it sent is released in order.
  void Drop(const std::string& entity_id);

  // The next item whose turn it is, or nullopt. After stall_s without a release while items
  // wait, the first item in order is forced out (see LockstepOrderOptions::stall_s).
  std::optional<LockstepRelease> Next(std::int64_t now_ns);

  std::size_t held() const;
  // Each entity's frontier, versions and held items, for the logs.
  std::string Describe() const;
  // Wall ns since the first item still held was last passed over (-1: nothing held).
  std::int64_t waiting_ns(std::int64_t now_ns) const {
    return waiting_since_ns_ < 0 ? -1 : now_ns - waiting_since_ns_;
  }
  long forced() const { return forced_; }

 private:
  // Order within an entity: (version position, 0 = delta / 1 = scan, scan seq, copy).
  using LocalKey = std::tuple<std::uint64_t, int, std::uint64_t, int>;
  struct Item {
    double stamp_s = 0.0;
    std::uint64_t from_version = 0;  // deltas
    std::uint64_t scans_before = 0;  // deltas: reference scans before it; scans: seq - 1
    bool scan = false;
    std::uint64_t token = 0;
  };
  struct Mark {  // reported progress not yet covered by what arrived
    std::uint64_t version = 0;
    std::uint64_t scans = 0;
    double stamp_s = 0.0;
  };
  struct Entity {
    bool seen = false;                 // an expected entity counts only once seen
    bool scans_known = true;           // false after a restart until its first sample
    bool status_heard = false;         // StatusHeard: its items may be released
    std::uint64_t released_version = 0;  // deltas applied up to here
    std::uint64_t received_version = 0;  // every delta up to here is released or held
    std::uint64_t released_scans = 0;    // reference scans handled up to this seq
    std::uint64_t received_scans = 0;    // every scan up to this seq is released or held
    std::set<std::uint64_t> held_scans;  // seqs
    double frontier_s = -1e300;        // every item before (frontier_s, id) is here
    std::vector<Mark> progress;
    std::map<LocalKey, Item> items;
    std::optional<Mark> finished;
    bool done = false;     // finished (all its deltas in) or dropped: never waited for
    bool skipped = false;  // stalled: not waited for until it catches up with released_s_
  };

  Entity& Get(const std::string& entity_id);
  // After a restart: the scans sent before the first sample heard count as handled.
  void LearnScans(Entity& entity, std::uint64_t scans_before);
  void Insert(Entity& entity, LocalKey key, const Item& item, std::int64_t now_ns);
  void Advance(Entity& entity);
  // The entity's first item if its turn within the entity has come (deltas contiguous).
  const Item* Ready(const Entity& entity) const;
  // No other entity can still send an item before (stamp_s, entity_id).
  bool Safe(const std::string& entity_id, double stamp_s) const;
  // Waiting entities that block (stamp_s, entity_id): the first one, or "".
  std::string Blocker(const std::string& entity_id, double stamp_s) const;
  LockstepRelease Release(const std::string& entity_id, Entity& entity, bool forced,
                          const std::string& waited_for, std::int64_t now_ns);

  LockstepOrderOptions options_;
  std::map<std::string, Entity> entities_;
  double released_s_ = -1e300;  // stamp of the last item released
  std::int64_t waiting_since_ns_ = -1;  // first item held with nothing released since; -1: none
  long forced_ = 0;
};

}  // namespace pena::services
