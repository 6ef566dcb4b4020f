#pragma once
// CARMEN logs: reader (FLASER, ODOM, ROBOTLASER1, RAWLASER1-4; plain or gzip) and writer
// (FLASER, ODOM). Line formats in docs/formats.md.

#include <filesystem>
#include <memory>
#include <ostream>

#include "pena/io/log_source.hpp"
#include "pena/sensors/laser_scan.hpp"
#include "pena/sensors/wheel_odometry.hpp"

namespace pena::io {

// Streams a CARMEN log. Lines of other message types (PARAM, SYNC, TRUEPOS, ...) and comments are
// skipped silently; a malformed line of a known type throws InputError "path:line: what".
std::unique_ptr<LogSource> OpenCarmenLog(const std::filesystem::path& path,
                                         const ReadOptions& options = {});

// Writes FLASER and ODOM lines (ROBOTLASER1 for scans whose beam geometry FLASER cannot express).
// Scans need odometry_pose (or logged_pose) for the pose fields.
class CarmenWriter {
 public:
  explicit CarmenWriter(const std::filesystem::path& path);
  ~CarmenWriter();
  void Write(const sensors::LaserScan& scan);
  void Write(const sensors::WheelOdometry& odometry);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Writes scans as Censi's CSM JSON lines (one laser_data object per line; "nan" no-returns as
// valid=0) so other matchers (sm1/sm2) can run on exactly the same data.
class CsmJsonWriter {
 public:
  explicit CsmJsonWriter(const std::filesystem::path& path);
  ~CsmJsonWriter();
  void Write(const sensors::LaserScan& scan);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace pena::io
