#pragma once
// pena-fusion's options: a plain struct filled from the config file (service_config.proto,
// FusionConfig) and the command line, validated with messages naming the key and its unit.

#include <filesystem>
#include <string>

#include "dds_participant.hpp"
#include "pena/fusion/fusion_store.hpp"
#include "service_config.pb.h"

namespace pena::services {

struct FusionServiceOptions {
  std::filesystem::path state_dir;    // journal + checkpoints (required)
  std::filesystem::path plan;         // a priori plan (line CSV, SVG or DXF); empty: none
  std::filesystem::path output_dir;   // final global map, stats, received poses; empty: none
  fusion::FusionStoreOptions store;   // silent_after_s, checkpoint_every, merge options
  bool corrections = true;            // match reference scans and send corrections
  double correction_interval_s = 1.0; // wall seconds between attempts per entity
  double correction_min_m = 0.03;     // smaller corrections are not sent (metres)
  double correction_min_rad = 0.01;   // ... (radians)
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
