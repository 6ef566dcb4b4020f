#pragma once
// Thresholds of the test for returns that move with a walking person (odometry::internal::
// WalkerFixedPoints, docs/odometry.md thirteenth round); a field of LaserOdometryOptions.

namespace pena::odometry {

// Thresholds of the test; lengths in metres. Checked by WalkerFixedPoints' constructor.
struct WalkerFixedPointsOptions {
  // Motion along the previous scan's x axis (the laser's heading, either way) the motion prior
  // must show between the two scans; below it nothing is dropped. A line across the heading that
  // moves sideways with the walker (a side step) matches itself shifted along its length, so
  // only this component tells it apart. A body-fixed return lies this far from its
  // motion-compensated position, so it must exceed static_m (0.15 m: walking at 0.6 m/s or more
  // at 4 Hz; a person standing or turning on the spot is never filtered).
  double min_forward_m = 0.15;
  // "The same place in the body frame": within body_along_m along the laser's x axis and
  // body_across_m across it of a previous return. Along x it is wide because a floor line does
  // not stay put: it lies h / sin(pitch) ahead, and the gait's pitch bob (+-1.5 deg) moves it by
  // h / sin^2(pitch) per radian, 0.9 m peak to peak at a 15 deg bend and 1.2 m height (0.4-1 m
  // between consecutive scans on loop170 seed 8). Across x it only needs to cover the point
  // spacing (0.5 deg beams: 4-5 cm at 5 m).
  double body_along_m = 1.5;
  double body_across_m = 0.15;
  // "Near a motion-compensated previous return": within static_m of the outline of the previous
  // scan moved by the motion prior (consecutive returns joined when at most outline_max_gap_m
  // apart, or when their bearings bracket the return's: a wall seen at grazing incidence, its
  // returns up to metres apart far down a corridor, stays one surface). Sized
  // for the prior's error over one scan interval (a few cm with the stride carried forward) plus
  // static_per_range_m per metre of range: a tilting laser's plane cuts a static wall a little
  // elsewhere at every scan (office seed 1 at 67.25 s: a wall 5-9 m ahead 0.11-0.14 m off its
  // position moved by the true motion, with 3-8 deg of pitch and +-2.5 deg of roll sway).
  double static_m = 0.12;
  double static_per_range_m = 0.02;
  double outline_max_gap_m = 0.5;
  // Turning faster than this between the two scans: nothing is dropped. In a turn the walker
  // slows down and the stride carried forward overstates the motion (office seed 1 at 65.75 s, a
  // 37 deg turn: the prior 0.2 m, the truth 0.08 m), so nearby walls fail the static test.
  double max_turn_rad = 0.1;
  // Only runs of at least this many consecutive marked returns (beam order) are dropped: a floor
  // line is 20-50 neighbouring beams; many of the walls that fail the test by chance (an
  // occlusion edge, a wall the tilt moved) come a few returns at a time.
  int min_run_points = 5;
  // More than this fraction of the scan found moving with the body: the motion prior is the
  // suspect (a stop it has not seen yet), so nothing is dropped. A floor line is 10-15 %.
  double max_fraction = 0.25;
};

}  // namespace pena::odometry
