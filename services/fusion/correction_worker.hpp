#pragma once
// pena-fusion's second worker: corrections (docs/fusion-service.md, "Threads"). Reference scans
// go from the DDS listener straight to it, not through the fusion worker's inbox, so a global
// map rebuild or a snapshot never holds a correction up. Only the newest reference scan of an
// entity matters: a newer one replaces the one still waiting (superseded); the newest request is
// served first, so when the worker cannot keep up the fresh requests get low latency and the old
// ones, once they waited longer than correction_max_wait_s, are dropped (stale: the entity sends
// another at its next reference change) instead of building a backlog. The fusion worker
// hands it what it needs of the fusion state as an immutable CorrectionContext after every
// change; the worker never touches the store. Alignment moves of placed entities go back to the
// fusion worker (the store is journaled there).

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "fusion_options.hpp"
#include "fusion_stats.hpp"
#include "pena/fusion/correction_filter.hpp"
#include "pena/geometry/pose2.hpp"
#include "pena/geometry/segment2.hpp"
#include "pena/line_map/line_segment.hpp"
#include "pena/pipeline/entity_pipeline.hpp"
#include "pena_dds/scanPubSubTypes.h"

namespace pena::services {

// What the correction worker knows of the fusion state (a copy; the fusion worker makes a new
// one after every change of the global map or of an alignment).
struct CorrectionContext {
  std::uint64_t global_version = 0;
  struct Wall {
    geometry::Segment2 segment;
    std::vector<std::string> owners;  // distinct provenance prefixes with their ':' ("ff1:", "plan:")
  };
  std::vector<Wall> walls;
  std::map<std::string, geometry::Pose2> map_from_entity;  // placed entities only

  // FusionState::CorrectionMap on this copy: the walls some source other than `entity_id`
  // supports (so an entity is not corrected against its own drift).
  std::vector<geometry::Segment2> CorrectionMap(const std::string& entity_id) const;
};

// Builds the context's walls from a global snapshot's segments (provenance keys "<source>:<id>").
std::vector<CorrectionContext::Wall> ContextWalls(const std::vector<line_map::LineSegment>& global);

// What the worker asks of the rest of the service.
struct CorrectionSinks {
  // Sends a correction to the entity (any thread; the service serialises the writer and seq).
  std::function<void(const std::string& entity_id, const pipeline::Correction& correction,
                     std::uint64_t reference_seq, std::uint64_t for_version)>
      send;
  // A placed entity's alignment should move (applied and journaled by the fusion worker).
  std::function<void(const std::string& entity_id, const geometry::Pose2& map_from_entity,
                     double confidence, std::uint64_t reference_seq)>
      realign;
};

class CorrectionWorker {
 public:
  CorrectionWorker(const FusionServiceOptions& options, FusionStats& stats, CorrectionSinks sinks);
  ~CorrectionWorker();  // stops the thread
  CorrectionWorker(const CorrectionWorker&) = delete;
  CorrectionWorker& operator=(const CorrectionWorker&) = delete;

  // Any thread. The fusion state as of now.
  void SetContext(std::shared_ptr<const CorrectionContext> context);
  // Any thread. From the entity's status: its kind picks the filter's defaults; an entity whose
  // start was unknown keeps its own frame (its odom_from_body is its entity_from_body).
  void SetEntity(const std::string& entity_id, bool robot, bool start_unknown);
  // Any thread (the DDS listener). Grows the entity's uncertainty by its odometry and, at most
  // once per correction_interval_s, queues the scan for matching (replacing a waiting one).
  // With `context` (lockstep) the scan is matched against that state rather than the latest.
  void Offer(const pena_dds::ReferenceScan& scan, std::int64_t received_ns,
             std::shared_ptr<const CorrectionContext> context = nullptr);
  // Any thread. The entity's frame was set by someone else (an operator): forget what we sent.
  void Forget(const std::string& entity_id);
  // Stops and joins the thread; requests still waiting are dropped (counted).
  void Stop();

 private:
  struct Request {
    pena_dds::ReferenceScan scan;
    std::int64_t received_ns = 0;
    std::shared_ptr<const CorrectionContext> context;  // null: the latest one
  };
  struct Entity {
    std::optional<fusion::CorrectionFilter> filter;
    bool robot = false;
    bool start_unknown = false;
    std::int64_t last_attempt_ns = 0;
    double last_attempt_stamp_s = -1e300;  // lockstep: the scan stamp of the last attempt
    std::optional<Request> pending;
    bool in_flight = false;
    // Predictions that came during a match: odometry pose and the entity's reported covariance.
    std::vector<std::pair<geometry::Pose2, std::optional<Eigen::Matrix3d>>> deferred_odometry;
    std::optional<geometry::Pose2> map_from_odom_sent;    // what our last correction set
    std::optional<geometry::Pose2> map_from_entity_sent;  // what our last realignment asked
  };
  // Everything one match needs, copied under the lock.
  struct Job {
    std::string entity_id;
    Request request;
    geometry::Pose2 entity_from_body;
    geometry::Pose2 map_from_entity;
    scan_matching::SearchWindow window;
    std::shared_ptr<const CorrectionContext> context;
    bool start_unknown = false;
  };

  void Loop();
  // The next job (oldest request first), or nullopt on stop. Drops stale ones.
  std::optional<Job> Next();
  void Run(const Job& job);
  // Blends the match into the entity's filter and delivers the result.
  void Finish(const Job& job, const fusion::FusionCorrection& match);
  // Lockstep: tells the entity its scan was attempted but brings nothing to apply (confidence 0).
  void AnswerNothing(const std::string& entity_id, const pena_dds::ReferenceScan& scan,
                     std::uint64_t for_version);
  // The corrected pose to deliver (map frame), or nullopt (rejected, gated, too small); counts.
  // Under mutex_.
  std::optional<geometry::Pose2> Blend(const Job& job, const fusion::FusionCorrection& match,
                                       const geometry::Pose2& predicted, Entity& entity);
  Entity& EntityOf(const std::string& entity_id);  // under mutex_
  fusion::CorrectionFilter& FilterOf(Entity& entity) const;

  const FusionServiceOptions& options_;
  FusionStats& stats_;
  CorrectionSinks sinks_;
  std::mutex mutex_;
  std::condition_variable ready_;
  bool stop_ = false;
  std::shared_ptr<const CorrectionContext> context_;
  std::map<std::string, Entity> entities_;
  std::deque<std::string> order_;  // entities with a pending request, newest request last
  std::vector<double> wait_ms_;    // queueing delay of every match started
  std::thread thread_;
};

}  // namespace pena::services
