#pragma once
// pena-fusion's options: a plain struct filled from the config file (service_config.proto,
// FusionConfig) and the command line, validated with messages naming the key and its unit.

#include <filesystem>
#include <string>

#include "dds_participant.hpp"
#include "lockstep_order.hpp"
#include "pena/fusion/correction.hpp"
#include "pena/fusion/correction_filter.hpp"
#include "pena/fusion/fusion_store.hpp"
#include "service_config.pb.h"

namespace pena::services {

// pena-fusion's participant profile when none is given (config dds.participant_profile or
// --profile): pena_loopback without shared memory (deploy/dds/pena-loopback.xml). A fusion
// restarted after kill -9 reuses its predecessor's ports; over Fast DDS 2.9.1 shared memory the
// entities' channels to them sometimes stay dead and the restarted fusion hears nothing
// (docs/fusion-service.md, "Persistence and restart").
inline constexpr const char* kFusionParticipantProfile = "pena_loopback_udp";

// A robot's laser odometry drifts far less than a person's (docs/demo.md: 0.02 m RMS against
// 0.7-0.8 m in the team mission), so its corrections get a far smaller gain.
inline fusion::CorrectionFilterOptions RobotFilterDefaults() {
  fusion::CorrectionFilterOptions options;
  options.initial_sd_m = 0.02;
  options.initial_sd_rad = 0.005;
  options.translation_noise_m_per_sqrt_m = 0.005;
  options.heading_noise_rad_per_sqrt_m = 0.0005;
  options.turn_noise_rad_per_sqrt_rad = 0.003;
  return options;
}

// With the filter the window follows the entity's uncertainty (0.3 m after a correction), so
// the widest one can be larger than ComputeCorrection's default: 2.4 m x 2.4 m x 20 deg lets a
// firefighter whose odometry jumped by a metre be found again.
inline fusion::CorrectionOptions WideCorrectionWindow() {
  fusion::CorrectionOptions options;
  options.window.size_x_m = 2.4;
  options.window.size_y_m = 2.4;
  options.window.size_theta_rad = 0.3490658503988659;
  return options;
}

struct FusionServiceOptions {
  std::filesystem::path state_dir;    // journal + checkpoints (required)
  std::filesystem::path plan;         // a priori plan (line CSV, SVG or DXF); empty: none
  std::filesystem::path output_dir;   // final global map, stats, received poses; empty: none
  fusion::FusionStoreOptions store;   // silent_after_s, checkpoint_every, merge options
  bool corrections = true;            // match reference scans and send corrections
  double correction_interval_s = 1.0; // seconds between attempts per entity (wall; lockstep: mission)
  // Lockstep with entities run with --await-corrections (a test and demo mode, docs/
  // fusion-service.md "Lockstep"): attempts are scheduled on the scans' own stamps
  // (correction_interval_s in mission seconds), none is superseded or dropped as stale, and
  // every attempt is answered (a correction, or a Correction with confidence 0: nothing to
  // apply), so the entity that waits for the answer sees the same corrections however loaded
  // the machine is. Command line only (--lockstep).
  bool lockstep = false;
  // Lockstep: the order deltas are applied and scans attempted in (lockstep_order.hpp), so the
  // global map is the same on every run too. Command line only.
  LockstepOrderOptions lockstep_order;
  // A reference scan that waited longer than this for the correction worker is dropped (the
  // entity's next one gets the next chance): the 200 ms latency budget minus a match.
  // Wall seconds; 0 = never dropped.
  double correction_max_wait_s = 0.15;
  double correction_min_m = 0.03;     // smaller raw corrections are not sent (metres); filtered
                                      // ones always are (the filter counted them as applied)
  double correction_min_rad = 0.01;   // ... (radians)
  // Blend corrections with each entity's pose uncertainty (fusion::CorrectionFilter); false:
  // the raw match replaces the pose (the behaviour before the filter, for comparison).
  bool filter_corrections = true;
  fusion::CorrectionOptions correction = WideCorrectionWindow();  // the match (widest window)
  fusion::CorrectionFilterOptions human_filter;   // laser odometry of a walking person
  fusion::CorrectionFilterOptions robot_filter = RobotFilterDefaults();  // wheel + laser
  double snapshot_period_s = 1.0;     // wall seconds between global snapshots while changing
  double tick_period_s = 1.0;         // wall seconds between silence checks
  DdsOptions dds;
  std::string log_level = "info";
  std::filesystem::path log_file;
};

// The options a config gives; relative paths resolve against the config file's directory.
// Throws io::InputError(config_path, 0, "key: what") for a bad value.
FusionServiceOptions FusionOptionsFromConfig(const config::FusionConfig& config,
                                             const std::filesystem::path& config_path);

// Checks the whole struct; throws std::invalid_argument naming the key and unit.
void ValidateFusionServiceOptions(const FusionServiceOptions& options);

}  // namespace pena::services
