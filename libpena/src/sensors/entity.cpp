#include "pena/sensors/entity.hpp"

namespace pena::sensors {

std::string_view ToString(EntityKind kind) {
  return kind == EntityKind::kHuman ? "human" : "robot";
}

std::optional<EntityKind> ParseEntityKind(std::string_view text) {
  if (text == "human") return EntityKind::kHuman;
  if (text == "robot") return EntityKind::kRobot;
  return std::nullopt;
}

}  // namespace pena::sensors
