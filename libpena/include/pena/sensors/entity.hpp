#pragma once
// What kind of rescue-team member carries the sensors.

#include <optional>
#include <string>
#include <string_view>

namespace pena::sensors {

// A firefighter (dead reckoning from gyro, compass, stride sensor; tilting laser) or a robot
// (wheel odometry; level laser).
enum class EntityKind { kHuman, kRobot };

// "human" or "robot".
std::string_view ToString(EntityKind kind);

// Parses "human" / "robot"; nullopt otherwise.
std::optional<EntityKind> ParseEntityKind(std::string_view text);

}  // namespace pena::sensors
