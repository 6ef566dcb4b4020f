#include "pena/pipeline/entity_pipeline.hpp"

#include <cmath>
#include <stdexcept>
#include <utility>
#include <variant>

#include "pena/dead_reckoning/human_dead_reckoning.hpp"
#include "plan_stage.hpp"

namespace pena::pipeline {
namespace {

// A stamp in the pose history matches a correction's stamp within this (TUM keeps 6 decimals).
constexpr double kStampTolerance_s = 1e-3;

bool Finite(const geometry::Pose2& pose) {
  return std::isfinite(pose.x_m) && std::isfinite(pose.y_m) && std::isfinite(pose.theta_rad);
}

bool Same(const geometry::Pose2& a, const geometry::Pose2& b) {
  return a.x_m == b.x_m && a.y_m == b.y_m && a.theta_rad == b.theta_rad;
}

// The covariance of a pose moved by the rigid transform a_from_b (rotate the x-y block).
Eigen::Matrix3d RotateCovariance(const Eigen::Matrix3d& covariance,
                                 const geometry::Pose2& a_from_b) {
  const double c = std::cos(a_from_b.theta_rad);
  const double s = std::sin(a_from_b.theta_rad);
  Eigen::Matrix3d jacobian = Eigen::Matrix3d::Identity();
  jacobian.topLeftCorner<2, 2>() << c, -s, s, c;
  return jacobian * covariance * jacobian.transpose();
}

}  // namespace

// Validates before any member is built from the options (the nested ones validate themselves).
const EntityPipelineOptions& EntityPipeline::Validated(const EntityPipelineOptions& options) {
  ValidateEntityPipelineOptions(options);
  return options;
}

void ValidateEntityPipelineOptions(const EntityPipelineOptions& options) {
  if (!(options.map_update_distance_m >= 0.0)) {
    throw std::invalid_argument("pipeline.map_update_distance_m must be >= 0 m, got " +
                                std::to_string(options.map_update_distance_m));
  }
  if (!(options.min_correction_confidence >= 0.0 && options.min_correction_confidence <= 1.0)) {
    throw std::invalid_argument("pipeline.min_correction_confidence must be in [0, 1], got " +
                                std::to_string(options.min_correction_confidence));
  }
  if (!(options.grid_reset_jump_m > 0.0)) {
    throw std::invalid_argument("pipeline.grid_reset_jump_m must be > 0 m, got " +
                                std::to_string(options.grid_reset_jump_m));
  }
  if (!(options.grid_reset_jump_rad > 0.0)) {
    throw std::invalid_argument("pipeline.grid_reset_jump_rad must be > 0 rad, got " +
                                std::to_string(options.grid_reset_jump_rad));
  }
  if (options.pose_history < 1) {
    throw std::invalid_argument("pipeline.pose_history must be >= 1 poses, got " +
                                std::to_string(options.pose_history));
  }
  line_map::ValidateLineExtractionOptions(options.extraction);
  ValidatePlanLocalisationOptions(options.plan_localisation);
  if (options.slam.enabled) slam::ValidateSlamOptions(options.slam.graph);
  if (!BentScanModeOf(ToString(options.bent_scans.mode))) {
    throw std::invalid_argument("pipeline.bent_scans.mode must be off, level or drop, got " +
                                std::to_string(static_cast<int>(options.bent_scans.mode)));
  }
  grid::ValidateBentScanOptions(options.bent_scans.judge);
}

const char* ToString(BentScanMode mode) {
  switch (mode) {
    case BentScanMode::kOff: return "off";
    case BentScanMode::kLevel: return "level";
    case BentScanMode::kDrop: return "drop";
  }
  return "unknown";
}

std::optional<BentScanMode> BentScanModeOf(std::string_view name) {
  for (const BentScanMode mode : {BentScanMode::kOff, BentScanMode::kLevel, BentScanMode::kDrop}) {
    if (name == ToString(mode)) return mode;
  }
  return std::nullopt;
}

void ValidatePlanLocalisationOptions(const PlanLocalisationOptions& options) {
  if (!(options.compass_tolerance_rad >= 0.0) || !std::isfinite(options.compass_tolerance_rad)) {
    throw std::invalid_argument("pipeline.plan_localisation.compass_tolerance_rad must be >= 0 rad, got " +
                                std::to_string(options.compass_tolerance_rad));
  }
  if (!(options.compass_wait_s >= 0.0) || !std::isfinite(options.compass_wait_s)) {
    throw std::invalid_argument("pipeline.plan_localisation.compass_wait_s must be >= 0 s, got " +
                                std::to_string(options.compass_wait_s));
  }
  if (options.relocalise_after_rounds < 0) {
    throw std::invalid_argument("pipeline.plan_localisation.relocalise_after_rounds must be >= 0 rounds, got " +
                                std::to_string(options.relocalise_after_rounds));
  }
  if (!(options.relocalise_compass_tolerance_rad > 0.0) ||
      !std::isfinite(options.relocalise_compass_tolerance_rad)) {
    throw std::invalid_argument(
        "pipeline.plan_localisation.relocalise_compass_tolerance_rad must be > 0 rad, got " +
        std::to_string(options.relocalise_compass_tolerance_rad));
  }
}

EntityPipeline::EntityPipeline(const EntityPipelineOptions& options, sensors::EntityKind kind,
                               std::string entity_id, const geometry::Pose2& world_from_start,
                               double start_stamp_s)
    : options_(Validated(options)),
      kind_(kind),
      entity_id_(std::move(entity_id)),
      start_stamp_s_(start_stamp_s),
      odometry_(options.odometry, kind, world_from_start, start_stamp_s),
      grid_(options.local_grid, Eigen::Vector2d(world_from_start.x_m, world_from_start.y_m)),
      local_map_(options.line_map),
      global_map_(options.line_map),
      last_world_from_body_(world_from_start),
      leveller_(options.bent_scans.judge) {
  if (entity_id_.empty()) throw std::invalid_argument("pipeline: entity id must not be empty");
  // The walker's position moves only at stride reports, which come when a stride ends: spread
  // over the scans inside it, the prediction follows the walker instead of lagging by a stride
  // (docs/dead-reckoning.md). The odometry's pace and slide checks expect it.
  const dead_reckoning::HumanDeadReckoningOptions& walking = options_.odometry.dead_reckoning;
  if (kind == sensors::EntityKind::kHuman && walking.stride_interpolation.enabled) {
    spread_.emplace(dead_reckoning::SpreadOptionsOf(walking));
  }
  if (options_.slam.enabled) slam_ = std::make_unique<slam::KeyframeSlam>(options_.slam.graph, kind);
}

EntityPipeline::~EntityPipeline() = default;
EntityPipeline::EntityPipeline(EntityPipeline&&) noexcept = default;
EntityPipeline& EntityPipeline::operator=(EntityPipeline&&) noexcept = default;

void EntityPipeline::Push(sensors::SensorRecord record) {
  const TimedCall call(clock_, PipelineStage::kOther);
  pushed_ = true;
  if (spread_) {
    const Timed timed(clock_, PipelineStage::kStrideSpreading);
    spread_->Push(std::move(record));
  } else {
    ready_.push_back(std::move(record));
  }
}

std::optional<sensors::SensorRecord> EntityPipeline::PopReady() {
  if (spread_) {
    const Timed timed(clock_, PipelineStage::kStrideSpreading);
    return spread_->Pop();
  }
  if (ready_.empty()) return std::nullopt;
  sensors::SensorRecord record = std::move(ready_.front());
  ready_.pop_front();
  return record;
}

std::optional<ScanStep> EntityPipeline::Next() {
  const TimedCall call(clock_, PipelineStage::kOther);
  while (std::optional<sensors::SensorRecord> record = PopReady()) {
    if (std::optional<ScanStep> step = Step(*record)) return step;
  }
  return std::nullopt;
}

void EntityPipeline::EndOfInput() {
  const TimedCall call(clock_, PipelineStage::kOther);
  const Timed timed(clock_, PipelineStage::kStrideSpreading);
  if (spread_) spread_->Finish();
}

std::vector<ScanStep> EntityPipeline::Add(const sensors::SensorRecord& record) {
  Push(record);
  std::vector<ScanStep> steps;
  while (std::optional<ScanStep> step = Next()) steps.push_back(std::move(*step));
  return steps;
}

std::optional<dead_reckoning::StrideInterpolationCounts> EntityPipeline::stride_spreading() const {
  if (!spread_) return std::nullopt;
  return spread_->counts();
}

std::optional<ScanStep> EntityPipeline::Step(const sensors::SensorRecord& record) {
  // An unknown start with a compass holds the scans until the first compass sample.
  if (plan_) {
    const Timed timed(clock_, PipelineStage::kPlan);
    if (!plan_->Admit(record, odometry_)) return std::nullopt;
  }
  // Section 2: dead reckoning predicts, the scan matcher corrects against the reference.
  std::optional<odometry::OdometryEstimate> estimate;
  {
    const Timed timed(clock_, PipelineStage::kOdometry);
    estimate = odometry_.Add(record);
  }
  if (!estimate) return std::nullopt;
  ScanStep step;
  const auto& scan = std::get<sensors::LaserScan>(record);
  // Section 4.2: against the plan first, so this scan is already placed where the plan says.
  std::optional<line_map::MapDelta> reset_delta;
  if (plan_) {
    const Timed timed(clock_, PipelineStage::kPlan);
    step.plan = LocaliseOnPlan(record, *estimate, reset_delta);
    step.plan_round = step.plan->correction;
  }
  odom_history_.emplace_back(estimate->stamp_s, estimate->world_from_body);
  while (odom_history_.size() > static_cast<std::size_t>(options_.pose_history)) {
    odom_history_.pop_front();
  }
  step.world_from_body = geometry::Compose(map_from_odom_, estimate->world_from_body);
  step.covariance = RotateCovariance(estimate->covariance, map_from_odom_);
  step.odometry = std::move(*estimate);
  step.scan = scan;
  // Beyond the paper (its future work): loop closures over the odometry's keyframes.
  if (slam_) {
    const Timed timed(clock_, PipelineStage::kSlam);
    slam_->Add(scan, step.odometry.world_from_body);
  }
  last_world_from_body_ = step.world_from_body;
  // Section 3: the scan goes into the local grid at the corrected pose (levelled or left out if
  // the first pass showed it bent); lines come out of it. A grid just reset by a plan correction
  // is fresh: nothing to extract at this scan.
  const Levelling levelling = JudgeBent(scan, step.world_from_body);
  step.bent = levelling.bent;
  if (!levelling.bent) {
    step.map_delta = UpdateMap(scan, step.world_from_body, !reset_delta);
  } else if (levelling.levelled) {
    step.map_delta = UpdateMap(*levelling.levelled, step.world_from_body, !reset_delta);
  }
  if (reset_delta) step.map_delta = std::move(reset_delta);
  return step;
}

const std::vector<geometry::Segment2>& EntityPipeline::plan() const {
  static const std::vector<geometry::Segment2> kNone;
  return plan_ ? plan_->plan() : kNone;
}

const std::vector<localisation::SegmentShift>& EntityPipeline::plan_shifts() const {
  static const std::vector<localisation::SegmentShift> kNone;
  return plan_ ? plan_->plan_shifts() : kNone;
}

const std::vector<localisation::PlanOpening>& EntityPipeline::plan_openings() const {
  static const std::vector<localisation::PlanOpening> kNone;
  return plan_ ? plan_->plan_openings() : kNone;
}

void EntityPipeline::SetPlan(std::vector<geometry::Segment2> plan_m) {
  if (plan_m.empty()) throw std::invalid_argument("pipeline: the plan has no segments");
  if (options_.plan_localisation.global_start && pushed_) {
    throw std::logic_error("pipeline: with plan_localisation.global_start the plan is set before the first record");
  }
  plan_ = std::make_unique<PlanStage>(options_.plan_localisation, options_.odometry, kind_, std::move(plan_m),
                                      map_from_odom_, start_stamp_s_, odometry_);
}

localisation::LocalisedPose EntityPipeline::LocaliseOnPlan(const sensors::SensorRecord& record,
                                                           odometry::OdometryEstimate& estimate,
                                                           std::optional<line_map::MapDelta>& delta) {
  PlanUpdate update = plan_->Update(record, estimate, odometry_);
  const std::optional<localisation::MapCorrection>& round = update.pose.correction;
  if (round) ++counts_.plan_rounds;
  if (round && round->accepted) ++counts_.plan_corrections;
  if (update.odometry_restarted) {
    // The odometry starts again on the plan: its old poses no longer answer corrections.
    odom_history_.clear();
    delta = PlaceMapFrame(plan_->map_from_odom(),
                          geometry::Compose(plan_->map_from_odom(), estimate.world_from_body));
  } else if ((round && round->accepted) || !Same(plan_->map_from_odom(), map_from_odom_)) {
    delta = MoveMapFrame(plan_->map_from_odom());
  }
  return std::move(update.pose);
}

std::optional<line_map::MapDelta> EntityPipeline::UpdateMap(
    const sensors::LaserScan& scan, const geometry::Pose2& world_from_body, bool may_extract) {
  if (!options_.build_line_map) return std::nullopt;
  {
    const Timed timed(clock_, PipelineStage::kGridInsertion);
    // The laser sits at the body origin (as in the simulator and the CARMEN logs).
    if (grid_.Insert(scan, world_from_body)) grid_has_scans_ = true;
  }
  if (!last_extraction_pose_) last_extraction_pose_ = world_from_body;
  if (!may_extract) return std::nullopt;
  const Timed timed(clock_, PipelineStage::kLineExtraction);
  std::optional<line_map::MapDelta> delta;
  if (grid_.NeedsRecentre(world_from_body)) {
    delta = ExtractAndIntegrate(grid_.Recentre(world_from_body));
  } else if (options_.map_update_distance_m > 0.0 &&
             std::hypot(world_from_body.x_m - last_extraction_pose_->x_m,
                        world_from_body.y_m - last_extraction_pose_->y_m) >=
                 options_.map_update_distance_m) {
    delta = ExtractAndIntegrate(grid_.ToImage());
  } else {
    return std::nullopt;
  }
  last_extraction_pose_ = world_from_body;
  if (delta->empty()) return std::nullopt;
  return delta;
}

line_map::MapDelta EntityPipeline::ExtractAndIntegrate(const grid::GridImage& image) {
  ++counts_.extractions;
  return local_map_.Integrate(line_map::ExtractLines(image, options_.extraction), entity_id_);
}

Placement EntityPipeline::Place(const sensors::LaserScan& scan,
                                const geometry::Pose2& world_from_body) {
  const TimedCall call(clock_, PipelineStage::kOther);
  last_world_from_body_ = world_from_body;
  Levelling levelling = JudgeBent(scan, world_from_body);
  Placement placement;
  placement.bent = levelling.bent;
  placement.scan = levelling.bent ? std::move(levelling.levelled) : scan;
  if (placement.scan) placement.map_delta = UpdateMap(*placement.scan, world_from_body);
  return placement;
}

void EntityPipeline::SetBentScanReference(grid::OccupancyGrid first_pass) {
  if (options_.bent_scans.mode == BentScanMode::kOff) {
    throw std::logic_error("pipeline: bent_scans.mode is off, so a first pass's grid has no use");
  }
  bent_reference_ = std::make_unique<grid::OccupancyGrid>(std::move(first_pass));
}

EntityPipeline::Levelling EntityPipeline::JudgeBent(const sensors::LaserScan& scan,
                                                    const geometry::Pose2& world_from_body) {
  Levelling levelling;
  if (!bent_reference_) return levelling;
  const Timed timed(clock_, PipelineStage::kBentScans);
  // The laser sits at the body origin, so the body pose is world_from_laser.
  const std::optional<grid::FloorLine> floor =
      leveller_.FloorLineOf(*bent_reference_, scan, world_from_body);
  if (!floor) return levelling;
  levelling.bent = true;
  ++counts_.bent_scans;
  if (options_.bent_scans.mode == BentScanMode::kLevel) {
    levelling.levelled = leveller_.Level(scan, *floor);
  }
  return levelling;
}

line_map::MapDelta EntityPipeline::Flush() {
  const TimedCall call(clock_, PipelineStage::kOther);
  const Timed timed(clock_, PipelineStage::kLineExtraction);
  if (!grid_has_scans_) return local_map_.Integrate({}, entity_id_);
  return ExtractAndIntegrate(grid_.ToImage());
}

CorrectionResult EntityPipeline::ApplyCorrection(const Correction& correction) {
  CorrectionResult result;
  geometry::Pose2 map_from_odom;
  result.status = Resolve(correction, map_from_odom);
  if (result.status != CorrectionStatus::kApplied) {
    ++counts_.corrections_ignored;
    return result;
  }
  result.map_delta = MoveMapFrame(map_from_odom);
  // The plan localiser goes on from the corrected frame (its next window is the narrow one).
  if (plan_) plan_->Reset(map_from_odom_);
  ++counts_.corrections_applied;
  return result;
}

CorrectionStatus EntityPipeline::Resolve(const Correction& correction,
                                         geometry::Pose2& map_from_odom) const {
  if (!(correction.confidence >= 0.0 && correction.confidence <= 1.0) ||
      !Finite(correction.map_from_odom) || !Finite(correction.world_from_body) ||
      !std::isfinite(correction.stamp_s)) {
    return CorrectionStatus::kInvalid;
  }
  if (correction.confidence < options_.min_correction_confidence) {
    return CorrectionStatus::kLowConfidence;
  }
  if (correction.kind == Correction::Kind::kMapFromOdom) {
    map_from_odom = correction.map_from_odom;
    return CorrectionStatus::kApplied;
  }
  // world_from_body = map_from_odom * odom_from_body at the stamp, solved for map_from_odom.
  const std::optional<geometry::Pose2> odom_from_body = OdomPoseAt(correction.stamp_s);
  if (!odom_from_body) return CorrectionStatus::kUnknownStamp;
  map_from_odom =
      geometry::Compose(correction.world_from_body, geometry::Inverse(*odom_from_body));
  return CorrectionStatus::kApplied;
}

std::optional<line_map::MapDelta> EntityPipeline::MoveMapFrame(
    const geometry::Pose2& map_from_odom) {
  // Where the entity is now, after the move.
  const geometry::Pose2 odom_from_body =
      geometry::Compose(geometry::Inverse(map_from_odom_), last_world_from_body_);
  return PlaceMapFrame(map_from_odom, geometry::Compose(map_from_odom, odom_from_body));
}

std::optional<line_map::MapDelta> EntityPipeline::PlaceMapFrame(
    const geometry::Pose2& map_from_odom, const geometry::Pose2& moved) {
  // A large move would blur the grid's walls, so the old grid's lines are kept and a fresh grid
  // starts at the corrected pose.
  const double jump_m =
      std::hypot(moved.x_m - last_world_from_body_.x_m, moved.y_m - last_world_from_body_.y_m);
  const double turn_rad =
      std::abs(geometry::NormalizeAngle(moved.theta_rad - last_world_from_body_.theta_rad));
  std::optional<line_map::MapDelta> delta;
  if (grid_has_scans_ &&
      (jump_m > options_.grid_reset_jump_m || turn_rad > options_.grid_reset_jump_rad)) {
    delta = ExtractAndIntegrate(grid_.ToImage());
    if (delta->empty()) delta.reset();
    grid_ = grid::LocalGrid(options_.local_grid, Eigen::Vector2d(moved.x_m, moved.y_m));
    grid_has_scans_ = false;
    last_extraction_pose_.reset();
    ++counts_.grid_resets;
  }
  map_from_odom_ = map_from_odom;
  last_world_from_body_ = moved;
  return delta;
}

std::optional<geometry::Pose2> EntityPipeline::OdomPoseAt(double stamp_s) const {
  for (auto it = odom_history_.rbegin(); it != odom_history_.rend(); ++it) {
    if (std::abs(it->first - stamp_s) <= kStampTolerance_s) return it->second;
    if (it->first < stamp_s - kStampTolerance_s) break;
  }
  return std::nullopt;
}

line_map::ApplyResult EntityPipeline::ApplyGlobalDelta(const line_map::MapDelta& delta) {
  line_map::ApplyResult result = global_map_.Apply(delta);
  ++(result.ok() ? counts_.global_deltas_applied : counts_.global_deltas_refused);
  return result;
}

void EntityPipeline::ResetGlobalMap(const line_map::MapSnapshot& snapshot) {
  global_map_ = line_map::LineMap::FromSnapshot(snapshot, options_.line_map);
}

const char* ToString(PipelineStage stage) {
  switch (stage) {
    case PipelineStage::kStrideSpreading: return "stride_spreading";
    case PipelineStage::kOdometry: return "odometry";
    case PipelineStage::kPlan: return "plan";
    case PipelineStage::kSlam: return "slam";
    case PipelineStage::kBentScans: return "bent_scans";
    case PipelineStage::kGridInsertion: return "grid_insertion";
    case PipelineStage::kLineExtraction: return "line_extraction";
    case PipelineStage::kOther: return "other";
    case PipelineStage::kCount: break;
  }
  return "unknown";
}

const char* ToString(CorrectionStatus status) {
  switch (status) {
    case CorrectionStatus::kApplied: return "applied";
    case CorrectionStatus::kLowConfidence: return "low_confidence";
    case CorrectionStatus::kUnknownStamp: return "unknown_stamp";
    case CorrectionStatus::kInvalid: return "invalid";
  }
  return "unknown";
}

}  // namespace pena::pipeline
