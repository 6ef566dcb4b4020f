#include "dds_participant.hpp"

#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <chrono>
#include <optional>
#include <set>

#include <spdlog/spdlog.h>

#include "dds_security.hpp"

namespace pena::services {

namespace dds = eprosima::fastdds::dds;

std::filesystem::path DefaultDdsDir() {
  if (const char* env = std::getenv("PENA_DDS_DIR"); env != nullptr && *env != '\0') return env;
  // An installed daemon: <prefix>/bin/pena-x finds <prefix>/share/pena/dds.
  std::error_code error;
  const std::filesystem::path binary = std::filesystem::read_symlink("/proc/self/exe", error);
  if (!error) {
    const std::filesystem::path installed =
        binary.parent_path().parent_path() / "share" / "pena" / "dds";
    if (std::filesystem::exists(installed / "pena-loopback.xml", error)) return installed;
  }
  return PENA_DEFAULT_DDS_DIR;
}

std::vector<std::filesystem::path> DefaultProfilesFiles() {
  const std::filesystem::path dir = DefaultDdsDir();
  return {dir / "pena-loopback.xml", dir / "pena-qos.xml"};
}

void LoadProfilesFile(const std::filesystem::path& path) {
  static std::mutex mutex;
  static std::set<std::filesystem::path> loaded;
  std::error_code error;
  const std::filesystem::path canonical = std::filesystem::canonical(path, error);
  if (error) throw DdsError(path.string() + ": cannot open the DDS profile file");
  const std::lock_guard<std::mutex> lock(mutex);
  if (loaded.contains(canonical)) return;
  // The factory has already loaded FASTRTPS_DEFAULT_PROFILES_FILE by itself (its first use);
  // loading that file again would define its profiles twice.
  dds::DomainParticipantFactory* factory = dds::DomainParticipantFactory::get_instance();
  factory->load_profiles();
  if (const char* env = std::getenv("FASTRTPS_DEFAULT_PROFILES_FILE")) {
    if (std::filesystem::equivalent(env, canonical, error)) {
      loaded.insert(canonical);
      return;
    }
  }
  if (factory->load_XML_profiles_file(canonical.string()) != ReturnCode_t::RETCODE_OK) {
    throw DdsError(path.string() + ": Fast DDS rejected the profile file (see its log above)");
  }
  loaded.insert(canonical);
}

Participant::Participant(const DdsOptions& options, const std::string& name) : name_(name) {
  if (options.profiles_files.empty()) {
    throw DdsError("dds.profiles_files is empty: refusing to run on Fast DDS's built-in default");
  }
  for (const std::filesystem::path& file : options.profiles_files) LoadProfilesFile(file);
  dds::DomainParticipantFactory* factory = dds::DomainParticipantFactory::get_instance();
  dds::DomainParticipantQos qos;
  if (factory->get_participant_qos_from_profile(options.participant_profile, qos) !=
      ReturnCode_t::RETCODE_OK) {
    throw DdsError("no DDS participant profile '" + options.participant_profile +
                   "' (is it in dds.profiles_files?)");
  }
  std::vector<std::pair<std::string, std::string>> properties;
  for (const auto& property : qos.properties().properties()) {
    properties.emplace_back(property.name(), property.value());
  }
  std::optional<SecurityFiles> security = SecurityFilesFromProperties(properties);
  if (!options.security_dir.empty()) {
    if (security) {
      throw DdsError("DDS Security is configured twice: by dds.security_dir " +
                     options.security_dir.string() + " and by participant profile '" +
                     options.participant_profile + "'; use one");
    }
    security = SecurityFilesIn(options.security_dir);
    for (auto& [key, value] : SecurityProperties(*security)) {
      qos.properties().properties().emplace_back(key, value);
    }
  }
  if (security) {
    CheckedIdentity checked = CheckSecurityFiles(*security);
    identity_ = std::move(checked.subject);
    common_name_ = std::move(checked.common_name);
  }
  participant_ = factory->create_participant(static_cast<dds::DomainId_t>(options.domain_id), qos,
                                             &writer_partitions_, dds::StatusMask::none());
  if (participant_ == nullptr) {
    throw DdsError("cannot create the DDS participant from profile '" +
                   options.participant_profile + "' on domain " +
                   std::to_string(options.domain_id) +
                   (security ? " with DDS Security as " + identity_ +
                                   " (Fast DDS refused the identity, governance or permissions; "
                                   "see its log above)"
                             : std::string()));
  }
  const std::string partition = !options.publish_partition.empty() ? options.publish_partition
                                : options.own_partition                ? common_name_
                                                                       : std::string();
  dds::PublisherQos publisher_qos = dds::PUBLISHER_QOS_DEFAULT;
  if (!partition.empty()) publisher_qos.partition().push_back(partition.c_str());
  own_partition_ = partition;
  // Secured entities write in partitions of their own (docs/security.md): readers take all.
  // Fast DDS matches the default partition only with an explicit "", not with "*".
  dds::SubscriberQos subscriber_qos = dds::SUBSCRIBER_QOS_DEFAULT;
  if (secured()) {
    subscriber_qos.partition().push_back("");
    subscriber_qos.partition().push_back("*");
  }
  publisher_ = participant_->create_publisher(publisher_qos);
  subscriber_ = participant_->create_subscriber(subscriber_qos);
  bool own_subscriber_failed = false;
  if (secured() && !partition.empty()) {
    dds::SubscriberQos own_qos = dds::SUBSCRIBER_QOS_DEFAULT;
    own_qos.partition().push_back(partition.c_str());
    own_subscriber_ = participant_->create_subscriber(own_qos);
    own_subscriber_failed = own_subscriber_ == nullptr;
  }
  if (publisher_ == nullptr || subscriber_ == nullptr || own_subscriber_failed) {
    participant_->delete_contained_entities();
    factory->delete_participant(participant_);
    throw DdsError("cannot create the DDS publisher or subscriber of '" + name + "'" +
                   (secured() ? " (do the permissions of " + identity_ + " allow partition '" +
                                    partition + "'?)"
                              : std::string()));
  }
}

dds::Subscriber* Participant::SubscriberFor(const std::string& topic) const {
  if (own_subscriber_ != nullptr && topic.starts_with("pena/sensors/")) return own_subscriber_;
  return subscriber_;
}

Participant::~Participant() {
  participant_->delete_contained_entities();
  dds::DomainParticipantFactory::get_instance()->delete_participant(participant_);
}

void Participant::WriterPartitions::on_publisher_discovery(
    dds::DomainParticipant* /*participant*/, eprosima::fastrtps::rtps::WriterDiscoveryInfo&& info) {
  using Status = eprosima::fastrtps::rtps::WriterDiscoveryInfo::DISCOVERY_STATUS;
  std::array<std::uint8_t, 16> guid{};
  const auto& prefix = info.info.guid().guidPrefix.value;
  const auto& entity = info.info.guid().entityId.value;
  std::copy(std::begin(prefix), std::end(prefix), guid.begin());
  std::copy(std::begin(entity), std::end(entity), guid.begin() + 12);
  const std::lock_guard<std::mutex> lock(mutex_);
  if (info.status == Status::REMOVED_WRITER) {
    partitions_.erase(guid);
    return;
  }
  std::vector<std::string> names;
  for (const auto& name : info.info.m_qos.m_partition.names()) names.push_back(name);
  partitions_[guid] = std::move(names);
  discovered_.notify_all();
}

bool Participant::WriterPartitions::Find(const std::array<std::uint8_t, 16>& guid,
                                         std::vector<std::string>& partitions, int wait_ms) {
  std::unique_lock<std::mutex> lock(mutex_);
  // Fast DDS matches a discovered writer before it reports it to this listener, on another
  // thread: its first sample can come first. Waiting here holds this reader for that moment,
  // once per writer.
  discovered_.wait_for(lock, std::chrono::milliseconds(wait_ms),
                       [&] { return partitions_.contains(guid); });
  const auto it = partitions_.find(guid);
  if (it == partitions_.end()) return false;
  partitions = it->second;
  return true;
}

bool Participant::AcceptsEntitySample(
    const eprosima::fastrtps::rtps::InstanceHandle_t& publication, const std::string& entity_id) {
  if (!secured()) return true;
  std::array<std::uint8_t, 16> guid{};
  for (std::size_t i = 0; i < guid.size(); ++i) guid[i] = publication.value[i];
  std::vector<std::string> partitions;
  bool known = true;
  if (std::equal(guid.begin(), guid.begin() + 12,
                 participant_->guid().guidPrefix.value)) {
    // Our own writer (discovery reports remote ones only).
    if (!own_partition_.empty()) partitions.push_back(own_partition_);
  } else {
    known = writer_partitions_.Find(guid, partitions, 500);
  }
  if (known && (partitions.empty() || (partitions.size() == 1 && partitions[0] == entity_id))) {
    return true;
  }
  const std::uint64_t refused = ++refused_samples_;
  if (refused <= 10 || refused % 1000 == 0) {
    std::string from;
    for (const std::string& partition : partitions) from += (from.empty() ? "" : ",") + partition;
    spdlog::warn("{}: refused a sample about entity '{}' from a writer {} ({} refused so far)",
                 name_, entity_id,
                 known ? "in partition '" + from + "'" : std::string("not discovered yet"),
                 refused);
  }
  return false;
}

dds::Topic* Participant::GetTopic(const std::string& name, dds::TypeSupport type) {
  const std::lock_guard<std::mutex> lock(topics_mutex_);
  if (const auto it = topics_.find(name); it != topics_.end()) return it->second;
  const std::string type_name = type.get_type_name();
  if (participant_->find_type(type_name).empty() &&
      type.register_type(participant_) != ReturnCode_t::RETCODE_OK) {
    throw DdsError("cannot register DDS type " + type_name);
  }
  dds::Topic* topic = participant_->create_topic(name, type_name, dds::TOPIC_QOS_DEFAULT);
  if (topic == nullptr) throw DdsError("cannot create DDS topic " + name + " (" + type_name + ")");
  topics_.emplace(name, topic);
  return topic;
}

}  // namespace pena::services
