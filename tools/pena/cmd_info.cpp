// pena info FILE...: what each log holds (entity, sensors, counts, duration, beams).
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"
#include "pena/io/log_source.hpp"
#include "pena/io/log_summary.hpp"

namespace pena::cli {
namespace {

struct InfoOptions {
  std::vector<std::string> files;
  io::ReadOptions read;
};

void RunInfo(const InfoOptions& options) {
  for (std::size_t i = 0; i < options.files.size(); ++i) {
    const std::unique_ptr<io::LogSource> source = io::OpenLog(options.files[i], options.read);
    if (i > 0) std::cout << '\n';
    std::cout << io::FormatSummary(io::SummarizeLog(*source)) << std::flush;
  }
}

}  // namespace

void AddInfoCommand(CLI::App& app) {
  auto options = std::make_shared<InfoOptions>();
  CLI::App* command =
      app.add_subcommand("info",
                         "Summarise sensor logs: CARMEN (.clf/.log, plain or gzip) or native "
                         "PeNa mission logs (.penalog)");
  command->add_option("FILE", options->files, "Log files to summarise")->required();
  command->add_flag("--skip-malformed", options->read.skip_malformed,
                    "Skip malformed lines (and count them) instead of stopping at the first");
  command
      ->add_option("--max-range", options->read.carmen_max_range_m,
                   "CARMEN maximum range, metres: ranges at or above it are no-returns")
      ->check(CLI::Range(0.01, 1000.0))
      ->capture_default_str();
  // Errors propagate: main prints them as one "pena: error: file:line: what" line.
  command->callback([options] { RunInfo(*options); });
}

}  // namespace pena::cli
