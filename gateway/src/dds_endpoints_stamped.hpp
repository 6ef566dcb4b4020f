#pragma once
// A DataWriter whose samples carry a given source timestamp: the far gateway republishes each
// sample with the wall-clock time the original was written, so a subscriber's
// reception - source time is the age across the link (fusion's pose-age statistics use it).

#include <cmath>
#include <cstdint>
#include <fastdds/dds/common/InstanceHandle.hpp>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/rtps/common/Time_t.h>
#include <string>

#include "dds_participant.hpp"
#include "topics.hpp"

namespace pena::gateway {

template <class PubSubType>
class StampedWriter {
 public:
  using Sample = typename PubSubType::type;

  // Throws services::DdsError naming topic and profile.
  StampedWriter(services::Participant& participant, const services::TopicSpec& spec)
      : participant_(participant) {
    writer_ = participant.publisher()->create_datawriter_with_profile(
        participant.GetTopic<PubSubType>(spec.name), spec.writer_profile);
    if (writer_ == nullptr) {
      throw services::DdsError(std::string("cannot create DDS writer on ") + spec.name +
                               " with profile " + spec.writer_profile);
    }
  }
  ~StampedWriter() { participant_.publisher()->delete_datawriter(writer_); }
  StampedWriter(const StampedWriter&) = delete;
  StampedWriter& operator=(const StampedWriter&) = delete;

  // Publishes `sample` with source timestamp `stamp_s` (wall seconds since the epoch).
  bool Write(Sample& sample, double stamp_s) {
    const double whole_s = std::floor(stamp_s);
    const eprosima::fastrtps::Time_t time(static_cast<std::int32_t>(whole_s),
                                          static_cast<std::uint32_t>((stamp_s - whole_s) * 1e9));
    return writer_->write_w_timestamp(&sample, eprosima::fastdds::dds::HANDLE_NIL, time) ==
           ReturnCode_t::RETCODE_OK;
  }
  // Readers currently matched.
  int matched() const {
    eprosima::fastdds::dds::PublicationMatchedStatus status;
    writer_->get_publication_matched_status(status);
    return status.current_count;
  }

 private:
  services::Participant& participant_;
  eprosima::fastdds::dds::DataWriter* writer_ = nullptr;
};

}  // namespace pena::gateway
