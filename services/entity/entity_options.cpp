#include "entity_options.hpp"

#include <cmath>
#include <stdexcept>

#include "config_loader.hpp"
#include "pena/io/input_error.hpp"

namespace pena::services {
namespace {

odometry::MotionPrior ParseMotionPrior(const std::string& text) {
  if (text == "auto") return odometry::MotionPrior::kAuto;
  if (text == "dead_reckoning") return odometry::MotionPrior::kDeadReckoning;
  if (text == "stride_only") return odometry::MotionPrior::kStrideOnly;
  if (text == "odometry") return odometry::MotionPrior::kOdometry;
  if (text == "none") return odometry::MotionPrior::kNone;
  throw std::invalid_argument("pipeline.motion_prior must be auto, dead_reckoning, stride_only, "
                              "odometry or none, got '" + text + "'");
}

void ApplyPipeline(const config::PipelineConfig& config, pipeline::EntityPipelineOptions& out) {
  if (config.has_motion_prior()) out.odometry.motion_prior = ParseMotionPrior(config.motion_prior());
  if (config.has_match_scans()) out.odometry.match_scans = config.match_scans();
  if (config.has_grid_resolution_m()) out.local_grid.grid.resolution_m = config.grid_resolution_m();
  if (config.has_local_grid_size_m()) out.local_grid.size_m = config.local_grid_size_m();
  if (config.has_map_update_distance_m()) {
    out.map_update_distance_m = config.map_update_distance_m();
  }
  if (config.has_min_correction_confidence()) {
    out.min_correction_confidence = config.min_correction_confidence();
  }
  dead_reckoning::StrideInterpolationOptions& spread = out.odometry.dead_reckoning.stride_interpolation;
  if (config.has_spread_strides()) spread.enabled = config.spread_strides();
  if (config.has_stride_hold_s()) spread.max_hold_s = config.stride_hold_s();
}

DdsOptions DdsFromConfig(const config::DdsConfig& config, const std::filesystem::path& path) {
  DdsOptions out;
  for (const std::string& file : config.profiles_files()) {
    out.profiles_files.push_back(ResolvePath(path, file));
  }
  if (out.profiles_files.empty()) out.profiles_files = DefaultProfilesFiles();
  out.participant_profile = config.participant_profile();
  out.domain_id = config.domain_id();
  if (config.has_security_dir()) out.security_dir = ResolvePath(path, config.security_dir());
  return out;
}

}  // namespace

EntityServiceOptions EntityOptionsFromConfig(const config::EntityConfig& config,
                                             const std::filesystem::path& config_path) {
  EntityServiceOptions out;
  try {
    if (config.has_input()) {
      out.input = IsLiveInput(config.input()) ? std::filesystem::path(kLiveInput)
                                              : ResolvePath(config_path, config.input());
    }
    if (config.has_live_input()) {
      if (config.has_input() && !IsLiveInput(config.input())) {
        throw std::invalid_argument("live_input applies only to input: \"dds\" (input is '" +
                                    config.input() + "')");
      }
      out.live.merge.reorder_window_s = config.live_input().reorder_window_s();
      out.live.idle_timeout_s = config.live_input().idle_timeout_s();
      out.live.end_grace_s = config.live_input().end_grace_s();
    }
    if (!config.plan().empty()) out.plan = ResolvePath(config_path, config.plan());
    out.entity_id = config.entity_id();
    if (config.has_kind()) {
      out.kind = sensors::ParseEntityKind(config.kind());
      if (!out.kind) throw std::invalid_argument("kind must be human or robot, got '" +
                                                 config.kind() + "'");
    }
    out.rate = config.rate();
    if (config.has_output_dir()) out.output_dir = ResolvePath(config_path, config.output_dir());
    out.record = config.record();
    out.heartbeat_period_s = config.heartbeat_period_s();
    out.range_quantum_m = config.range_quantum_m();
    out.linger_s = config.linger_s();
    out.wait_for_readers_s = config.wait_for_readers_s();
    out.read.carmen_max_range_m = config.carmen_max_range_m();
    ApplyPipeline(config.pipeline(), out.pipeline);
    out.dds = DdsFromConfig(config.dds(), config_path);
    out.log_level = config.log().level();
    if (config.log().has_file()) out.log_file = ResolvePath(config_path, config.log().file());
  } catch (const std::invalid_argument& error) {
    throw io::InputError(config_path, 0, error.what());
  }
  return out;
}

bool IsLiveInput(const std::filesystem::path& input) { return input == kLiveInput; }

LiveSensorOptions LiveOptionsOf(const EntityServiceOptions& options) {
  LiveSensorOptions live = options.live;
  live.entity_id = options.entity_id;
  return live;
}

void ValidateEntityOptions(const EntityServiceOptions& options) {
  auto require = [](bool ok, const std::string& message) {
    if (!ok) throw std::invalid_argument(message);
  };
  require(!options.input.empty(),
          "input is required (a sensors.penalog, a CARMEN log, or dds for the live sensor topics)");
  if (IsLiveInput(options.input)) ValidateLiveSensorOptions(LiveOptionsOf(options));
  require(options.rate >= 0.0, "rate must be >= 0 (0 = as fast as possible), got " +
                                   std::to_string(options.rate));
  require(options.heartbeat_period_s > 0.0, "heartbeat_period_s must be > 0 s, got " +
                                                std::to_string(options.heartbeat_period_s));
  require(options.range_quantum_m > 0.0, "range_quantum_m must be > 0 m, got " +
                                             std::to_string(options.range_quantum_m));
  require(options.linger_s >= 0.0, "linger_s must be >= 0 s, got " +
                                       std::to_string(options.linger_s));
  require(options.await_corrections_s >= 0.0,
          "--await-corrections must be >= 0 (mission seconds between awaited attempts; 0 = off), "
          "got " + std::to_string(options.await_corrections_s));
  for (std::size_t i = 0; i < options.hold_at_s.size(); ++i) {
    const double t = options.hold_at_s[i];
    require(std::isfinite(t) && t >= 0.0 && (i == 0 || t > options.hold_at_s[i - 1]),
            "--hold-at must be increasing mission times >= 0 s, got " + std::to_string(t) +
                " at position " + std::to_string(i + 1));
  }
  require(options.hold_at_s.empty() || !IsLiveInput(options.input),
          "--hold-at needs a log input: the live sensor topics (input dds) are not ours to hold");
  CorrectionGate{options.corrections};  // throws naming corrections.<field>
  require(options.wait_for_readers_s >= 0.0, "wait_for_readers_s must be >= 0 s, got " +
                                                 std::to_string(options.wait_for_readers_s));
  require(options.dds.domain_id >= 0 && options.dds.domain_id <= 232,
          "dds.domain_id must be in 0..232, got " + std::to_string(options.dds.domain_id));
  // The plan is in the map frame; an unknown start runs the chain in the entity's own frame until
  // the fusion places it, so map localisation against the plan would compare different frames.
  require(!(options.start_unknown && !options.plan.empty()),
          "--unknown-start and plan (" + options.plan.string() +
              ") cannot be used together: the plan is in the map frame, the chain of an entity "
              "with an unknown start in its own frame (the fusion places it; drop one of them)");
  require(options.record ? !options.output_dir.empty() : true,
          "record needs output_dir (the recording goes to output_dir/recording)");
  const double hold_s = options.pipeline.odometry.dead_reckoning.stride_interpolation.max_hold_s;
  require(hold_s > 0.0 && std::isfinite(hold_s),
          "pipeline.stride_hold_s must be > 0 s (sensor seconds), got " + std::to_string(hold_s));
  pipeline::ValidateEntityPipelineOptions(options.pipeline);
}

}  // namespace pena::services
