// libpena <-> DDS conversions: exact round trips for what a LineMap produces, bounds named.
#include <gtest/gtest.h>

#include <stdexcept>

#include "from_dds.hpp"
#include "pena/line_map/line_map.hpp"
#include "to_dds.hpp"

namespace pena::services {
namespace {

line_map::LineSegment Wall(double x0, double y0, double x1, double y1) {
  line_map::LineSegment wall;
  wall.segment = {{x0, y0}, {x1, y1}};
  wall.support_cells = 40;
  wall.observations = 120;
  wall.rms_error_m = 0.0123;
  return wall;
}

TEST(Conversions, LineMapDeltasRoundTripExactly) {
  line_map::LineMap map;
  const line_map::MapDelta first =
      map.Integrate({Wall(0.0, 0.0, 5.0, 0.0), Wall(0.0, 3.0, 5.0, 3.0)}, "ff1");
  const line_map::MapDelta second = map.Integrate({Wall(4.9, 0.01, 9.0, 0.0)}, "ff1");
  line_map::LineMap receiver;
  for (const line_map::MapDelta& delta : {first, second}) {
    const pena_dds::LineMapDelta sample = ToDdsLineMapDelta(delta, "ff1", 12.5);
    EXPECT_EQ(sample.entity_id().to_string(), "ff1");
    EXPECT_EQ(sample.schema_version(), pena_dds::SCHEMA_VERSION);
    ASSERT_TRUE(receiver.Apply(FromDds(sample)).ok());
  }
  EXPECT_TRUE(line_map::SameMap(receiver.Snapshot(), map.Snapshot()));
  const line_map::MapSnapshot snapshot =
      FromDds(ToDdsGlobalMapSnapshot(map.Snapshot(), "global", 1.0));
  EXPECT_TRUE(line_map::SameMap(snapshot, map.Snapshot()));
  EXPECT_EQ(snapshot.next_id, map.Snapshot().next_id);
}

TEST(Conversions, GlobalWallSupportRoundTripsAndIsBounded) {
  line_map::LineMap map;
  map.Integrate({Wall(0.0, 0.0, 5.0, 0.0), Wall(0.0, 3.0, 5.0, 3.0)}, "global");
  line_map::MapSnapshot global = map.Snapshot();
  global.segments[0].seen_by_entities = 2;
  global.segments[0].error_sd_m = line_map::Quantise(0.14, line_map::kErrorSdQuantumM);
  global.segments[1].seen_by_entities = 1;
  global.segments[1].error_sd_m = line_map::kMaxErrorSdM;
  const pena_dds::GlobalMapSnapshot sample = ToDdsGlobalMapSnapshot(global, "global", 1.0);
  EXPECT_EQ(sample.segments()[0].seen_by_entities(), 2);
  EXPECT_EQ(sample.segments()[0].error_sd_cm(), 14);
  EXPECT_EQ(sample.segments()[1].error_sd_cm(), 65535);
  EXPECT_TRUE(line_map::SameMap(FromDds(sample), global));
  line_map::LineSegment crowded = global.segments[0];
  crowded.seen_by_entities = 70000;
  EXPECT_THROW(ToDds(crowded), std::invalid_argument);
  line_map::LineSegment vague = global.segments[0];
  vague.error_sd_m = 700.0;
  EXPECT_THROW(ToDds(vague), std::invalid_argument);
}

TEST(Conversions, TooLongIdsAndListsAreRefusedNamingTheField) {
  line_map::LineMap map;
  const line_map::MapDelta delta = map.Integrate({Wall(0.0, 0.0, 5.0, 0.0)}, "ff1");
  try {
    ToDdsLineMapDelta(delta, std::string(40, 'x'), 0.0);
    FAIL() << "no exception";
  } catch (const std::length_error& error) {
    EXPECT_NE(std::string(error.what()).find("entity_id"), std::string::npos);
  }
  line_map::MapDelta big = delta;
  big.added.assign(pena_dds::DELTA_MAX_SEGMENTS + 1, delta.added.front());
  EXPECT_THROW(ToDdsLineMapDelta(big, "ff1", 0.0), std::length_error);
  line_map::LineSegment unquantised = delta.added.front();
  unquantised.segment.start_m.x() = 0.0004;
  EXPECT_THROW(ToDds(unquantised), std::invalid_argument);
}

TEST(Conversions, OtherSchemaVersionsAreRejected) {
  line_map::LineMap map;
  pena_dds::LineMapDelta sample =
      ToDdsLineMapDelta(map.Integrate({Wall(0.0, 0.0, 5.0, 0.0)}, "ff1"), "ff1", 0.0);
  sample.schema_version(pena_dds::SCHEMA_VERSION + 1);
  EXPECT_THROW(FromDds(sample), std::invalid_argument);
}

TEST(Conversions, ReferenceScansKeepRangesToTheQuantum) {
  sensors::LaserScan scan;
  scan.stamp_s = 3.0;
  scan.geometry = {-1.0, 0.01, 30.0};
  scan.ranges_m = {1.234f, sensors::LaserScan::kNoReturn, 29.99f, 35.0f};
  pipeline::ScanStep step;
  step.world_from_body = {1.0, 2.0, 0.5};
  step.odometry.world_from_body = {1.0, 2.0, 0.5};
  const sensors::LaserScan back =
      FromDds(ToDdsReferenceScan(scan, step, "robot1", 7, 3, 0.01));
  ASSERT_EQ(back.ranges_m.size(), 4u);
  EXPECT_NEAR(back.ranges_m[0], 1.23, 1e-5);
  EXPECT_FALSE(back.IsReturn(1));
  EXPECT_NEAR(back.ranges_m[2], 29.99, 1e-4);
  EXPECT_FALSE(back.IsReturn(3));  // beyond max range: a no-return stays one
  EXPECT_DOUBLE_EQ(back.stamp_s, 3.0);
}

TEST(Conversions, CorrectionsRoundTrip) {
  pipeline::Correction correction;
  correction.kind = pipeline::Correction::Kind::kPose;
  correction.stamp_s = 17.25;
  correction.world_from_body = {3.0, -1.0, 0.25};
  correction.confidence = 0.75;
  const pipeline::Correction back = FromDds(ToDdsCorrection(correction, "ff2", 4, 9, 2));
  EXPECT_EQ(back.kind, pipeline::Correction::Kind::kPose);
  EXPECT_DOUBLE_EQ(back.stamp_s, 17.25);
  EXPECT_DOUBLE_EQ(back.world_from_body.theta_rad, 0.25);
  EXPECT_FLOAT_EQ(static_cast<float>(back.confidence), 0.75f);
}

}  // namespace
}  // namespace pena::services
