#include "dds_participant.hpp"

#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <set>

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
  participant_ = factory->create_participant_with_profile(
      static_cast<dds::DomainId_t>(options.domain_id), options.participant_profile);
  if (participant_ == nullptr) {
    throw DdsError("cannot create the DDS participant from profile '" +
                   options.participant_profile + "' on domain " +
                   std::to_string(options.domain_id) + " (is the profile in dds.profiles_files?)");
  }
  publisher_ = participant_->create_publisher(dds::PUBLISHER_QOS_DEFAULT);
  subscriber_ = participant_->create_subscriber(dds::SUBSCRIBER_QOS_DEFAULT);
  if (publisher_ == nullptr || subscriber_ == nullptr) {
    participant_->delete_contained_entities();
    factory->delete_participant(participant_);
    throw DdsError("cannot create the DDS publisher or subscriber of '" + name + "'");
  }
}

Participant::~Participant() {
  participant_->delete_contained_entities();
  dds::DomainParticipantFactory::get_instance()->delete_participant(participant_);
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
