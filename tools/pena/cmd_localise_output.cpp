// pena localise, its outputs: DIR/trajectory.tum (the anchored poses), status.csv (one line per
// plan round), summary.json, and the errors against a simulated mission's truth.tum.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli_support.hpp"
#include "cmd_localise.hpp"
#include "pena/eval/stamp_matching.hpp"
#include "pena/io/line_csv.hpp"
#include "pena/io/trajectory_io.hpp"
#include "pena/localisation/trajectory_smoother.hpp"

namespace pena::cli::localise {
namespace {

bool InBox(const geometry::Pose2& p, const std::vector<geometry::Segment2>& plan) {
  Eigen::Vector2d lo = plan.front().start_m, hi = lo;
  for (const auto& s : plan) lo = lo.cwiseMin(s.start_m).cwiseMin(s.end_m), hi = hi.cwiseMax(s.start_m).cwiseMax(s.end_m);
  return p.x_m >= lo.x() && p.x_m <= hi.x() && p.y_m >= lo.y() && p.y_m <= hi.y();
}

}  // namespace

geometry::Trajectory Trajectory(const Run& run) {
  geometry::Trajectory out;
  for (const auto& p : run.poses) {
    if (p.anchored) out.push_back({p.stamp_s, p.map_from_body});
  }
  return out;
}

geometry::Trajectory Smoothed(const Run& run, const localisation::TrajectorySmootherOptions& options) {
  geometry::Trajectory out = Trajectory(run);
  const localisation::SmoothedTrajectory smoothed = localisation::SmoothTrajectory(run.poses, options);
  if (!smoothed.solved) return out;
  for (std::size_t i = 0; i < out.size(); ++i) out[i].pose = smoothed.map_from_body[i];
  return out;
}

void WriteStatusCsv(const std::filesystem::path& path, const Run& run) {
  std::ofstream out(path);
  out << "stamp,status,accepted,confidence,score,hits,points,virtual_points,constraint_ratio,"
         "degenerate,along_drop,window_xy_m,window_theta_deg,correction_x,correction_y,correction_theta_deg,"
         "x,y,theta,recast,first_score,ends_corrected,lost\n";
  for (std::size_t i = 0; i < run.rounds.size(); ++i) {
    const localisation::MapCorrection& r = run.rounds[i];
    const geometry::Pose2& c = r.correction;
    const geometry::Pose2& p = r.map_from_body_after;
    out << Fixed(r.stamp_s, 6) << ',' << localisation::ToString(r.status) << ',' << (r.accepted ? 1 : 0)
        << ',' << Fixed(r.confidence, 3) << ',' << Fixed(r.score, 3) << ',' << r.hits << ',' << r.points
        << ',' << r.virtual_points << ',' << Fixed(r.constraint_ratio, 4) << ',' << (r.degenerate ? 1 : 0)
        << ',' << Fixed(r.along_drop, 3) << ',' << Fixed(r.window_xy_m, 3) << ',' << Fixed(r.window_theta_rad / kDeg, 2) << ','
        << Fixed(c.x_m, 4) << ',' << Fixed(c.y_m, 4) << ',' << Fixed(c.theta_rad / kDeg, 3) << ','
        << Fixed(p.x_m, 4) << ',' << Fixed(p.y_m, 4) << ',' << Fixed(p.theta_rad, 5) << ','
        << (r.recast ? 1 : 0) << ',' << Fixed(r.first_score, 3) << ',' << (r.ends_corrected ? 1 : 0) << ','
        << (run.round_lost[i] ? 1 : 0) << '\n';
  }
  if (!out.flush()) throw std::runtime_error(path.string() + ": cannot write");
}

void WriteAdaptedPlan(const std::filesystem::path& out_dir, const Run& run) {
  std::vector<io::LineRow> rows;
  rows.reserve(run.adapted_plan.size());
  for (std::size_t i = 0; i < run.adapted_plan.size(); ++i) {
    rows.push_back({static_cast<std::int64_t>(i), run.adapted_plan[i], ""});
  }
  io::WriteLineCsv(out_dir / "plan-adapted.csv", rows);
  const std::filesystem::path path = out_dir / "plan-shifts.csv";
  std::ofstream out(path);
  out << "id,offset_m,rounds\n";
  for (const localisation::SegmentShift& shift : run.plan_shifts) {
    out << shift.index << ',' << Fixed(shift.offset_m, 4) << ',' << shift.rounds << '\n';
  }
  if (!out.flush()) throw std::runtime_error(path.string() + ": cannot write");
  const std::filesystem::path openings_path = out_dir / "plan-openings.csv";
  std::ofstream openings(openings_path);
  openings << "id,from_m,to_m,rounds,added_id\n";
  for (const localisation::PlanOpening& cut : run.plan_openings) {
    openings << cut.index << ',' << Fixed(cut.from_m, 3) << ',' << Fixed(cut.to_m, 3) << ',' << cut.rounds << ','
             << cut.added_index << '\n';
  }
  if (!openings.flush()) throw std::runtime_error(openings_path.string() + ": cannot write");
}

TruthErrors CompareWithTruth(const geometry::Trajectory& estimate, const geometry::Trajectory& truth,
                             const std::vector<geometry::Segment2>& plan) {
  TruthErrors e;
  double sum_sq = 0.0, sum_all_sq = 0.0, heading_sq = 0.0;
  long all = 0;
  bool was_in = true;
  double since_entry_m = 1e9;
  std::optional<geometry::Pose2> last_truth;
  std::optional<double> recovering;
  for (const auto& est : estimate) {
    const auto index = eval::FindStamp(truth, est.stamp_s);
    if (!index) continue;
    const geometry::Pose2& t = truth[*index].pose;
    if (last_truth) since_entry_m += std::hypot(t.x_m - last_truth->x_m, t.y_m - last_truth->y_m);
    last_truth = t;
    const bool in = InBox(t, plan);
    if (in && !was_in) since_entry_m = 0.0, recovering = 0.0;
    was_in = in;
    const double err = std::hypot(est.pose.x_m - t.x_m, est.pose.y_m - t.y_m);
    if (!in) { ++e.outside; continue; }
    if (recovering && err < 0.15) e.recovery_m.push_back(since_entry_m), recovering.reset();
    sum_all_sq += err * err, ++all;
    if (since_entry_m < 5.0) continue;
    const double dh = geometry::NormalizeAngle(est.pose.theta_rad - t.theta_rad) / kDeg;
    sum_sq += err * err, heading_sq += dh * dh, ++e.in_map;
  }
  if (recovering) e.recovery_m.push_back(-1.0);  // never recovered
  const double n = static_cast<double>(e.in_map);
  if (e.in_map > 0) e.in_map_rms_m = std::sqrt(sum_sq / n), e.in_map_heading_rms_deg = std::sqrt(heading_sq / n);
  if (all > 0) e.all_in_map_rms_m = std::sqrt(sum_all_sq / static_cast<double>(all));
  return e;
}

std::vector<LostInterval> LostIntervals(const Run& run) {
  std::vector<LostInterval> out;
  const localisation::LocalisedPose* last = nullptr;
  for (const auto& p : run.poses) {
    const bool open = !out.empty() && !out.back().to_s;
    if (p.lost && !open) out.push_back({p.stamp_s, std::nullopt, 0.0});
    else if (!p.lost && open) out.back().to_s = p.stamp_s;
    if (p.lost && last) {
      const geometry::Pose2& a = last->odometry.world_from_body;
      const geometry::Pose2& b = p.odometry.world_from_body;
      out.back().walked_m += std::hypot(b.x_m - a.x_m, b.y_m - a.y_m);
    }
    last = &p;
  }
  return out;
}

Counts CountRun(const Run& run) {
  Counts c;
  for (const auto& r : run.rounds) {
    ++c.rounds;
    if (r.accepted) ++c.accepted, c.mean_confidence += r.confidence;
    if (r.status == localisation::MapStatus::kReacquired) ++c.reacquired;
    if (r.status == localisation::MapStatus::kOutsideMap) ++c.outside_rounds;
    if (r.ends_corrected) ++c.ends_corrected;
  }
  for (const auto& p : run.poses) c.outside_scans += p.status == localisation::MapStatus::kOutsideMap ? 1 : 0;
  if (c.accepted > 0) c.mean_confidence /= static_cast<double>(c.accepted);
  return c;
}

std::string GlobalJson(const Run& run) {
  if (!run.global) return "null";
  std::string out = "{\"stamp\": " + Fixed(run.global_stamp_s, 6) + ", \"attempts\": " +
                    std::to_string(run.global_attempts) + ", \"margin\": " + Fixed(run.global->margin, 3) +
                    ", \"hypotheses\": [";
  for (std::size_t i = 0; i < run.global->hypotheses.size(); ++i) {
    const auto& h = run.global->hypotheses[i];
    out += (i ? ", " : "") + std::string("{\"x\": ") + Fixed(h.map_from_body.x_m, 3) + ", \"y\": " +
           Fixed(h.map_from_body.y_m, 3) + ", \"theta_deg\": " + Fixed(h.map_from_body.theta_rad / kDeg, 2) +
           ", \"score\": " + Fixed(h.score, 3) + "}";
  }
  return out + "]}";
}

std::string TruthJson(const std::optional<TruthErrors>& e) {
  if (!e) return "null";
  std::string recovery = "[";
  for (std::size_t i = 0; i < e->recovery_m.size(); ++i) recovery += (i ? ", " : "") + Fixed(e->recovery_m[i], 2);
  return "{\"in_map_scans\": " + std::to_string(e->in_map) + ", \"outside_scans\": " + std::to_string(e->outside) +
         ", \"in_map_rms_m\": " + Fixed(e->in_map_rms_m, 4) + ", \"in_map_heading_rms_deg\": " +
         Fixed(e->in_map_heading_rms_deg, 3) + ", \"all_in_map_rms_m\": " + Fixed(e->all_in_map_rms_m, 4) +
         ", \"recovery_walk_m\": " + recovery + "]}";
}

// The walls plan adaptation moved: [{"id": i, "offset_m": o, "rounds": n}, ...].
std::string ShiftsJson(const Run& run) {
  std::string json = "[";
  for (const localisation::SegmentShift& shift : run.plan_shifts) {
    if (json.size() > 1) json += ", ";
    json += "{\"id\": " + std::to_string(shift.index) + ", \"offset_m\": " + Fixed(shift.offset_m, 4) +
            ", \"rounds\": " + std::to_string(shift.rounds) + "}";
  }
  return json + "]";
}

// The openings plan adaptation cut: [{"id": i, "from_m": a, "to_m": b, "rounds": n}, ...].
std::string OpeningsJson(const Run& run) {
  std::string json = "[";
  for (const localisation::PlanOpening& cut : run.plan_openings) {
    if (json.size() > 1) json += ", ";
    json += "{\"id\": " + std::to_string(cut.index) + ", \"from_m\": " + Fixed(cut.from_m, 3) +
            ", \"to_m\": " + Fixed(cut.to_m, 3) + ", \"rounds\": " + std::to_string(cut.rounds) + "}";
  }
  return json + "]";
}

// The lost stretches: [{"from": s, "to": s or null, "walked_m": m}, ...].
std::string LostJson(const Run& run) {
  std::string json = "[";
  for (const LostInterval& lost : LostIntervals(run)) {
    if (json.size() > 1) json += ", ";
    json += "{\"from\": " + Fixed(lost.from_s, 6) + ", \"to\": " + (lost.to_s ? Fixed(*lost.to_s, 6) : "null") +
            ", \"walked_m\": " + Fixed(lost.walked_m, 2) + "}";
  }
  return json + "]";
}

void WriteSummary(const std::filesystem::path& path, const LocaliseArgs& args, const Run& run,
                  const std::optional<TruthErrors>& truth, const std::optional<TruthErrors>& truth_online) {
  const Counts c = CountRun(run);
  std::ofstream out(path);
  out << "{\"log\": " << JsonString(args.log) << ", \"map\": " << JsonString(args.map)
      << ", \"start_pose_source\": " << JsonString(run.start_source) << ", \"records\": " << run.records
      << ", \"scans\": " << run.poses.size() << ", \"rounds\": " << c.rounds << ", \"accepted\": " << c.accepted
      << ", \"reacquired\": " << c.reacquired << ", \"ends_corrected\": " << c.ends_corrected
      << ", \"outside_rounds\": " << c.outside_rounds
      << ", \"outside_scans\": " << c.outside_scans << ", \"mean_confidence\": " << Fixed(c.mean_confidence, 3)
      << ", \"lost_intervals\": " << LostJson(run)
      << ", \"global\": " << GlobalJson(run) << ", \"plan_shifts\": " << ShiftsJson(run)
      << ", \"plan_openings\": " << OpeningsJson(run)
      << ", \"truth\": " << TruthJson(truth);
  if (args.smooth) out << ", \"smoothed\": true, \"truth_online\": " << TruthJson(truth_online);
  out << ", \"processing_wall_s\": " << Fixed(run.wall_s, 3) << "}\n";
  if (!out.flush()) throw std::runtime_error(path.string() + ": cannot write");
}

// truth.tum next to a simulated entity's native log, if there is one.
geometry::Trajectory TruthNextTo(const io::LogSource& source) {
  const std::filesystem::path truth = source.description().path.parent_path() / "truth.tum";
  if (source.description().format != "pena-log" || !std::filesystem::exists(truth)) return {};
  return io::ReadTum(truth);
}

}  // namespace pena::cli::localise
