#pragma once
// Link frames over one TCP connection (docs/gateway.md, "Transport"): the alternative to UdpLink
// kept for the transport measurement. A byte stream, split into frames by FrameStreamDecoder;
// one side listens, the other connects (and reconnects after an error).

#include <cstdint>
#include <string>
#include <vector>

#include "pena/gateway/frame.hpp"

namespace pena::gateway {

struct TcpLinkOptions {
  bool listen = false;                  // true: accept one peer on bind_*; false: connect to peer_*
  std::string bind_address = "127.0.0.1";
  std::uint16_t bind_port = 0;
  std::string peer_address = "127.0.0.1";
  std::uint16_t peer_port = 0;
  std::size_t max_pending_bytes = 1 << 20;  // frames waiting in user space beyond this are dropped
};

class TcpLink {
 public:
  // Opens the listening socket (listen) or nothing yet (connect happens in Receive); throws
  // std::runtime_error with the address and errno text.
  explicit TcpLink(TcpLinkOptions options);
  ~TcpLink();
  TcpLink(const TcpLink&) = delete;
  TcpLink& operator=(const TcpLink&) = delete;

  // Queues a frame for the stream; false (and `error`) if not connected or the queue is full.
  bool Send(const std::string& frame, std::string* error);
  // Waits up to timeout_s, accepts/connects, writes what is queued, returns complete frames read
  // (re-encoded whole frames, for LinkSession::OnFrame); rejected stream bytes are counted.
  std::vector<std::string> Receive(double timeout_s);
  bool connected() const { return fd_ >= 0 && connected_; }
  // Frames the stream decoder rejected (garbage, bad CRC).
  std::uint64_t rejected_frames() const { return rejected_; }
  // Connections lost (error or close) and the last reason.
  std::uint64_t drops() const { return drops_; }
  const std::string& last_drop() const { return last_drop_; }
  // Bytes queued in user space, not yet accepted by the kernel.
  std::size_t pending_bytes() const { return pending_.size(); }

 private:
  void TryConnect();
  void Flush();
  void Drop(const std::string& why);

  TcpLinkOptions options_;
  int listen_fd_ = -1;
  int fd_ = -1;
  bool connected_ = false;
  double next_connect_s_ = 0.0;
  std::string pending_;
  FrameStreamDecoder decoder_;
  std::uint64_t rejected_ = 0;
  std::uint64_t drops_ = 0;
  std::string last_drop_;
};

}  // namespace pena::gateway
