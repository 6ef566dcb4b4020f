#pragma once
// Shared between the files of `pena localise` (cmd_localise.cpp: options and the run over the
// log; cmd_localise_output.cpp: trajectory, status.csv, summary.json and the comparison with a
// simulation's truth; cmd_localise_picture.cpp: localisation.png).

#include <filesystem>
#include <numbers>
#include <opencv2/core/mat.hpp>
#include <optional>
#include <string>
#include <vector>

#include "pena/geometry/segment2.hpp"
#include "pena/geometry/trajectory.hpp"
#include "pena/io/log_source.hpp"
#include "pena/localisation/global_localiser.hpp"
#include "pena/localisation/localised_pose.hpp"
#include "pena/localisation/map_localiser.hpp"
#include "pena/localisation/plan_openings.hpp"
#include "pena/localisation/trajectory_smoother.hpp"
#include "pena/pipeline/entity_pipeline.hpp"

namespace pena::cli::localise {

inline constexpr double kDeg = std::numbers::pi / 180.0;

struct LocaliseArgs {
  std::string log, map, out, start, map_transform;
  double map_scale = 1.0;
  bool global = false;
  bool every_scan = false;
  bool smooth = false;  // --smooth: trajectory.tum smoothed offline, trajectory-online.tum causal
  bool quiet = false;
  io::ReadOptions read;
  std::vector<std::string> settings;  // --set NAME=VALUE (numeric plan-matching options, for sweeps)
};

// Everything the run produced.
struct Run {
  std::vector<localisation::LocalisedPose> poses;
  std::vector<localisation::MapCorrection> rounds;
  std::vector<char> round_lost;  // per round: judged lost after it (LocalisedPose::lost)
  std::optional<localisation::GlobalResult> global;  // the one that anchored the start
  double global_stamp_s = 0.0;
  int global_attempts = 0;
  std::string start_source;
  long records = 0;
  double wall_s = 0.0;
  // With plan adaptation: the walls the rounds moved, and the plan as matched at the end.
  std::vector<localisation::SegmentShift> plan_shifts;
  std::vector<localisation::PlanOpening> plan_openings;
  std::vector<geometry::Segment2> adapted_plan;
};

// Errors against a simulated mission's truth.tum: inside the plan's box (the mapped part) and
// the recovery after each re-entry from outside it.
struct TruthErrors {
  long in_map = 0, outside = 0;
  double in_map_rms_m = 0.0, in_map_heading_rms_deg = 0.0;  // excluding 5 m after re-entries
  double all_in_map_rms_m = 0.0;                            // including them
  std::vector<double> recovery_m;  // per re-entry: walked metres until the error is < 0.15 m
};

// A stretch of the walk judged lost: from the scan it was judged lost at to the scan it was found
// at (none: never found), with the metres walked on odometry meanwhile.
struct LostInterval {
  double from_s = 0.0;
  std::optional<double> to_s;
  double walked_m = 0.0;
};

// The lost stretches of the run, in time order.
std::vector<LostInterval> LostIntervals(const Run& run);

// The rounds of the status timeline, counted.
struct Counts {
  long rounds = 0, accepted = 0, reacquired = 0, outside_rounds = 0, outside_scans = 0, ends_corrected = 0;
  double mean_confidence = 0.0;  // over accepted rounds
};

// The anchored poses of the run, in the plan's frame.
geometry::Trajectory Trajectory(const Run& run);

// The anchored poses smoothed offline (localisation::SmoothTrajectory); the causal ones if the
// optimisation failed.
geometry::Trajectory Smoothed(const Run& run, const localisation::TrajectorySmootherOptions& options);

// DIR/status.csv: one line per plan-matching round (the status timeline).
void WriteStatusCsv(const std::filesystem::path& path, const Run& run);

// The estimate against truth.tum, inside the plan's bounding box and at re-entries into it.
TruthErrors CompareWithTruth(const geometry::Trajectory& estimate, const geometry::Trajectory& truth,
                             const std::vector<geometry::Segment2>& plan);

// The rounds, acceptances, re-acquisitions and stretches outside the plan of the run.
Counts CountRun(const Run& run);

// DIR/summary.json: counts, the global start's hypotheses and the errors against truth.
// With --smooth, `truth_online` holds the causal trajectory's errors ("truth_online").
void WriteSummary(const std::filesystem::path& path, const LocaliseArgs& args, const Run& run,
                  const std::optional<TruthErrors>& truth, const std::optional<TruthErrors>& truth_online);

// --set NAME=VALUE (cmd_localise_settings.cpp): the pipeline's odometry and plan-stage options,
// and with --smooth the smoother's (smooth.NAME); unknown names are errors (AddLocaliseCommand
// refuses smooth.* without --smooth).
void ApplySettings(const std::vector<std::string>& settings, pipeline::EntityPipelineOptions& options);
localisation::TrajectorySmootherOptions SmootherOptions(const std::vector<std::string>& settings);

// DIR/plan-adapted.csv: the plan as matched at the end (line CSV, the input's segment order and
// ids), and DIR/plan-shifts.csv: `id,offset_m,rounds` per moved segment.
void WriteAdaptedPlan(const std::filesystem::path& out_dir, const Run& run);

// truth.tum next to a simulated entity's native log, if there is one (else empty).
geometry::Trajectory TruthNextTo(const io::LogSource& source);

// localisation.png: the plan, the path on it, stretches outside it, re-acquisitions, the true path.
cv::Mat Picture(const Run& run, const std::vector<geometry::Segment2>& plan, const geometry::Trajectory& truth,
                const std::string& title);

}  // namespace pena::cli::localise
