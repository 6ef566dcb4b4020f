#pragma once
// The per-entity facade (paper sections 2 and 3): spread a person's strides over the scans they
// span, predict with dead reckoning or odometry, match the scan against the reference, update the
// local grid, extract lines and integrate them into the entity's line map, apply corrections from
// the fusion service and keep the global map it sends; with an a priori plan, localise on it
// (section 4.2; optionally from an unknown start, with lost and found); given a first pass's grid
// of the same walk, level bent scans before they reach the map. Every program that runs an
// entity's chain (`pena odometry`, `pena localise`, `pena map`'s passes, pena-entity, the
// benchmarks) calls this class. Pure: no DDS, no threads, no files. One instance per entity; not
// thread-safe.

#include <Eigen/Core>
#include <cstdint>
#include <deque>
#include <optional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "pena/dead_reckoning/stride_interpolator.hpp"
#include "pena/geometry/pose2.hpp"
#include "pena/geometry/segment2.hpp"
#include "pena/grid/bent_scan.hpp"
#include "pena/grid/local_grid.hpp"
#include "pena/grid/occupancy_grid.hpp"
#include "pena/line_map/line_extractor.hpp"
#include "pena/line_map/line_map.hpp"
#include "pena/localisation/localised_pose.hpp"
#include "pena/localisation/map_localiser.hpp"
#include "pena/odometry/laser_odometry.hpp"
#include "pena/pipeline/plan_localisation_options.hpp"
#include "pena/sensors/entity.hpp"
#include "pena/sensors/record.hpp"
#include "pena/slam/keyframe_slam.hpp"
#include "pena/stage_clock.hpp"

namespace pena::pipeline {

// What the bent-scan stage does with a scan that the first pass's grid shows bent.
enum class BentScanMode {
  kOff,    // nothing: every scan reaches the map as measured (no first-pass grid may be given)
  kLevel,  // ranges cut to their horizontal part, the floor's returns left out
  kDrop,   // the whole scan is left out of the map
};

// The bent-scan stage (docs/grid.md, "Bent scans"): with a first pass's grid of the same walk
// (SetBentScanReference), scans it shows bent are levelled or left out before the map stages.
struct BentScanStageOptions {
  BentScanMode mode = BentScanMode::kOff;
  grid::BentScanOptions judge;  // which scans are bent, and how they are levelled
};

// The keyframe SLAM stage (docs/slam.md): every scan's odometry pose goes to a KeyframeSlam,
// which corrects them with loop closures; the corrected trajectory is read at the end (slam()).
struct SlamStageOptions {
  bool enabled = false;
  slam::SlamOptions graph;
};

// Options of the whole per-entity chain; validated by EntityPipeline's constructor.
struct EntityPipelineOptions {
  // Its dead_reckoning.stride_interpolation also says whether a person's strides are spread over
  // the scans inside them before the odometry sees them (on by default; docs/dead-reckoning.md).
  odometry::LaserOdometryOptions odometry;
  // The local grid, line extraction and line map; off for the poses alone (`pena odometry`).
  bool build_line_map = true;
  grid::LocalGridOptions local_grid;
  line_map::LineExtractionOptions extraction;
  line_map::LineMapOptions line_map;
  // Lines are extracted from the local grid when the window recentres and, in between, after
  // the entity travelled this far since the last extraction. Metres, >= 0 (0 = at recentre only).
  double map_update_distance_m = 5.0;
  // Corrections with a lower confidence are ignored. Unitless, in [0, 1].
  double min_correction_confidence = 0.3;
  // A correction moving the map frame more than this (translation) starts a fresh local grid,
  // so scans placed before and after it do not blur one wall into two. Metres, > 0.
  double grid_reset_jump_m = 0.10;
  // The same for the heading. Radians, > 0.
  double grid_reset_jump_rad = 0.035;  // 2 deg
  // Odometry poses remembered for corrections given at a past stamp. Count, >= 1.
  int pose_history = 4096;
  // Localisation on an a priori plan (paper section 4.2), used once SetPlan gave one: a round at
  // every reference change of the odometry, and the optional unknown start, lost and found and
  // relocalisation.
  PlanLocalisationOptions plan_localisation;
  // Bent scans levelled or left out of the map, judged against a first pass's grid; off.
  BentScanStageOptions bent_scans;
  // Keyframe SLAM over the odometry's poses (`pena map`); off.
  SlamStageOptions slam;
};

// Throws std::invalid_argument naming the field and its unit (nested options included).
void ValidateEntityPipelineOptions(const EntityPipelineOptions& options);

// "off", "level", "drop"; BentScanModeOf reads them back (nullopt for any other name).
const char* ToString(BentScanMode mode);
std::optional<BentScanMode> BentScanModeOf(std::string_view name);

// What one laser scan produced.
struct ScanStep {
  sensors::LaserScan scan;              // the scan this step placed, as it was fed
  odometry::OdometryEstimate odometry;  // in the odometry frame (odom_from_body)
  geometry::Pose2 world_from_body;      // map_from_odom * odom_from_body: the best estimate
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();  // of world_from_body (x, y, theta)
  std::optional<line_map::MapDelta> map_delta;  // the local line map's change, if it changed
  // The round against the plan at this scan (a plan is set and the reference changed).
  std::optional<localisation::MapCorrection> plan_round;
  // What the plan stage reported at this scan (a plan is set): pose on the plan, status, the
  // unknown start's hypotheses, lost and found. Its map_from_body is world_from_body.
  std::optional<localisation::LocalisedPose> plan;
  // The bent-scan stage found the scan bent: the map stages got it levelled, or not at all.
  bool bent = false;
};

// What Place did with a scan.
struct Placement {
  // The scan as the map stages took it (levelled when bent); nullopt when left out (bent, kDrop).
  std::optional<sensors::LaserScan> scan;
  bool bent = false;  // the bent-scan stage found it bent
  std::optional<line_map::MapDelta> map_delta;  // the local line map's change, if it changed
};

// A correction from the fusion service (or an operator).
struct Correction {
  enum class Kind {
    kMapFromOdom,  // map_from_odom replaces the current transform
    kPose,         // the body was at world_from_body at stamp_s (a past scan's stamp)
  };
  Kind kind = Kind::kMapFromOdom;
  geometry::Pose2 map_from_odom;
  double stamp_s = 0.0;
  geometry::Pose2 world_from_body;
  double confidence = 1.0;  // [0, 1]
};

// Why a correction was or was not applied.
enum class CorrectionStatus {
  kApplied,
  kLowConfidence,  // below min_correction_confidence
  kUnknownStamp,   // kPose for a stamp not in the pose history (within 1 ms)
  kInvalid,        // non-finite values or confidence outside [0, 1]
};

// The outcome of ApplyCorrection: the status, and the lines the old local grid held if the
// correction moved the map frame enough to start a fresh grid.
struct CorrectionResult {
  CorrectionStatus status = CorrectionStatus::kApplied;
  std::optional<line_map::MapDelta> map_delta;
};

// Counters over the run.
struct PipelineCounts {
  long extractions = 0;
  long corrections_applied = 0;
  long corrections_ignored = 0;
  long grid_resets = 0;
  long global_deltas_applied = 0;
  long global_deltas_refused = 0;
  long plan_rounds = 0;       // map-localisation rounds against the plan
  long plan_corrections = 0;  // of which accepted (they moved map_from_odom)
  long bent_scans = 0;        // scans the bent-scan stage levelled or left out
};

// Where the pipeline's time goes (EntityPipeline::stage_times()). Exclusive: the odometry's and
// the SLAM's own stages are in LaserOdometry::stage_times() and KeyframeSlam::stage_times().
enum class PipelineStage {
  kStrideSpreading,  // a person's strides spread over their scans
  kOdometry,         // LaserOdometry::Add
  kPlan,             // localisation on the plan
  kSlam,             // KeyframeSlam::Add
  kBentScans,        // the bent-scan stage's judgement and levelling
  kGridInsertion,    // a scan into the local grid
  kLineExtraction,   // the grid's image, line extraction, the line map's integration
  kOther,            // the rest of Push, Next, EndOfInput, Place and Flush
  kCount
};
using PipelineStageTimes = StageTimes<PipelineStage>;

// "stride_spreading", "odometry", "plan", "slam", "bent_scans", "grid_insertion",
// "line_extraction", "other".
const char* ToString(PipelineStage stage);

class PlanStage;

// The chain of one entity. The odometry frame starts at world_from_start; until a correction
// arrives map_from_odom is the identity, so the odometry frame is the world frame.
class EntityPipeline {
 public:
  // Throws std::invalid_argument for bad options or an empty entity id.
  EntityPipeline(const EntityPipelineOptions& options, sensors::EntityKind kind,
                 std::string entity_id, const geometry::Pose2& world_from_start,
                 double start_stamp_s);
  ~EntityPipeline();
  EntityPipeline(EntityPipeline&&) noexcept;
  EntityPipeline& operator=(EntityPipeline&&) noexcept;

  // Feeds one record in time order. Its scans come out of Next: a person's records wait in the
  // stride spreading for the report that ends their stride, so a record may release no scan or
  // several; other entities' records are ready at once.
  void Push(sensors::SensorRecord record);
  // Processes the ready records up to the next laser scan and returns its step; nullopt when no
  // scan is ready. A correction applied between two calls acts from the next scan on.
  std::optional<ScanStep> Next();
  // End of input: what the stride spreading holds becomes ready (take it with Next, then Flush).
  void EndOfInput();
  // Push, then every step Next gives: for callers that act on no step before the next one.
  std::vector<ScanStep> Add(const sensors::SensorRecord& record);
  // Extracts the lines of the current window into the line map (end of input); the delta may
  // be empty.
  line_map::MapDelta Flush();
  // A scan whose pose comes from outside the pipeline (a trajectory, the log's own poses, an
  // offline SLAM): the stages after the odometry alone (bent scans, local grid, lines), as Next
  // runs them; the odometry and the plan stage do not see it. Not to be mixed with Push.
  Placement Place(const sensors::LaserScan& scan, const geometry::Pose2& world_from_body);

  // Starts the bent-scan stage (options.bent_scans.mode not off): from now on a scan that
  // `first_pass` shows bent at its pose is levelled or left out before the map stages.
  // first_pass: the grid of a first pass over the same walk at the same poses (world frame).
  // Throws std::logic_error when bent_scans.mode is off.
  void SetBentScanReference(grid::OccupancyGrid first_pass);
  bool has_bent_scan_reference() const { return bent_reference_ != nullptr; }

  // The SLAM stage (options.slam.enabled), nullptr when off: its counts and closures as it goes;
  // Finish it at the end of input before reading its corrected Trajectory.
  slam::KeyframeSlam* slam() { return slam_.get(); }

  // Localises against an a priori plan (map frame, metres) at every reference change from now on.
  // Throws std::invalid_argument for an empty plan or bad options.plan_localisation, and
  // std::logic_error with plan_localisation.global_start once a record was pushed.
  void SetPlan(std::vector<geometry::Segment2> plan_m);
  bool has_plan() const { return plan_ != nullptr; }
  // The plan as matched now (with plan adaptation's moves and cuts); empty without a plan.
  const std::vector<geometry::Segment2>& plan() const;
  // The plan walls the localiser moved where it saw them (plan adaptation); empty without a plan.
  const std::vector<localisation::SegmentShift>& plan_shifts() const;
  // The openings plan adaptation cut into the plan; empty without a plan.
  const std::vector<localisation::PlanOpening>& plan_openings() const;

  // Applies a correction (see CorrectionStatus).
  CorrectionResult ApplyCorrection(const Correction& correction);
  // Applies a global-map delta in order; on a gap the caller asks for a snapshot.
  line_map::ApplyResult ApplyGlobalDelta(const line_map::MapDelta& delta);
  // Replaces the global map by a snapshot (late join, gap); throws std::invalid_argument for a
  // malformed snapshot (the old map stays).
  void ResetGlobalMap(const line_map::MapSnapshot& snapshot);

  const std::string& entity_id() const { return entity_id_; }
  // The entity's own line map (world frame at the time each scan was placed).
  const line_map::LineMap& local_map() const { return local_map_; }
  // The fused map the fusion service sent.
  const line_map::LineMap& global_map() const { return global_map_; }
  // The current correction of the odometry frame.
  const geometry::Pose2& map_from_odom() const { return map_from_odom_; }
  const odometry::OdometryCounts& odometry_counts() const { return odometry_.counts(); }
  // The odometry itself (its dead-reckoning counts, for reports).
  const odometry::LaserOdometry& odometry() const { return odometry_; }
  // What the stride spreading did; nullopt when it is off (not a person, or disabled).
  std::optional<dead_reckoning::StrideInterpolationCounts> stride_spreading() const;
  const PipelineCounts& counts() const { return counts_; }
  // Wall time per stage over the run; total: inside Push, Next, EndOfInput, Place and Flush.
  const PipelineStageTimes& stage_times() const { return clock_.times(); }

 private:
  using Timed = StageClock<PipelineStage>::Scope;
  using TimedCall = StageClock<PipelineStage>::Call;
  static const EntityPipelineOptions& Validated(const EntityPipelineOptions& options);
  // The next record ready for the odometry, if any.
  std::optional<sensors::SensorRecord> PopReady();
  // One record after the stride spreading: a laser scan yields its step, anything else nullopt.
  std::optional<ScanStep> Step(const sensors::SensorRecord& record);
  // Extracts the lines of `image` and integrates them; the delta may be empty.
  line_map::MapDelta ExtractAndIntegrate(const grid::GridImage& image);
  // What the bent-scan stage made of a scan: not bent (it reaches the map as measured), or bent
  // and levelled (kLevel) or left out (kDrop: no levelled scan).
  struct Levelling {
    bool bent = false;
    std::optional<sensors::LaserScan> levelled;
  };
  // The bent-scan stage at a scan placed at world_from_body; without a reference nothing is bent.
  Levelling JudgeBent(const sensors::LaserScan& scan, const geometry::Pose2& world_from_body);
  // Runs the grid and line steps for a scan placed at world_from_body (extraction only if
  // `may_extract`).
  std::optional<line_map::MapDelta> UpdateMap(const sensors::LaserScan& scan,
                                              const geometry::Pose2& world_from_body,
                                              bool may_extract = true);
  // Checks a correction and gives the map_from_odom it asks for.
  CorrectionStatus Resolve(const Correction& correction, geometry::Pose2& map_from_odom) const;
  // Switches to a new map_from_odom; a large move first extracts the grid and starts a new one.
  std::optional<line_map::MapDelta> MoveMapFrame(const geometry::Pose2& map_from_odom);
  // The odometry pose at `stamp_s` (within 1 ms) from the history.
  std::optional<geometry::Pose2> OdomPoseAt(double stamp_s) const;
  // The plan stage at a scan; a correction or a restart of the odometry on the plan moves the map
  // frame (the old grid's lines, if it was reset, go to `delta`). `estimate` becomes the
  // restarted odometry's after a restart.
  localisation::LocalisedPose LocaliseOnPlan(const sensors::SensorRecord& record,
                                             odometry::OdometryEstimate& estimate,
                                             std::optional<line_map::MapDelta>& delta);
  // The map frame becomes map_from_odom with the entity at world_from_body; if that moved it
  // more than a grid reset jump, the grid's lines are extracted and a fresh grid starts.
  std::optional<line_map::MapDelta> PlaceMapFrame(const geometry::Pose2& map_from_odom,
                                                  const geometry::Pose2& world_from_body);

  EntityPipelineOptions options_;
  sensors::EntityKind kind_;
  std::string entity_id_;
  double start_stamp_s_ = 0.0;
  bool pushed_ = false;  // a record was pushed
  // A person's strides spread over their scans (dead_reckoning::StrideInterpolator); unset when off.
  std::optional<dead_reckoning::StrideInterpolator> spread_;
  std::deque<sensors::SensorRecord> ready_;  // pushed records, when nothing is spread
  odometry::LaserOdometry odometry_;
  grid::LocalGrid grid_;
  line_map::LineMap local_map_;
  line_map::LineMap global_map_;
  geometry::Pose2 map_from_odom_;
  std::optional<geometry::Pose2> last_extraction_pose_;
  geometry::Pose2 last_world_from_body_;
  bool grid_has_scans_ = false;
  std::deque<std::pair<double, geometry::Pose2>> odom_history_;  // (stamp_s, odom_from_body)
  std::unique_ptr<PlanStage> plan_;  // set by SetPlan
  grid::BentScanLeveller leveller_;   // options.bent_scans.judge
  std::unique_ptr<grid::OccupancyGrid> bent_reference_;  // set by SetBentScanReference
  std::unique_ptr<slam::KeyframeSlam> slam_;  // the SLAM stage, when enabled
  PipelineCounts counts_;
  StageClock<PipelineStage> clock_;
};

// "applied", "low_confidence", "unknown_stamp", "invalid".
const char* ToString(CorrectionStatus status);

}  // namespace pena::pipeline
