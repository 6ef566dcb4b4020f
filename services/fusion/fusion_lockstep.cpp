// pena-fusion --lockstep: deltas and reference scans handled in one mission-time order
// (lockstep_order.hpp, docs/fusion-service.md "Lockstep"). Part of FusionService
// (fusion_service.hpp).
#include <spdlog/spdlog.h>

#include "fusion_service.hpp"

namespace pena::services {

void FusionService::LockstepJoin(const std::string& entity_id) {
  // After a restart the store already holds the entity's map up to some version.
  const bool known = store_->state().entity(entity_id) != nullptr;
  lockstep_order_->Join(entity_id, known ? store_->state().local_map(entity_id).version() : 0,
                        !known);
}

void FusionService::LockstepProgress(const Event& event) {
  if (!lockstep_order_) return;
  if (const auto* pose = std::get_if<pena_dds::EntityPose>(&event.sample)) {
    const std::string entity_id = pose->entity_id().to_string();
    LockstepJoin(entity_id);
    lockstep_order_->Progress(entity_id, pose->stamp_s(), pose->local_map_version(),
                              pose->reference_scans_sent());
  } else if (const auto* status = std::get_if<pena_dds::EntityStatus>(&event.sample)) {
    const std::string entity_id = status->entity_id().to_string();
    LockstepJoin(entity_id);
    lockstep_order_->StatusHeard(entity_id);
    if (status->state() == pena_dds::ENTITY_FINISHED || status->state() == pena_dds::ENTITY_FAILED) {
      lockstep_order_->Finished(entity_id, status->local_map_version(),
                                status->reference_scans_sent());
    } else {
      lockstep_order_->Progress(entity_id, status->stamp_s(), status->local_map_version(),
                                status->reference_scans_sent());
    }
  }
}

bool FusionService::HoldInOrder(Event& event) {
  if (!lockstep_order_) return false;
  const std::uint64_t token = next_token_;
  if (const auto* delta = std::get_if<pena_dds::LineMapDelta>(&event.sample)) {
    const std::string entity_id = delta->entity_id().to_string();
    LockstepJoin(entity_id);
    lockstep_order_->AddDelta(entity_id, delta->stamp_s(), delta->from_version(),
                              delta->to_version(), delta->reference_scans_sent(), token, NowNs());
  } else if (const auto* scan = std::get_if<pena_dds::ReferenceScan>(&event.sample)) {
    const std::string entity_id = scan->entity_id().to_string();
    LockstepJoin(entity_id);
    lockstep_order_->AddScan(entity_id, scan->stamp_s(), scan->local_map_version(), scan->seq(),
                             token, NowNs());
  } else {
    return false;
  }
  held_.emplace(token, std::move(event));
  ++next_token_;
  return true;
}

void FusionService::ReleaseInOrder() {
  if (!lockstep_order_) return;
  // A wait of seconds is normal at the start (an entity whose log starts later in mission time
  // replays its first records); longer ones say who holds the others up.
  const std::int64_t now_ns = NowNs();
  if (lockstep_order_->waiting_ns(now_ns) > 2'000'000'000 && now_ns - lockstep_logged_ns_ > 2'000'000'000) {
    lockstep_logged_ns_ = now_ns;
    spdlog::info("lockstep: waiting {:.1f} s; {}",
                 static_cast<double>(lockstep_order_->waiting_ns(now_ns)) * 1e-9,
                 lockstep_order_->Describe());
  }
  while (std::optional<LockstepRelease> release = lockstep_order_->Next(NowNs())) {
    const auto it = held_.find(release->token);
    if (release->forced) {
      stats_.Add("lockstep_forced");
      spdlog::warn("lockstep: {}'s sample released after {} s without progress from {}; the "
                   "order may differ from another run's",
                   release->entity_id, options_.lockstep_order.stall_s,
                   release->waited_for.empty() ? "an entity" : release->waited_for);
    }
    if (it == held_.end()) continue;  // cannot happen: every token was held
    const Event event = std::move(it->second);
    held_.erase(it);
    Dispatch(event);
  }
}

}  // namespace pena::services
