#pragma once
// A UDP socket carrying link frames, one frame per datagram (docs/gateway.md, "Transport").
// Binds 127.0.0.1 unless told otherwise; sends to one peer; never blocks longer than asked.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace pena::gateway {

// Where to listen and where the peer is (IPv4 dotted quads).
struct UdpLinkOptions {
  std::string bind_address = "127.0.0.1";
  std::uint16_t bind_port = 0;  // 0: any free port (see UdpLink::port)
  std::string peer_address = "127.0.0.1";
  std::uint16_t peer_port = 0;
};

class UdpLink {
 public:
  // Opens and binds the socket; throws std::runtime_error with the address and errno text.
  explicit UdpLink(UdpLinkOptions options);
  ~UdpLink();
  UdpLink(const UdpLink&) = delete;
  UdpLink& operator=(const UdpLink&) = delete;

  // Sends one frame to the peer; false (and `error` set) if the kernel refused it.
  bool Send(const std::string& frame, std::string* error);
  // Waits up to timeout_s for datagrams and returns those that arrived (from the peer only).
  std::vector<std::string> Receive(double timeout_s);
  // The bound port.
  std::uint16_t port() const { return port_; }
  // Datagrams dropped because they did not come from the configured peer.
  std::uint64_t foreign_datagrams() const { return foreign_; }

 private:
  int fd_ = -1;
  std::uint16_t port_ = 0;
  UdpLinkOptions options_;
  std::uint64_t foreign_ = 0;
};

}  // namespace pena::gateway
