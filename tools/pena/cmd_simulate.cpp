// pena simulate: runs a scenario (built-in or file) and writes the mission directory: per-entity
// native logs and ground truth, floor plan, observed walls, a priori plan and mission.png.
// Layout and models: docs/simulator.md.
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <opencv2/imgcodecs.hpp>
#include <sstream>
#include <stdexcept>
#include <string>

#include "cli_support.hpp"
#include "commands.hpp"
#include "pena/sim/mission_picture.hpp"
#include "pena/sim/mission_writer.hpp"
#include "pena/sim/scenario.hpp"
#include "pena/sim/simulator.hpp"

namespace pena::cli {
namespace {

struct SimulateArgs {
  std::string scenario;
  std::uint64_t seed = 1;
  std::string out;
  int laps = 0;
  double wall_thickness_m = 0.0;
  bool print_scenario = false;
};

// The scenario's text and the origin its parse errors name.
struct ScenarioSource {
  std::string text;
  std::string origin;
};

ScenarioSource LoadScenarioSource(const std::string& name_or_file) {
  if (const auto builtin = sim::BuiltinScenarioText(name_or_file)) {
    return {std::string(*builtin), "builtin:" + name_or_file};
  }
  std::ifstream file(name_or_file, std::ios::binary);
  if (!file) {
    std::string names;
    for (const std::string& name : sim::BuiltinScenarioNames())
      names += (names.empty() ? "" : ", ") + name;
    throw std::runtime_error("--scenario " + name_or_file + ": neither a built-in scenario (" +
                             names + ") nor a readable file");
  }
  std::ostringstream text;
  text << file.rdbuf();
  return {text.str(), name_or_file};
}

double Percent(std::size_t part, std::size_t whole) {
  return whole == 0 ? 0.0 : 100.0 * static_cast<double>(part) / static_cast<double>(whole);
}

void PrintSummary(const sim::SimulationResult& result, const sim::MissionFiles& files,
                  const std::string& picture, double runtime_s) {
  std::size_t scans = 0, with_floor_or_ceiling = 0;
  for (const sim::EntityRecording& entity : result.entities) {
    scans += entity.scans;
    with_floor_or_ceiling += entity.scans_with_floor_or_ceiling;
    std::cout << "  " << entity.id << " (" << sensors::ToString(entity.kind)
              << "): " << entity.scans << " scans, " << Fixed(entity.end_s - entity.start_s, 1)
              << " s, floor/ceiling hits in "
              << Fixed(Percent(entity.scans_with_floor_or_ceiling, entity.scans), 1)
              << "% of scans\n";
  }
  std::cout << "mission " << result.mission << ": " << result.entities.size() << " entities, "
            << scans << " scans, " << Fixed(result.end_s - result.start_s, 1)
            << " s of mission, floor/ceiling hits in "
            << Fixed(Percent(with_floor_or_ceiling, scans), 1) << "% of scans, "
            << result.observed.size() << " observed wall segments; simulated in "
            << Fixed(runtime_s, 2) << " s\n";
  std::cout << "wrote " << files.floorplan.string() << ", " << files.observed.string();
  if (files.apriori) std::cout << ", " << files.apriori->string();
  std::cout << ", " << picture << '\n';
  for (const sim::EntityFiles& entity : files.entities) {
    std::cout << "wrote " << entity.log.string() << ", " << entity.truth_tum.string() << ", "
              << entity.truth_relations.string() << '\n';
  }
}

void RunSimulate(const SimulateArgs& args) {
  const ScenarioSource source = LoadScenarioSource(args.scenario);
  if (args.print_scenario) {
    std::cout << source.text << std::flush;
    return;
  }
  if (args.out.empty()) throw std::runtime_error("simulate: --out DIR is required");
  sim::Scenario scenario = sim::ParseScenario(source.text, source.origin);
  if (args.laps > 0) {
    for (sim::EntitySpec& entity : scenario.entities) entity.laps = args.laps;
  }
  if (const std::string problem = sim::ValidateScenario(scenario); !problem.empty()) {
    throw std::runtime_error(source.origin + ": " + problem);
  }
  sim::SimulationOptions options;
  options.seed = args.seed;
  options.wall_thickness_m = args.wall_thickness_m;
  const auto started = std::chrono::steady_clock::now();
  const sim::SimulationResult result = sim::Simulator(options).Run(scenario);
  std::string producer =
      "pena simulate --scenario " + args.scenario + " --seed " + std::to_string(args.seed);
  if (args.laps > 0) producer += " --laps " + std::to_string(args.laps);
  if (args.wall_thickness_m > 0.0) {
    producer += " --wall-thickness " + Fixed(args.wall_thickness_m, 3);
  }
  const sim::MissionFiles files = sim::WriteMission(scenario, result, args.out, producer);
  const std::string picture = (std::filesystem::path(args.out) / "mission.png").string();
  if (!cv::imwrite(picture, sim::RenderMission(scenario, result))) {
    throw std::runtime_error(picture + ": cannot write the PNG");
  }
  const std::chrono::duration<double> runtime = std::chrono::steady_clock::now() - started;
  PrintSummary(result, files, picture, runtime.count());
}

}  // namespace

void AddSimulateCommand(CLI::App& app) {
  auto args = std::make_shared<SimulateArgs>();
  CLI::App* command = app.add_subcommand(
      "simulate",
      "Simulate a rescue mission: native sensor logs, ground truth, plans and a picture");
  command
      ->add_option("--scenario", args->scenario,
                   "Built-in scenario name (loop170, office, team) or scenario file")
      ->required();
  command->add_option("--seed", args->seed, "Random seed; the same seed writes the same bytes")
      ->capture_default_str();
  command->add_option("--out", args->out, "Output directory (created if missing)");
  command->add_option("--laps", args->laps, "Laps for every entity (overrides the scenario)")
      ->check(CLI::Range(1, 1000));
  command
      ->add_option("--wall-thickness", args->wall_thickness_m,
                   "Metres: the laser meets each wall as a box this thick (door jambs, both "
                   "faces); walkers and floorplan.csv keep the lines (docs/simulator.md)")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  command->add_flag("--print-scenario", args->print_scenario,
                    "Print the scenario text and exit (start your own file from a built-in)");
  command->callback([args] { RunSimulate(*args); });
}

}  // namespace pena::cli
