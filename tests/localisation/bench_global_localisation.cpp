// Global localisation on the simulated `office` mission (its acceptance figure): the firefighter's
// log is started at random scans whose true pose is in the mapped corridor (y 13-15 m,
// x 4.5-41.5 m), with no start pose, and run through the entity pipeline's plan stage (global_start) on the
// partial, partly wrong a priori plan until it anchors. Prints how many anchor within 0.3 m and
// 3 deg of the true pose at the anchoring scan, the median CPU time and walked distance until
// then, and for comparison how many of the first scans alone were right (best hypothesis of the
// first whole-plan search).
//   bench_global_localisation [POSES=100] [SIM_SEED=1] [PICK_SEED=1]
// Environment (diagnosis; the figures are unchanged without them): PENA_BENCH_TRACE=1 prints
// every keyframe's share of returning beams, its leader and the track at the true pose,
// PENA_BENCH_ONLY=3,17 runs only those of the picked starts, PENA_BENCH_SET=name=value,... sets
// tracker options, PENA_BENCH_FIRST_SCAN_ONLY=1 stops each start at its first scan (the first
// search and the odometry's starting heading).
// The headline runs each start until it anchors or the log ends (then the leader is the answer);
// beside it, the same starts cut at 30 m of walk (an unanchored start answered by the leader
// then). The count of starts the log leaves less than 1 m / 3 m of
// walk after is printed. The log goes in as `pena localise` takes it: the pipeline spreads a
// person's strides over the scans inside them (PENA_BENCH_SET=odometry.stride_interpolation.enabled=0: as logged).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <deque>
#include <numbers>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "pena/pipeline/entity_pipeline.hpp"
#include "pena/sim/scenario.hpp"
#include "pena/sim/simulator.hpp"

namespace {

using namespace pena;

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kWalkLimit_m = 30.0;

struct Errors {
  double position_m = 0.0, heading_deg = 0.0;
  bool ok() const { return position_m <= 0.3 && heading_deg <= 3.0; }
};

Errors Compare(const geometry::Pose2& estimate, const geometry::Pose2& truth) {
  return {std::hypot(estimate.x_m - truth.x_m, estimate.y_m - truth.y_m),
          std::abs(geometry::NormalizeAngle(estimate.theta_rad - truth.theta_rad)) / kDeg};
}

// Record indices of the ground truth records just before scans taken in the mapped corridor.
std::vector<std::size_t> CorridorStarts(const sim::EntityRecording& entity) {
  std::vector<std::size_t> starts;
  for (std::size_t i = 0; i + 1 < entity.records.size(); ++i) {
    const auto* truth = std::get_if<sensors::GroundTruth>(&entity.records[i]);
    if (!truth || !std::holds_alternative<sensors::LaserScan>(entity.records[i + 1])) continue;
    const geometry::Pose2& p = truth->world_from_body;
    if (p.y_m > 13.0 && p.y_m < 15.0 && p.x_m > 4.5 && p.x_m < 41.5) starts.push_back(i);
  }
  return starts;
}

// Metres the entity walks from the start record to the end of the log (truth).
double WalkLeft(const sim::EntityRecording& entity, std::size_t start) {
  double walked_m = 0.0;
  std::optional<geometry::Pose2> previous;
  for (std::size_t i = start; i < entity.records.size(); ++i) {
    const auto* t = std::get_if<sensors::GroundTruth>(&entity.records[i]);
    if (!t) continue;
    if (previous) walked_m += std::hypot(t->world_from_body.x_m - previous->x_m, t->world_from_body.y_m - previous->y_m);
    previous = t->world_from_body;
  }
  return walked_m;
}

struct Trial {
  bool anchored = false;
  Errors anchor, first_scan;
  bool first_found = false;
  double cpu_s = 0.0, walked_m = 0.0, mission_s = 0.0;
  int searches = 0;
  geometry::Pose2 start_truth, anchor_truth, anchor_estimate;
  bool forced = false;  // not anchored: the leading hypothesis at the last scan is the answer
  std::optional<geometry::Pose2> leader;
  geometry::Pose2 leader_truth;
  // The answer had the walk been cut at kWalkLimit_m: the anchor before it, else the leader then.
  std::optional<Errors> cut;
  bool cut_anchored = false;
  // The unknown phase's odometry starts at the compass heading (the mission frame's): how far
  // its heading is off the true one at the first scan it gives.
  double first_odometry_heading_off_deg = 0.0;
};

// PENA_BENCH_SET=name=value,...: tracker options (and the chain's compass_tolerance_deg and a few
// odometry options, prefixed "odometry.") for
// comparing variants on the same starts.
void ApplySettings(pipeline::EntityPipelineOptions& options) {
  pipeline::PlanLocalisationOptions& chain = options.plan_localisation;
  localisation::GlobalTrackerOptions& o = chain.tracker;
  const char* list = std::getenv("PENA_BENCH_SET");
  if (!list) return;
  std::string text(list);
  std::size_t begin = 0;
  while (begin < text.size()) {
    std::size_t end = text.find(',', begin);
    if (end == std::string::npos) end = text.size();
    const std::string item = text.substr(begin, end - begin);
    begin = end + 1;
    const std::size_t eq = item.find('=');
    if (eq == std::string::npos) continue;
    const std::string name = item.substr(0, eq);
    const double value = std::atof(item.c_str() + eq + 1);
    if (name == "min_agreement") o.min_agreement = value;
    else if (name == "decide_margin_beams") o.decide_margin_beams = value;
    else if (name == "drop_margin_beams") o.drop_margin_beams = value;
    else if (name == "max_keyframes") o.max_keyframes = static_cast<int>(value);
    else if (name == "min_keyframes") o.min_keyframes = static_cast<int>(value);
    else if (name == "min_travel_m") o.min_travel_m = value;
    else if (name == "through_weight") o.through_weight = value;
    else if (name == "final_keyframes") o.final_keyframes = static_cast<int>(value);
    else if (name == "freeze_history_keyframes") o.freeze_history_keyframes = static_cast<int>(value);
    else if (name == "boundary_fraction") o.boundary_fraction = value;
    else if (name == "freeze_ranking") o.freeze_ranking = static_cast<int>(value);
    else if (name == "answer_on_plan") o.answer_on_plan = value != 0.0;
    else if (name == "return_fit_keyframes") o.return_fit_keyframes = static_cast<int>(value);
    else if (name == "min_followed_keyframes") o.min_followed_keyframes = static_cast<int>(value);
    else if (name == "min_decide_return_fraction") o.min_decide_return_fraction = value;
    else if (name == "min_decide_return_keyframes") o.min_decide_return_keyframes = static_cast<int>(value);
    else if (name == "compass_tolerance_deg") chain.compass_tolerance_rad = value * kDeg;
    // The whole-plan localiser underneath (beam agreement, docs/localisation.md).
    else if (name == "agreement_tolerance_m") chain.global.agreement_tolerance_m = value;
    // The odometry underneath (docs/odometry.md).
    else if (name == "odometry.max_stride_period_s") options.odometry.dead_reckoning.max_stride_period_s = value;
    else if (name == "odometry.stride_interpolation.enabled") options.odometry.dead_reckoning.stride_interpolation.enabled = value != 0.0;
    else if (name == "odometry.stopped_stride_fraction") options.odometry.dead_reckoning.stopped_stride_fraction = value;
    else if (name == "odometry.turning_on_the_spot_rad_s") options.odometry.dead_reckoning.turning_on_the_spot_rad_s = value;
    else if (name == "odometry.overdue_turn_rad") options.odometry.dead_reckoning.overdue_turn_rad = value;
    else if (name == "odometry.local_map_keyframes") options.odometry.local_map_keyframes = static_cast<int>(value);
    else {
      std::fprintf(stderr, "PENA_BENCH_SET: unknown tracker option %s\n", name.c_str());
      std::exit(2);
    }
  }
}

// PENA_BENCH_TRACE=1: per keyframe, the rank and evidence of the track at the true pose.
void Trace(const localisation::GlobalResult& ranked, const geometry::Pose2& truth, double walked_m) {
  const auto& h = ranked.hypotheses;
  int true_rank = -1;
  for (std::size_t r = 0; r < h.size() && true_rank < 0; ++r) {
    if (localisation::SamePlace(h[r].map_from_body, truth)) true_rank = static_cast<int>(r);
  }
  std::printf("  kf walked %5.1f truth %6.2f %6.2f %6.1f: %zu tracks, leader %6.2f %6.2f %6.1f ev %6.0f ag %.2f",
              walked_m, truth.x_m, truth.y_m, truth.theta_rad / kDeg, h.size(), h[0].map_from_body.x_m,
              h[0].map_from_body.y_m, h[0].map_from_body.theta_rad / kDeg, h[0].score, h[0].agreement);
  if (h.size() > 1) {
    std::printf(", 2nd %6.2f %6.2f ev %6.0f margin %5.0f", h[1].map_from_body.x_m, h[1].map_from_body.y_m, h[1].score,
                ranked.margin);
  }
  if (true_rank >= 0) {
    std::printf(", true rank %d ev %6.0f ag %.2f\n", true_rank, h[static_cast<std::size_t>(true_rank)].score,
                h[static_cast<std::size_t>(true_rank)].agreement);
  } else {
    std::printf(", true not followed\n");
  }
}

Trial Run(const sim::EntityRecording& entity, const std::vector<geometry::Segment2>& plan, std::size_t start) {
  Trial trial;
  const bool trace = std::getenv("PENA_BENCH_TRACE") != nullptr;
  // Diagnosis: the first scan's figures only (the first search, the odometry's starting heading).
  const bool first_scan_only = std::getenv("PENA_BENCH_FIRST_SCAN_ONLY") != nullptr;
  pipeline::EntityPipelineOptions options;
  options.build_line_map = false;
  options.plan_localisation.global_start = true;
  options.plan_localisation.lost.enabled = true;  // as `pena localise`
  ApplySettings(options);
  const sensors::GroundTruth& first_truth = std::get<sensors::GroundTruth>(entity.records[start]);
  trial.start_truth = first_truth.world_from_body;
  const std::clock_t cpu_start = std::clock();
  pipeline::EntityPipeline chain(options, entity.kind, entity.id, geometry::Pose2{}, first_truth.stamp_s);
  chain.SetPlan(plan);
  geometry::Pose2 truth = first_truth.world_from_body;
  std::optional<geometry::Pose2> previous;
  bool first_scan = true;
  // The truth records read and not yet passed by a scan: the pipeline gives a person's scans when
  // their stride ends, and each truth record counts (walk, cut) just before its scan.
  std::deque<sensors::GroundTruth> truths;
  const auto pass_truth = [&](const sensors::GroundTruth& t) {
    truth = t.world_from_body;
    if (previous) trial.walked_m += std::hypot(truth.x_m - previous->x_m, truth.y_m - previous->y_m);
    previous = truth;
    if (!trial.cut && trial.walked_m >= kWalkLimit_m && trial.leader) trial.cut = Compare(*trial.leader, trial.leader_truth);
  };
  // One scan's report; true when the trial is over.
  const auto on_scan = [&](const pipeline::ScanStep& step) {
    while (!truths.empty() && truths.front().stamp_s <= step.odometry.stamp_s) {
      pass_truth(truths.front());
      truths.pop_front();
    }
    const localisation::LocalisedPose* pose = &*step.plan;
    trial.searches += pose->global_searched ? 1 : 0;
    if (first_scan && pose->global && !pose->global->hypotheses.empty()) {
      trial.first_found = true;
      trial.first_scan = Compare(pose->global->hypotheses.front().map_from_body, truth);
    }
    if (first_scan) {
      trial.first_odometry_heading_off_deg =
          std::abs(geometry::NormalizeAngle(pose->odometry.world_from_body.theta_rad - truth.theta_rad)) / kDeg;
    }
    first_scan = false;
    if (first_scan_only) return true;
    if (pose->global && !pose->global->hypotheses.empty()) {
      trial.leader = pose->global->hypotheses.front().map_from_body, trial.leader_truth = truth;
      if (trace) {
        std::printf("  returns %.2f", static_cast<double>(step.scan.CountReturns()) / static_cast<double>(step.scan.ranges_m.size()));
        Trace(*pose->global, truth, trial.walked_m);
      }
    }
    if (!pose->anchored) return false;
    trial.anchored = true;
    trial.anchor = Compare(pose->map_from_body, truth);
    trial.anchor_truth = truth;
    trial.anchor_estimate = pose->map_from_body;
    trial.mission_s = pose->stamp_s - first_truth.stamp_s;
    if (!trial.cut) trial.cut = trial.anchor, trial.cut_anchored = true;
    return true;
  };
  bool over = false;
  for (std::size_t i = start; i < entity.records.size() && !over; ++i) {
    if (const auto* t = std::get_if<sensors::GroundTruth>(&entity.records[i])) {
      truths.push_back(*t);
      continue;
    }
    chain.Push(entity.records[i]);
    while (const std::optional<pipeline::ScanStep> step = over ? std::nullopt : chain.Next()) over = on_scan(*step);
  }
  if (!over) {
    chain.EndOfInput();
    while (const std::optional<pipeline::ScanStep> step = over ? std::nullopt : chain.Next()) over = on_scan(*step);
  }
  if (!over) {
    for (const sensors::GroundTruth& t : truths) pass_truth(t);
  }
  trial.cpu_s = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
  if (!trial.anchored && trial.leader) {
    // The log ended first: the leader then is the answer.
    trial.forced = true;
    trial.anchor = Compare(*trial.leader, trial.leader_truth);
    trial.anchor_truth = trial.leader_truth;
    trial.anchor_estimate = *trial.leader;
    if (!trial.cut) trial.cut = trial.anchor;
  }
  return trial;
}

double Median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  const int poses = argc > 1 ? std::atoi(argv[1]) : 100;
  sim::SimulationOptions sim_options;
  sim_options.seed = argc > 2 ? std::strtoull(argv[2], nullptr, 10) : 1;
  const unsigned pick_seed = argc > 3 ? static_cast<unsigned>(std::atoi(argv[3])) : 1u;
  const sim::Scenario office = sim::ParseScenario(*sim::BuiltinScenarioText("office"), "office");
  const sim::SimulationResult mission = sim::Simulator(sim_options).Run(office);
  const sim::EntityRecording& entity = mission.entities.front();
  std::vector<std::size_t> starts = CorridorStarts(entity);
  std::mt19937 rng(pick_seed);
  std::shuffle(starts.begin(), starts.end(), rng);
  starts.resize(std::min<std::size_t>(starts.size(), static_cast<std::size_t>(poses)));
  int good = 0, anchored = 0, first_good = 0, forced = 0, short_1m = 0, short_3m = 0;
  int cut_good = 0, cut_anchored = 0, heading_off_10deg = 0;
  double heading_off_max_deg = 0.0;
  std::vector<double> cpu_s, walked_m, mission_s;
  // PENA_BENCH_ONLY=3,17: run only these of the picked starts (0-based), for diagnosis.
  std::vector<int> only;
  if (const char* list = std::getenv("PENA_BENCH_ONLY")) {
    for (const char* p = list; *p;) {
      char* end = nullptr;
      only.push_back(static_cast<int>(std::strtol(p, &end, 10)));
      p = *end ? end + 1 : end;
    }
  }
  // Starts the log leaves too little walk after to decide (min_travel_m 3 m): fair to count apart.
  for (const std::size_t start : starts) {
    const double left_m = WalkLeft(entity, start);
    short_1m += left_m < 1.0 ? 1 : 0;
    short_3m += left_m < 3.0 ? 1 : 0;
  }
  for (std::size_t index = 0; index < starts.size(); ++index) {
    if (!only.empty() && std::find(only.begin(), only.end(), static_cast<int>(index)) == only.end()) continue;
    const std::size_t start = starts[index];
    const Trial t = Run(entity, *office.apriori, start);
    first_good += t.first_found && t.first_scan.ok() ? 1 : 0;
    anchored += t.anchored ? 1 : 0;
    good += (t.anchored || t.forced) && t.anchor.ok() ? 1 : 0;
    forced += t.forced ? 1 : 0;
    cut_good += t.cut && t.cut->ok() ? 1 : 0;
    cut_anchored += t.cut_anchored ? 1 : 0;
    heading_off_10deg += t.first_odometry_heading_off_deg > 10.0 ? 1 : 0;
    heading_off_max_deg = std::max(heading_off_max_deg, t.first_odometry_heading_off_deg);
    cpu_s.push_back(t.cpu_s);
    if (t.anchored) walked_m.push_back(t.walked_m), mission_s.push_back(t.mission_s);
    std::printf("#%zu start %6.2f %6.2f %7.1f deg: %s", index, t.start_truth.x_m, t.start_truth.y_m,
                t.start_truth.theta_rad / kDeg, t.anchored ? "anchored" : !t.forced ? "nothing" : "log ended, leader");
    if (t.anchored || t.forced) {
      std::printf(" after %.1f m / %.1f s, %d searches, error %.3f m %.2f deg%s (at %.2f %.2f -> %.2f %.2f %.1f deg)",
                  t.walked_m, t.mission_s, t.searches, t.anchor.position_m, t.anchor.heading_deg,
                  t.anchor.ok() ? "" : " MISS", t.anchor_truth.x_m, t.anchor_truth.y_m, t.anchor_estimate.x_m,
                  t.anchor_estimate.y_m, t.anchor_estimate.theta_rad / kDeg);
    }
    if (t.cut && !t.cut_anchored && t.walked_m >= kWalkLimit_m) {
      std::printf("; at 30 m the leader: error %.3f m %.2f deg%s", t.cut->position_m, t.cut->heading_deg,
                  t.cut->ok() ? "" : " MISS");
    }
    std::printf("; cpu %.2f s; first scan alone %s\n", t.cpu_s, t.first_found && t.first_scan.ok() ? "right" : "wrong");
    std::fflush(stdout);
  }
  std::printf("office global localisation: %d / %zu within 0.3 m and 3 deg (%d anchored, %d taken from the leader "
              "when the log ended; %d right by the first scan alone); median CPU %.2f s (max %.2f s), median walk %.1f m / %.1f s of mission until "
              "anchored (sim seed %llu, pick seed %u)\n",
              good, starts.size(), anchored, forced, first_good, Median(cpu_s),
              cpu_s.empty() ? 0.0 : *std::max_element(cpu_s.begin(), cpu_s.end()), Median(walked_m),
              Median(mission_s), static_cast<unsigned long long>(sim_options.seed), pick_seed);
  std::printf("cut at 30 m of walk: %d / %zu within 0.3 m and 3 deg (%d anchored before it)\n", cut_good,
              starts.size(), cut_anchored);
  std::printf("starts whose odometry began more than 10 deg off the true heading: %d (at most %.1f deg)\n",
              heading_off_10deg, heading_off_max_deg);
  std::printf("starts whose log ends within 1 m of walking: %d; within 3 m (min_travel_m): %d\n", short_1m, short_3m);
  return 0;
}
