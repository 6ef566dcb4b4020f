#include "correction_worker.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>

#include "dds_endpoints.hpp"
#include "from_dds.hpp"
#include "pena/fusion/correction.hpp"
#include "to_dds.hpp"

namespace pena::services {
namespace {

// The covariance of world_from_body the entity reported with its scan, if it is usable.
std::optional<Eigen::Matrix3d> ReportedCovariance(const pena_dds::ReferenceScan& scan) {
  Eigen::Matrix3d covariance;
  for (int i = 0; i < 9; ++i) covariance(i / 3, i % 3) = scan.covariance()[static_cast<std::size_t>(i)];
  if (!covariance.allFinite() || covariance.diagonal().minCoeff() < 0.0) return std::nullopt;
  return covariance;
}

bool IsIdentity(const geometry::Pose2& pose) {
  return pose.x_m == 0.0 && pose.y_m == 0.0 && pose.theta_rad == 0.0;
}

// "ff1:12" -> "ff1:"; a key without ':' is its own owner.
std::string OwnerOf(const std::string& key) {
  const std::size_t colon = key.find(':');
  return colon == std::string::npos ? key : key.substr(0, colon + 1);
}

}  // namespace

std::vector<CorrectionContext::Wall> ContextWalls(
    const std::vector<line_map::LineSegment>& global) {
  std::vector<CorrectionContext::Wall> walls;
  walls.reserve(global.size());
  for (const line_map::LineSegment& segment : global) {
    CorrectionContext::Wall wall{segment.segment, {}};
    for (const std::string& key : segment.provenance) {
      std::string owner = OwnerOf(key);
      if (std::find(wall.owners.begin(), wall.owners.end(), owner) == wall.owners.end()) {
        wall.owners.push_back(std::move(owner));
      }
    }
    walls.push_back(std::move(wall));
  }
  return walls;
}

std::vector<geometry::Segment2> CorrectionContext::CorrectionMap(
    const std::string& entity_id) const {
  const std::string own = entity_id + ":";
  std::vector<geometry::Segment2> out;
  for (const Wall& wall : walls) {
    for (const std::string& owner : wall.owners) {
      if (owner != own) {
        out.push_back(wall.segment);
        break;
      }
    }
  }
  return out;
}

CorrectionWorker::CorrectionWorker(const FusionServiceOptions& options, FusionStats& stats,
                                   CorrectionSinks sinks)
    : options_(options), stats_(stats), sinks_(std::move(sinks)) {
  thread_ = std::thread([this] { Loop(); });
}

CorrectionWorker::~CorrectionWorker() { Stop(); }

void CorrectionWorker::Stop() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (stop_ && !thread_.joinable()) return;
    stop_ = true;
  }
  ready_.notify_all();
  if (thread_.joinable()) thread_.join();
  const std::lock_guard<std::mutex> lock(mutex_);
  stats_.Add("corrections_dropped_at_stop", static_cast<long>(order_.size()));
  if (!wait_ms_.empty()) {
    stats_.Add("correction_wait_p50_us", static_cast<long>(1e3 * Quantile(wait_ms_, 0.5)));
    stats_.Add("correction_wait_p99_us", static_cast<long>(1e3 * Quantile(wait_ms_, 0.99)));
    stats_.Add("correction_wait_max_us",
               static_cast<long>(1e3 * *std::max_element(wait_ms_.begin(), wait_ms_.end())));
  }
}

void CorrectionWorker::SetContext(std::shared_ptr<const CorrectionContext> context) {
  const std::lock_guard<std::mutex> lock(mutex_);
  context_ = std::move(context);
}

void CorrectionWorker::SetEntity(const std::string& entity_id, bool robot, bool start_unknown) {
  const std::lock_guard<std::mutex> lock(mutex_);
  Entity& entity = EntityOf(entity_id);
  entity.robot = robot;
  entity.start_unknown = start_unknown;
}

void CorrectionWorker::Forget(const std::string& entity_id) {
  const std::lock_guard<std::mutex> lock(mutex_);
  EntityOf(entity_id).map_from_odom_sent.reset();
}

CorrectionWorker::Entity& CorrectionWorker::EntityOf(const std::string& entity_id) {
  return entities_[entity_id];
}

fusion::CorrectionFilter& CorrectionWorker::FilterOf(Entity& entity) const {
  // Created at the first scan with the kind's defaults (known from the status by then).
  if (!entity.filter) {
    entity.filter.emplace(entity.robot ? options_.robot_filter : options_.human_filter);
  }
  return *entity.filter;
}

void CorrectionWorker::Offer(const pena_dds::ReferenceScan& scan, std::int64_t received_ns,
                             std::shared_ptr<const CorrectionContext> context) {
  const std::string entity_id = scan.entity_id().to_string();
  const geometry::Pose2 odom_from_body = FromDds(scan.odom_from_body());
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    Entity& entity = EntityOf(entity_id);
    // The entity's own odometry grows its uncertainty at every reference, attempted or not
    // (after the match in flight, which was predicted up to its own scan).
    if (entity.in_flight) {
      entity.deferred_odometry.emplace_back(odom_from_body, ReportedCovariance(scan));
    } else {
      FilterOf(entity).Predict(odom_from_body, ReportedCovariance(scan));
    }
    if (options_.lockstep) {
      // On the scans' own stamps, as the entity counts them: it waits for exactly these.
      if (scan.stamp_s() - entity.last_attempt_stamp_s < options_.correction_interval_s) return;
      entity.last_attempt_stamp_s = scan.stamp_s();
    } else {
      const std::int64_t interval_ns =
          static_cast<std::int64_t>(options_.correction_interval_s * 1e9);
      if (received_ns - entity.last_attempt_ns < interval_ns) return;
      if (context_ == nullptr || context_->map_from_entity.count(entity_id) == 0) return;
    }
    if (entity.pending) {
      stats_.Add("corrections_superseded");  // only the newest scan matters
      order_.erase(std::find(order_.begin(), order_.end(), entity_id));
    }
    order_.push_back(entity_id);  // the newest request is served first
    entity.pending = Request{scan, received_ns, std::move(context)};
  }
  ready_.notify_one();
}

void CorrectionWorker::Loop() {
  while (std::optional<Job> job = Next()) Run(*job);
}

std::optional<CorrectionWorker::Job> CorrectionWorker::Next() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (true) {
    ready_.wait(lock, [this] { return stop_ || !order_.empty(); });
    if (stop_) return std::nullopt;
    const std::string entity_id = order_.back();
    order_.pop_back();
    Entity& entity = EntityOf(entity_id);
    Request request = std::move(*entity.pending);
    entity.pending.reset();
    const std::int64_t now_ns = NowNs();
    const double waited_ms = static_cast<double>(now_ns - request.received_ns) * 1e-6;
    if (!options_.lockstep && options_.correction_max_wait_s > 0.0 &&
        waited_ms > 1e3 * options_.correction_max_wait_s) {
      // Too old to be worth the matching time: the next reference scan gets the next chance.
      stats_.Add("corrections_stale");
      continue;
    }
    std::shared_ptr<const CorrectionContext> context = request.context ? request.context : context_;
    const bool known = context != nullptr && context->map_from_entity.count(entity_id) > 0;
    if (!known) {
      // Not placed (yet): nothing to match against; in lockstep the entity waits for an answer.
      if (options_.lockstep) {
        const std::uint64_t version = context ? context->global_version : 0;
        lock.unlock();
        AnswerNothing(entity_id, request.scan, version);
        lock.lock();
      }
      continue;
    }
    const auto placed = context->map_from_entity.find(entity_id);
    wait_ms_.push_back(waited_ms);
    entity.last_attempt_ns = now_ns;
    entity.in_flight = true;
    Job job;
    job.entity_id = entity_id;
    job.context = context;
    job.start_unknown = entity.start_unknown;
    job.map_from_entity = entity.map_from_entity_sent.value_or(placed->second);
    // The pose the entity will hold once it applied what was sent (a scan taken before the last
    // correction arrived still carries the old one: blending against it would undo that one).
    // An entity whose start was unknown keeps its own frame: its odometry is entity_from_body.
    const geometry::Pose2 odom_from_body = FromDds(request.scan.odom_from_body());
    if (entity.start_unknown) {
      job.entity_from_body = odom_from_body;
    } else if (options_.filter_corrections && entity.map_from_odom_sent) {
      job.entity_from_body = geometry::Compose(*entity.map_from_odom_sent, odom_from_body);
    } else {
      job.entity_from_body = FromDds(request.scan.world_from_body());
    }
    // Section 4.2's window, sized to the prediction's uncertainty: a drifted entity searches
    // wide, one just corrected searches narrowly (fewer aliased junctions within reach).
    job.window = options_.filter_corrections ? FilterOf(entity).Window(options_.correction.window)
                                             : fusion::CorrectionOptions{}.window;
    job.request = std::move(request);
    return job;
  }
}

void CorrectionWorker::Run(const Job& job) {
  const std::int64_t start_ns = NowNs();
  fusion::CorrectionOptions options = options_.correction;
  options.window = job.window;
  fusion::FusionCorrection match;
  try {
    match = fusion::ComputeCorrection(job.entity_id, FromDds(job.request.scan),
                                      job.entity_from_body, job.map_from_entity,
                                      job.context->CorrectionMap(job.entity_id), options);
  } catch (const std::exception& error) {
    // A malformed scan (bad geometry, too many beams): dropped, the worker goes on.
    match.reason = error.what();
    stats_.Add("samples_dropped");
    spdlog::warn("{}: reference scan {} dropped: {}", job.entity_id, job.request.scan.seq(),
                 error.what());
  }
  stats_.Add("correction_attempts");
  stats_.Add("correction_compute_us", (NowNs() - start_ns) / 1000);
  Finish(job, match);
}

std::optional<geometry::Pose2> CorrectionWorker::Blend(const Job& job,
                                                      const fusion::FusionCorrection& match,
                                                      const geometry::Pose2& predicted,
                                                      Entity& entity) {
  const std::uint64_t seq = job.request.scan.seq();
  if (!match.accepted) {
    stats_.Add("corrections_rejected");
    spdlog::debug("{}: no correction at reference {}: {}", job.entity_id, seq, match.reason);
    return std::nullopt;
  }
  geometry::Pose2 corrected = match.matched_map_from_body;
  if (options_.filter_corrections) {
    const fusion::FilteredCorrection filtered = FilterOf(entity).Update(predicted, match);
    if (filtered.degenerate) stats_.Add("corrections_degenerate");
    if (!filtered.accepted) {
      stats_.Add("corrections_gated");
      spdlog::debug("{}: correction at reference {} refused: {}", job.entity_id, seq,
                    filtered.reason);
      return std::nullopt;
    }
    corrected = filtered.map_from_body;
  }
  const geometry::Pose2 move = geometry::Between(predicted, corrected);
  // Raw corrections below the minimum are not sent; filtered ones always are, because the
  // filter has counted them as applied.
  if (!options_.filter_corrections && std::hypot(move.x_m, move.y_m) < options_.correction_min_m &&
      std::abs(move.theta_rad) < options_.correction_min_rad) {
    stats_.Add("corrections_small");
    return std::nullopt;
  }
  spdlog::info("{}: correction at reference {} moves it ({:.3f} m, {:.3f} m, {:.4f} rad), "
               "score {:.2f}, confidence {:.2f}",
               job.entity_id, seq, move.x_m, move.y_m, move.theta_rad, match.score,
               match.confidence);
  return corrected;
}

void CorrectionWorker::Finish(const Job& job, const fusion::FusionCorrection& match) {
  const pena_dds::ReferenceScan& scan = job.request.scan;
  const geometry::Pose2 predicted = geometry::Compose(job.map_from_entity, job.entity_from_body);
  std::optional<geometry::Pose2> blended;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    Entity& entity = EntityOf(job.entity_id);
    entity.in_flight = false;
    blended = Blend(job, match, predicted, entity);
    // The odometry that came during the match is predicted after it.
    for (const auto& [odom, reported] : entity.deferred_odometry) {
      FilterOf(entity).Predict(odom, reported);
    }
    entity.deferred_odometry.clear();
    // Recorded under the same lock as in_flight: a later match for this entity must not be
    // overwritten by this older one.
    if (blended && IsIdentity(job.map_from_entity) && !job.start_unknown) {
      // The entity solves world_from_body = map_from_odom * odom_from_body at the stamp.
      entity.map_from_odom_sent =
          geometry::Compose(*blended, geometry::Inverse(FromDds(scan.odom_from_body())));
    } else if (blended) {
      entity.map_from_entity_sent =
          geometry::Compose(*blended, geometry::Inverse(job.entity_from_body));
    }
  }
  if (!blended) {
    if (options_.lockstep) AnswerNothing(job.entity_id, scan, job.context->global_version);
    return;
  }
  const geometry::Pose2 corrected = *blended;
  if (IsIdentity(job.map_from_entity) && !job.start_unknown) {
    // The entity corrects its own frame, so its later walls arrive corrected: the fusion keeps
    // map_from_entity = I (docs/fusion.md, "Contract with the entity").
    pipeline::Correction correction;
    correction.kind = pipeline::Correction::Kind::kPose;
    correction.stamp_s = scan.stamp_s();
    correction.world_from_body = corrected;
    correction.confidence = match.confidence;
    sinks_.send(job.entity_id, correction, scan.seq(), job.context->global_version);
  } else {
    // A placed entity keeps its own frame: the fusion moves its walls instead (journaled by the
    // fusion worker, which also tells the entity its new frame).
    sinks_.realign(job.entity_id,
                   geometry::Compose(corrected, geometry::Inverse(job.entity_from_body)),
                   match.confidence, scan.seq());
  }
}

void CorrectionWorker::AnswerNothing(const std::string& entity_id,
                                     const pena_dds::ReferenceScan& scan,
                                     std::uint64_t for_version) {
  pipeline::Correction answer;
  answer.kind = pipeline::Correction::Kind::kPose;
  answer.stamp_s = scan.stamp_s();
  answer.world_from_body = FromDds(scan.world_from_body());
  answer.confidence = 0.0;  // below any entity's minimum: ignored, but it answers the scan
  sinks_.send(entity_id, answer, scan.seq(), for_version);
}

}  // namespace pena::services
