// pena-fusion: corrections and placement (docs/fusion-service.md). Reference scans go from the
// listener to the CorrectionWorker (correction_worker.cpp: matched against virtual scans of the
// global map, gated and blended by the entity's fusion::CorrectionFilter, sent back); the fusion
// worker keeps the worker's copy of the state current, applies the alignment moves it asks for,
// and tells an entity whose start was unknown where placement put it. Part of FusionService
// (fusion_service.hpp).
#include <spdlog/spdlog.h>

#include <chrono>
#include <cmath>
#include <thread>

#include "from_dds.hpp"
#include "fusion_service.hpp"
#include "to_dds.hpp"

namespace pena::services {

void FusionService::OnReferenceScan(pena_dds::ReferenceScan&& sample, const SampleMeta& meta) {
  // In lockstep the fusion worker offers it in mission-time order, with the map of that moment.
  if (options_.lockstep && corrections_) {
    inbox_.Push(Event{Sample(std::move(sample)), meta});
    return;
  }
  Handle(sample, meta);
}

void FusionService::Handle(const pena_dds::ReferenceScan& sample, const SampleMeta& meta) {
  const std::string entity_id = sample.entity_id().to_string();
  pena_dds::ReferenceScanPubSubType type;
  stats_.Count("received", topics::kReferenceScan.name, entity_id,
               type.getSerializedSizeProvider(const_cast<pena_dds::ReferenceScan*>(&sample))());
  if (!corrections_) return;
  try {
    CheckSchemaVersion(sample.schema_version(), "ReferenceScan");
    if (lockstep_order_) {
      AwaitCorrectionReader(entity_id, meta);
      // The map as of this scan's turn: every delta before it applied, none after.
      if (context_dirty_) RefreshCorrectionContext();
      corrections_->Offer(sample, NowNs(), context_);
    } else {
      corrections_->Offer(sample, NowNs());
    }
  } catch (const std::logic_error& error) {
    stats_.Add("samples_dropped");
    spdlog::warn("sample dropped: {}", error.what());
  }
}

void FusionService::AwaitCorrectionReader(const std::string& entity_id, const SampleMeta& meta) {
  // In lockstep the entity waits for the answer; it is lost if written before our correction
  // writer matched the entity's reader (the entity's side may match first). Once per entity.
  if (correction_reader_seen_.count(entity_id) > 0) return;
  const std::int64_t until_ns = NowNs() + 2'000'000'000;
  while (!correction_writer_.MatchesParticipantOf(meta.publication) && NowNs() < until_ns) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  if (!correction_writer_.MatchesParticipantOf(meta.publication)) {
    spdlog::warn("{}: its correction reader did not match within 2 s; answering anyway",
                 entity_id);
  }
  correction_reader_seen_.insert(entity_id);
}

CorrectionSinks FusionService::Sinks() {
  CorrectionSinks sinks;
  sinks.send = [this](const std::string& entity_id, const pipeline::Correction& correction,
                      std::uint64_t reference_seq, std::uint64_t for_version) {
    SendCorrection(entity_id, correction, reference_seq, for_version);
  };
  sinks.realign = [this](const std::string& entity_id, const geometry::Pose2& map_from_entity,
                         double confidence, std::uint64_t reference_seq) {
    inbox_.Push(Event{Sample(Realign{entity_id, map_from_entity, confidence, reference_seq}),
                      SampleMeta{NowNs(), NowNs(), {}}});
  };
  return sinks;
}

void FusionService::RefreshCorrectionContext() {
  context_dirty_ = false;
  context_refreshed_ns_ = NowNs();
  if (!corrections_) return;
  auto context = std::make_shared<CorrectionContext>();
  const fusion::FusionState& state = store_->state();
  context->global_version = state.global_version();
  context->walls = ContextWalls(state.GlobalSnapshot().segments);
  for (const std::string& entity_id : state.entity_ids()) {
    const fusion::EntityStatus* status = state.entity(entity_id);
    if (status != nullptr && status->map_from_entity) {
      context->map_from_entity[entity_id] = *status->map_from_entity;
    }
  }
  context_ = context;
  corrections_->SetContext(std::move(context));
}

void FusionService::Handle(const Realign& request, const SampleMeta& /*meta*/) {
  // A placed entity keeps its own frame: the fusion moves its walls (journaled) and tells it.
  Apply(fusion::AlignmentCorrection{NowS(), request.entity_id, request.map_from_entity,
                                    request.confidence});
  // Confidence 1: this is the frame the fusion holds for the entity's walls now.
  if (start_unknown_[request.entity_id]) SendPlacement(request.entity_id, 1.0, request.reference_seq);
}

void FusionService::AfterPlacement(const std::string& entity_id,
                                   const fusion::FusionOutput& output) {
  if (!output.placement) return;
  const fusion::PlacementResult& placement = *output.placement;
  const double best = placement.hypotheses.empty() ? 0.0 : placement.hypotheses.front().score;
  if (!placement.placed) {
    const geometry::Pose2 at =
        placement.hypotheses.empty() ? geometry::Pose2{} : placement.hypotheses.front().map_from_entity;
    spdlog::info("{}: placement pending ({} m of walls, {} hypotheses, best score {:.2f} at "
                 "({:.3f} m, {:.3f} m, {:.4f} rad), margin {:.1f} m): {}",
                 entity_id, placement.local_length_m, placement.hypotheses.size(), best, at.x_m,
                 at.y_m, at.theta_rad, placement.margin_m, placement.reason);
    return;
  }
  const geometry::Pose2& pose = placement.map_from_entity;
  spdlog::info("{}: placed at ({:.3f} m, {:.3f} m, {:.4f} rad): score {:.2f}, margin {:.1f} m over "
               "{} hypotheses, {:.1f} m of walls",
               entity_id, pose.x_m, pose.y_m, pose.theta_rad, best, placement.margin_m,
               placement.hypotheses.size(), placement.local_length_m);
  SendPlacement(entity_id, 1.0, 0);
}

void FusionService::SendPlacement(const std::string& entity_id, double confidence,
                                  std::uint64_t reference_seq) {
  const fusion::EntityStatus* status = store_->state().entity(entity_id);
  if (status == nullptr || !status->map_from_entity) return;
  // The entity's pipeline runs in its own frame with map_from_odom = I, so the frame it needs
  // is map_from_entity itself; it applies it to the poses it publishes, not to its map.
  pipeline::Correction correction;
  correction.kind = pipeline::Correction::Kind::kMapFromOdom;
  correction.map_from_odom = *status->map_from_entity;
  correction.confidence = confidence;
  SendCorrection(entity_id, correction, reference_seq, store_->state().global_version());
  placement_sent_[entity_id] = true;
}

}  // namespace pena::services
