#include "annotation_log.hpp"

#include <fastdds/rtps/common/SerializedPayload.h>
#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>

#include "pena_dds/operatorPubSubTypes.h"

namespace pena::services {
namespace {

using eprosima::fastrtps::rtps::SerializedPayload_t;

// A record of at most this many bytes (the IDL bounds the sample far below it).
constexpr std::uint32_t kMaxRecordBytes = 1 << 20;

std::string Serialise(const pena_dds::Annotation& sample) {
  pena_dds::AnnotationPubSubType type;
  auto* data = const_cast<pena_dds::Annotation*>(&sample);
  SerializedPayload_t payload(type.getSerializedSizeProvider(data)());
  if (!type.serialize(data, &payload)) {
    throw std::runtime_error("the annotation does not serialise");
  }
  return std::string(reinterpret_cast<const char*>(payload.data), payload.length);
}

bool Deserialise(const std::string& bytes, pena_dds::Annotation& sample) {
  pena_dds::AnnotationPubSubType type;
  SerializedPayload_t payload(static_cast<std::uint32_t>(bytes.size()));
  std::memcpy(payload.data, bytes.data(), bytes.size());
  payload.length = static_cast<std::uint32_t>(bytes.size());
  try {
    return type.deserialize(&payload, &sample);
  } catch (const std::exception&) {
    return false;
  }
}

}  // namespace

AnnotationLog::AnnotationLog(std::filesystem::path path) : path_(std::move(path)) {
  std::string file;
  {
    std::ifstream in(path_, std::ios::binary);
    file.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  std::size_t at = 0;
  while (file.size() - at >= 4) {
    std::uint32_t length = 0;
    std::memcpy(&length, file.data() + at, 4);
    if (length == 0 || length > kMaxRecordBytes) {
      throw std::runtime_error(path_.string() + ": byte " + std::to_string(at) +
                               ": record length " + std::to_string(length) + " is not 1.." +
                               std::to_string(kMaxRecordBytes));
    }
    if (file.size() - at - 4 < length) break;  // torn by a crash while writing
    std::string bytes = file.substr(at + 4, length);
    pena_dds::Annotation sample;
    if (!Deserialise(bytes, sample)) {
      throw std::runtime_error(path_.string() + ": byte " + std::to_string(at) +
                               ": not an Annotation sample");
    }
    const std::string id = sample.annotation_id().to_string();
    if (!latest_bytes_.contains(id)) order_.push_back(id);
    latest_bytes_[id] = std::move(bytes);
    ++records_;
    at += 4 + length;
  }
  fd_ = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_CLOEXEC, 0644);
  // A torn record is cut off, so that the next one starts where the reader looks for it.
  if (fd_ < 0 || ::ftruncate(fd_, static_cast<off_t>(at)) != 0 ||
      ::lseek(fd_, 0, SEEK_END) < 0) {
    throw std::runtime_error("cannot open " + path_.string() + ": " + std::strerror(errno));
  }
}

AnnotationLog::~AnnotationLog() {
  if (fd_ >= 0) ::close(fd_);
}

void AnnotationLog::Append(const pena_dds::Annotation& sample) {
  const std::string id = sample.annotation_id().to_string();
  std::string bytes = Serialise(sample);
  const auto known = latest_bytes_.find(id);
  if (known != latest_bytes_.end() && known->second == bytes) return;
  const auto length = static_cast<std::uint32_t>(bytes.size());
  std::string record(4, '\0');
  std::memcpy(record.data(), &length, 4);
  record += bytes;
  if (::write(fd_, record.data(), record.size()) != static_cast<ssize_t>(record.size()) ||
      ::fdatasync(fd_) != 0) {
    throw std::runtime_error("cannot append to " + path_.string() + ": " + std::strerror(errno));
  }
  if (known == latest_bytes_.end()) order_.push_back(id);
  latest_bytes_[id] = std::move(bytes);
  ++records_;
}

std::vector<pena_dds::Annotation> AnnotationLog::Latest() const {
  std::vector<pena_dds::Annotation> out;
  for (const std::string& id : order_) {
    pena_dds::Annotation sample;
    Deserialise(latest_bytes_.at(id), sample);  // decoded once when read or written
    out.push_back(std::move(sample));
  }
  return out;
}

}  // namespace pena::services
