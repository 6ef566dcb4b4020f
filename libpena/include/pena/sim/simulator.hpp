#pragma once
// The mission simulator: moves every entity of a scenario along its route and produces the
// sensor streams its body would record, with ground truth at every scan.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "pena/sensors/ground_truth.hpp"
#include "pena/sensors/laser_scan.hpp"
#include "pena/sensors/record.hpp"
#include "pena/sim/human_motion.hpp"
#include "pena/sim/robot_motion.hpp"
#include "pena/sim/scenario.hpp"
#include "pena/sim/sensor_models.hpp"
#include "pena/sim/wall_coverage.hpp"

namespace pena::sim {

// Everything tunable, with defaults after the paper's hardware (SICK at 4 Hz, 361 beams).
struct SimulationOptions {
  std::uint64_t seed = 1;
  int laps_override = 0;          // > 0 replaces every entity's laps
  // The laser meets each wall as a box this thick around its line (door jambs, both faces;
  // ThickWallFaces), and the observed walls are those faces; the walkers, floorplan.csv and the
  // a priori plan keep the lines. 0: walls without thickness, as the scenarios draw them.
  double wall_thickness_m = 0.0;
  double motion_rate_hz = 100.0;  // dense true trajectory; every sensor rate must divide it
  double laser_rate_hz = 4.0;
  int laser_beams = 361;
  double laser_angle_min_rad = -1.5707963267948966;  // -90 deg
  double laser_angle_max_rad = 1.5707963267948966;   // +90 deg
  double laser_max_range_m = 30.0;
  double human_laser_height_m = 1.2;
  double robot_laser_height_m = 0.4;
  double gyro_rate_hz = 100.0;     // humans
  double compass_rate_hz = 10.0;   // humans
  double odometry_rate_hz = 20.0;  // robots
  LaserNoiseOptions laser_noise;
  GyroOptions gyro;
  CompassOptions compass;
  StrideOptions stride;
  WheelOdometryOptions wheel_odometry;
  HumanMotionOptions human;  // rate_hz is taken from motion_rate_hz
  RobotMotionOptions robot;  // rate_hz is taken from motion_rate_hz
  WallCoverageOptions coverage;
};

// Beam counts of one entity's scans by what they hit (returned beams only).
struct HitCounts {
  std::size_t wall = 0;
  std::size_t floor = 0;
  std::size_t ceiling = 0;
  std::size_t no_return = 0;
};

// One entity's simulated recording.
struct EntityRecording {
  std::string id;
  sensors::EntityKind kind = sensors::EntityKind::kHuman;
  sensors::LaserGeometry laser;
  double laser_height_m = 0.0;
  std::vector<sensors::SensorRecord> records;  // time order; GroundTruth just before each scan
  std::vector<sensors::GroundTruth> truth;     // one per scan, same stamps
  std::size_t scans = 0;
  std::size_t scans_with_floor_or_ceiling = 0;  // scans with at least one such returned beam
  HitCounts beams;
  double start_s = 0.0;
  double end_s = 0.0;
};

// The whole mission.
struct SimulationResult {
  std::string mission;
  std::vector<EntityRecording> entities;  // scenario order
  std::vector<ObservedSegment> observed;  // wall parts hit by any entity's returned beams
  double start_s = 0.0;
  double end_s = 0.0;
};

// Runs scenarios. Same options (seed included) and scenario give identical results.
class Simulator {
 public:
  // Throws std::invalid_argument naming the bad field and its unit.
  explicit Simulator(const SimulationOptions& options = {});

  // Simulates every entity. Throws std::invalid_argument for an unusable scenario.
  SimulationResult Run(const Scenario& scenario) const;

  const SimulationOptions& options() const { return options_; }
  // The laser geometry the simulated scans carry.
  sensors::LaserGeometry LaserGeometry() const;

 private:
  SimulationOptions options_;
};

}  // namespace pena::sim
