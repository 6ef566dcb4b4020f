#include "console_picture.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace pena::services {
namespace {

constexpr std::int64_t kSecond = 1'000'000'000;

PoseUpdate Pose(const std::string& id, std::uint64_t seq, double x, double y,
                std::int64_t heard_ns) {
  PoseUpdate p;
  p.entity_id = id;
  p.seq = seq;
  p.stamp_s = static_cast<double>(seq);
  p.world_from_body = {x, y, 0.0};
  p.covariance[0] = 0.04;
  p.covariance[4] = 0.01;
  p.status = "matched";
  p.heard_ns = heard_ns;
  return p;
}

line_map::LineSegment Wall(std::int64_t id, double x, const std::string& source) {
  line_map::LineSegment s;
  s.id = id;
  s.segment.start_m = {x, 0.0};
  s.segment.end_m = {x, 4.0};
  s.provenance = {source};
  return s;
}

TEST(ConsolePicture, SnapshotHoldsWhatTheDeltasSent) {
  ConsolePicture picture;
  picture.OnPose(Pose("ff1", 1, 0.0, 0.0, kSecond));
  line_map::MapSnapshot map;
  map.version = 3;
  map.next_id = 3;
  map.segments = {Wall(1, 0.0, "plan:4"), Wall(2, 2.0, "ff1:7")};
  picture.OnMapSnapshot(map);
  const auto first = picture.TakeDelta(kSecond);
  ASSERT_TRUE(first);
  EXPECT_EQ((*first)["map"]["upsert"].size(), 2u);
  EXPECT_EQ((*first)["entities"][0]["trail_add"].size(), 1u);

  picture.OnPose(Pose("ff1", 2, 1.0, 0.0, kSecond));
  const auto second = picture.TakeDelta(kSecond);
  ASSERT_TRUE(second);
  EXPECT_FALSE(second->contains("map"));  // the map did not change: not sent again
  ASSERT_EQ((*second)["entities"][0]["trail_add"].size(), 1u);  // only the new trail point
  EXPECT_DOUBLE_EQ((*second)["entities"][0]["trail_add"][0][1].get<double>(), 1.0);
  EXPECT_FALSE(picture.TakeDelta(kSecond));  // nothing new

  const nlohmann::json snapshot = picture.Snapshot(kSecond);
  EXPECT_EQ(snapshot["entities"][0]["trail"].size(), 2u);
  ASSERT_EQ(snapshot["map"]["segments"].size(), 2u);
  EXPECT_EQ(snapshot["map"]["segments"][0][5], 0);  // plan only
  EXPECT_EQ(snapshot["map"]["segments"][1][5], 1);  // observed
}

TEST(ConsolePicture, WallsCarryWhoSawThemAndAChangeOfSupportIsSentAgain) {
  ConsolePicture picture;
  line_map::MapSnapshot map;
  map.version = 1;
  map.next_id = 3;
  line_map::LineSegment lone = Wall(1, 0.0, "ff2:3");
  lone.seen_by_entities = 1;
  lone.error_sd_m = 0.23;
  line_map::LineSegment both = Wall(2, 2.0, "ff1:7");
  both.provenance = {"ff1:7", "ff3:2", "ff1:9", "plan:4"};
  both.seen_by_entities = 3;  // one entity's copy was withheld: counted, not in the provenance
  both.error_sd_m = 0.05;
  map.segments = {lone, both};
  picture.OnMapSnapshot(map);
  ASSERT_TRUE(picture.TakeDelta(kSecond));
  const nlohmann::json shown = picture.Snapshot(kSecond)["map"]["segments"];
  ASSERT_EQ(shown.size(), 2u);
  EXPECT_EQ(shown[0][6], 1);
  EXPECT_DOUBLE_EQ(shown[0][7].get<double>(), 0.23);
  EXPECT_EQ(shown[0][8], nlohmann::json::array({"ff2"}));
  EXPECT_EQ(shown[1][6], 3);
  EXPECT_EQ(shown[1][8], nlohmann::json::array({"ff1", "ff3"}));

  // A second entity confirms the lone wall: same geometry, new support, sent again.
  line_map::MapDelta confirmed;
  confirmed.from_version = 1;
  confirmed.to_version = 2;
  confirmed.changed = {lone};
  confirmed.changed[0].provenance = {"ff1:11", "ff2:3"};
  confirmed.changed[0].seen_by_entities = 2;
  confirmed.changed[0].error_sd_m = 0.08;
  picture.OnMapDelta(confirmed);
  const auto delta = picture.TakeDelta(kSecond);
  ASSERT_TRUE(delta);
  ASSERT_EQ((*delta)["map"]["upsert"].size(), 1u);
  EXPECT_EQ((*delta)["map"]["upsert"][0][6], 2);
  EXPECT_EQ((*delta)["map"]["upsert"][0][8], nlohmann::json::array({"ff1", "ff2"}));
}

TEST(ConsolePicture, EarlyDeltaWaitsForItsPredecessor) {
  ConsolePicture picture;
  line_map::MapDelta second;
  second.from_version = 1;
  second.to_version = 2;
  second.added = {Wall(2, 2.0, "ff1:1")};
  picture.OnMapDelta(second);
  EXPECT_EQ(picture.map_version(), 0u);
  line_map::MapDelta first;
  first.from_version = 0;
  first.to_version = 1;
  first.added = {Wall(1, 0.0, "ff1:0")};
  picture.OnMapDelta(first);
  EXPECT_EQ(picture.map_version(), 2u);
}

TEST(ConsolePicture, EntityTurnsStaleWithTimeAlone) {
  ConsolePicture picture(PictureOptions{3.0, 100, 0.05});
  picture.OnPose(Pose("r1", 1, 0.0, 0.0, kSecond));
  EXPECT_EQ((*picture.TakeDelta(kSecond))["entities"][0]["state"], "tracking");
  EXPECT_FALSE(picture.TakeDelta(2 * kSecond));
  const auto later = picture.TakeDelta(5 * kSecond);
  ASSERT_TRUE(later);
  EXPECT_EQ((*later)["entities"][0]["state"], "stale");
}

TEST(ConsolePicture, RotationMovesTheTrailFromItsStampOn) {
  ConsolePicture picture;
  for (std::uint64_t i = 1; i <= 4; ++i) {
    picture.OnPose(Pose("ff2", i, static_cast<double>(i), 0.0, kSecond));
  }
  picture.TakeDelta(kSecond);
  CorrectionRecord rotate;
  rotate.correction_id = "op/1-1";
  rotate.operator_id = "op";
  rotate.kind = "rotate";
  rotate.entity_id = "ff2";
  rotate.stamp_s = 2.0;
  // About (2, 0): the direction +x becomes +y (90 degrees).
  rotate.geometry = localisation::RotationCorrection{2.0, {2.0, 0.0}, {3.0, 0.0}, {2.0, 1.0}};
  picture.OnCorrection(rotate);
  picture.OnCorrection(rotate);  // the same durable sample again: listed once
  const auto delta = picture.TakeDelta(kSecond);
  ASSERT_TRUE(delta);
  const nlohmann::json& trail = (*delta)["entities"][0]["trail"];  // whole: sent points moved
  ASSERT_EQ(trail.size(), 4u);
  EXPECT_NEAR(trail[0][1].get<double>(), 1.0, 1e-9);  // before the stamp: unchanged
  EXPECT_NEAR(trail[3][1].get<double>(), 2.0, 1e-9);  // (4, 0) -> (2, 2)
  EXPECT_NEAR(trail[3][2].get<double>(), 2.0, 1e-9);
  ASSERT_EQ((*delta)["corrections"].size(), 1u);
  EXPECT_NEAR((*delta)["corrections"][0]["transform"][2].get<double>(), M_PI / 2, 1e-9);
}

// pena-fusion's answer updates the listed correction; a refusal takes the trail's move back.
TEST(ConsolePicture, FusionAnswerUpdatesTheListAndARefusalTakesTheMoveBack) {
  ConsolePicture picture;
  for (std::uint64_t i = 1; i <= 4; ++i) {
    picture.OnPose(Pose("ff2", i, static_cast<double>(i), 0.0, kSecond));
  }
  CorrectionRecord rotate;
  rotate.correction_id = "op/7";
  rotate.operator_id = "op";
  rotate.kind = "rotate";
  rotate.entity_id = "ff2";
  rotate.stamp_s = 2.0;
  rotate.geometry = localisation::RotationCorrection{2.0, {2.0, 0.0}, {3.0, 0.0}, {2.0, 1.0}};
  picture.OnCorrection(rotate);
  auto delta = picture.TakeDelta(kSecond);
  ASSERT_TRUE(delta);
  EXPECT_EQ((*delta)["corrections"][0]["state"], "sent");
  CorrectionRecord refused = rotate;
  refused.refusal = "no pose of ff2 heard yet";
  picture.OnCorrection(refused);
  picture.OnCorrection(refused);  // the answer again: nothing more
  delta = picture.TakeDelta(kSecond);
  ASSERT_TRUE(delta);
  ASSERT_EQ((*delta)["corrections"].size(), 1u);
  EXPECT_EQ((*delta)["corrections"][0]["state"], "refused");
  EXPECT_EQ((*delta)["corrections"][0]["refusal"], "no pose of ff2 heard yet");
  const nlohmann::json& trail = (*delta)["entities"][0]["trail"];
  ASSERT_EQ(trail.size(), 4u);
  EXPECT_NEAR(trail[3][1].get<double>(), 4.0, 1e-9);  // back where the entity put it
  EXPECT_NEAR(trail[3][2].get<double>(), 0.0, 1e-9);
  EXPECT_EQ(picture.Snapshot(kSecond)["corrections"][0]["state"], "refused");
}

// An undo takes the last correction in force back: the trail returns, the list says so.
TEST(ConsolePicture, UndoTakesTheLastCorrectionBack) {
  ConsolePicture picture;
  for (std::uint64_t i = 1; i <= 4; ++i) {
    picture.OnPose(Pose("ff1", i, static_cast<double>(i), 0.0, kSecond));
  }
  CorrectionRecord shift;
  shift.correction_id = "op/1";
  shift.operator_id = "op";
  shift.kind = "translate";
  shift.entity_id = "ff1";
  shift.stamp_s = 3.0;
  shift.geometry = localisation::TranslationCorrection{3.0, {3.0, 0.0}, {3.0, 1.0}};
  picture.OnCorrection(shift);
  EXPECT_EQ(picture.LastInForce("ff1"), picture.FindCorrection("op/1"));
  picture.TakeDelta(kSecond);
  CorrectionRecord undo;
  undo.correction_id = "op/2";
  undo.operator_id = "op";
  undo.kind = "undo";
  undo.entity_id = "ff1";
  undo.stamp_s = 3.0;
  undo.undoes = "op/1";
  picture.OnCorrection(undo);
  EXPECT_EQ(picture.LastInForce("ff1"), nullptr);
  const auto delta = picture.TakeDelta(kSecond);
  ASSERT_TRUE(delta);
  const nlohmann::json& trail = (*delta)["entities"][0]["trail"];
  ASSERT_EQ(trail.size(), 4u);
  EXPECT_NEAR(trail[3][2].get<double>(), 0.0, 1e-9);  // (4, 1) back to (4, 0)
  bool undone_listed = false;
  for (const auto& c : (*delta)["corrections"]) {
    if (c["id"] == "op/1") undone_listed = c["undone"].get<bool>();
  }
  EXPECT_TRUE(undone_listed);
}

// A gateway's report on the radio link reaches the browsers.
TEST(ConsolePicture, LinkHealthIsShown) {
  ConsolePicture picture;
  LinkRecord link;
  link.gateway_id = "post";
  link.peer_alive = true;
  link.peer_heard_age_s = 0.4;
  link.budget_bit_s = 8640.0;
  link.heard_ns = kSecond;
  picture.OnLinkHealth(link);
  const auto delta = picture.TakeDelta(2 * kSecond);
  ASSERT_TRUE(delta);
  ASSERT_EQ((*delta)["links"].size(), 1u);
  EXPECT_EQ((*delta)["links"][0]["id"], "post");
  EXPECT_EQ((*delta)["links"][0]["peer_alive"], true);
  EXPECT_NEAR((*delta)["links"][0]["report_age_s"].get<double>(), 1.0, 1e-9);
  EXPECT_FALSE(picture.TakeDelta(2 * kSecond));  // nothing new
  EXPECT_EQ(picture.Snapshot(2 * kSecond)["links"].size(), 1u);
}

TEST(ConsolePicture, NearestTrailPoseGivesTheMomentOfTheOrigin) {
  ConsolePicture picture;
  for (std::uint64_t i = 1; i <= 5; ++i) {
    picture.OnPose(Pose("ff3", i, static_cast<double>(i), 0.0, kSecond));
  }
  const auto nearest = picture.NearestTrailPose("ff3", {3.1, 0.4});
  ASSERT_TRUE(nearest);
  EXPECT_DOUBLE_EQ(nearest->stamp_s, 3.0);
  EXPECT_NEAR(nearest->distance_m, std::hypot(0.1, 0.4), 1e-12);
  EXPECT_FALSE(picture.NearestTrailPose("nobody", {0.0, 0.0}));
}

}  // namespace
}  // namespace pena::services
