#include "fusion_options.hpp"

#include <stdexcept>

#include "config_loader.hpp"
#include "pena/io/input_error.hpp"

namespace pena::services {
namespace {

DdsOptions DdsFromConfig(const config::DdsConfig& config, const std::filesystem::path& path) {
  DdsOptions out;
  for (const std::string& file : config.profiles_files()) {
    out.profiles_files.push_back(ResolvePath(path, file));
  }
  if (out.profiles_files.empty()) out.profiles_files = DefaultProfilesFiles();
  // Not given: kFusionParticipantProfile (no shared memory), so a fusion restarted after
  // kill -9 hears its entities again (fusion_options.hpp).
  out.participant_profile = config.has_participant_profile() ? config.participant_profile()
                                                              : kFusionParticipantProfile;
  out.domain_id = config.domain_id();
  if (config.has_security_dir()) out.security_dir = ResolvePath(path, config.security_dir());
  return out;
}

void Require(bool ok, const std::string& message) {
  if (!ok) throw std::invalid_argument(message);
}

}  // namespace

FusionServiceOptions FusionOptionsFromConfig(const config::FusionConfig& config,
                                             const std::filesystem::path& config_path) {
  FusionServiceOptions out;
  if (config.has_state_dir()) out.state_dir = ResolvePath(config_path, config.state_dir());
  if (config.has_plan() && !config.plan().empty()) {
    out.plan = ResolvePath(config_path, config.plan());
  }
  if (config.has_output_dir()) out.output_dir = ResolvePath(config_path, config.output_dir());
  out.store.fusion.silent_after_s = config.silent_after_s();
  if (config.checkpoint_every() < 1) {
    throw io::InputError(config_path, 0, "checkpoint_every must be >= 1 (records), got " +
                                             std::to_string(config.checkpoint_every()));
  }
  out.store.checkpoint_every = static_cast<std::size_t>(config.checkpoint_every());
  out.corrections = config.corrections();
  out.correction_interval_s = config.correction_interval_s();
  out.correction_min_m = config.correction_min_m();
  out.correction_min_rad = config.correction_min_rad();
  out.snapshot_period_s = config.snapshot_period_s();
  out.tick_period_s = config.tick_period_s();
  out.dds = DdsFromConfig(config.dds(), config_path);
  out.log_level = config.log().level();
  if (config.log().has_file()) out.log_file = ResolvePath(config_path, config.log().file());
  return out;
}

void ValidateFusionServiceOptions(const FusionServiceOptions& options) {
  Require(!options.state_dir.empty(), "state_dir is required (the journal directory)");
  Require(options.store.fusion.silent_after_s > 0.0,
          "silent_after_s must be > 0 s, got " + std::to_string(options.store.fusion.silent_after_s));
  Require(options.correction_interval_s >= 0.0, "correction_interval_s must be >= 0 s, got " +
                                                     std::to_string(options.correction_interval_s));
  Require(options.correction_max_wait_s >= 0.0,
          "correction_max_wait_s must be >= 0 s, got " +
              std::to_string(options.correction_max_wait_s));
  Require(options.correction_min_m >= 0.0,
          "correction_min_m must be >= 0 m, got " + std::to_string(options.correction_min_m));
  Require(options.correction_min_rad >= 0.0,
          "correction_min_rad must be >= 0 rad, got " + std::to_string(options.correction_min_rad));
  Require(options.snapshot_period_s > 0.0,
          "snapshot_period_s must be > 0 s, got " + std::to_string(options.snapshot_period_s));
  Require(options.tick_period_s > 0.0,
          "tick_period_s must be > 0 s, got " + std::to_string(options.tick_period_s));
  Require(options.dds.domain_id >= 0 && options.dds.domain_id <= 232,
          "dds.domain_id must be in 0..232, got " + std::to_string(options.dds.domain_id));
  Require(options.plan.empty() || std::filesystem::exists(options.plan),
          "plan: no such file " + options.plan.string());
  ValidateLockstepOrderOptions(options.lockstep_order);
  fusion::ValidateFusionOptions(options.store.fusion);
  fusion::ValidateCorrectionFilterOptions(options.human_filter);
  fusion::ValidateCorrectionFilterOptions(options.robot_filter);
}

}  // namespace pena::services
