// pena export --log LOG [--carmen OUT [--perturb-odometry SEED]] [--csm OUT]
//             [--tum OUT [--pose odometry|logged]]:
// converts a log's scans (and odometry) to the text formats other tools read; with
// --perturb-odometry the CARMEN output's odometry carries sim::OdometryNoiseModel's errors.
#include <cstdint>
#include <iostream>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include "cli_support.hpp"
#include "commands.hpp"
#include "pena/geometry/trajectory.hpp"
#include "pena/io/carmen.hpp"
#include "pena/io/log_source.hpp"
#include "pena/io/trajectory_io.hpp"
#include "pena/sim/odometry_perturbation.hpp"

namespace pena::cli {
namespace {

struct ExportOptions {
  std::string log;
  std::string carmen;
  std::string csm;
  std::string tum;
  std::string pose = "odometry";
  std::optional<std::uint64_t> perturb_seed;  // --perturb-odometry: the noise model's seed
  io::ReadOptions read;
};

struct ExportCounts {
  std::size_t scans = 0;
  std::size_t odometry = 0;
  std::size_t not_representable = 0;  // gyro, compass, stride, ground truth: no CARMEN line
  std::size_t tum_left_out = 0;       // scans without the pose, or not after the previous stamp
  std::size_t restamped = 0;          // --perturb-odometry: scans given a stamp after the previous
};

// With --perturb-odometry, the time a scan that is not after the previous one is put after it.
constexpr double kRestampS = 0.2;

// The scan's pose for the TUM output, if it has the kind asked for.
std::optional<geometry::Pose2> TumPose(const sensors::LaserScan& scan, const std::string& kind) {
  return kind == "logged" ? scan.logged_pose : scan.odometry_pose;
}

// Adds the scan's pose to the trajectory; TUM needs increasing stamps, so later duplicates and
// small steps back (radish logs) are left out and counted.
void AppendTum(const sensors::LaserScan& scan, const std::string& kind,
               geometry::Trajectory& trajectory, ExportCounts& counts) {
  const std::optional<geometry::Pose2> pose = TumPose(scan, kind);
  if (!pose || (!trajectory.empty() && !(scan.stamp_s > trajectory.back().stamp_s))) {
    ++counts.tum_left_out;
    return;
  }
  trajectory.push_back({scan.stamp_s, *pose});
}

void RunExport(const ExportOptions& options) {
  if (options.carmen.empty() && options.csm.empty() && options.tum.empty()) {
    throw CLI::ValidationError("export", "give at least one output: --carmen, --csm or --tum");
  }
  const std::unique_ptr<io::LogSource> source = io::OpenLog(options.log, options.read);
  std::unique_ptr<io::CarmenWriter> carmen;
  std::unique_ptr<io::CsmJsonWriter> csm;
  if (!options.carmen.empty()) carmen = std::make_unique<io::CarmenWriter>(options.carmen);
  if (!options.csm.empty()) csm = std::make_unique<io::CsmJsonWriter>(options.csm);
  geometry::Trajectory trajectory;
  ExportCounts counts;
  // The perturbed odometry travels in the scans' pose fields (the chain's prior where a scan has
  // one); ODOM records are left out, since perturbing them apart would give two odometries.
  std::optional<sim::OdometryPerturber> perturber;
  std::optional<double> last_scan_stamp_s;
  if (options.perturb_seed) perturber.emplace(sim::OdometryNoiseModel{}, *options.perturb_seed);
  while (std::optional<sensors::SensorRecord> record = source->Next()) {
    if (auto* scan = std::get_if<sensors::LaserScan>(&*record)) {
      ++counts.scans;
      // Some corrected logs have no usable time (orebro: every stamp 0; csail: stamps rounded to
      // 6 digits): a perturbed run needs one, so such scans follow the previous one by kRestampS.
      if (perturber && last_scan_stamp_s && !(scan->stamp_s > *last_scan_stamp_s)) {
        scan->stamp_s = *last_scan_stamp_s + kRestampS;
        ++counts.restamped;
      }
      last_scan_stamp_s = scan->stamp_s;
      // The TUM output keeps the poses as read: for a perturbed log, its truth.
      if (!options.tum.empty()) AppendTum(*scan, options.pose, trajectory, counts);
      if (perturber) {
        if (!scan->odometry_pose) {
          throw std::runtime_error(options.log + ": scan " + std::to_string(counts.scans) +
                                   " has no odometry pose to perturb (--perturb-odometry)");
        }
        scan->odometry_pose = perturber->Perturb(*scan->odometry_pose);
      }
      if (carmen) carmen->Write(*scan);
      if (csm) csm->Write(*scan);
    } else if (const auto* odometry = std::get_if<sensors::WheelOdometry>(&*record)) {
      ++counts.odometry;
      if (carmen && !perturber) carmen->Write(*odometry);
    } else {
      ++counts.not_representable;
    }
  }
  if (!options.tum.empty()) {
    if (trajectory.empty() && counts.scans > 0) {
      throw std::runtime_error(options.log + ": no scan has a " + options.pose +
                               " pose for --tum (try --pose " +
                               (options.pose == "logged" ? "odometry" : "logged") + ")");
    }
    io::WriteTum(options.tum, trajectory);
  }
  std::cout << "exported " << counts.scans << " scans, " << counts.odometry << " odometry records";
  if (!options.tum.empty()) std::cout << ", " << trajectory.size() << " " << options.pose << " poses";
  std::cout << " from " << options.log << '\n';
  if (counts.not_representable > 0) {
    std::cout << "left out " << counts.not_representable
              << " records with no text form (gyro, compass, stride, ground truth)\n";
  }
  if (counts.tum_left_out > 0) {
    std::cout << "left out of the TUM file " << counts.tum_left_out
              << " scans without that pose or not after the previous stamp\n";
  }
  if (counts.restamped > 0) {
    std::cout << "restamped " << counts.restamped << " scans not after the previous one (+"
              << Fixed(kRestampS, 1) << " s each)\n";
  }
  if (perturber) {
    std::cout << "odometry perturbed (seed " << *options.perturb_seed << "): distance scale "
              << Fixed(perturber->distance_scale(), 4) << ", turn scale "
              << Fixed(perturber->turn_scale(), 4) << ", " << perturber->slips() << " slips\n";
  }
  if (source->skipped() > 0) std::cout << "skipped " << source->skipped() << " malformed lines\n";
}

}  // namespace

void AddExportCommand(CLI::App& app) {
  auto options = std::make_shared<ExportOptions>();
  CLI::App* command = app.add_subcommand(
      "export", "Convert a log's scans to CARMEN, CSM JSON (sm1/sm2) and/or a TUM trajectory");
  command->add_option("--log", options->log, "Input log: CARMEN (plain or gzip) or PeNa mission log")
      ->required();
  CLI::Option* carmen_option = command->add_option(
      "--carmen", options->carmen, "Write FLASER/ODOM lines to this CARMEN file");
  command
      ->add_option("--perturb-odometry", options->perturb_seed,
                   "SEED: the CARMEN output's odometry (the scans' pose fields; ODOM records are "
                   "left out) gets the documented noise model's errors (scale, heading random "
                   "walk, sudden slips; docs/evaluation.md); --tum keeps the poses as read, the "
                   "perturbed run's truth")
      ->needs(carmen_option);
  command->add_option("--csm", options->csm, "Write Censi CSM laser_data JSON, one scan per line");
  CLI::Option* tum = command->add_option(
      "--tum", options->tum, "Write the scans' poses at the scan stamps as a TUM trajectory");
  command->add_option("--pose", options->pose, "Pose written to --tum: odometry or logged")
      ->check(CLI::IsMember({"odometry", "logged"}))
      ->needs(tum)
      ->capture_default_str();
  command->add_flag("--skip-malformed", options->read.skip_malformed,
                    "Skip malformed lines (and count them) instead of stopping at the first");
  command->add_option("--max-range", options->read.carmen_max_range_m,
                      "CARMEN FLASER maximum range, metres: ranges at or above it are no-returns")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  // Errors propagate: main prints them as one "pena: error: file:line: what" line.
  command->callback([options] { RunExport(*options); });
}

}  // namespace pena::cli
