#pragma once
// Options of the pipeline's plan-localisation stage (EntityPipeline::SetPlan): virtual scan
// matching against an a priori plan (paper section 4.2) and its optional parts, an unknown start
// found on the whole plan, lost and found, and relocalisation of a lost entity with a compass
// (docs/localisation.md).

#include "pena/localisation/global_localiser.hpp"
#include "pena/localisation/global_tracker.hpp"
#include "pena/localisation/lost_and_found.hpp"
#include "pena/localisation/map_localiser.hpp"

namespace pena::pipeline {

struct PlanLocalisationOptions {
  // A round at every reference change of the odometry (every scan with map.every_scan).
  localisation::MapLocaliserOptions map;
  // Unknown start: global hypotheses are followed (GlobalTracker) until one wins, then the
  // odometry starts again there; the plan must then be set before the first record.
  bool global_start = false;
  // With a compass, the unknown phase starts at the compass heading and searches within this of
  // it. Radians, >= 0 (0: every heading; entities without a compass search every heading).
  double compass_tolerance_rad = 0.5235987755982988;  // 30 deg
  // How long the unknown phase waits for a first compass sample before searching every heading.
  // Seconds, >= 0.
  double compass_wait_s = 1.0;
  localisation::GlobalLocaliserOptions global;
  localisation::GlobalTrackerOptions tracker;
  // Relocalise a lost entity with a compass by following global hypotheses after this many
  // rejected rounds at the largest window. Rounds, >= 0 (0 = off).
  int relocalise_after_rounds = 0;
  // Relocalisation winners this far off the compass are refused. Radians, > 0.
  double relocalise_compass_tolerance_rad = 0.5235987755982988;  // 30 deg
  // Lost and found once anchored (docs/localisation.md, "Lost and found"). Off here; `pena
  // localise` turns it on.
  localisation::LostAndFoundOptions lost{.enabled = false};
};

// Throws std::invalid_argument naming the field and its unit (the nested localisation options
// are validated when the stage is built, by SetPlan).
void ValidatePlanLocalisationOptions(const PlanLocalisationOptions& options);

}  // namespace pena::pipeline
