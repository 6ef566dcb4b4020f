#include "browser_request.hpp"

#include <gtest/gtest.h>

#include <string>

namespace pena::services {
namespace {

TEST(BrowserRequest, ParsesAThreePointRotation) {
  const BrowserRequest r = ParseBrowserRequest(R"({"type":"rotate","req":7,"entity":"ff1",)"
                                               R"("origin":[1,2],"wrong":[3.5,2],"correct":[1,4.5]})");
  ASSERT_TRUE(r.ok()) << r.error();
  EXPECT_EQ(r.req, 7);
  const auto& rotate = std::get<RotateRequest>(r.command());
  EXPECT_EQ(rotate.entity_id, "ff1");
  EXPECT_DOUBLE_EQ(rotate.origin_m.y(), 2.0);
  EXPECT_DOUBLE_EQ(rotate.wrong_m.x(), 3.5);
  EXPECT_DOUBLE_EQ(rotate.correct_m.y(), 4.5);
}

TEST(BrowserRequest, ParsesAMarkAndItsRetraction) {
  const BrowserRequest mark = ParseBrowserRequest(
      R"({"type":"annotate","kind":"victim_found","position":[4.5,-2],"text":"two people"})");
  ASSERT_TRUE(mark.ok()) << mark.error();
  const auto& a = std::get<AnnotateRequest>(mark.command());
  EXPECT_EQ(a.kind, "victim_found");
  EXPECT_DOUBLE_EQ(a.position_m.x(), 4.5);
  EXPECT_EQ(a.text, "two people");
  EXPECT_DOUBLE_EQ(a.radius_m, 0.0);
  const BrowserRequest retract = ParseBrowserRequest(R"({"type":"retract","id":"op/1-3"})");
  ASSERT_TRUE(retract.ok()) << retract.error();
  EXPECT_EQ(std::get<RetractRequest>(retract.command()).annotation_id, "op/1-3");
}

TEST(BrowserRequest, ParsesTranslationUndoAndMoveOfAMark) {
  const BrowserRequest t = ParseBrowserRequest(
      R"({"type":"translate","entity":"ff2","point":[1,2],"correct":[1.5,-2]})");
  ASSERT_TRUE(t.ok()) << t.error();
  const auto& translate = std::get<TranslateRequest>(t.command());
  EXPECT_EQ(translate.entity_id, "ff2");
  EXPECT_DOUBLE_EQ(translate.point_m.y(), 2.0);
  EXPECT_DOUBLE_EQ(translate.correct_m.x(), 1.5);
  const BrowserRequest u = ParseBrowserRequest(R"({"type":"undo","id":"op/17"})");
  ASSERT_TRUE(u.ok()) << u.error();
  EXPECT_EQ(std::get<UndoRequest>(u.command()).correction_id, "op/17");
  const BrowserRequest m = ParseBrowserRequest(R"({"type":"move_mark","id":"op/3","position":[7,8]})");
  ASSERT_TRUE(m.ok()) << m.error();
  EXPECT_EQ(std::get<MoveMarkRequest>(m.command()).annotation_id, "op/3");
  EXPECT_DOUBLE_EQ(std::get<MoveMarkRequest>(m.command()).position_m.y(), 8.0);
}

// A dangerous area as a polygon: its centroid is the position, its farthest corner the radius.
TEST(BrowserRequest, ParsesADangerousAreaPolygon) {
  const BrowserRequest r = ParseBrowserRequest(
      R"({"type":"annotate","kind":"dangerous_area","outline":[[0,0],[4,0],[4,3],[0,3]],"text":"gas"})");
  ASSERT_TRUE(r.ok()) << r.error();
  const auto& a = std::get<AnnotateRequest>(r.command());
  ASSERT_EQ(a.outline_m.size(), 4u);
  EXPECT_DOUBLE_EQ(a.position_m.x(), 2.0);
  EXPECT_DOUBLE_EQ(a.position_m.y(), 1.5);
  EXPECT_DOUBLE_EQ(a.radius_m, 2.5);
}

// Each hostile message is refused with an error that names what was wrong.
struct Hostile {
  std::string text;
  std::string error_mentions;
};

class RefusesHostileInput : public ::testing::TestWithParam<Hostile> {};

TEST_P(RefusesHostileInput, WithAnErrorNamingTheField) {
  const BrowserRequest r = ParseBrowserRequest(GetParam().text);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().find(GetParam().error_mentions), std::string::npos) << r.error();
}

INSTANTIATE_TEST_SUITE_P(
    BrowserRequest, RefusesHostileInput,
    ::testing::Values(
        Hostile{"not json", "not valid JSON"}, Hostile{"[1,2]", "JSON object"},
        Hostile{R"({"req":1})", "message.type: missing"},
        Hostile{R"({"type":5})", "message.type: not a string"},
        Hostile{R"({"type":"format_disk"})", "unknown type"},
        Hostile{R"({"type":"ping","req":"x"})", "message.req"},
        Hostile{R"({"type":"rotate","entity":"ff1","origin":[1,2],"wrong":[3,4]})",
                "rotate.correct: missing"},
        Hostile{R"({"type":"rotate","entity":7,"origin":[1,2],"wrong":[3,4],"correct":[5,6]})",
                "rotate.entity: not a string"},
        Hostile{R"({"type":"rotate","entity":"<script>","origin":[1,2],"wrong":[3,4],"correct":[5,6]})",
                "rotate.entity: only"},
        Hostile{R"({"type":"rotate","entity":"ff1","origin":[1,"NaN"],"wrong":[3,4],"correct":[5,6]})",
                "rotate.origin[1]: not a number"},
        Hostile{R"({"type":"rotate","entity":"ff1","origin":[1,2],"wrong":[1e999,4],"correct":[5,6]})",
                "not valid JSON"},  // a number beyond double: the parser refuses it
        Hostile{R"({"type":"rotate","entity":"ff1","origin":[1,2],"wrong":[3,4],"correct":[5,6,7]})",
                "rotate.correct: must be an array"},
        Hostile{R"({"type":"rotate","entity":"ff1","origin":[1,2],"wrong":[3,4],"correct":[5,2e5]})",
                "within"},
        Hostile{"{\"type\":\"ping\",\"pad\":\"" + std::string(5000, 'x') + "\"}",
                "larger than 4096"},
        Hostile{R"({"type":"annotate","kind":"bomb","position":[1,2]})", "annotate.kind: unknown"},
        Hostile{R"({"type":"annotate","kind":"exit","position":[1,2],"radius_m":-1})",
                "annotate.radius_m"},
        Hostile{R"({"type":"annotate","kind":"exit","position":[1,2],"text":7})",
                "annotate.text: not a string"},
        Hostile{"{\"type\":\"annotate\",\"kind\":\"exit\",\"position\":[1,2],\"text\":\"" +
                    std::string(300, 'y') + "\"}",
                "annotate.text: at most 255"},
        Hostile{R"({"type":"retract"})", "retract.id: missing"},
        Hostile{R"({"type":"translate","entity":"ff1","point":[1,2]})", "translate.correct: missing"},
        Hostile{R"({"type":"translate","entity":"ff1","point":[1,2],"correct":[null,2]})",
                "translate.correct[0]: not a number"},
        Hostile{R"({"type":"undo","id":5})", "undo.id: not a string"},
        Hostile{R"({"type":"move_mark","id":"op/1","position":"here"})", "move_mark.position"},
        Hostile{R"({"type":"annotate","kind":"dangerous_area","outline":[[0,0],[1,1]]})",
                "annotate.outline: must be an array of 3"},
        Hostile{R"({"type":"annotate","kind":"dangerous_area","outline":[[0,0],[1,1],[2,"x"]]})",
                "annotate.outline[2][1]: not a number"},
        Hostile{R"({"type":"annotate","kind":"exit","outline":[[0,0],[1,1],[2,0]]})",
                "only a dangerous_area"},
        Hostile{"{\"type\":\"annotate\",\"kind\":\"dangerous_area\",\"outline\":[" +
                    [] {
                      std::string points;
                      for (int i = 0; i < 65; ++i) points += std::string(i ? "," : "") + "[1,2]";
                      return points;
                    }() + "]}",
                "annotate.outline: must be an array of 3 to 64"}));

}  // namespace
}  // namespace pena::services
