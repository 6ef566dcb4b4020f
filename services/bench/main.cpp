// pena-load: the fusion scale benchmark (docs/benchmarks.md). Starts an unmodified pena-fusion
// on loopback DDS, publishes N simulated entities' poses, reference scans, line-map deltas and
// status at mission speed (4 Hz scans), and prints correction latency (reference scan sent ->
// correction received) per window, fusion's CPU and memory, and the totals. A benchmark: it
// reports, it does not judge. --security DIR (deploy/security/make-identities.sh output) runs
// it secured: pena-fusion as DIR/fusion, the simulated entities through one participant with
// DIR/gateway's identity (it may write every entity's data, as a gateway relaying a team does).
#include <CLI/CLI.hpp>
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <thread>

#include "load_run.hpp"
#include "proc_stats.hpp"

extern char** environ;

namespace {

using namespace pena::services;
using namespace pena::services::bench;

struct Cli {
  std::string mission, fusion = PENA_FUSION_BIN, work = "/tmp/pena-load", security;
  int domain = 77;
  double duration_s = 60.0;
  bool plan = true;
  std::vector<std::string> fusion_args;  // passed on to pena-fusion after --config
  LoadOptions load;
};

std::filesystem::path DdsDir() { return std::filesystem::path(PENA_SOURCE_DIR) / "deploy" / "dds"; }

DdsOptions Loopback(int domain, const std::string& security) {
  setenv("FASTRTPS_DEFAULT_PROFILES_FILE", (DdsDir() / "pena-loopback.xml").c_str(), 1);
  DdsOptions options;
  options.profiles_files = {DdsDir() / "pena-loopback.xml", DdsDir() / "pena-qos.xml"};
  options.domain_id = domain;
  if (!security.empty()) options.security_dir = std::filesystem::path(security) / "gateway";
  return options;
}

// pena-fusion's config: defaults, except that every accepted correction is sent (no minimum
// move), so each one is a latency sample.
std::filesystem::path WriteFusionConfig(const Cli& cli) {
  const std::filesystem::path work(cli.work);
  std::filesystem::remove_all(work / "state");
  std::filesystem::create_directories(work);
  const std::filesystem::path path = work / "fusion.conf";
  std::ofstream out(path);
  out << "state_dir: \"" << (work / "state").string() << "\"\n"
      << "output_dir: \"" << (work / "fusion_out").string() << "\"\n"
      << "correction_min_m: 0\ncorrection_min_rad: 0\n";
  const std::filesystem::path plan = std::filesystem::path(cli.mission) / "apriori.csv";
  if (cli.plan && std::filesystem::exists(plan)) out << "plan: \"" << plan.string() << "\"\n";
  out << "dds { profiles_files: \"" << (DdsDir() / "pena-loopback.xml").string() << "\"\n"
      << "  profiles_files: \"" << (DdsDir() / "pena-qos.xml").string() << "\"\n"
      << "  participant_profile: \"pena_loopback\" domain_id: " << cli.domain;
  if (!cli.security.empty()) {
    out << "\n  security_dir: \"" << (std::filesystem::absolute(cli.security) / "fusion").string()
        << "\"";
  }
  out << " }\n"
      << "log { level: \"warn\" }\n";
  return path;
}

pid_t SpawnFusion(const Cli& cli, const std::filesystem::path& config) {
  const std::string log = (std::filesystem::path(cli.work) / "fusion.log").string();
  std::vector<std::string> args = {cli.fusion, "--config", config.string()};
  args.insert(args.end(), cli.fusion_args.begin(), cli.fusion_args.end());
  std::vector<char*> argv;
  for (std::string& arg : args) argv.push_back(arg.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  pid_t pid = -1;
  const int error = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  return error == 0 ? pid : -1;
}

std::vector<SourceStream> ComputeSources(const Cli& cli) {
  std::vector<SourceStream> sources;
  const double cpu0 = SelfCpuS();
  for (const std::filesystem::path& dir : MissionEntities(cli.mission)) {
    sources.push_back(ComputeSourceStream(dir, cli.duration_s));
    const SourceStream& s = sources.back();
    std::printf("source %-8s %4zu scans, %3ld reference scans, %3ld deltas in %.0f s\n",
                s.entity_id.c_str(), s.scans.size(), s.reference_scans, s.deltas, cli.duration_s);
  }
  std::printf("entity chains computed in %.1f CPU s (before the timed run)\n", SelfCpuS() - cpu0);
  return sources;
}

void PrintSummary(const std::vector<WindowFigures>& windows, const ProcSample& fusion,
                  double load_cpu_s, int entities) {
  WindowFigures all;
  all.start_s = windows.empty() ? 0.0 : windows.front().start_s;
  all.end_s = windows.empty() ? 0.0 : windows.back().end_s;
  for (const WindowFigures& w : windows) {
    all.reference_scans_sent += w.reference_scans_sent;
    all.latencies_ms.insert(all.latencies_ms.end(), w.latencies_ms.begin(), w.latencies_ms.end());
    all.fusion_cpu_s += w.fusion_cpu_s;
  }
  all.fusion_rss_kb = fusion.rss_kb;
  PrintWindow("all", all, entities);
  std::printf("fusion: CPU %.1f s in %.1f s wall (%.0f %% of one core), peak RSS (VmHWM) %.1f MB; "
              "pena-load CPU %.1f s\n", all.fusion_cpu_s, all.end_s - all.start_s,
              100.0 * all.fusion_cpu_s / std::max(all.end_s - all.start_s, 1e-9),
              static_cast<double>(fusion.hwm_kb) / 1024.0, load_cpu_s);
}

// Fusion's own counters (correction attempts, matching time, superseded and stale requests,
// queueing delay), from the "counters" object of its fusion_stats.json, on one line.
void PrintFusionCounters(const std::filesystem::path& stats) {
  std::ifstream in(stats);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t start = text.find("\"counters\"");
  if (start == std::string::npos) return;
  std::string line;
  for (std::size_t i = text.find('{', start) + 1; i < text.size() && text[i] != '}'; ++i) {
    if (text[i] == '\n' || text[i] == '"') continue;
    if (text[i] == ' ' && !line.empty() && line.back() == ' ') continue;
    line += text[i];
  }
  std::printf("fusion counters:%s\n", line.c_str());
}

int Run(const Cli& cli) {
  const DdsOptions dds = Loopback(cli.domain, cli.security);
  std::printf("DDS Security: %s\n", cli.security.empty() ? "off" : "on");
  std::vector<SourceStream> sources = ComputeSources(cli);
  const pid_t fusion = SpawnFusion(cli, WriteFusionConfig(cli));
  if (fusion < 0) {
    std::fprintf(stderr, "pena-load: cannot start %s\n", cli.fusion.c_str());
    return 1;
  }
  LoadOptions options = cli.load;
  options.fusion_pid = fusion;
  LoadRun run(dds, std::move(sources), options);
  if (!run.WaitForFusion(30.0)) {
    std::fprintf(stderr, "pena-load: pena-fusion did not match within 30 s (log: %s/fusion.log)\n",
                 cli.work.c_str());
    kill(fusion, SIGKILL);
    waitpid(fusion, nullptr, 0);
    return 1;
  }
  const double cpu0 = SelfCpuS();
  const std::vector<WindowFigures> windows = run.Replay();
  const ProcSample last = ReadProc(fusion).value_or(ProcSample{});
  const double load_cpu_s = SelfCpuS() - cpu0;
  kill(fusion, SIGINT);
  int status = 0;
  waitpid(fusion, &status, 0);
  run.PrintTotals();
  PrintSummary(windows, last, load_cpu_s, cli.load.entities);
  PrintFusionCounters(std::filesystem::path(cli.work) / "fusion_out" / "fusion_stats.json");
  std::printf("fusion exit %d; its stats: %s/fusion_out/fusion_stats.json, log %s/fusion.log\n",
              WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status), cli.work.c_str(),
              cli.work.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("pena-load: N simulated entities at 4 Hz against pena-fusion on loopback DDS");
  Cli cli;
  app.add_option("--mission", cli.mission, "Simulated mission directory (pena simulate --out)")
      ->required();
  app.add_option("--entities", cli.load.entities, "Entities published")->capture_default_str();
  app.add_option("--duration", cli.duration_s, "Mission seconds replayed per entity")
      ->capture_default_str();
  app.add_option("--spread", cli.load.spread_m, "Copy r of a source is moved r * this far in x "
                 "(m; 0: all copies in one building)")->capture_default_str();
  app.add_option("--window", cli.load.window_s, "Report period, s")->capture_default_str();
  app.add_option("--drain", cli.load.drain_s, "Wait for late corrections, s")->capture_default_str();
  app.add_option("--fusion", cli.fusion, "pena-fusion executable")->capture_default_str();
  app.add_option("--work", cli.work, "Scratch directory (fusion config, state, log)")
      ->capture_default_str();
  app.add_option("--domain", cli.domain, "DDS domain id")->capture_default_str();
  app.add_option("--security", cli.security,
                 "DDS Security: the identities directory of deploy/security/make-identities.sh");
  app.add_flag("!--no-plan", cli.plan, "Do not give fusion the mission's apriori.csv");
  app.add_option("--fusion-arg", cli.fusion_args,
                 "An argument passed on to pena-fusion (repeatable), e.g. "
                 "--fusion-arg=--correction-max-wait --fusion-arg=0.15");
  CLI11_PARSE(app, argc, argv);
  if (cli.load.entities < 1 || cli.duration_s <= 0.0 || cli.load.window_s <= 0.0) {
    std::fprintf(stderr, "pena-load: --entities >= 1, --duration > 0 s and --window > 0 s\n");
    return 1;
  }
  try {
    return Run(cli);
  } catch (const std::exception& error) {
    std::fprintf(stderr, "pena-load: %s\n", error.what());
    return 1;
  }
}
