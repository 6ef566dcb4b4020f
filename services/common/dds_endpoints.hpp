#pragma once
// Typed DDS writers and readers created from the XML profiles of a TopicSpec. A Reader's
// listener only takes samples and hands them to a callback that enqueues them (WorkQueue):
// the one worker thread that owns the algorithm object does everything else.

#include <array>
#include <chrono>
#include <cstdint>
#include <fastdds/dds/core/status/LivelinessChangedStatus.hpp>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/DataReaderListener.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <algorithm>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "dds_participant.hpp"
#include "topics.hpp"

namespace pena::services {

// A DDS instance or publication handle (16 bytes), comparable and usable as a map key.
using Handle = std::array<std::uint8_t, 16>;

// What the middleware says about a received sample.
struct SampleMeta {
  std::int64_t source_time_ns = 0;     // writer's clock (system clock, ns since the epoch)
  std::int64_t reception_time_ns = 0;  // this process's system clock when taken
  Handle publication;                  // the writer that sent it
};

// A change in how many matched writers are alive (liveliness QoS, lease in pena-qos.xml).
struct LivelinessChange {
  int alive = 0;
  int not_alive = 0;
  int alive_change = 0;
  int not_alive_change = 0;
  Handle publication;  // the writer whose liveliness changed
};

// System clock now, ns since the epoch (the clock Fast DDS stamps source_timestamp with).
std::int64_t NowNs();
// The bytes of a Fast DDS handle.
Handle ToHandle(const eprosima::fastrtps::rtps::InstanceHandle_t& handle);

// A DataWriter of PubSubType::type on spec.name with spec.writer_profile.
template <class PubSubType>
class Writer {
 public:
  using Sample = typename PubSubType::type;

  // Throws DdsError naming topic and profile.
  Writer(Participant& participant, const TopicSpec& spec)
      : participant_(participant), topic_name_(spec.name) {
    writer_ = participant.publisher()->create_datawriter_with_profile(
        participant.GetTopic<PubSubType>(spec.name), spec.writer_profile);
    if (writer_ == nullptr) {
      throw DdsError(std::string("cannot create DDS writer on ") + spec.name + " with profile " +
                     spec.writer_profile);
    }
  }
  ~Writer() { participant_.publisher()->delete_datawriter(writer_); }
  Writer(const Writer&) = delete;
  Writer& operator=(const Writer&) = delete;

  // Publishes one sample; false if the middleware refused it (e.g. reliable history full).
  bool Write(Sample& sample) { return writer_->write(&sample); }
  // Readers currently matched.
  int matched() const {
    eprosima::fastdds::dds::PublicationMatchedStatus status;
    writer_->get_publication_matched_status(status);
    return status.current_count;
  }
  // A reader of the participant whose writer `publication` is (same GUID prefix) is matched.
  // Discovery is asymmetric: a reader can see this writer before this writer sees it, and what
  // is written meanwhile never reaches it (volatile durability).
  bool MatchesParticipantOf(const Handle& publication) const {
    std::vector<eprosima::fastrtps::rtps::InstanceHandle_t> subscriptions;
    // A middleware that cannot list them: do not wait for what cannot be seen.
    if (writer_->get_matched_subscriptions(subscriptions) != ReturnCode_t::RETCODE_OK) return true;
    for (const auto& subscription : subscriptions) {
      const Handle bytes = ToHandle(subscription);
      if (std::equal(publication.begin(), publication.begin() + 12, bytes.begin())) return true;
    }
    return false;
  }
  // Waits until every matched reliable reader acknowledged everything; false on timeout.
  bool WaitForAcknowledgments(double timeout_s) {
    return writer_->wait_for_acknowledgments(eprosima::fastrtps::Duration_t(timeout_s)) ==
           ReturnCode_t::RETCODE_OK;
  }
  const std::string& topic_name() const { return topic_name_; }
  // The history depth its XML profile gave (keep last N).
  int history_depth() const { return writer_->get_qos().history().depth; }

 private:
  Participant& participant_;
  std::string topic_name_;
  eprosima::fastdds::dds::DataWriter* writer_ = nullptr;
};

// A DataReader of PubSubType::type whose listener takes every valid sample and passes it on.
template <class PubSubType>
class Reader {
 public:
  using Sample = typename PubSubType::type;
  // Called on a middleware thread: only enqueue.
  using SampleCallback = std::function<void(Sample&&, const SampleMeta&)>;
  using LivelinessCallback = std::function<void(const LivelinessChange&)>;

  // Throws DdsError naming topic and profile.
  Reader(Participant& participant, const TopicSpec& spec, SampleCallback on_sample,
         LivelinessCallback on_liveliness = {})
      : participant_(participant),
        listener_(participant, std::move(on_sample), std::move(on_liveliness)) {
    subscriber_ = participant.SubscriberFor(spec.name);
    reader_ = subscriber_->create_datareader_with_profile(
        participant.GetTopic<PubSubType>(spec.name), spec.reader_profile, &listener_);
    if (reader_ == nullptr) {
      throw DdsError(std::string("cannot create DDS reader on ") + spec.name + " with profile " +
                     spec.reader_profile);
    }
  }
  ~Reader() {
    reader_->set_listener(nullptr);
    subscriber_->delete_datareader(reader_);
  }
  Reader(const Reader&) = delete;
  Reader& operator=(const Reader&) = delete;

  // Writers currently matched.
  int matched() const {
    eprosima::fastdds::dds::SubscriptionMatchedStatus status;
    reader_->get_subscription_matched_status(status);
    return status.current_count;
  }

 private:
  class Listener : public eprosima::fastdds::dds::DataReaderListener {
   public:
    Listener(Participant& participant, SampleCallback on_sample, LivelinessCallback on_liveliness)
        : participant_(participant),
          on_sample_(std::move(on_sample)),
          on_liveliness_(std::move(on_liveliness)) {}

    void on_data_available(eprosima::fastdds::dds::DataReader* reader) override {
      Sample sample;
      eprosima::fastdds::dds::SampleInfo info;
      while (reader->take_next_sample(&sample, &info) == ReturnCode_t::RETCODE_OK) {
        if (info.valid_data && FromItsEntity(sample, info)) {
          const SampleMeta meta{info.source_timestamp.to_ns(), NowNs(),
                                ToHandle(info.publication_handle)};
          on_sample_(std::move(sample), meta);
        }
        sample = Sample();
      }
    }

    void on_liveliness_changed(
        eprosima::fastdds::dds::DataReader* /*reader*/,
        const eprosima::fastdds::dds::LivelinessChangedStatus& status) override {
      if (!on_liveliness_) return;
      on_liveliness_({status.alive_count, status.not_alive_count, status.alive_count_change,
                      status.not_alive_count_change, ToHandle(status.last_publication_handle)});
    }

   private:
    // A sample keyed by an entity comes from that entity's writer (Participant::
    // AcceptsEntitySample); samples without an entity_id are not checked here.
    bool FromItsEntity(const Sample& sample, const eprosima::fastdds::dds::SampleInfo& info) {
      if constexpr (requires { sample.entity_id().to_string(); }) {
        return participant_.AcceptsEntitySample(info.publication_handle,
                                                sample.entity_id().to_string());
      } else {
        return true;
      }
    }

    Participant& participant_;
    SampleCallback on_sample_;
    LivelinessCallback on_liveliness_;
  };

  Participant& participant_;
  Listener listener_;
  eprosima::fastdds::dds::Subscriber* subscriber_ = nullptr;
  eprosima::fastdds::dds::DataReader* reader_ = nullptr;
};

}  // namespace pena::services
