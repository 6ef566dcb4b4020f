// Runs LaserOdometry over the first scans of a CARMEN log through an installed libpena and
// prints the final pose and the match counts. usage: odometry_on_log LOG [SCANS]
#include <cmath>
#include <cstdlib>
#include <exception>
#include <iostream>
#include <optional>
#include <string>
#include <variant>

#include "pena/io/log_source.hpp"
#include "pena/odometry/laser_odometry.hpp"

int main(int argc, char** argv) try {
  if (argc < 2) {
    std::cerr << "usage: odometry_on_log LOG [SCANS]\n";
    return EXIT_FAILURE;
  }
  const long wanted = argc > 2 ? std::stol(argv[2]) : 200;
  const auto log = pena::io::OpenLog(argv[1]);
  std::optional<pena::odometry::LaserOdometry> chain;
  std::optional<pena::odometry::OdometryEstimate> last;
  long scans = 0;
  while (scans < wanted) {
    const std::optional<pena::sensors::SensorRecord> record = log->Next();
    if (!record) break;
    const auto* scan = std::get_if<pena::sensors::LaserScan>(&*record);
    if (!chain) {
      // Start where the log's odometry says the first scan was taken.
      if (scan == nullptr || !scan->odometry_pose) continue;
      chain.emplace(pena::odometry::LaserOdometryOptions{}, pena::sensors::EntityKind::kRobot,
                    *scan->odometry_pose, scan->stamp_s);
    }
    if (const auto estimate = chain->Add(*record)) last = estimate;
    if (scan != nullptr) ++scans;
  }
  if (!chain || !last) {
    std::cerr << argv[1] << ": no laser scan with an odometry pose\n";
    return EXIT_FAILURE;
  }
  const pena::odometry::OdometryCounts& counts = chain->counts();
  const pena::geometry::Pose2& pose = last->world_from_body;
  std::cout << "scans " << counts.scans << " matched " << counts.matched << " keyframes "
            << counts.keyframes << " final pose " << pose.x_m << " " << pose.y_m << " "
            << pose.theta_rad << "\n";
  const bool finite = std::isfinite(pose.x_m) && std::isfinite(pose.y_m) && std::isfinite(pose.theta_rad);
  return finite && counts.scans == wanted && counts.matched > wanted / 2 ? EXIT_SUCCESS : EXIT_FAILURE;
} catch (const std::exception& error) {
  std::cerr << "odometry_on_log: " << error.what() << "\n";
  return EXIT_FAILURE;
}
