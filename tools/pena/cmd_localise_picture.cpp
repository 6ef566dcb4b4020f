// pena localise, its picture: DIR/localisation.png, drawn like the paper's Fig. 9.
#include <algorithm>
#include <opencv2/core/mat.hpp>
#include <string>
#include <vector>

#include "cmd_localise.hpp"
#include "pena/viz/map_canvas.hpp"

namespace pena::cli::localise {
namespace {
const cv::Scalar kLost{0, 200, 230};    // yellow: lost, searching the plan
const cv::Scalar kFound{255, 0, 255};   // magenta: found again
}  // namespace

// Like the paper's Fig. 9: the plan, the path on it, stretches judged outside the plan in another
// colour, re-acquisitions ringed; the true path (simulation) underneath.
cv::Mat Picture(const Run& run, const std::vector<geometry::Segment2>& plan, const geometry::Trajectory& truth,
                const std::string& title) {
  Eigen::Vector2d lo = plan.front().start_m, hi = lo;
  for (const auto& s : plan) lo = lo.cwiseMin(s.start_m).cwiseMin(s.end_m), hi = hi.cwiseMax(s.start_m).cwiseMax(s.end_m);
  for (const auto& p : run.poses) {
    if (p.anchored) lo = lo.cwiseMin(Eigen::Vector2d(p.map_from_body.x_m, p.map_from_body.y_m)),
                    hi = hi.cwiseMax(Eigen::Vector2d(p.map_from_body.x_m, p.map_from_body.y_m));
  }
  viz::MapCanvasOptions options;
  options.legend_panel_px = 230;
  viz::MapCanvas canvas(lo.array() - 1.0, hi.array() + 1.0, options);
  canvas.DrawSegments(plan, viz::colors::kBlack, 2);
  std::vector<geometry::Segment2> moved;  // where plan adaptation put the walls it moved
  for (const auto& shift : run.plan_shifts) moved.push_back(run.adapted_plan[static_cast<std::size_t>(shift.index)]);
  canvas.DrawSegments(moved, viz::colors::kOrange, 2);
  std::vector<geometry::Segment2> cut;  // stretches of drawn walls the rounds saw through
  for (const auto& opening : run.plan_openings) cut.push_back(opening.stretch);
  canvas.DrawSegments(cut, viz::colors::kWhite, 4);
  canvas.DrawSegments(cut, viz::colors::kTeal, 1);
  std::vector<Eigen::Vector2d> truth_m;
  for (const auto& t : truth) truth_m.emplace_back(t.pose.x_m, t.pose.y_m);
  if (!truth_m.empty()) canvas.DrawPolyline(truth_m, viz::colors::kGreen, 1);
  for (std::size_t i = 1; i < run.poses.size(); ++i) {
    const auto& a = run.poses[i - 1];
    const auto& b = run.poses[i];
    if (!a.anchored || !b.anchored) continue;
    const bool outside = b.status == localisation::MapStatus::kOutsideMap;
    if (b.found) continue;  // the jump to where it was found is no walk
    canvas.DrawSegment({{a.map_from_body.x_m, a.map_from_body.y_m}, {b.map_from_body.x_m, b.map_from_body.y_m}},
                       b.lost ? kLost : outside ? viz::colors::kRed : viz::colors::kBlue, b.lost ? 3 : 2);
  }
  bool any_lost = false, any_found = false;
  for (const auto& p : run.poses) {
    any_lost = any_lost || p.lost;
    if (p.found) {
      any_found = true;
      canvas.DrawCircle({p.map_from_body.x_m, p.map_from_body.y_m}, 0.6, kFound, 2);
    }
  }
  for (const auto& r : run.rounds) {
    if (r.status == localisation::MapStatus::kReacquired || r.status == localisation::MapStatus::kRelocalised) {
      canvas.DrawCircle({r.map_from_body_after.x_m, r.map_from_body_after.y_m}, 0.4, viz::colors::kPurple, 2);
    }
  }
  const auto first = std::find_if(run.poses.begin(), run.poses.end(), [](const auto& p) { return p.anchored; });
  if (first != run.poses.end()) canvas.DrawCircle({first->map_from_body.x_m, first->map_from_body.y_m}, 0.5, viz::colors::kBlack, 2);
  canvas.DrawText(hi + Eigen::Vector2d(-0.5 * (hi.x() - lo.x()), 0.7), title, viz::colors::kBlack);
  canvas.AddLegendEntry("a priori plan", viz::colors::kBlack);
  if (!moved.empty()) canvas.AddLegendEntry("walls moved where seen", viz::colors::kOrange);
  if (!cut.empty()) canvas.AddLegendEntry("walls cut open", viz::colors::kTeal);
  canvas.AddLegendEntry("path, matched on the plan", viz::colors::kBlue);
  canvas.AddLegendEntry("path, outside the plan", viz::colors::kRed);
  canvas.AddLegendEntry("re-acquired", viz::colors::kPurple);
  if (any_lost) canvas.AddLegendEntry("path, lost (searching)", kLost);
  if (any_found) canvas.AddLegendEntry("found again", kFound);
  if (!truth_m.empty()) canvas.AddLegendEntry("true path", viz::colors::kGreen);
  canvas.DrawScaleBar();
  canvas.DrawLegend();
  return canvas.image();
}

}  // namespace pena::cli::localise
