#pragma once
// What the service tests share: the loopback profile, a domain id of their own, scratch dirs.

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>

#include "dds_participant.hpp"
#include "scoped_temp_dir.hpp"

namespace pena::services::testing {

// Makes deploy/dds/pena-loopback.xml this process's Fast DDS default (inherited by spawned
// daemons), so nothing here can run on the built-in default profile.
inline void UseLoopbackByDefault() {
  const std::filesystem::path dir = std::filesystem::path(PENA_SOURCE_DIR) / "deploy" / "dds";
  setenv("FASTRTPS_DEFAULT_PROFILES_FILE", (dir / "pena-loopback.xml").c_str(), 1);
}

// Every participant of these tests runs on deploy/dds/pena-loopback.xml: the process default
// and loaded explicitly.
inline DdsOptions LoopbackDds(int domain_id) {
  UseLoopbackByDefault();
  const std::filesystem::path dir = std::filesystem::path(PENA_SOURCE_DIR) / "deploy" / "dds";
  DdsOptions options;
  options.profiles_files = {dir / "pena-loopback.xml", dir / "pena-qos.xml"};
  options.participant_profile = "pena_loopback";
  options.domain_id = domain_id;
  return options;
}

// The same without shared memory (profile pena_loopback_udp), for every participant of a test
// that kills one abruptly. With Fast DDS 2.9.1, a survivor's shared-memory teardown after a peer
// died of SIGSEGV sometimes segfaults inside SharedMemTransport::delete_input_channel (2 in 60
// parallel runs of the crash test; docs/dds.md, "Shared memory and killed peers").
inline DdsOptions LoopbackUdpDds(int domain_id) {
  DdsOptions options = LoopbackDds(domain_id);
  options.participant_profile = "pena_loopback_udp";
  return options;
}

// A DDS domain id no other test process on this machine holds: the first of 100..229 whose lock
// file /tmp/pena-dds-domain-N.lock this process can flock (held until the process ends, so
// parallel ctest runs, and other checkouts' tests, never share a domain). `offset` only spreads
// the starting point.
inline int TestDomain(int offset = 0) {
  for (int i = 0; i < 130; ++i) {
    const int domain = 100 + (offset * 17 + static_cast<int>(getpid()) + i) % 130;
    const std::string path = "/tmp/pena-dds-domain-" + std::to_string(domain) + ".lock";
    const int fd = open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0666);
    if (fd < 0) continue;
    if (flock(fd, LOCK_EX | LOCK_NB) == 0) return domain;  // fd stays open: the lock is held
    close(fd);
  }
  throw std::runtime_error("no free DDS test domain in 100..229");
}

// A fresh, empty directory `name` in this test's own temporary directory (removed at exit).
inline std::filesystem::path ScratchDir(const std::string& name) {
  return pena::testing::FreshTempDir(name);
}

}  // namespace pena::services::testing
