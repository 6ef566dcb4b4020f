// pena-fusion's participant profile: without a profile given it runs on pena_loopback_udp, which
// has no shared-memory transport (a fusion restarted after kill -9 reuses its predecessor's
// ports, and Fast DDS 2.9.1 shared-memory channels to them sometimes stayed dead:
// docs/fusion-service.md, "Persistence and restart"); a profile given in the config is kept.
#include <gtest/gtest.h>

#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/domain/qos/DomainParticipantQos.hpp>
#include <fastdds/rtps/transport/UDPv4TransportDescriptor.h>
#include <fastdds/rtps/transport/shared_mem/SharedMemTransportDescriptor.h>

#include "fusion_options.hpp"

namespace pena::services {
namespace {

namespace dds = eprosima::fastdds::dds;

TEST(FusionOptions, WithoutAProfileTheFusionRunsOnTheLoopbackProfileWithoutSharedMemory) {
  const FusionServiceOptions defaults = FusionOptionsFromConfig(config::FusionConfig{}, "");
  EXPECT_EQ(defaults.dds.participant_profile, kFusionParticipantProfile);

  config::FusionConfig given;
  given.mutable_dds()->set_participant_profile("pena_loopback");
  EXPECT_EQ(FusionOptionsFromConfig(given, "").dds.participant_profile, "pena_loopback");

  // The profile as Fast DDS reads it from deploy/dds/pena-loopback.xml: UDP only.
  for (const std::filesystem::path& file : DefaultProfilesFiles()) LoadProfilesFile(file);
  dds::DomainParticipantQos qos;
  ASSERT_EQ(dds::DomainParticipantFactory::get_instance()->get_participant_qos_from_profile(
                kFusionParticipantProfile, qos),
            ReturnCode_t::RETCODE_OK);
  EXPECT_FALSE(qos.transport().use_builtin_transports);
  int udp = 0;
  for (const auto& transport : qos.transport().user_transports) {
    EXPECT_EQ(dynamic_cast<eprosima::fastdds::rtps::SharedMemTransportDescriptor*>(transport.get()),
              nullptr);
    udp += dynamic_cast<eprosima::fastdds::rtps::UDPv4TransportDescriptor*>(transport.get()) !=
           nullptr;
  }
  EXPECT_EQ(udp, 1);
}

}  // namespace
}  // namespace pena::services
