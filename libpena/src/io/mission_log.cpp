#include "pena/io/mission_log.hpp"

#include <zlib.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <variant>

#include "mission_log_codec.hpp"
#include "pena/io/input_error.hpp"
#include "pena/io/log_summary.hpp"

// Layout (docs/mission-log.md): magic (8) | major u16 LE | minor u16 LE | header frame | record
// frames. A frame is varint(size) | message | crc32 LE of varint and message. The file is read
// through zlib's gzFile, so a gzip-compressed log reads the same as a plain one; offsets in errors
// count uncompressed bytes. Conversions to and from the schema are in mission_log_codec.cpp.

namespace pena::io {
namespace {

using detail::FormatError;

constexpr std::array<char, 8> kMagic = {'\x89', 'P', 'E', 'N', 'A', 'L', 'O', 'G'};
constexpr std::uint16_t kMinorVersion = 2;  // 1: LaserGeometry.sweep_s; 2: .interlace
constexpr std::uint64_t kMaxFrameBytes = 64u << 20;  // far above any real record; guards a bad size
// A crashed recorder loses at most this much log time or data (sync points of the stream).
constexpr double kFlushEveryS = 1.0;
constexpr std::size_t kFlushEveryBytes = 256u << 10;

std::array<double, kSensorKindCount> NoStamps() {
  std::array<double, kSensorKindCount> stamps{};
  stamps.fill(-std::numeric_limits<double>::infinity());
  return stamps;
}

}  // namespace

// ------------------------------------------------------------------------------------------------

struct MissionLogWriter::Impl {
  std::filesystem::path path;
  gzFile file = nullptr;
  sensors::LaserGeometry header_laser;
  std::array<double, kSensorKindCount> last_stamp_s = NoStamps();
  double flushed_stamp_s = std::numeric_limits<double>::quiet_NaN();
  std::size_t unflushed_bytes = 0;
  std::string frame;

  // Here, not in ~MissionLogWriter, so that a constructor that throws still closes the file.
  ~Impl() {
    if (file != nullptr) gzclose(file);
  }

  [[noreturn]] void Fail(const std::string& what) const {
    throw std::runtime_error("mission log " + path.string() + ": " + what);
  }

  void WriteBytes(const char* data, std::size_t size) {
    if (gzwrite(file, data, static_cast<unsigned>(size)) != static_cast<int>(size)) {
      int code = 0;
      const char* message = gzerror(file, &code);
      Fail(std::string("write failed: ") + (code == Z_ERRNO ? std::strerror(errno) : message));
    }
    unflushed_bytes += size;
  }

  void WriteFrame(const google::protobuf::MessageLite& message) {
    const std::size_t size = message.ByteSizeLong();
    if (size > kMaxFrameBytes) {
      throw std::invalid_argument("mission log " + path.string() + ": record of " +
                                  std::to_string(size) + " bytes exceeds the format's limit of " +
                                  std::to_string(kMaxFrameBytes));
    }
    frame.clear();
    for (std::uint64_t rest = size;; rest >>= 7) {  // varint: 7 bits per byte, low first
      frame.push_back(static_cast<char>((rest & 0x7Fu) | (rest >= 0x80u ? 0x80u : 0u)));
      if (rest < 0x80u) break;
    }
    const std::size_t body = frame.size();
    frame.resize(body + size + 4);
    message.SerializeWithCachedSizesToArray(reinterpret_cast<std::uint8_t*>(frame.data() + body));
    const uLong crc =
        crc32(0L, reinterpret_cast<const Bytef*>(frame.data()), static_cast<uInt>(body + size));
    for (std::size_t i = 0; i < 4; ++i) {
      frame[body + size + i] = static_cast<char>((crc >> (8 * i)) & 0xFFu);
    }
    WriteBytes(frame.data(), frame.size());
  }

  // Sync points let a reader recover everything before a crash of the recording process.
  void MaybeFlush(double stamp_s) {
    if (std::isnan(flushed_stamp_s)) flushed_stamp_s = stamp_s;
    if (stamp_s - flushed_stamp_s < kFlushEveryS && unflushed_bytes < kFlushEveryBytes) return;
    if (gzflush(file, Z_SYNC_FLUSH) != Z_OK)
      Fail("flush failed: " + std::string(std::strerror(errno)));
    flushed_stamp_s = stamp_s;
    unflushed_bytes = 0;
  }
};

MissionLogWriter::MissionLogWriter(const std::filesystem::path& path,
                                   const MissionLogHeader& header)
    : impl_(std::make_unique<Impl>()) {
  impl_->path = path;
  if (const std::string problem = detail::CheckHeader(header); !problem.empty()) {
    throw std::invalid_argument("mission log " + path.string() + ": " + problem);
  }
  impl_->header_laser = header.laser;
  // Compressed when the name ends in .gz (a third to half smaller, see the doc); "T" = plain.
  const char* mode = path.extension() == ".gz" ? "wb6" : "wbT";
  impl_->file = gzopen(path.c_str(), mode);
  if (impl_->file == nullptr) impl_->Fail("cannot create: " + std::string(std::strerror(errno)));
  std::array<char, kMagic.size() + 4> preamble{};
  std::memcpy(preamble.data(), kMagic.data(), kMagic.size());
  const std::array<std::uint16_t, 2> version = {
      static_cast<std::uint16_t>(kMissionLogFormatVersion), kMinorVersion};
  for (std::size_t i = 0; i < 2; ++i) {
    preamble[kMagic.size() + 2 * i] = static_cast<char>(version[i] & 0xFFu);
    preamble[kMagic.size() + 2 * i + 1] = static_cast<char>(version[i] >> 8);
  }
  impl_->WriteBytes(preamble.data(), preamble.size());
  impl_->WriteFrame(detail::ToProto(header));
}

MissionLogWriter::~MissionLogWriter() = default;

void MissionLogWriter::Write(const sensors::SensorRecord& record) {
  if (impl_->file == nullptr) impl_->Fail("write after Close()");
  const double stamp_s = sensors::StampOf(record);
  double& last_stamp_s = impl_->last_stamp_s[record.index()];
  if (const std::string problem = detail::CheckStamp(record.index(), stamp_s, last_stamp_s);
      !problem.empty()) {
    throw std::invalid_argument("mission log " + impl_->path.string() + ": " + problem);
  }
  if (const auto* scan = std::get_if<sensors::LaserScan>(&record)) {
    if (const std::string problem = detail::CheckGeometry(scan->geometry, "scan.geometry");
        !problem.empty()) {
      throw std::invalid_argument("mission log " + impl_->path.string() + ": " + problem);
    }
  }
  impl_->WriteFrame(detail::ToProto(record, impl_->header_laser));
  last_stamp_s = stamp_s;
  impl_->MaybeFlush(stamp_s);
}

void MissionLogWriter::Close() {
  if (impl_->file == nullptr) return;
  const int result = gzclose(impl_->file);
  impl_->file = nullptr;
  if (result != Z_OK)
    impl_->Fail("close failed (data may be lost): " + std::string(std::strerror(errno)));
}

// ------------------------------------------------------------------------------------------------

struct MissionLogReader::Impl {
  std::filesystem::path path;
  gzFile file = nullptr;
  MissionLogHeader header;
  LogDescription description;
  std::uint64_t offset = 0;  // uncompressed bytes consumed
  bool cut_gzip = false;     // the gzip stream ended without its trailer
  std::size_t index = 0;     // records read after the header (the header is record 0)
  std::array<double, kSensorKindCount> last_stamp_s = NoStamps();
  std::string frame;

  // Here, not in ~MissionLogReader, so that a constructor that throws still closes the file.
  ~Impl() {
    if (file != nullptr) gzclose(file);
  }

  [[noreturn]] void Fail(std::uint64_t at, const std::string& what) const {
    const std::string where = index == 0 ? "header" : "record " + std::to_string(index);
    throw InputError(path, index, where + " at byte offset " + std::to_string(at) + ": " + what);
  }

  // Reads up to `size` bytes; fewer only at the end of the data (a cut gzip stream ends there too).
  std::size_t Read(char* out, std::size_t size, std::uint64_t at) {
    std::size_t done = 0;
    while (done < size) {
      const int got = gzread(file, out + done, static_cast<unsigned>(size - done));
      if (got > 0) {
        done += static_cast<std::size_t>(got);
        continue;
      }
      int code = Z_OK;
      const char* message = gzerror(file, &code);
      if (code == Z_BUF_ERROR) {  // a gzip stream cut short: what came before is still good
        cut_gzip = true;
        break;
      }
      if (got == 0) break;
      Fail(at, std::string("read failed: ") + (code == Z_ERRNO ? std::strerror(errno) : message));
    }
    offset += done;
    return done;
  }

  // Reads one frame into `frame` (message bytes only). False at a clean end of the data.
  bool ReadFrame() {
    const std::uint64_t start = offset;
    std::uint64_t size = 0;
    std::array<char, 10> varint{};
    std::size_t length = 0;
    for (;; ++length) {
      if (length == varint.size()) Fail(start, "corrupt record size (varint too long)");
      if (Read(&varint[length], 1, start) == 0) {
        if (length == 0 && cut_gzip) {
          Fail(start,
               "truncated gzip stream (the recording was cut; the records before are whole)");
        }
        if (length == 0) return false;
        Fail(start, "truncated record (the file ends inside its size)");
      }
      const auto byte = static_cast<unsigned char>(varint[length]);
      size |= static_cast<std::uint64_t>(byte & 0x7Fu) << (7 * length);
      if ((byte & 0x80u) == 0) break;
    }
    ++length;
    if (size > kMaxFrameBytes) {
      Fail(start, "corrupt record size (" + std::to_string(size) + " bytes, limit " +
                      std::to_string(kMaxFrameBytes) + ")");
    }
    frame.resize(length + size + 4);
    std::memcpy(frame.data(), varint.data(), length);
    const std::size_t got = Read(frame.data() + length, size + 4, start);
    if (got < size + 4) {
      Fail(start, "truncated record (the file ends after " + std::to_string(got) + " of " +
                      std::to_string(size + 4) + " bytes)");
    }
    CheckCrc(start, length + size);
    frame.erase(0, length);
    frame.resize(size);
    return true;
  }

  void CheckCrc(std::uint64_t start, std::size_t covered) const {
    const auto* bytes = reinterpret_cast<const unsigned char*>(frame.data());
    std::uint32_t stored = 0;
    for (std::size_t i = 0; i < 4; ++i)
      stored |= static_cast<std::uint32_t>(bytes[covered + i]) << (8 * i);
    const auto computed = static_cast<std::uint32_t>(crc32(0L, bytes, static_cast<uInt>(covered)));
    if (stored != computed) {
      std::array<char, 64> text{};
      std::snprintf(text.data(), text.size(), "stored 0x%08x, computed 0x%08x", stored, computed);
      Fail(start, "corrupt record (CRC mismatch: " + std::string(text.data()) + ")");
    }
  }

  void ReadPreamble() {
    std::array<char, kMagic.size() + 4> preamble{};
    const std::size_t got = Read(preamble.data(), preamble.size(), 0);
    if (got == 0) throw InputError(path, 0, "empty file, not a PeNa mission log");
    if (got < kMagic.size() || !std::equal(kMagic.begin(), kMagic.end(), preamble.begin())) {
      throw InputError(path, 0, "not a PeNa mission log (bad magic bytes)");
    }
    if (got < preamble.size()) throw InputError(path, 0, "truncated preamble (no format version)");
    const auto byte = [&](std::size_t i) { return static_cast<unsigned char>(preamble[i]); };
    const unsigned major = byte(8) | (byte(9) << 8u);
    const unsigned minor = byte(10) | (byte(11) << 8u);
    if (major != kMissionLogFormatVersion) {
      throw InputError(path, 0,
                       "unsupported mission log format version " + std::to_string(major) + "." +
                           std::to_string(minor) + " (this reader reads version " +
                           std::to_string(kMissionLogFormatVersion) + ".x)");
    }
  }

  void ReadHeader() {
    const std::uint64_t start = offset;
    if (!ReadFrame()) Fail(start, "truncated (the file ends before the header record)");
    log::MissionLogHeader proto;
    if (!proto.ParseFromString(frame)) Fail(start, "header record does not parse");
    try {
      header = detail::FromProto(proto);
    } catch (const FormatError& error) {
      Fail(start, error.what());
    }
    description = {path, "pena-log", header.entity_id, header.kind, header.mission};
  }
};

MissionLogReader::MissionLogReader(const std::filesystem::path& path)
    : impl_(std::make_unique<Impl>()) {
  impl_->path = path;
  impl_->description.path = path;
  impl_->file = gzopen(path.c_str(), "rb");
  if (impl_->file == nullptr) {
    throw InputError(path, 0, "cannot open: " + std::string(std::strerror(errno)));
  }
  gzbuffer(impl_->file, 64u << 10);
  impl_->ReadPreamble();
  impl_->ReadHeader();
}

MissionLogReader::~MissionLogReader() = default;

const MissionLogHeader& MissionLogReader::header() const { return impl_->header; }

const LogDescription& MissionLogReader::description() const { return impl_->description; }

std::optional<sensors::SensorRecord> MissionLogReader::Next() {
  Impl& in = *impl_;
  while (true) {
    const std::uint64_t start = in.offset;
    ++in.index;
    if (!in.ReadFrame()) {
      --in.index;  // stays at the last record so that repeated calls keep returning nullopt
      return std::nullopt;
    }
    log::Record proto;
    if (!proto.ParseFromString(in.frame)) in.Fail(start, "record does not parse");
    std::optional<sensors::SensorRecord> record;
    try {
      record = detail::FromProto(proto, in.header.laser);
    } catch (const FormatError& error) {
      in.Fail(start, error.what());
    }
    if (!record) continue;  // a record type from a newer minor version: skip
    double& last_stamp_s = in.last_stamp_s[record->index()];
    const double stamp_s = sensors::StampOf(*record);
    if (const std::string problem = detail::CheckStamp(record->index(), stamp_s, last_stamp_s);
        !problem.empty()) {
      in.Fail(start, problem);
    }
    last_stamp_s = stamp_s;
    return record;
  }
}

bool IsMissionLog(const std::filesystem::path& path) {
  gzFile file = gzopen(path.c_str(), "rb");
  if (file == nullptr) return false;
  std::array<char, kMagic.size()> start{};
  const int got = gzread(file, start.data(), static_cast<unsigned>(start.size()));
  gzclose(file);
  return got == static_cast<int>(start.size()) && start == kMagic;
}

}  // namespace pena::io
