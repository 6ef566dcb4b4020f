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

// pena-fusion's default participant profile: loopback without shared memory, whose channels may
// stay dead for a fusion restarted after kill -9 (docs/fusion-service.md, "Persistence and restart").
inline constexpr const char* kFusionParticipantProfile = "pena_loopback_udp";

// A robot's laser odometry drifts far less than a person's, so its corrections get a far smaller gain.
inline fusion::CorrectionFilterOptions RobotFilterDefaults() {
  fusion::CorrectionFilterOptions options;
  options.initial_sd_m = 0.02;
  options.initial_sd_rad = 0.005;
  options.translation_noise_m_per_sqrt_m = 0.005;
  options.heading_noise_rad_per_sqrt_m = 0.0005;
  options.turn_noise_rad_per_sqrt_rad = 0.003;
  return options;
}

// The widest correction window when the filter sizes it by the entity's uncertainty (2.4 m x
// 2.4 m x 20 deg: a firefighter whose odometry jumped by a metre is found again).
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
  // Lockstep with entities run with --await-corrections: every attempt, scheduled on mission time,
  // is answered (docs/fusion-service.md, "Lockstep"). Command line only (--lockstep).
  bool lockstep = false;
  // Lockstep: the order deltas are applied and scans attempted in (lockstep_order.hpp), so the
  // global map is the same on every run too. Command line only.
  LockstepOrderOptions lockstep_order;
  // A reference scan waiting longer than this for the correction worker is dropped (the 200 ms
  // latency budget minus a match). Wall seconds; 0 = never dropped.
  double correction_max_wait_s = 0.15;
  double correction_min_m = 0.03;     // smaller raw corrections are not sent (metres); filtered
                                      // ones always are (the filter counted them as applied)
  double correction_min_rad = 0.01;   // ... (radians)
  // Blend corrections with each entity's pose uncertainty (fusion::CorrectionFilter); false: the
  // raw match replaces the pose (for comparison).
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
