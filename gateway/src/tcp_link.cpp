#include "pena/gateway/tcp_link.hpp"

#include "ipv4_address.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>
#include <stdexcept>

namespace pena::gateway {
namespace {

double MonotonicS() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

void NoDelay(int fd) {
  const int one = 1;
  setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof(one));
}

}  // namespace

TcpLink::TcpLink(TcpLinkOptions options) : options_(std::move(options)) {
  if (!options_.listen) return;
  const sockaddr_in local = Ipv4Address(options_.bind_address, options_.bind_port, "tcp");
  listen_fd_ = socket(AF_INET, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  const int one = 1;
  setsockopt(listen_fd_, SOL_SOCKET, SO_REUSEADDR, &one, sizeof(one));
  if (listen_fd_ < 0 || bind(listen_fd_, reinterpret_cast<const sockaddr*>(&local), sizeof(local)) != 0 ||
      listen(listen_fd_, 1) != 0) {
    throw std::runtime_error("tcp link: listen " + options_.bind_address + ":" +
                             std::to_string(options_.bind_port) + ": " + std::strerror(errno));
  }
}

TcpLink::~TcpLink() {
  if (fd_ >= 0) close(fd_);
  if (listen_fd_ >= 0) close(listen_fd_);
}

void TcpLink::Drop(const std::string& why) {
  if (connected_) {
    ++drops_;
    last_drop_ = why;
  }
  if (fd_ >= 0) close(fd_);
  fd_ = -1;
  connected_ = false;
  pending_.clear();
  decoder_ = FrameStreamDecoder();
}

void TcpLink::TryConnect() {
  if (options_.listen) {
    const int fd = accept4(listen_fd_, nullptr, nullptr, SOCK_NONBLOCK | SOCK_CLOEXEC);
    if (fd < 0) return;
    if (fd_ >= 0) close(fd_);  // a reconnecting peer replaces the old connection
    fd_ = fd;
    connected_ = true;
    NoDelay(fd_);
    return;
  }
  if (fd_ >= 0 || MonotonicS() < next_connect_s_) return;
  next_connect_s_ = MonotonicS() + 1.0;
  const sockaddr_in peer = Ipv4Address(options_.peer_address, options_.peer_port, "tcp");
  fd_ = socket(AF_INET, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  NoDelay(fd_);
  if (connect(fd_, reinterpret_cast<const sockaddr*>(&peer), sizeof(peer)) != 0 && errno != EINPROGRESS) {
    Drop(std::string("connect: ") + std::strerror(errno));
  }
}

bool TcpLink::Send(const std::string& frame, std::string* error) {
  if (!connected()) {
    if (error != nullptr) *error = "not connected";
    return false;
  }
  if (pending_.size() + frame.size() > options_.max_pending_bytes) {
    if (error != nullptr) *error = "send queue full";
    return false;
  }
  pending_ += frame;
  Flush();
  return true;
}

void TcpLink::Flush() {
  while (connected() && !pending_.empty()) {
    const ssize_t sent = send(fd_, pending_.data(), pending_.size(), MSG_NOSIGNAL);
    if (sent > 0) {
      pending_.erase(0, static_cast<std::size_t>(sent));
    } else {
      if (sent < 0 && errno != EAGAIN && errno != EWOULDBLOCK) Drop(std::string("send: ") + std::strerror(errno));
      return;
    }
  }
}

std::vector<std::string> TcpLink::Receive(double timeout_s) {
  TryConnect();
  std::vector<std::string> frames;
  const int timeout_ms = static_cast<int>(std::lround(std::max(0.0, timeout_s) * 1000.0));
  pollfd descriptor{fd_ >= 0 ? fd_ : listen_fd_, POLLIN, 0};
  if (fd_ >= 0 && (!connected_ || !pending_.empty())) descriptor.events |= POLLOUT;
  if (descriptor.fd < 0 || poll(&descriptor, 1, timeout_ms) <= 0) return frames;
  if (fd_ < 0) return frames;  // the listener is readable: accept on the next call
  if (!connected_ && (descriptor.revents & (POLLOUT | POLLERR | POLLHUP)) != 0) {
    int error = 0;
    socklen_t size = sizeof(error);
    getsockopt(fd_, SOL_SOCKET, SO_ERROR, &error, &size);
    if (error != 0) {
      Drop(std::string("connect: ") + std::strerror(error));
      return frames;
    }
    connected_ = true;
  }
  Flush();
  char buffer[4096];
  while (connected()) {
    const ssize_t got = recv(fd_, buffer, sizeof(buffer), 0);
    if (got == 0 || (got < 0 && errno != EAGAIN && errno != EWOULDBLOCK)) {
      Drop(got == 0 ? "closed by the peer" : std::string("recv: ") + std::strerror(errno));
      break;
    }
    if (got < 0) break;
    for (FrameResult& frame : decoder_.Feed(std::string_view(buffer, static_cast<std::size_t>(got)))) {
      if (!frame.ok()) {
        ++rejected_;
        continue;
      }
      frames.push_back(EncodeFrame(frame.payload, false));
    }
  }
  return frames;
}

}  // namespace pena::gateway
