// Shared by the odometry tests: an option out of range is refused with a message naming it.
#pragma once

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "pena/odometry/laser_odometry.hpp"

namespace pena::odometry::testing {

// A person's odometry with `options` is refused with a message naming `field`.
inline void ExpectRefused(const LaserOdometryOptions& options, const std::string& field) {
  try {
    LaserOdometry odometry(options, sensors::EntityKind::kHuman, {}, 0.0);
    ADD_FAILURE() << "accepted " << field;
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find(field), std::string::npos) << error.what();
  }
}

}  // namespace pena::odometry::testing
