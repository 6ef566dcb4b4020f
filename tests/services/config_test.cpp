// Strict config loading: unknown keys and bad values are errors naming file and line.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <vector>

#include "config_loader.hpp"
#include "entity_options.hpp"
#include "service_test_support.hpp"

namespace pena::services {
namespace {

std::filesystem::path Write(const std::string& name, const std::string& text) {
  const std::filesystem::path path = testing::ScratchDir("config") / name;
  std::ofstream(path) << text;
  return path;
}

TEST(ConfigLoader, ReadsAValidEntityConfigAndResolvesPathsAgainstIt) {
  const auto path = Write("entity.conf",
                          "input: \"mission/ff1\"\nrate: 10\nrecord: true\noutput_dir: \"out\"\n"
                          "pipeline { map_update_distance_m: 3 }\n"
                          "dds { participant_profile: \"pena_loopback\" domain_id: 7 }\n");
  const auto config = LoadTextConfig<config::EntityConfig>(path);
  const EntityServiceOptions options = EntityOptionsFromConfig(config, path);
  EXPECT_EQ(options.input, path.parent_path() / "mission/ff1");
  EXPECT_DOUBLE_EQ(options.rate, 10.0);
  EXPECT_DOUBLE_EQ(options.pipeline.map_update_distance_m, 3.0);
  EXPECT_EQ(options.dds.domain_id, 7);
  EXPECT_EQ(options.dds.profiles_files.size(), 2u);  // the defaults: loopback + QoS
  EXPECT_NO_THROW(ValidateEntityOptions(options));
}

TEST(ConfigLoader, LiveInputIsReadAndValidatedStrictly) {
  const auto path = Write("live.conf",
                          "input: \"dds\"\nentity_id: \"ff1\"\n"
                          "live_input { reorder_window_s: 0.5 idle_timeout_s: 30 }\n");
  EntityServiceOptions options =
      EntityOptionsFromConfig(LoadTextConfig<config::EntityConfig>(path), path);
  EXPECT_TRUE(IsLiveInput(options.input));  // not resolved against the config's directory
  EXPECT_DOUBLE_EQ(options.live.merge.reorder_window_s, 0.5);
  EXPECT_DOUBLE_EQ(options.live.idle_timeout_s, 30.0);
  EXPECT_DOUBLE_EQ(options.live.end_grace_s, 2.0);
  EXPECT_NO_THROW(ValidateEntityOptions(options));
  options.live.merge.reorder_window_s = -1.0;
  EXPECT_THROW(ValidateEntityOptions(options), std::invalid_argument);
  options.live.merge.reorder_window_s = 0.2;
  options.entity_id.clear();  // whose samples?
  EXPECT_THROW(ValidateEntityOptions(options), std::invalid_argument);
  // live_input with a file input is a mistake, named with the file.
  const auto wrong = Write("wrong.conf", "input: \"ff1.penalog\"\nlive_input { }\n");
  EXPECT_THROW(EntityOptionsFromConfig(LoadTextConfig<config::EntityConfig>(wrong), wrong),
               io::InputError);
}

TEST(ConfigLoader, HoldTimesMustIncreaseAndNeedALogInput) {
  EntityServiceOptions options;
  options.input = "ff1.penalog";
  options.hold_at_s = {17.0, 22.0};
  EXPECT_NO_THROW(ValidateEntityOptions(options));
  for (const std::vector<double>& bad : {std::vector<double>{22.0, 17.0}, {17.0, 17.0}, {-1.0},
                                         {17.0, std::nan("")}}) {
    options.hold_at_s = bad;
    try {
      ValidateEntityOptions(options);
      FAIL() << "no exception for hold_at_s of " << bad.size() << " times";
    } catch (const std::invalid_argument& error) {
      EXPECT_NE(std::string(error.what()).find("--hold-at"), std::string::npos) << error.what();
      EXPECT_NE(std::string(error.what()).find("at position"), std::string::npos) << error.what();
    }
  }
  // The live sensor topics are paced by the sensors: not the entity's to hold.
  options.input = "dds";
  options.entity_id = "ff1";
  options.hold_at_s = {17.0};
  EXPECT_THROW(ValidateEntityOptions(options), std::invalid_argument);
}

TEST(ConfigLoader, UnknownKeyIsAnErrorNamingFileAndLine) {
  const auto path = Write("typo.conf", "input: \"x\"\n\nrat: 10\n");
  try {
    LoadTextConfig<config::EntityConfig>(path);
    FAIL() << "no exception";
  } catch (const io::InputError& error) {
    EXPECT_EQ(error.line(), 3u);
    EXPECT_NE(std::string(error.what()).find("typo.conf:3"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("rat"), std::string::npos) << error.what();
  }
}

TEST(ConfigLoader, BadValuesAreNamed) {
  const auto path = Write("bad.conf", "input: \"x\"\nkind: \"dog\"\n");
  EXPECT_THROW(EntityOptionsFromConfig(LoadTextConfig<config::EntityConfig>(path), path),
               io::InputError);
  const auto rate = Write("rate.conf", "input: \"x\"\nrate: -1\n");
  try {
    ValidateEntityOptions(EntityOptionsFromConfig(LoadTextConfig<config::EntityConfig>(rate), rate));
    FAIL() << "no exception";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("rate"), std::string::npos);
  }
  EXPECT_THROW(LoadTextConfig<config::EntityConfig>("/nonexistent/entity.conf"), io::InputError);
}

// On by default (docs/services.md, "Stride spreading in the service").
TEST(ConfigLoader, StrideSpreadingIsOnByDefaultCanBeTurnedOffAndItsHoldIsChecked) {
  const auto path = Write("spread.conf", "input: \"x\"\n");
  EntityServiceOptions options =
      EntityOptionsFromConfig(LoadTextConfig<config::EntityConfig>(path), path);
  EXPECT_TRUE(options.pipeline.odometry.dead_reckoning.stride_interpolation.enabled);
  const auto off = Write("off.conf", "input: \"x\"\npipeline { spread_strides: false }\n");
  options = EntityOptionsFromConfig(LoadTextConfig<config::EntityConfig>(off), off);
  EXPECT_FALSE(options.pipeline.odometry.dead_reckoning.stride_interpolation.enabled);
  const auto on = Write("on.conf", "input: \"x\"\npipeline { spread_strides: true stride_hold_s: 0 }\n");
  options = EntityOptionsFromConfig(LoadTextConfig<config::EntityConfig>(on), on);
  EXPECT_TRUE(options.pipeline.odometry.dead_reckoning.stride_interpolation.enabled);
  try {
    ValidateEntityOptions(options);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("pipeline.stride_hold_s"), std::string::npos) << error.what();
  }
}

// Installed daemons find share/pena/dds beside their bin/ (tests/install checks it is installed);
// a build-tree binary falls back to deploy/dds of its source tree; PENA_DDS_DIR overrides both.
TEST(DdsProfiles, DefaultDirIsTheEnvironmentsElseTheSourceTrees) {
  ::unsetenv("PENA_DDS_DIR");
  const std::filesystem::path source = std::filesystem::path(PENA_SOURCE_DIR) / "deploy" / "dds";
  EXPECT_EQ(DefaultDdsDir(), source);
  ::setenv("PENA_DDS_DIR", "/opt/pena/share/pena/dds", 1);
  EXPECT_EQ(DefaultDdsDir(), "/opt/pena/share/pena/dds");
  const std::vector<std::filesystem::path> files = DefaultProfilesFiles();
  ASSERT_EQ(files.size(), 2u);
  EXPECT_EQ(files[0], "/opt/pena/share/pena/dds/pena-loopback.xml");
  EXPECT_EQ(files[1], "/opt/pena/share/pena/dds/pena-qos.xml");
  ::setenv("PENA_DDS_DIR", "", 1);  // empty: as if unset
  EXPECT_EQ(DefaultDdsDir(), source);
  ::unsetenv("PENA_DDS_DIR");
}

}  // namespace
}  // namespace pena::services
