#include "pena/sim/mission_picture.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "pena/geometry/pose2.hpp"

namespace pena::sim {
namespace {

const std::array<cv::Scalar, 5> kEntityColors = {viz::colors::kBlue, viz::colors::kRed,
                                                 viz::colors::kGreen, viz::colors::kPurple,
                                                 viz::colors::kTeal};

cv::Scalar Lighter(const cv::Scalar& color) { return 0.5 * color + 0.5 * viz::colors::kWhite; }

// The world box holding walls, plan and paths, with half a metre around.
void Bounds(const Scenario& scenario, const SimulationResult& result, Eigen::Vector2d& min_m,
            Eigen::Vector2d& max_m) {
  min_m = Eigen::Vector2d::Constant(1e300);
  max_m = Eigen::Vector2d::Constant(-1e300);
  const auto grow = [&](const Eigen::Vector2d& point) {
    min_m = min_m.cwiseMin(point);
    max_m = max_m.cwiseMax(point);
  };
  const auto grow_walls = [&](const std::vector<geometry::Segment2>& walls) {
    for (const auto& wall : walls) {
      grow(wall.start_m);
      grow(wall.end_m);
    }
  };
  grow_walls(scenario.walls);
  if (scenario.apriori) grow_walls(*scenario.apriori);
  for (const auto& entity : result.entities) {
    for (const auto& pose : entity.truth)
      grow({pose.world_from_body.x_m, pose.world_from_body.y_m});
  }
  if (min_m.x() > max_m.x()) min_m = max_m = Eigen::Vector2d::Zero();
  min_m -= Eigen::Vector2d::Constant(0.5);
  max_m += Eigen::Vector2d::Constant(0.5);
}

// The scan's returns as the 2D laser would report them, placed at the true pose: floor and
// ceiling hits show up where a 2D algorithm would put them.
std::vector<Eigen::Vector2d> ScanPoints(const sensors::LaserScan& scan,
                                        const geometry::Pose2& world_from_body) {
  std::vector<Eigen::Vector2d> points;
  for (std::size_t b = 0; b < scan.ranges_m.size(); ++b) {
    if (!scan.IsReturn(b)) continue;
    const double r = scan.ranges_m[b];
    const double a = scan.BeamAngle(b);
    points.push_back(geometry::TransformPoint(world_from_body, {r * std::cos(a), r * std::sin(a)}));
  }
  return points;
}

void DrawEntity(viz::MapCanvas& canvas, const EntityRecording& entity, const cv::Scalar& color,
                int scans_to_draw) {
  std::vector<Eigen::Vector2d> path;
  for (const auto& pose : entity.truth)
    path.push_back({pose.world_from_body.x_m, pose.world_from_body.y_m});
  // Scans spread evenly: scan k of n at index k * (count - 1) / (n - 1).
  std::vector<const sensors::LaserScan*> scans;
  for (const auto& record : entity.records) {
    if (const auto* scan = std::get_if<sensors::LaserScan>(&record)) scans.push_back(scan);
  }
  const std::size_t count =
      std::min<std::size_t>(scans.size(), static_cast<std::size_t>(std::max(scans_to_draw, 0)));
  for (std::size_t k = 0; k < count; ++k) {
    const std::size_t index = count == 1 ? 0 : k * (scans.size() - 1) / (count - 1);
    canvas.DrawPoints(ScanPoints(*scans[index], entity.truth[index].world_from_body),
                      Lighter(color), 1);
  }
  canvas.DrawPolyline(path, color, 2);
  if (!path.empty()) {
    canvas.DrawPoints({path.front()}, color, 4);
    canvas.DrawText(path.front() + Eigen::Vector2d(0.3, 0.3), entity.id, color);
  }
}

}  // namespace

cv::Mat RenderMission(const Scenario& scenario, const SimulationResult& result,
                      const MissionPictureOptions& options) {
  Eigen::Vector2d min_m, max_m;
  Bounds(scenario, result, min_m, max_m);
  viz::MapCanvas canvas(min_m, max_m, options.canvas);
  for (const SmokeZone& zone : scenario.smoke) {
    canvas.DrawBox(zone.area.min_m, zone.area.max_m, viz::colors::kLightGray, true);
  }
  for (const MagneticDisturbance& zone : scenario.magnetic) {
    canvas.DrawCircle(zone.center_m, zone.radius_m, viz::colors::kPurple, 1);
  }
  if (scenario.apriori) canvas.DrawSegments(*scenario.apriori, viz::colors::kOrange, 4);
  canvas.DrawSegments(scenario.walls, viz::colors::kBlack, 2);
  canvas.AddLegendEntry("true walls", viz::colors::kBlack);
  if (scenario.apriori) canvas.AddLegendEntry("a priori plan", viz::colors::kOrange);
  if (!scenario.smoke.empty()) canvas.AddLegendEntry("smoke", viz::colors::kLightGray);
  if (!scenario.magnetic.empty())
    canvas.AddLegendEntry("magnetic disturbance", viz::colors::kPurple);
  for (std::size_t e = 0; e < result.entities.size(); ++e) {
    const cv::Scalar& color = kEntityColors[e % kEntityColors.size()];
    DrawEntity(canvas, result.entities[e], color, options.scans_per_entity);
    canvas.AddLegendEntry(result.entities[e].id + " true path", color);
    canvas.AddLegendEntry(result.entities[e].id + " scans at true pose", Lighter(color));
  }
  canvas.DrawScaleBar();
  canvas.DrawLegend();
  return canvas.image().clone();
}

}  // namespace pena::sim
