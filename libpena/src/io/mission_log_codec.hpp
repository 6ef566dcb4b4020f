#pragma once
// Conversions between libpena types and the mission log schema (idl/pena_log.proto), and the
// checks both the writer and the reader apply. Internal to the io module.

#include <cstddef>
#include <optional>
#include <stdexcept>
#include <string>

#include "pena/io/mission_log.hpp"
#include "pena/sensors/record.hpp"
#include "pena_log.pb.h"

namespace pena::io::detail {

// A bad field in one message; the reader adds path, record index and byte offset.
class FormatError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Empty if `laser` is usable for scans, else what is wrong, naming the field as `name`.field.
std::string CheckGeometry(const sensors::LaserGeometry& laser, const std::string& name);
// True for the all-zero geometry: "no default, every scan carries its own".
bool IsUnsetGeometry(const sensors::LaserGeometry& laser);
// Empty if the writer can store `header`, else what is wrong.
std::string CheckHeader(const MissionLogHeader& header);
// Empty if `stamp_s` may follow `previous_s` in the stream of sensor `sensor` (SensorRecord index).
std::string CheckStamp(std::size_t sensor, double stamp_s, double previous_s);

// Scans whose geometry equals `header_laser` leave it out; ranges become millimetre deltas.
log::Record ToProto(const sensors::SensorRecord& record,
                    const sensors::LaserGeometry& header_laser);
// nullopt for a payload this reader does not know (a record type of a later minor version).
// Throws FormatError for a scan without usable geometry or with a negative range.
std::optional<sensors::SensorRecord> FromProto(const log::Record& record,
                                               const sensors::LaserGeometry& header_laser);

log::MissionLogHeader ToProto(const MissionLogHeader& header);
// Throws FormatError for an unknown entity kind or an unusable laser geometry.
MissionLogHeader FromProto(const log::MissionLogHeader& header);

}  // namespace pena::io::detail
