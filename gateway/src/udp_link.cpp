#include "pena/gateway/udp_link.hpp"

#include "ipv4_address.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <stdexcept>

namespace pena::gateway {

UdpLink::UdpLink(UdpLinkOptions options) : options_(std::move(options)) {
  const sockaddr_in local = Ipv4Address(options_.bind_address, options_.bind_port, "udp");
  Ipv4Address(options_.peer_address, options_.peer_port, "udp");  // validate early
  fd_ = socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  if (fd_ < 0) throw std::runtime_error(std::string("udp link: socket: ") + std::strerror(errno));
  if (bind(fd_, reinterpret_cast<const sockaddr*>(&local), sizeof(local)) != 0) {
    const std::string why = std::strerror(errno);
    close(fd_);
    throw std::runtime_error("udp link: bind " + options_.bind_address + ":" +
                             std::to_string(options_.bind_port) + ": " + why);
  }
  sockaddr_in bound{};
  socklen_t size = sizeof(bound);
  getsockname(fd_, reinterpret_cast<sockaddr*>(&bound), &size);
  port_ = ntohs(bound.sin_port);
}

UdpLink::~UdpLink() {
  if (fd_ >= 0) close(fd_);
}

bool UdpLink::Send(const std::string& frame, std::string* error) {
  const sockaddr_in peer = Ipv4Address(options_.peer_address, options_.peer_port, "udp");
  const ssize_t sent = sendto(fd_, frame.data(), frame.size(), 0,
                              reinterpret_cast<const sockaddr*>(&peer), sizeof(peer));
  if (sent == static_cast<ssize_t>(frame.size())) return true;
  if (error != nullptr) *error = sent < 0 ? std::strerror(errno) : "short send";
  return false;
}

std::vector<std::string> UdpLink::Receive(double timeout_s) {
  std::vector<std::string> frames;
  pollfd descriptor{fd_, POLLIN, 0};
  const int timeout_ms = static_cast<int>(std::lround(std::max(0.0, timeout_s) * 1000.0));
  if (poll(&descriptor, 1, timeout_ms) <= 0) return frames;
  const sockaddr_in peer = Ipv4Address(options_.peer_address, options_.peer_port, "udp");
  std::string buffer(65536, '\0');
  while (true) {
    sockaddr_in from{};
    socklen_t size = sizeof(from);
    const ssize_t got = recvfrom(fd_, buffer.data(), buffer.size(), 0,
                                 reinterpret_cast<sockaddr*>(&from), &size);
    if (got < 0) break;  // EAGAIN: drained
    if (from.sin_addr.s_addr != peer.sin_addr.s_addr || from.sin_port != peer.sin_port) {
      ++foreign_;
      continue;
    }
    frames.emplace_back(buffer.data(), static_cast<std::size_t>(got));
  }
  return frames;
}

}  // namespace pena::gateway
