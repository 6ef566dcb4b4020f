// Global localisation on the simulated `office` mission (issue 5 acceptance): scans of the
// firefighter taken at random true poses in the mapped corridor (y 13-15 m, x 4.5-41.5 m) are
// localised on the partial, partly wrong a priori plan with no start pose. Prints how many land
// within 0.3 m and 3 deg of the truth and the median time per localisation.
//   bench_global_localisation [POSES=100] [SIM_SEED=1] [PICK_SEED=1]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "pena/localisation/global_localiser.hpp"
#include "pena/scan_matching/point_set.hpp"
#include "pena/sim/scenario.hpp"
#include "pena/sim/simulator.hpp"

namespace {

using namespace pena;

struct Sample {
  geometry::Pose2 truth;
  sensors::LaserScan scan;
};

std::vector<Sample> CorridorScans(const sim::EntityRecording& entity) {
  std::vector<Sample> samples;
  const sensors::GroundTruth* truth = nullptr;
  for (const sensors::SensorRecord& record : entity.records) {
    if (const auto* t = std::get_if<sensors::GroundTruth>(&record)) truth = t;
    const auto* scan = std::get_if<sensors::LaserScan>(&record);
    if (!scan || !truth || truth->stamp_s != scan->stamp_s) continue;
    const geometry::Pose2& p = truth->world_from_body;
    if (p.y_m > 13.0 && p.y_m < 15.0 && p.x_m > 4.5 && p.x_m < 41.5) samples.push_back({p, *scan});
  }
  return samples;
}

}  // namespace

int main(int argc, char** argv) {
  const int poses = argc > 1 ? std::atoi(argv[1]) : 100;
  sim::SimulationOptions sim_options;
  sim_options.seed = argc > 2 ? std::strtoull(argv[2], nullptr, 10) : 1;
  const unsigned pick_seed = argc > 3 ? static_cast<unsigned>(std::atoi(argv[3])) : 1u;
  const sim::Scenario office = sim::ParseScenario(*sim::BuiltinScenarioText("office"), "office");
  const sim::SimulationResult mission = sim::Simulator(sim_options).Run(office);
  std::vector<Sample> samples = CorridorScans(mission.entities.front());
  std::mt19937 rng(pick_seed);
  std::shuffle(samples.begin(), samples.end(), rng);
  samples.resize(std::min<std::size_t>(samples.size(), static_cast<std::size_t>(poses)));
  const localisation::GlobalLocaliser localiser(*office.apriori);
  int good = 0;
  std::vector<double> times_s;
  for (const Sample& sample : samples) {
    const auto start = std::chrono::steady_clock::now();
    const localisation::GlobalResult result =
        localiser.Localise(sample.scan);
    times_s.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    const bool found = !result.hypotheses.empty();
    const geometry::Pose2 best = found ? result.hypotheses.front().map_from_body : geometry::Pose2{};
    const double error_m = std::hypot(best.x_m - sample.truth.x_m, best.y_m - sample.truth.y_m);
    const double error_deg =
        std::abs(geometry::NormalizeAngle(best.theta_rad - sample.truth.theta_rad)) * 180.0 / std::numbers::pi;
    const bool ok = found && error_m <= 0.3 && error_deg <= 3.0;
    good += ok ? 1 : 0;
    if (!ok) {
      std::printf("miss: truth %.2f %.2f %.1f deg -> %.2f %.2f %.1f deg (agreement %.2f, margin %.2f)\n",
                  sample.truth.x_m, sample.truth.y_m, sample.truth.theta_rad * 180.0 / std::numbers::pi,
                  best.x_m, best.y_m, best.theta_rad * 180.0 / std::numbers::pi,
                  found ? result.hypotheses.front().agreement : 0.0, result.margin);
    }
  }
  std::sort(times_s.begin(), times_s.end());
  const double median_s = times_s.empty() ? 0.0 : times_s[times_s.size() / 2];
  std::printf("office global localisation: %d / %zu within 0.3 m and 3 deg; median %.3f s, max %.3f s "
              "(sim seed %llu, pick seed %u)\n",
              good, samples.size(), median_s, times_s.empty() ? 0.0 : times_s.back(),
              static_cast<unsigned long long>(sim_options.seed), pick_seed);
  return 0;
}
