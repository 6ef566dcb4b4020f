// Round trips of the gateway's encodings: map packing of a team's real deltas, items, frames.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "pena/gateway/frame.hpp"
#include "pena/gateway/link_codec.hpp"
#include "pena/gateway/synthetic_team.hpp"
#include "pena/line_map/map_packing.hpp"

namespace pena::gateway {
namespace {

using line_map::PackDelta;
using line_map::PackSnapshot;
using line_map::UnpackDelta;
using line_map::UnpackSnapshot;

// Real deltas: a synthetic team's LineMaps integrate and merge walls.
std::vector<line_map::MapDelta> TeamDeltas(double duration_s, const std::string& only = "") {
  SyntheticTeamOptions options;
  options.alarm_period_s = 0.0;
  SyntheticTeam team(options);
  std::vector<line_map::MapDelta> deltas;
  for (DomainItem& item : team.Advance(duration_s)) {
    auto* change = std::get_if<MapChange>(&item);
    if (change != nullptr && (only.empty() || change->map_id == only)) {
      deltas.push_back(std::get<line_map::MapDelta>(change->change));
    }
  }
  return deltas;
}

TEST(MapPacking, DeltasAndSnapshotsRoundTripExactly) {
  const std::vector<line_map::MapDelta> deltas = TeamDeltas(120.0);
  ASSERT_GT(deltas.size(), 100U);
  std::size_t changed = 0;
  for (const line_map::MapDelta& delta : deltas) {
    std::string error;
    std::optional<line_map::MapDelta> back = UnpackDelta(PackDelta(delta), &error);
    ASSERT_TRUE(back) << error;
    ASSERT_EQ(back->added.size(), delta.added.size());
    ASSERT_EQ(back->changed.size(), delta.changed.size());
    for (std::size_t i = 0; i < delta.added.size(); ++i) {
      EXPECT_TRUE(line_map::SameSegment(back->added[i], delta.added[i]));
    }
    for (std::size_t i = 0; i < delta.changed.size(); ++i) {
      EXPECT_TRUE(line_map::SameSegment(back->changed[i], delta.changed[i]));
    }
    EXPECT_EQ(back->removed, delta.removed);
    changed += delta.changed.size() + delta.removed.size();
  }
  EXPECT_GT(changed, 0U) << "the team's maps should merge revisited walls";
  line_map::LineMap map;
  for (const line_map::MapDelta& delta : TeamDeltas(120.0, "ff1")) {
    ASSERT_TRUE(map.Apply(delta).ok());
  }
  ASSERT_GT(map.size(), 10U);
  std::string error;
  std::optional<line_map::MapSnapshot> snapshot = UnpackSnapshot(PackSnapshot(map.Snapshot()), &error);
  ASSERT_TRUE(snapshot) << error;
  snapshot->version = map.version();
  EXPECT_TRUE(line_map::SameMap(*snapshot, map.Snapshot()));
  EXPECT_EQ(snapshot->next_id, map.Snapshot().next_id);
}

TEST(MapPacking, RejectsEveryTruncation) {
  const std::vector<line_map::MapDelta> deltas = TeamDeltas(20.0);
  ASSERT_FALSE(deltas.empty());
  const std::string packed = PackDelta(deltas.front());
  for (std::size_t size = 0; size < packed.size(); ++size) {
    std::string error;
    EXPECT_FALSE(UnpackDelta(packed.substr(0, size), &error)) << "size " << size;
    EXPECT_FALSE(error.empty());
  }
}

TEST(MapPacking, RejectsEverySnapshotTruncationAndTrailingBytes) {
  line_map::LineMap map;
  for (const line_map::MapDelta& delta : TeamDeltas(60.0, "ff1")) ASSERT_TRUE(map.Apply(delta).ok());
  const std::string packed = PackSnapshot(map.Snapshot());
  for (std::size_t size = 0; size < packed.size(); ++size) {
    std::string error;
    EXPECT_FALSE(UnpackSnapshot(packed.substr(0, size), &error)) << "size " << size;
    EXPECT_FALSE(error.empty());
  }
  std::string error;
  EXPECT_FALSE(UnpackSnapshot(packed + '\0', &error));
  EXPECT_NE(error.find("trailing"), std::string::npos) << error;
}

TEST(LinkCodec, PoseRoundTripsWithinQuanta) {
  const PoseUpdate pose{"ff1", {12.345, -7.891, 3.0}, 100.1234};
  link::Item item;
  ToProto(pose, 100000, &item);
  std::string error;
  std::optional<DomainItem> back = FromProto(item, 100000, &error);
  ASSERT_TRUE(back) << error;
  const auto& got = std::get<PoseUpdate>(*back);
  EXPECT_EQ(got.entity, "ff1");
  EXPECT_NEAR(got.world_from_body.x_m, 12.345, 0.005);
  EXPECT_NEAR(got.world_from_body.y_m, -7.891, 0.005);
  EXPECT_NEAR(geometry::NormalizeAngle(got.world_from_body.theta_rad - 3.0), 0.0,
              0.05 * std::numbers::pi / 180.0);
  EXPECT_NEAR(got.stamp_s, 100.1234, 0.0005);
  EXPECT_EQ(got.position_sd_m, 0.0);  // unknown stays unknown, and costs no byte
  EXPECT_LE(item.ByteSizeLong(), 22U);
}

// The uncertainty crosses rounded up (the far side is never more certain), in a few bytes.
TEST(LinkCodec, PoseUncertaintyRoundsUpWithinAQuantum) {
  const PoseUpdate pose{"ff1", {12.345, -7.891, 3.0}, 100.1234, 0.1234, 0.0123};
  link::Item item;
  ToProto(pose, 100000, &item);
  std::string error;
  std::optional<DomainItem> back = FromProto(item, 100000, &error);
  ASSERT_TRUE(back) << error;
  const auto& got = std::get<PoseUpdate>(*back);
  EXPECT_GE(got.position_sd_m, 0.1234);
  EXPECT_LT(got.position_sd_m, 0.1234 + 0.01);
  EXPECT_GE(got.heading_sd_rad, 0.0123);
  EXPECT_LT(got.heading_sd_rad, 0.0123 + 0.1 * std::numbers::pi / 180.0);
  EXPECT_LE(item.ByteSizeLong(), 26U);
  // Not finite or negative: unknown.
  for (double bad : {std::numeric_limits<double>::quiet_NaN(), -1.0}) {
    link::Item odd;
    ToProto(PoseUpdate{"ff1", {}, 100.0, bad, bad}, 100000, &odd);
    back = FromProto(odd, 100000, &error);
    ASSERT_TRUE(back) << error;
    EXPECT_EQ(std::get<PoseUpdate>(*back).position_sd_m, 0.0);
    EXPECT_EQ(std::get<PoseUpdate>(*back).heading_sd_rad, 0.0);
  }
}

// A pose's mission time crosses at 1 ms, besides its wall-clock stamp.
TEST(LinkCodec, PoseCarriesItsMissionTime) {
  PoseUpdate pose{"ff1", {1.0, 2.0, 0.5}, 100.1234};
  pose.mission_stamp_s = 12.3456;
  link::Item item;
  ToProto(pose, 100000, &item);
  std::string error;
  std::optional<DomainItem> back = FromProto(item, 100000, &error);
  ASSERT_TRUE(back) << error;
  const auto& got = std::get<PoseUpdate>(*back);
  ASSERT_TRUE(got.mission_stamp_s);
  EXPECT_NEAR(*got.mission_stamp_s, 12.3456, 0.0005);
  EXPECT_NEAR(got.stamp_s, 100.1234, 0.0005);
  EXPECT_LE(item.ByteSizeLong(), 26U);
}

// An operator's correction crosses whole: points at 1 mm, its mission time at 1 us, who made it,
// and pena-fusion's answer.
TEST(LinkCodec, OperatorCorrectionRoundTripsWithItsMissionTimeAndOperator) {
  OperatorCorrection c;
  c.correction_id = "post/176500000000003";
  c.operator_id = "post";
  c.kind = 3;  // OPERATOR_ROTATE
  c.entity = "ff2";
  c.mission_stamp_s = 41.234567;
  c.origin_x_m = 1.2344;
  c.origin_y_m = -2.5;
  c.wrong_x_m = 4.0;
  c.wrong_y_m = 0.0011;
  c.correct_x_m = 3.5;
  c.correct_y_m = 1.75;
  c.console_seq = 3;
  c.refusal = "no pose of ff2 heard yet";
  c.stamp_s = 100.5;
  c.undoes_id = "post/176500000000001";
  link::Item item;
  ToProto(c, 100000, &item);
  std::string error;
  std::optional<DomainItem> back = FromProto(item, 100000, &error);
  ASSERT_TRUE(back) << error;
  const auto& got = std::get<OperatorCorrection>(*back);
  EXPECT_EQ(got.correction_id, c.correction_id);
  EXPECT_EQ(got.operator_id, "post");
  EXPECT_EQ(got.kind, 3U);
  EXPECT_EQ(got.entity, "ff2");
  EXPECT_NEAR(got.mission_stamp_s, 41.234567, 1e-6);
  EXPECT_NEAR(got.origin_x_m, 1.2344, 0.0005);
  EXPECT_NEAR(got.origin_y_m, -2.5, 0.0005);
  EXPECT_NEAR(got.wrong_y_m, 0.0011, 0.0005);
  EXPECT_NEAR(got.correct_x_m, 3.5, 0.0005);
  EXPECT_NEAR(got.correct_y_m, 1.75, 0.0005);
  EXPECT_EQ(got.console_seq, 3U);
  EXPECT_FALSE(got.applied);
  EXPECT_EQ(got.refusal, c.refusal);
  EXPECT_EQ(got.undoes_id, c.undoes_id);
  EXPECT_NEAR(got.stamp_s, 100.5, 0.0005);
  // A kind beyond OPERATOR_UNDO, or no id, is refused naming the field.
  item.mutable_operator_correction()->set_kind(6);
  EXPECT_FALSE(FromProto(item, 100000, &error));
  EXPECT_NE(error.find("kind"), std::string::npos) << error;
  item.mutable_operator_correction()->set_kind(3);
  item.mutable_operator_correction()->clear_correction_id();
  EXPECT_FALSE(FromProto(item, 100000, &error));
  EXPECT_NE(error.find("correction_id"), std::string::npos) << error;
}

// An area crosses with its outline and radius (1 cm), a mark with its mission time.
TEST(LinkCodec, AnnotationCarriesOutlineRadiusAndMissionTime) {
  Annotation a{true, "post", 7u << 4, 3.0, 4.0, 100.0, "smoke"};
  a.mission_stamp_s = 55.5;
  a.radius_m = 2.004;
  a.outline_m = {{1.0, 1.0}, {5.0, 1.0}, {5.0, 6.0}};
  link::Item item;
  ToProto(a, 100000, &item);
  std::string error;
  std::optional<DomainItem> back = FromProto(item, 100000, &error);
  ASSERT_TRUE(back) << error;
  const auto& got = std::get<Annotation>(*back);
  ASSERT_TRUE(got.mission_stamp_s);
  EXPECT_NEAR(*got.mission_stamp_s, 55.5, 0.0005);
  EXPECT_GE(got.radius_m, 2.004);
  EXPECT_LT(got.radius_m, 2.004 + 0.01);
  ASSERT_EQ(got.outline_m.size(), 3U);
  EXPECT_NEAR(got.outline_m[2].second, 6.0, 0.005);
  // An odd number of outline values is refused.
  item.mutable_annotation()->add_outline_cm(5);
  EXPECT_FALSE(FromProto(item, 100000, &error));
  EXPECT_NE(error.find("outline_cm"), std::string::npos) << error;
}

// A relayed operator correction keeps its operator: the entity applies it beyond its bound.
TEST(LinkCodec, CorrectionCarriesItsOperator) {
  const Correction c{"ff1", {1.0, 2.0, 0.1}, 7, 100.0, "post"};
  link::Item item;
  ToProto(c, 100000, &item);
  std::string error;
  std::optional<DomainItem> back = FromProto(item, 100000, &error);
  ASSERT_TRUE(back) << error;
  EXPECT_EQ(std::get<Correction>(*back).operator_id, "post");
}

TEST(LinkCodec, RejectsHeadingOutOfRangeAndEmptyBodies) {
  link::Item item;
  item.mutable_pose()->set_heading_ddeg(3600);
  std::string error;
  EXPECT_FALSE(FromProto(item, 0, &error));
  EXPECT_NE(error.find("heading"), std::string::npos);
  EXPECT_FALSE(FromProto(link::Item(), 0, &error));
}

TEST(Frame, RoundTripsPlainAndDeflated) {
  const std::string text(300, 'a');
  for (bool compress : {false, true}) {
    const std::string frame = EncodeFrame(text, compress);
    FrameResult result = DecodeFrame(frame);
    ASSERT_TRUE(result.ok()) << result.message;
    EXPECT_EQ(result.payload, text);
    EXPECT_EQ(result.consumed, frame.size());
    if (compress) {
      EXPECT_LT(frame.size(), text.size());
    }
  }
  // Incompressible payloads go plain: compression never makes a frame longer.
  const std::string random_bytes = "\x13\x9a\xf0\x01\x7e";
  EXPECT_EQ(EncodeFrame(random_bytes, true).size(), random_bytes.size() + 10U);
}

}  // namespace
}  // namespace pena::gateway
