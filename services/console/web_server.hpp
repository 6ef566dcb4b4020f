#pragma once
// pena-console's HTTP and WebSocket server (Boost.Beast, one I/O thread). GET serves the page's
// assets compiled into the binary (web_assets.hpp); /ws upgrades to a WebSocket whose text
// messages go to a callback. The console's worker answers through Send and Broadcast, which
// may be called from any thread. A browser that does not keep up (more than
// max_pending_bytes waiting to be written) is disconnected instead of stalling anyone; a
// reloaded page gets a fresh snapshot.

#include <cstdint>
#include <functional>
#include <memory>
#include <string>

namespace pena::services {

// What the server tells its owner (called on the I/O thread: only enqueue).
struct WebServerCallbacks {
  std::function<void(std::uint64_t session)> on_open;
  std::function<void(std::uint64_t session, std::string text)> on_message;
  std::function<void(std::uint64_t session)> on_close;
};

// The server's settings.
struct WebServerOptions {
  std::string bind_address = "127.0.0.1";
  std::uint16_t port = 8090;                       // 0: any free port (see WebServer::port)
  std::size_t max_message_bytes = 64 * 1024;       // larger WebSocket messages close the socket
  std::size_t max_pending_bytes = 16 * 1024 * 1024;  // per browser, before it is disconnected
};

class WebServer {
 public:
  // Binds and starts the I/O thread; throws std::runtime_error naming address and port.
  WebServer(const WebServerOptions& options, WebServerCallbacks callbacks);
  ~WebServer();
  WebServer(const WebServer&) = delete;
  WebServer& operator=(const WebServer&) = delete;

  // The port bound (the chosen one when options.port was 0).
  std::uint16_t port() const;
  // Sends one text message to a session; `ready` makes it receive broadcasts from then on (the
  // snapshot is sent with ready = true, so no delta reaches a browser before its snapshot).
  void Send(std::uint64_t session, std::string text, bool ready = false);
  // Sends one text message to every ready session.
  void Broadcast(std::string text);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace pena::services
