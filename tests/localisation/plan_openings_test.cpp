// Walls the plan draws across real openings are cut where accepted rounds see far through them.
#include "pena/localisation/plan_openings.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <vector>

#include "pena/localisation/plan_adaptation.hpp"

namespace pena::localisation {
namespace {

using geometry::Segment2;

Segment2 Wall(double x1, double y1, double x2, double y2) { return {{x1, y1}, {x2, y2}}; }

// The returns of a 360-beam scan (1 deg apart) at `origin` against `walls`, nearest hits only.
scan_matching::Points2 Scan(const std::vector<Segment2>& walls, const Eigen::Vector2d& origin) {
  scan_matching::Points2 points;
  for (int b = 0; b < 360; ++b) {
    const double angle = b * std::numbers::pi / 180.0;
    const Eigen::Vector2d d(std::cos(angle), std::sin(angle));
    double best = std::numeric_limits<double>::infinity();
    for (const Segment2& w : walls) {
      const Eigen::Vector2d e = w.end_m - w.start_m;
      const Eigen::Vector2d to = w.start_m - origin;
      const double den = d.x() * e.y() - d.y() * e.x();
      if (std::abs(den) < 1e-12) continue;
      const double t = (to.x() * e.y() - to.y() * e.x()) / den;
      const double u = (to.x() * d.y() - to.y() * d.x()) / den;
      if (t > 0.0 && u >= 0.0 && u <= 1.0) best = std::min(best, t);
    }
    if (std::isfinite(best)) points.push_back(origin + best * d);
  }
  return points;
}

// A corridor (y 0-2, x 0-10) with a 2 m passage south at x 4-6, 6 m deep.
std::vector<Segment2> CorridorWithPassage() {
  return {Wall(0, 2, 10, 2), Wall(0, 0, 4, 0), Wall(6, 0, 10, 0), Wall(0, 0, 0, 2), Wall(10, 0, 10, 2),
          Wall(4, 0, 4, -6), Wall(6, 0, 6, -6), Wall(4, -6, 6, -6)};
}

// The same corridor with its south wall drawn straight across the passage (the plan's index 1).
std::vector<Segment2> PlanDrawnShut() {
  return {Wall(0, 2, 10, 2), Wall(0, 0, 10, 0), Wall(0, 0, 0, 2), Wall(10, 0, 10, 2)};
}

// Rounds from the corridor's middle line at x = 3, 4, ... (cycling), poses right.
std::vector<PlanOpening> Walk(PlanOpenings& openings, const std::vector<Segment2>& truth,
                              std::vector<Segment2>& plan, int rounds, double y_m = 1.0) {
  std::vector<PlanOpening> cuts;
  for (int i = 0; i < rounds; ++i) {
    const Eigen::Vector2d origin(3.0 + i % 5, y_m);
    for (const PlanOpening& cut : openings.Observe(Scan(truth, origin), origin, plan)) cuts.push_back(cut);
  }
  return cuts;
}

// Whether the plan's line y = 0 has a wall at x.
bool WallAt(const std::vector<Segment2>& plan, double x) {
  for (const Segment2& s : plan) {
    if (std::abs(s.start_m.y()) < 1e-9 && std::abs(s.end_m.y()) < 1e-9 &&
        std::min(s.start_m.x(), s.end_m.x()) <= x && x <= std::max(s.start_m.x(), s.end_m.x())) {
      return true;
    }
  }
  return false;
}

TEST(PlanOpenings, AWallDrawnAcrossAPassageIsCutWhereTheRoundsSeeThrough) {
  std::vector<Segment2> plan = PlanDrawnShut();
  PlanOpenings openings({});
  // From each place in the corridor beams end 1 m behind the wall's line through about half of
  // the opening only: the stretches are cut as they collect their rounds, the parts keep theirs.
  const std::vector<PlanOpening> cuts = Walk(openings, CorridorWithPassage(), plan, 15);
  ASSERT_GE(cuts.size(), 1u);
  EXPECT_EQ(cuts[0].index, 1);
  EXPECT_GE(cuts[0].rounds, 3);
  EXPECT_EQ(cuts[0].added_index, 4);
  EXPECT_NEAR(plan[1].end_m.x(), cuts[0].from_m, 1e-9);
  EXPECT_NEAR(cuts[0].stretch.start_m.x(), cuts[0].from_m, 1e-9);  // on the map: the wall starts at x 0
  EXPECT_NEAR(cuts[0].stretch.end_m.x(), cuts[0].to_m, 1e-9);
  EXPECT_NEAR(cuts[0].stretch.end_m.y(), 0.0, 1e-9);
  EXPECT_EQ(openings.openings().size(), cuts.size());
  // The opening is x 4-6; beams crossing near the jambs end less than 1 m behind the line.
  for (const double x : {4.4, 4.8, 5.2, 5.6}) EXPECT_FALSE(WallAt(plan, x)) << "x " << x;
  for (const double x : {0.5, 2.0, 3.9, 6.1, 8.0, 9.5}) EXPECT_TRUE(WallAt(plan, x)) << "x " << x;
}

TEST(PlanOpenings, NotBeforeMinRounds) {
  std::vector<Segment2> plan = PlanDrawnShut();
  PlanOpenings openings({});
  EXPECT_TRUE(Walk(openings, CorridorWithPassage(), plan, 2).empty());  // each stretch seen at most twice
  EXPECT_EQ(plan.size(), 4u);
}

TEST(PlanOpenings, AWallDrawnALittleInFrontOfTheRealOneIsNotCut) {
  // The plan's south wall 0.4 m north of the real one: every beam to the real wall crosses it,
  // grazing ones end far along the beam, but all of them only 0.4 m behind its line.
  std::vector<Segment2> truth{Wall(0, 2, 10, 2), Wall(0, 0, 10, 0), Wall(0, 0, 0, 2), Wall(10, 0, 10, 2)};
  std::vector<Segment2> plan{Wall(0, 2, 10, 2), Wall(0, 0.4, 10, 0.4), Wall(0, 0, 0, 2), Wall(10, 0, 10, 2)};
  PlanOpenings openings({});
  EXPECT_TRUE(Walk(openings, truth, plan, 20, 1.2).empty());
  EXPECT_EQ(plan.size(), 4u);
}

TEST(PlanOpenings, ARealWallSeenThroughNowAndThenStays) {
  // The passage is closed in 2 of every 5 rounds (a door): seen as wall too often to be cut.
  std::vector<Segment2> plan = PlanDrawnShut();
  std::vector<Segment2> closed = CorridorWithPassage();
  closed.push_back(Wall(4, 0, 6, 0));
  PlanOpenings openings({});
  for (int i = 0; i < 20; ++i) {
    const Eigen::Vector2d origin(3.0 + i % 5, 1.0);
    openings.Observe(Scan(i % 5 < 2 ? closed : CorridorWithPassage(), origin), origin, plan);
  }
  EXPECT_TRUE(openings.openings().empty());
}

TEST(PlanOpenings, PlanAdaptationCutsAndCountsTheNewPart) {
  PlanAdaptation adaptation({}, PlanDrawnShut());
  bool changed = false;
  for (int i = 0; i < 10; ++i) {
    const Eigen::Vector2d origin(3.0 + i % 5, 1.0);
    changed = adaptation.Observe(Scan(CorridorWithPassage(), origin), {origin, Eigen::Vector3d::Zero(), 5.0}) || changed;
  }
  EXPECT_TRUE(changed);
  ASSERT_FALSE(adaptation.openings().empty());
  std::size_t added = 0;
  for (const PlanOpening& cut : adaptation.openings()) added += cut.added_index >= 0 ? 1 : 0;
  EXPECT_EQ(adaptation.plan().size(), 4u + added);
  EXPECT_FALSE(WallAt(adaptation.plan(), 5.0));
  PlanAdaptationOptions off;
  off.openings.enabled = false;
  PlanAdaptation kept(off, PlanDrawnShut());
  for (int i = 0; i < 10; ++i) {
    const Eigen::Vector2d origin(3.0 + i % 5, 1.0);
    kept.Observe(Scan(CorridorWithPassage(), origin), {origin, Eigen::Vector3d::Zero(), 5.0});
  }
  EXPECT_TRUE(kept.openings().empty());
  EXPECT_EQ(kept.plan().size(), 4u);
}

TEST(PlanOpenings, RejectsBadOptionsNamingTheField) {
  PlanOpeningsOptions options;
  options.bin_m = 0.0;
  try {
    PlanOpenings openings(options);
    FAIL() << "accepted bin_m = 0";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("plan_adaptation.openings.bin_m"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace pena::localisation
