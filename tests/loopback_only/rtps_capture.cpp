// rtps_capture: counts the packets on every network interface of this network namespace with an
// AF_PACKET socket (needs CAP_NET_RAW), and among them the UDP datagrams and the RTPS messages
// (UDP payload starting with "RTPS", DDS's wire protocol). Runs until SIGINT/SIGTERM or
// --seconds, then prints one line per interface and a summary:
//   iface <name> loopback <0|1> packets <n> udp <n> rtps <n>
//   non_loopback_packets <n> non_loopback_udp <n> non_loopback_rtps <n> loopback_rtps <n>
// It prints "ready" once the socket is bound. Used by loopback_only_test.sh.
#include <arpa/inet.h>
#include <linux/if_ether.h>
#include <linux/if_packet.h>
#include <net/if.h>
#include <poll.h>
#include <signal.h>
#include <sys/socket.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <string>

namespace {

volatile sig_atomic_t stop_requested = 0;
void OnStop(int /*signal*/) { stop_requested = 1; }

struct Counts {
  long packets = 0;
  long udp = 0;
  long rtps = 0;
};

// The UDP payload of an IPv4 or IPv6 packet (no link header: SOCK_DGRAM), or nullptr.
const unsigned char* UdpPayload(const unsigned char* packet, std::size_t size,
                                unsigned short ethertype, std::size_t* payload_size) {
  std::size_t header = 0;
  if (ethertype == ETH_P_IP && size >= 20 && (packet[0] >> 4) == 4 && packet[9] == 17) {
    header = static_cast<std::size_t>(packet[0] & 0x0F) * 4;
  } else if (ethertype == ETH_P_IPV6 && size >= 40 && (packet[0] >> 4) == 6 && packet[6] == 17) {
    header = 40;  // UDP right after the fixed header (no extension headers)
  } else {
    return nullptr;
  }
  if (size < header + 8) return nullptr;
  *payload_size = size - header - 8;
  return packet + header + 8;
}

bool IsLoopback(int ifindex) {
  char name[IF_NAMESIZE] = {};
  return if_indextoname(static_cast<unsigned>(ifindex), name) != nullptr &&
         std::strcmp(name, "lo") == 0;
}

std::string NameOf(int ifindex) {
  char name[IF_NAMESIZE] = {};
  if (if_indextoname(static_cast<unsigned>(ifindex), name) == nullptr) {
    return "if" + std::to_string(ifindex);
  }
  return name;
}

void Print(const std::map<int, Counts>& counts) {
  Counts outside;
  long loopback_rtps = 0;
  for (const auto& [ifindex, c] : counts) {
    const bool loopback = IsLoopback(ifindex);
    std::printf("iface %s loopback %d packets %ld udp %ld rtps %ld\n", NameOf(ifindex).c_str(),
                loopback ? 1 : 0, c.packets, c.udp, c.rtps);
    if (loopback) {
      loopback_rtps += c.rtps;
    } else {
      outside.packets += c.packets;
      outside.udp += c.udp;
      outside.rtps += c.rtps;
    }
  }
  std::printf("non_loopback_packets %ld non_loopback_udp %ld non_loopback_rtps %ld "
              "loopback_rtps %ld\n", outside.packets, outside.udp, outside.rtps, loopback_rtps);
}

}  // namespace

int main(int argc, char** argv) {
  double seconds = 3600.0;
  if (argc == 3 && std::strcmp(argv[1], "--seconds") == 0) seconds = std::atof(argv[2]);
  const int fd = socket(AF_PACKET, SOCK_DGRAM, htons(ETH_P_ALL));
  if (fd < 0) {
    std::fprintf(stderr, "rtps_capture: AF_PACKET socket: %s\n", std::strerror(errno));
    return 77;
  }
  signal(SIGINT, OnStop);
  signal(SIGTERM, OnStop);
  std::printf("ready\n");
  std::fflush(stdout);
  std::map<int, Counts> counts;
  std::array<unsigned char, 65536> buffer{};
  const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (!stop_requested && std::chrono::steady_clock::now() < until) {
    pollfd poll_fd{fd, POLLIN, 0};
    if (poll(&poll_fd, 1, 100) <= 0) continue;
    sockaddr_ll from{};
    socklen_t from_size = sizeof from;
    const ssize_t size = recvfrom(fd, buffer.data(), buffer.size(), MSG_DONTWAIT,
                                  reinterpret_cast<sockaddr*>(&from), &from_size);
    if (size <= 0) continue;
    Counts& c = counts[from.sll_ifindex];
    ++c.packets;
    std::size_t payload_size = 0;
    const unsigned char* payload = UdpPayload(buffer.data(), static_cast<std::size_t>(size),
                                              ntohs(from.sll_protocol), &payload_size);
    if (payload == nullptr) continue;
    ++c.udp;
    if (payload_size >= 4 && std::memcmp(payload, "RTPS", 4) == 0) ++c.rtps;
  }
  close(fd);
  Print(counts);
  return 0;
}
