#pragma once
// pena-entity's options: a plain struct filled from the config file (service_config.proto,
// EntityConfig) and the command line, validated with messages naming the key and its unit.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "correction_gate.hpp"
#include "dds_participant.hpp"
#include "live_sensor_source.hpp"
#include "pena/io/log_source.hpp"
#include "pena/pipeline/entity_pipeline.hpp"
#include "pena/sensors/entity.hpp"
#include "service_config.pb.h"

namespace pena::services {

struct EntityServiceOptions {
  std::filesystem::path input;        // native log, CARMEN log, or "dds" (kLiveInput)
  std::filesystem::path plan;         // a priori plan (map localisation); empty: none
  std::string entity_id;              // empty: the log's own, else the file's stem
  std::optional<sensors::EntityKind> kind;  // empty: the log's own, else robot
  double rate = 1.0;                  // time scale; 0 = as fast as possible
  std::filesystem::path output_dir;   // empty: no files written
  bool record = false;                // record sent/received samples under output_dir/recording
  double heartbeat_period_s = 1.0;    // wall seconds
  double range_quantum_m = 0.01;
  double linger_s = 2.0;              // wall seconds to wait for acknowledgements at the end
  double wait_for_readers_s = 0.0;    // wall seconds to wait for a line-map reader at the start
  // The chain runs in the entity's own frame until the fusion places it (docs/services.md,
  // "Unknown start"). Command line only (--unknown-start).
  bool start_unknown = false;
  // Lockstep with pena-fusion --lockstep --correction-interval of the same value (mission s; 0 =
  // off): wait for the fusion's answer at the scans it attempts. Command line only.
  double await_corrections_s = 0.0;
  // Mission times (the log's stamps, s, increasing) at which the entity stops its clock until a
  // SIGUSR1 releases it: nothing is read or published meanwhile, corrections and heartbeats are
  // served, and the pause is not counted in the pacing. Lets a test act at a fixed mission time
  // on a loaded machine. Log input only; command line only (--hold-at).
  std::vector<double> hold_at_s;
  // What corrections are applied (docs/security.md): increasing seq, and within chi-square
  // max_chi2 of the entity's own uncertainty unless an operator sent them. Command line only
  // (--correction-max-chi2).
  CorrectionGateOptions corrections;
  // input "dds": the live sensor topics (entity_id required; live.entity_id is set from it).
  LiveSensorOptions live;
  io::ReadOptions read;
  // libpena's defaults: a person's strides are spread over their scans (pipeline.spread_strides,
  // on; docs/services.md, "Stride spreading in the service").
  pipeline::EntityPipelineOptions pipeline;
  DdsOptions dds;
  std::string log_level = "info";
  std::filesystem::path log_file;
};

// The options a config gives; relative paths resolve against the config file's directory.
// Throws io::InputError(config_path, 0, "key: what") for a bad value.
EntityServiceOptions EntityOptionsFromConfig(const config::EntityConfig& config,
                                             const std::filesystem::path& config_path);

// True when `input` names the live sensor topics ("dds") rather than a file.
bool IsLiveInput(const std::filesystem::path& input);

// The live input's options with the entity id filled in.
LiveSensorOptions LiveOptionsOf(const EntityServiceOptions& options);

// Checks the whole struct; throws std::invalid_argument naming the key and unit.
void ValidateEntityOptions(const EntityServiceOptions& options);

}  // namespace pena::services
