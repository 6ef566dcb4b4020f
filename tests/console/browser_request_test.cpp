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
        Hostile{R"({"type":"retract"})", "retract.id: missing"}));

}  // namespace
}  // namespace pena::services
