#pragma once
// RAII around a Fast DDS 2.9 DomainParticipant created from an XML profile (never the built-in
// default), with one publisher, one subscriber and the topics its writers and readers share.
// Shape after the Fast DDS examples: the constructor throws DdsError, the destructor deletes
// every contained entity and then the participant.

#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/domain/DomainParticipantListener.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/topic/Topic.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>
#include <array>
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <map>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

#include "dds_sample_bounds.hpp"

namespace pena::services {

// A DDS entity could not be created (names the entity and the profile).
class DdsError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Where the participant's and the endpoints' QoS come from.
struct DdsOptions {
  // XML profile files loaded in order before the participant is created (absolute paths).
  std::vector<std::filesystem::path> profiles_files;
  // The participant profile; "pena_loopback" keeps every packet on this machine.
  std::string participant_profile = "pena_loopback";
  // DDS domain; tests use their own so parallel runs do not meet.
  int domain_id = 0;
  // DDS Security: this participant's identity directory (deploy/security/make-identities.sh;
  // docs/security.md). Empty: none configured here; the participant is then open unless its XML
  // profile configures security itself.
  std::filesystem::path security_dir;
  // The partition this participant's writers publish in; empty: the default partition, or with
  // own_partition the secured participant's own (its certificate's common name). A secured
  // entity writes in the partition of its id, the only one its permissions allow.
  std::string publish_partition;
  bool own_partition = false;
};

// Where the default profile files live: $PENA_DDS_DIR when set, else share/pena/dds beside an
// installed binary (<prefix>/bin/..), else deploy/dds of the source tree this was built from.
std::filesystem::path DefaultDdsDir();

// The default profile files: pena-loopback.xml and pena-qos.xml of DefaultDdsDir().
std::vector<std::filesystem::path> DefaultProfilesFiles();

// Loads an XML profile file once per process (later calls for the same file do nothing).
// Throws DdsError naming the file if Fast DDS rejects it.
void LoadProfilesFile(const std::filesystem::path& path);

// The generated type with a deserialize that refuses (false) every payload it cannot read. The
// generated code catches only NotEnoughMemoryException, so a sample from any peer with, e.g., a
// bad encapsulation header (BadParamException) would escape take_next_sample and end the
// process; and it sizes a Segment's provenance list from the wire unchecked, so the lists are
// checked against their bounds first (dds_sample_bounds.hpp). Every topic of a Participant
// registers its type this way.
template <class PubSubType>
class CheckedType : public PubSubType {
 public:
  bool deserialize(eprosima::fastrtps::rtps::SerializedPayload_t* payload, void* data) override {
    try {
      if (!SampleKeepsBounds(*payload, static_cast<const typename PubSubType::type*>(nullptr))) {
        return false;
      }
      return PubSubType::deserialize(payload, data);
    } catch (const std::exception&) {
      return false;
    }
  }
};

// A participant with its publisher, subscriber and topics.
class Participant {
 public:
  // Loads the profile files, then creates the participant from participant_profile, secured
  // when options.security_dir or the profile configures DDS Security. The security files are
  // checked first (CheckSecurityFiles): a missing or invalid one throws DdsError naming it; it
  // never falls back to an open participant.
  Participant(const DdsOptions& options, const std::string& name);
  ~Participant();
  Participant(const Participant&) = delete;
  Participant& operator=(const Participant&) = delete;

  // The topic `name` of type PubSubType, created on first use (default topic QoS: the
  // endpoints' profiles carry all QoS).
  template <class PubSubType>
  eprosima::fastdds::dds::Topic* GetTopic(const std::string& name) {
    return GetTopic(name, eprosima::fastdds::dds::TypeSupport(new CheckedType<PubSubType>()));
  }

  eprosima::fastdds::dds::DomainParticipant* get() const { return participant_; }
  eprosima::fastdds::dds::Publisher* publisher() const { return publisher_; }
  eprosima::fastdds::dds::Subscriber* subscriber() const { return subscriber_; }
  // The subscriber whose readers of `topic` are created: a secured participant with a partition
  // of its own (an entity) reads the sensor topics (pena/sensors/*) only in that partition, the
  // only one its permissions let it read them in (its own driver's); everything else in all.
  eprosima::fastdds::dds::Subscriber* SubscriberFor(const std::string& topic) const;
  const std::string& name() const { return name_; }
  // The certificate subject of a secured participant (RFC 2253); empty when open.
  const std::string& identity() const { return identity_; }
  // Its certificate's common name (an entity's id, "fusion", ...); empty when open.
  const std::string& common_name() const { return common_name_; }
  bool secured() const { return !identity_.empty(); }

  // Whether a sample about entity `entity_id` (its key) from writer `publication` is taken.
  // Open: always. Secured: only if that writer publishes in the default partition, which no
  // entity identity may, or in exactly the partition `entity_id`, the only one that entity's
  // permissions allow (docs/security.md). DDS Security checks which partitions a writer may use;
  // this checks that a sample's key names the writer's own entity. Refusals are counted and the
  // first few logged.
  bool AcceptsEntitySample(const eprosima::fastrtps::rtps::InstanceHandle_t& publication,
                           const std::string& entity_id);
  // Samples refused by AcceptsEntitySample.
  std::uint64_t refused_samples() const { return refused_samples_.load(); }

 private:
  eprosima::fastdds::dds::Topic* GetTopic(const std::string& name,
                                          eprosima::fastdds::dds::TypeSupport type);

  // Records each remote writer's partitions as discovery reports them.
  class WriterPartitions : public eprosima::fastdds::dds::DomainParticipantListener {
   public:
    void on_publisher_discovery(eprosima::fastdds::dds::DomainParticipant* participant,
                                eprosima::fastrtps::rtps::WriterDiscoveryInfo&& info) override;
    // The partitions of `guid`'s writer, waiting up to `wait_ms` for its discovery to be
    // reported (a sample can overtake that report); false if it is still unknown.
    bool Find(const std::array<std::uint8_t, 16>& guid, std::vector<std::string>& partitions,
              int wait_ms);

   private:
    std::mutex mutex_;
    std::condition_variable discovered_;
    std::map<std::array<std::uint8_t, 16>, std::vector<std::string>> partitions_;
  };

  std::string name_;
  WriterPartitions writer_partitions_;
  std::atomic<std::uint64_t> refused_samples_{0};
  std::string own_partition_;
  std::string identity_;
  std::string common_name_;
  eprosima::fastdds::dds::DomainParticipant* participant_ = nullptr;
  eprosima::fastdds::dds::Publisher* publisher_ = nullptr;
  eprosima::fastdds::dds::Subscriber* subscriber_ = nullptr;
  eprosima::fastdds::dds::Subscriber* own_subscriber_ = nullptr;  // own partition; or null
  std::mutex topics_mutex_;
  std::map<std::string, eprosima::fastdds::dds::Topic*> topics_;
};

}  // namespace pena::services
