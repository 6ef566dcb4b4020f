#include "pena/sim/simulator.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>

#include "pena/sim/laser_raycaster.hpp"
#include "pena/sim/wall_thickness.hpp"

namespace pena::sim {
namespace {

void Require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument(what);
}

// Motion samples per sensor sample; the rate must divide the motion rate exactly.
std::size_t Divisor(double motion_rate_hz, double rate_hz, const std::string& field) {
  Require(rate_hz > 0.0, "simulation." + field + " must be > 0 Hz, got " + std::to_string(rate_hz));
  const double ratio = motion_rate_hz / rate_hz;
  Require(ratio >= 1.0 && std::abs(ratio - std::round(ratio)) < 1e-9,
          "simulation." + field + " must divide motion_rate_hz (" + std::to_string(motion_rate_hz) +
              " Hz), got " + std::to_string(rate_hz) + " Hz");
  return static_cast<std::size_t>(std::round(ratio));
}

// FNV-1a: the random streams of an entity follow its id, not its position in the file.
std::uint64_t HashId(const std::string& id) {
  std::uint64_t hash = 0xCBF29CE484222325ULL;
  for (const char c : id) {
    hash ^= static_cast<unsigned char>(c);
    hash *= 0x100000001B3ULL;
  }
  return hash;
}

enum Stream : std::uint64_t { kMotion = 1, kLaser, kGyro, kCompass, kStride, kOdometry };

// Shorter landings are shuffles on the spot, not steps the sensor resolves.
constexpr double kMinLandingStepM = 0.05;
// How long a walker stands still before the last step counts as landed.
constexpr double kStandBeforeLandingS = 0.2;

// Simulates one entity; holds the per-entity sensor models.
class EntitySimulator {
 public:
  EntitySimulator(const SimulationOptions& options, const Scenario& scenario,
                  const LaserRaycaster& raycaster, WallCoverage& coverage, Random random)
      : o_(options),
        scenario_(scenario),
        raycaster_(raycaster),
        coverage_(coverage),
        random_(random),
        laser_noise_(options.laser_noise, random.Derive(kLaser)) {}

  EntityRecording Run(const EntitySpec& spec, const sensors::LaserGeometry& laser);

 private:
  void AddScan(const TrueState& state, EntityRecording& out,
               const std::optional<geometry::Pose2>& odometry_pose);
  void AddHumanSensors(const TrueMotion& motion, std::size_t i, std::size_t& next_step,
                       std::size_t& last_step_index, EntityRecording& out);
  bool Standing(const TrueMotion& motion, std::size_t i) const;

  const SimulationOptions& o_;
  const Scenario& scenario_;
  const LaserRaycaster& raycaster_;
  WallCoverage& coverage_;
  Random random_;
  LaserNoiseModel laser_noise_;
  std::optional<GyroModel> gyro_;
  std::optional<CompassModel> compass_;
  std::optional<StrideModel> stride_;
  std::size_t gyro_every_ = 1, compass_every_ = 1, laser_every_ = 1, odometry_every_ = 1;
};

EntityRecording EntitySimulator::Run(const EntitySpec& spec, const sensors::LaserGeometry& laser) {
  const bool human = spec.kind == sensors::EntityKind::kHuman;
  EntityRecording out;
  out.id = spec.id;
  out.kind = spec.kind;
  out.laser = laser;
  out.laser_height_m = human ? o_.human_laser_height_m : o_.robot_laser_height_m;
  laser_every_ = Divisor(o_.motion_rate_hz, o_.laser_rate_hz, "laser_rate_hz");
  gyro_every_ = Divisor(o_.motion_rate_hz, o_.gyro_rate_hz, "gyro_rate_hz");
  compass_every_ = Divisor(o_.motion_rate_hz, o_.compass_rate_hz, "compass_rate_hz");
  odometry_every_ = Divisor(o_.motion_rate_hz, o_.odometry_rate_hz, "odometry_rate_hz");
  Random motion_random = random_.Derive(kMotion);
  TrueMotion motion;
  if (human) {
    HumanMotionOptions human_options = o_.human;
    human_options.rate_hz = o_.motion_rate_hz;
    motion = HumanMotion(human_options).Generate(spec, scenario_.walls, motion_random);
    gyro_.emplace(o_.gyro, random_.Derive(kGyro));
    compass_.emplace(o_.compass, scenario_.magnetic, random_.Derive(kCompass));
    stride_.emplace(o_.stride, random_.Derive(kStride));
  } else {
    RobotMotionOptions robot_options = o_.robot;
    robot_options.rate_hz = o_.motion_rate_hz;
    motion = RobotMotion(robot_options).Generate(spec);
  }
  WheelOdometryModel odometry(o_.wheel_odometry, random_.Derive(kOdometry));
  const double dt_s = 1.0 / o_.motion_rate_hz;
  std::size_t next_step = 0, last_step_index = 0;
  for (std::size_t i = 0; i < motion.states.size(); ++i) {
    const TrueState& state = motion.states[i];
    std::optional<geometry::Pose2> odometry_pose;
    if (human) {
      AddHumanSensors(motion, i, next_step, last_step_index, out);
    } else {
      if (i > 0) odometry.Advance(state, dt_s);
      if (i % odometry_every_ == 0) out.records.push_back(odometry.Current());
      odometry_pose = odometry.Current().odom_pose;
    }
    if (i % laser_every_ == 0) AddScan(state, out, odometry_pose);
  }
  out.start_s = motion.states.front().stamp_s;
  out.end_s = motion.states.back().stamp_s;
  return out;
}

void EntitySimulator::AddHumanSensors(const TrueMotion& motion, std::size_t i,
                                      std::size_t& next_step, std::size_t& last_step_index,
                                      EntityRecording& out) {
  const TrueState& state = motion.states[i];
  if (i > 0 && i % gyro_every_ == 0) {
    // The gyro reports the mean rate over its own interval, so integrating it gives the truth.
    TrueState interval = state;
    const double before = motion.states[i - gyro_every_].world_from_body.theta_rad;
    const double period_s = static_cast<double>(gyro_every_) / o_.motion_rate_hz;
    interval.yaw_rate_rad_s =
        geometry::NormalizeAngle(state.world_from_body.theta_rad - before) / period_s;
    out.records.push_back(gyro_->Measure(interval, period_s));
  }
  if (i % compass_every_ == 0) out.records.push_back(compass_->Measure(state));
  const geometry::Pose2& from = motion.states[last_step_index].world_from_body;
  const double length_m =
      std::hypot(state.world_from_body.x_m - from.x_m, state.world_from_body.y_m - from.y_m);
  if (next_step < motion.step_end_indices.size() && motion.step_end_indices[next_step] == i) {
    out.records.push_back(stride_->Measure(state.stamp_s, length_m));
    last_step_index = i;
    ++next_step;
  } else if (length_m >= kMinLandingStepM && Standing(motion, i)) {
    // A walker who comes to a stand mid-stride puts the trailing foot down, and the stride sensor
    // measures that last, short step. Without it the distance walked since the last full step
    // stays unreported for the whole stop (0.4-0.5 m at walking speed).
    out.records.push_back(stride_->MeasureLanding(state.stamp_s, length_m));
    last_step_index = i;
  }
}

bool EntitySimulator::Standing(const TrueMotion& motion, std::size_t i) const {
  // Standing for a while, not passing through zero speed: a side or back step ends at rest for
  // an instant and the gait goes on, its displacement in the step that ends next.
  const auto ticks = static_cast<std::size_t>(std::ceil(kStandBeforeLandingS * o_.motion_rate_hz));
  if (i < ticks) return false;
  for (std::size_t k = i + 1 - ticks; k <= i; ++k) {
    if (motion.states[k].speed_m_s != 0.0) return false;
  }
  return true;
}

void EntitySimulator::AddScan(const TrueState& state, EntityRecording& out,
                              const std::optional<geometry::Pose2>& odometry_pose) {
  sensors::GroundTruth truth{state.stamp_s, state.world_from_body, out.laser_height_m,
                             state.pitch_rad, state.roll_rad};
  out.truth.push_back(truth);
  out.records.push_back(truth);
  sensors::LaserScan scan;
  scan.stamp_s = state.stamp_s;
  scan.geometry = out.laser;
  scan.odometry_pose = odometry_pose;
  const LaserPose pose = LaserPoseFrom(truth);
  const Eigen::Vector2d position = pose.position_m.head<2>();
  const double max_range_m = SmokeMaxRange(scenario_.smoke, position, out.laser.max_range_m);
  // Any wall a beam can reach lies within max range horizontally: cull the rest once per scan.
  const std::vector<std::size_t> candidates = raycaster_.WallsNear(position, max_range_m);
  const auto beams = static_cast<std::size_t>(o_.laser_beams);
  scan.ranges_m.reserve(beams);
  bool floor_or_ceiling = false;
  for (std::size_t b = 0; b < beams; ++b) {
    const BeamHit hit = raycaster_.Cast(pose, scan.BeamAngle(b), max_range_m, candidates);
    const float range = laser_noise_.Measure(hit, max_range_m);
    scan.ranges_m.push_back(range);
    if (range == sensors::LaserScan::kNoReturn) {
      ++out.beams.no_return;
    } else if (hit.kind == HitKind::kWall) {
      ++out.beams.wall;
      coverage_.Mark(hit.wall_index, hit.along_m);
    } else {
      floor_or_ceiling = true;
      ++(hit.kind == HitKind::kFloor ? out.beams.floor : out.beams.ceiling);
    }
  }
  ++out.scans;
  if (floor_or_ceiling) ++out.scans_with_floor_or_ceiling;
  out.records.push_back(std::move(scan));
}

}  // namespace

Simulator::Simulator(const SimulationOptions& options) : options_(options) {
  const auto& o = options;
  Require(o.motion_rate_hz > 0.0, "simulation.motion_rate_hz must be > 0 Hz");
  Divisor(o.motion_rate_hz, o.laser_rate_hz, "laser_rate_hz");
  Divisor(o.motion_rate_hz, o.gyro_rate_hz, "gyro_rate_hz");
  Divisor(o.motion_rate_hz, o.compass_rate_hz, "compass_rate_hz");
  Divisor(o.motion_rate_hz, o.odometry_rate_hz, "odometry_rate_hz");
  Require(o.laser_beams >= 2,
          "simulation.laser_beams must be >= 2, got " + std::to_string(o.laser_beams));
  Require(o.laser_angle_max_rad > o.laser_angle_min_rad,
          "simulation.laser_angle_max_rad must be > laser_angle_min_rad (rad)");
  Require(o.laser_max_range_m > 0.0, "simulation.laser_max_range_m must be > 0 m");
  Require(o.human_laser_height_m > 0.0 && o.robot_laser_height_m > 0.0,
          "simulation.human_laser_height_m and robot_laser_height_m must be > 0 m");
  Require(o.laps_override >= 0, "simulation.laps_override must be >= 0");
  Require(o.wall_thickness_m >= 0.0 && o.wall_thickness_m <= 1.0,
          "simulation.wall_thickness_m must be in [0, 1] m, got " +
              std::to_string(o.wall_thickness_m));
  // Construct each model once so bad sub-options fail here, not halfway through a mission.
  HumanMotionOptions human = o.human;
  human.rate_hz = o.motion_rate_hz;
  static_cast<void>(HumanMotion(human));
  RobotMotionOptions robot = o.robot;
  robot.rate_hz = o.motion_rate_hz;
  static_cast<void>(RobotMotion(robot));
  static_cast<void>(LaserNoiseModel(o.laser_noise, Random(0)));
  static_cast<void>(GyroModel(o.gyro, Random(0)));
  static_cast<void>(CompassModel(o.compass, {}, Random(0)));
  static_cast<void>(StrideModel(o.stride, Random(0)));
  static_cast<void>(WheelOdometryModel(o.wheel_odometry, Random(0)));
  static_cast<void>(WallCoverage({}, o.coverage));
}

sensors::LaserGeometry Simulator::LaserGeometry() const {
  const double span = options_.laser_angle_max_rad - options_.laser_angle_min_rad;
  return {options_.laser_angle_min_rad, span / static_cast<double>(options_.laser_beams - 1),
          options_.laser_max_range_m};
}

SimulationResult Simulator::Run(const Scenario& scenario) const {
  Require(scenario.ceiling_height_m >
              std::max(options_.human_laser_height_m, options_.robot_laser_height_m),
          "scenario " + scenario.name + ": ceiling_height_m must be above the laser heights");
  // The laser's walls: the scenario's lines, or boxes around them (the walkers keep the lines).
  const bool thick = options_.wall_thickness_m > 0.0;
  const std::vector<geometry::Segment2> laser_walls =
      thick ? ThickWallFaces(scenario.walls, options_.wall_thickness_m) : scenario.walls;
  const LaserRaycaster raycaster(laser_walls, scenario.ceiling_height_m);
  WallCoverage coverage(laser_walls, options_.coverage);
  const Random base(options_.seed);
  SimulationResult result;
  result.mission = scenario.name;
  for (EntitySpec spec : scenario.entities) {
    if (options_.laps_override > 0) spec.laps = options_.laps_override;
    Require(!spec.route.empty() && spec.laps >= 1 && spec.cruise_speed_m_s > 0.0,
            "scenario " + scenario.name + ": entity " + spec.id +
                " needs a route, laps >= 1 and cruise_speed_m_s > 0 m/s");
    EntitySimulator entity(options_, scenario, raycaster, coverage, base.Derive(HashId(spec.id)));
    result.entities.push_back(entity.Run(spec, LaserGeometry()));
  }
  result.observed = coverage.Segments();
  if (thick) {  // a face's id is its wall's, as floorplan.csv numbers them
    for (ObservedSegment& part : result.observed) part.wall_index /= kFacesPerThickWall;
  }
  if (!result.entities.empty()) {
    result.start_s = result.entities.front().start_s;
    result.end_s = result.entities.front().end_s;
    for (const EntityRecording& entity : result.entities) {
      result.start_s = std::min(result.start_s, entity.start_s);
      result.end_s = std::max(result.end_s, entity.end_s);
    }
  }
  return result;
}

}  // namespace pena::sim
