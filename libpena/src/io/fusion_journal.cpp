#include "pena/io/fusion_journal.hpp"

#include <fcntl.h>
#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "pena/io/input_error.hpp"

// Layout (docs/formats.md). Journal file journal-<first sequence>.pfj: magic "PENAFJNL", u32
// version, then frames u32 size | u64 sequence | payload | u32 CRC-32 of size, sequence and
// payload. Checkpoint file checkpoint-<sequence>.pfc: magic "PENAFCKP", u32 version, one frame.
// All integers little-endian. The frame's CRC is the mission log's idea (docs/mission-log.md).

namespace pena::io {
namespace {

namespace fs = std::filesystem;

constexpr std::string_view kJournalMagic = "PENAFJNL";
constexpr std::string_view kCheckpointMagic = "PENAFCKP";
constexpr std::size_t kHeaderBytes = 12;
constexpr std::size_t kFrameOverhead = 16;             // size, sequence, CRC
constexpr std::uint64_t kMaxPayloadBytes = 256u << 20;  // guards a corrupt size

void PutU32(std::string& out, std::uint32_t value) {
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<char>((value >> (8 * i)) & 0xFFu));
}
void PutU64(std::string& out, std::uint64_t value) {
  for (int i = 0; i < 8; ++i) out.push_back(static_cast<char>((value >> (8 * i)) & 0xFFu));
}
std::uint64_t GetLE(std::string_view bytes, std::size_t at, int size) {
  std::uint64_t value = 0;
  for (int i = 0; i < size; ++i) {
    value |= static_cast<std::uint64_t>(static_cast<unsigned char>(bytes[at + static_cast<std::size_t>(i)])) << (8 * i);
  }
  return value;
}
std::uint32_t Crc(std::string_view bytes) {
  return static_cast<std::uint32_t>(
      crc32(0L, reinterpret_cast<const Bytef*>(bytes.data()), static_cast<uInt>(bytes.size())));
}

std::string Header(std::string_view magic) {
  std::string header(magic);
  PutU32(header, kFusionJournalFormatVersion);
  return header;
}

std::string Frame(std::uint64_t sequence, std::string_view payload) {
  std::string frame;
  PutU32(frame, static_cast<std::uint32_t>(payload.size()));
  PutU64(frame, sequence);
  frame.append(payload);
  PutU32(frame, Crc(frame));
  return frame;
}

std::string ReadAll(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("fusion journal: cannot open " + path.string());
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

std::string FileName(const char* prefix, std::uint64_t sequence, const char* extension) {
  std::array<char, 64> name{};
  std::snprintf(name.data(), name.size(), "%s-%020llu%s", prefix,
                static_cast<unsigned long long>(sequence), extension);
  return name.data();
}

// Sequence numbers of the files named prefix-<n>.ext in dir, sorted.
std::map<std::uint64_t, fs::path> List(const fs::path& dir, const std::string& prefix,
                                       const std::string& extension) {
  std::map<std::uint64_t, fs::path> files;
  for (const fs::directory_entry& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    if (name.size() != prefix.size() + 21 + extension.size() || name.rfind(prefix + "-", 0) != 0 ||
        entry.path().extension() != extension) {
      continue;
    }
    const std::string digits = name.substr(prefix.size() + 1, 20);
    if (digits.find_first_not_of("0123456789") != std::string::npos) continue;
    files.emplace(std::stoull(digits), entry.path());
  }
  return files;
}

// One journal file's whole records; a torn last record is reported, not thrown.
struct FileRecords {
  std::vector<JournalRecord> records;
  std::size_t valid_bytes = 0;
  std::string torn;
};

void CheckHeader(std::string_view bytes, std::string_view magic, const fs::path& path) {
  if (bytes.substr(0, magic.size()) != magic) {
    throw InputError(path, 0, "byte 0: not a PeNa fusion file (bad magic)");
  }
  const auto version = static_cast<std::uint32_t>(GetLE(bytes, magic.size(), 4));
  if (version != kFusionJournalFormatVersion) {
    throw InputError(path, 0, "byte 8: format version " + std::to_string(version) +
                                  ", this reader knows " +
                                  std::to_string(kFusionJournalFormatVersion));
  }
}

FileRecords ReadJournalFile(const fs::path& path) {
  const std::string bytes = ReadAll(path);
  FileRecords file;
  if (bytes.size() < kHeaderBytes) {  // created, header not yet written when the crash came
    file.torn = path.string() + ": torn header (" + std::to_string(bytes.size()) + " bytes dropped)";
    return file;
  }
  CheckHeader(bytes, kJournalMagic, path);
  std::size_t at = kHeaderBytes;
  while (at < bytes.size()) {
    const std::size_t left = bytes.size() - at;
    const std::uint64_t size = left >= 4 ? GetLE(bytes, at, 4) : 0;
    const bool whole = left >= kFrameOverhead && size <= kMaxPayloadBytes &&
                       size + kFrameOverhead <= left;
    const std::size_t end = whole ? at + kFrameOverhead + size : bytes.size();
    const bool crc_ok = whole && GetLE(bytes, end - 4, 4) ==
                                     Crc(std::string_view(bytes).substr(at, end - 4 - at));
    if (!crc_ok) {
      if (end < bytes.size()) {
        throw InputError(path, 0, "byte " + std::to_string(at) +
                                      ": corrupt record (CRC mismatch) followed by more data");
      }
      file.torn = path.string() + ": torn record at byte " + std::to_string(at) + " (" +
                  std::to_string(left) + " bytes dropped; the records before it are whole)";
      break;
    }
    file.records.push_back({GetLE(bytes, at + 4, 8), bytes.substr(at + 12, size)});
    at = end;
  }
  file.valid_bytes = std::max(at, kHeaderBytes);
  if (!file.torn.empty()) file.valid_bytes = at;
  return file;
}

JournalRecord ReadCheckpointFile(const fs::path& path) {
  const std::string bytes = ReadAll(path);
  if (bytes.size() < kHeaderBytes + kFrameOverhead) {
    throw InputError(path, 0, "byte 0: checkpoint shorter than its header");
  }
  CheckHeader(bytes, kCheckpointMagic, path);
  const std::uint64_t size = GetLE(bytes, kHeaderBytes, 4);
  if (size + kHeaderBytes + kFrameOverhead != bytes.size() ||
      GetLE(bytes, bytes.size() - 4, 4) !=
          Crc(std::string_view(bytes).substr(kHeaderBytes, bytes.size() - 4 - kHeaderBytes))) {
    throw InputError(path, 0, "byte 12: corrupt checkpoint (size or CRC mismatch)");
  }
  return {GetLE(bytes, kHeaderBytes + 4, 8), bytes.substr(kHeaderBytes + 12, size)};
}

[[noreturn]] void IoFail(const std::string& what, const fs::path& path) {
  throw std::runtime_error("fusion journal " + path.string() + ": " + what + ": " +
                           std::strerror(errno));
}

void WriteAllFd(int fd, std::string_view bytes, const fs::path& path) {
  while (!bytes.empty()) {
    const ssize_t written = ::write(fd, bytes.data(), bytes.size());
    if (written < 0 && errno == EINTR) continue;
    if (written <= 0) IoFail("write failed", path);
    bytes.remove_prefix(static_cast<std::size_t>(written));
  }
}

void SyncDir(const fs::path& dir) {
  const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY);
  if (fd < 0) IoFail("cannot open directory", dir);
  const int result = ::fsync(fd);
  ::close(fd);
  if (result != 0) IoFail("directory sync failed", dir);
}

}  // namespace

struct FusionJournal::Impl {
  fs::path dir;
  FusionJournalOptions options;
  JournalRecovery recovery;
  std::uint64_t next_sequence = 1;
  std::optional<std::uint64_t> previous_checkpoint;  // kept one generation for safety
  fs::path journal_path;
  int fd = -1;

  ~Impl() {
    if (fd >= 0) ::close(fd);
  }

  void Recover() {
    const auto checkpoints = List(dir, "checkpoint", ".pfc");
    std::uint64_t covered = 0;
    if (!checkpoints.empty()) {
      JournalRecord checkpoint = ReadCheckpointFile(checkpoints.rbegin()->second);
      covered = checkpoint.sequence;
      recovery.checkpoint_sequence = covered;
      recovery.checkpoint_payload = std::move(checkpoint.payload);
      if (checkpoints.size() > 1) previous_checkpoint = std::prev(checkpoints.end(), 2)->first;
    }
    const auto journals = List(dir, "journal", ".pfj");
    next_sequence = covered + 1;
    std::size_t valid_bytes = 0;
    for (const auto& [first, path] : journals) {
      FileRecords file = ReadJournalFile(path);
      if (!file.torn.empty()) {
        recovery.torn_tail += (recovery.torn_tail.empty() ? "" : "; ") + file.torn;
      }
      for (JournalRecord& record : file.records) {
        if (record.sequence <= covered) continue;
        if (record.sequence != next_sequence) {
          throw InputError(path, 0, "record " + std::to_string(record.sequence) + " follows " +
                                        std::to_string(next_sequence - 1) +
                                        ": records are missing");
        }
        ++next_sequence;
        recovery.records.push_back(std::move(record));
      }
      journal_path = path;
      valid_bytes = file.valid_bytes;
    }
    if (!journals.empty()) OpenJournal(valid_bytes);
  }

  // Opens journal_path for appending after cutting a torn tail (and writing a missing header).
  void OpenJournal(std::size_t valid_bytes) {
    fd = ::open(journal_path.c_str(), O_WRONLY | O_CREAT, 0644);
    if (fd < 0) IoFail("cannot open", journal_path);
    if (::ftruncate(fd, static_cast<off_t>(valid_bytes)) != 0) IoFail("cannot cut", journal_path);
    if (::lseek(fd, 0, SEEK_END) < 0) IoFail("cannot seek", journal_path);
    if (valid_bytes < kHeaderBytes) {
      if (::ftruncate(fd, 0) != 0) IoFail("cannot cut", journal_path);
      WriteAllFd(fd, Header(kJournalMagic), journal_path);
    }
  }

  void StartJournal() {
    if (fd >= 0) ::close(fd);
    fd = -1;
    journal_path = dir / FileName("journal", next_sequence, ".pfj");
    OpenJournal(0);
    SyncDir(dir);
  }
};

FusionJournal::FusionJournal(const fs::path& dir, FusionJournalOptions options)
    : impl_(std::make_unique<Impl>()) {
  impl_->dir = dir;
  impl_->options = options;
  std::error_code error;
  fs::create_directories(dir, error);
  if (error) {
    throw std::runtime_error("fusion journal " + dir.string() + ": cannot create: " +
                             error.message());
  }
  impl_->Recover();
}

FusionJournal::~FusionJournal() = default;

const JournalRecovery& FusionJournal::recovered() const { return impl_->recovery; }
std::uint64_t FusionJournal::next_sequence() const { return impl_->next_sequence; }
const fs::path& FusionJournal::dir() const { return impl_->dir; }

std::uint64_t FusionJournal::Append(std::string_view payload) {
  if (payload.size() > kMaxPayloadBytes) {
    throw std::invalid_argument("fusion journal: record of " + std::to_string(payload.size()) +
                                " bytes exceeds the format's limit");
  }
  if (impl_->fd < 0) impl_->StartJournal();
  const std::uint64_t sequence = impl_->next_sequence;
  WriteAllFd(impl_->fd, Frame(sequence, payload), impl_->journal_path);
  if (impl_->options.durability == JournalDurability::kFsync && ::fdatasync(impl_->fd) != 0) {
    IoFail("sync failed", impl_->journal_path);
  }
  ++impl_->next_sequence;
  return sequence;
}

void FusionJournal::WriteCheckpoint(std::string_view payload) {
  const std::uint64_t covered = impl_->next_sequence - 1;
  const fs::path path = impl_->dir / FileName("checkpoint", covered, ".pfc");
  const fs::path temporary = fs::path(path).concat(".tmp");
  const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd < 0) IoFail("cannot create", temporary);
  WriteAllFd(fd, Header(kCheckpointMagic) + Frame(covered, payload), temporary);
  const bool synced = ::fsync(fd) == 0;
  ::close(fd);
  if (!synced) IoFail("sync failed", temporary);
  if (::rename(temporary.c_str(), path.c_str()) != 0) IoFail("cannot rename", temporary);
  impl_->StartJournal();  // syncs the directory: the rename is durable too
  // Keep this checkpoint and the previous generation; older files are covered twice over.
  const std::uint64_t keep_from = impl_->previous_checkpoint.value_or(covered);
  for (const auto& [sequence, old] : List(impl_->dir, "checkpoint", ".pfc")) {
    if (sequence < keep_from) fs::remove(old);
  }
  for (const auto& [first, old] : List(impl_->dir, "journal", ".pfj")) {
    if (first <= keep_from && old != impl_->journal_path) fs::remove(old);
  }
  impl_->previous_checkpoint = covered;
}

}  // namespace pena::io
