#include "web_server.hpp"

#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/post.hpp>
#include <boost/asio/strand.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>
#include <deque>
#include <map>
#include <optional>
#include <stdexcept>
#include <thread>

#include "web_assets.hpp"

namespace pena::services {
namespace {

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
using tcp = asio::ip::tcp;

class WsSession;

// State only the I/O thread touches.
struct Registry {
  WebServerCallbacks callbacks;
  std::size_t max_message_bytes = 0;
  std::size_t max_pending_bytes = 0;
  std::uint64_t next_id = 1;
  std::map<std::uint64_t, std::weak_ptr<WsSession>> sessions;
};

// One browser's WebSocket: reads messages into the callback; writes queued texts one at a time.
class WsSession : public std::enable_shared_from_this<WsSession> {
 public:
  WsSession(tcp::socket&& socket, Registry& registry)
      : ws_(std::move(socket)), registry_(registry), id_(registry.next_id++) {}

  void Start(http::request<http::string_body> request) {
    ws_.read_message_max(registry_.max_message_bytes);
    ws_.set_option(websocket::stream_base::timeout::suggested(beast::role_type::server));
    ws_.async_accept(request, [self = shared_from_this()](beast::error_code error) {
      if (error) return;
      self->registry_.sessions[self->id_] = self;
      if (self->registry_.callbacks.on_open) self->registry_.callbacks.on_open(self->id_);
      self->Read();
    });
  }

  void Queue(std::shared_ptr<const std::string> text, bool ready) {
    if (closed_) return;
    if (ready) ready_ = true;
    pending_bytes_ += text->size();
    if (pending_bytes_ > registry_.max_pending_bytes) {
      // Too slow a browser: drop it rather than hold memory or anyone else back.
      Close();
      return;
    }
    outbox_.push_back(std::move(text));
    if (outbox_.size() == 1) Write();
  }

  bool ready() const { return ready_; }

 private:
  void Read() {
    ws_.async_read(buffer_, [self = shared_from_this()](beast::error_code error, std::size_t) {
      if (error) {
        self->Closed();
        return;
      }
      std::string text = beast::buffers_to_string(self->buffer_.data());
      self->buffer_.consume(self->buffer_.size());
      if (self->registry_.callbacks.on_message) {
        self->registry_.callbacks.on_message(self->id_, std::move(text));
      }
      self->Read();
    });
  }

  void Write() {
    ws_.text(true);
    ws_.async_write(asio::buffer(*outbox_.front()),
                    [self = shared_from_this()](beast::error_code error, std::size_t) {
                      if (error) {
                        self->Closed();
                        return;
                      }
                      self->pending_bytes_ -= self->outbox_.front()->size();
                      self->outbox_.pop_front();
                      if (!self->outbox_.empty()) self->Write();
                    });
  }

  void Close() {
    closed_ = true;
    outbox_.clear();
    beast::error_code ignored;
    beast::get_lowest_layer(ws_).socket().shutdown(tcp::socket::shutdown_both, ignored);
    beast::get_lowest_layer(ws_).socket().close(ignored);
    Closed();
  }

  void Closed() {
    if (registry_.sessions.erase(id_) > 0 && registry_.callbacks.on_close) {
      registry_.callbacks.on_close(id_);
    }
  }

  websocket::stream<beast::tcp_stream> ws_;
  Registry& registry_;
  std::uint64_t id_;
  beast::flat_buffer buffer_;
  std::deque<std::shared_ptr<const std::string>> outbox_;
  std::size_t pending_bytes_ = 0;
  bool ready_ = false;
  bool closed_ = false;
};

// One HTTP connection: serves the assets, or hands the socket to a WsSession on /ws.
class HttpSession : public std::enable_shared_from_this<HttpSession> {
 public:
  HttpSession(tcp::socket&& socket, Registry& registry)
      : stream_(std::move(socket)), registry_(registry) {}

  void Read() {
    parser_.emplace();
    parser_->body_limit(8 * 1024);
    parser_->header_limit(16 * 1024);
    stream_.expires_after(std::chrono::seconds(30));
    http::async_read(stream_, buffer_, *parser_,
                     [self = shared_from_this()](beast::error_code error, std::size_t) {
                       if (error) return;  // closed, timed out or malformed: drop it
                       self->Handle(self->parser_->release());
                     });
  }

 private:
  void Handle(http::request<http::string_body> request) {
    if (websocket::is_upgrade(request)) {
      if (request.target() != "/ws") return;
      stream_.expires_never();
      std::make_shared<WsSession>(stream_.release_socket(), registry_)->Start(std::move(request));
      return;
    }
    auto response = std::make_shared<http::response<http::string_body>>();
    response->version(request.version());
    response->keep_alive(request.keep_alive());
    response->set(http::field::server, "pena-console");
    response->set(http::field::cache_control, "no-store");
    std::string_view target(request.target().data(), request.target().size());
    if (const auto q = target.find('?'); q != std::string_view::npos) target = target.substr(0, q);
    const WebAsset* asset = FindWebAsset(target == "/" ? "/index.html" : target);
    if (request.method() != http::verb::get && request.method() != http::verb::head) {
      response->result(http::status::method_not_allowed);
      response->set(http::field::content_type, "text/plain");
      response->body() = "only GET\n";
    } else if (asset == nullptr) {
      response->result(http::status::not_found);
      response->set(http::field::content_type, "text/plain");
      response->body() = "not found\n";
    } else {
      response->result(http::status::ok);
      response->set(http::field::content_type, std::string(asset->content_type));
      if (request.method() == http::verb::get) response->body() = std::string(asset->body);
    }
    response->prepare_payload();
    http::async_write(stream_, *response,
                      [self = shared_from_this(), response](beast::error_code error, std::size_t) {
                        if (error || !response->keep_alive()) {
                          beast::error_code ignored;
                          self->stream_.socket().shutdown(tcp::socket::shutdown_send, ignored);
                          return;
                        }
                        self->Read();
                      });
  }

  beast::tcp_stream stream_;
  Registry& registry_;
  beast::flat_buffer buffer_;
  std::optional<http::request_parser<http::string_body>> parser_;
};

}  // namespace

struct WebServer::Impl {
  asio::io_context io{1};
  tcp::acceptor acceptor{io};
  Registry registry;
  std::thread thread;

  void Accept() {
    acceptor.async_accept(asio::make_strand(io), [this](beast::error_code error,
                                                        tcp::socket socket) {
      if (!error) std::make_shared<HttpSession>(std::move(socket), registry)->Read();
      if (acceptor.is_open()) Accept();
    });
  }
};

WebServer::WebServer(const WebServerOptions& options, WebServerCallbacks callbacks)
    : impl_(std::make_unique<Impl>()) {
  impl_->registry.callbacks = std::move(callbacks);
  impl_->registry.max_message_bytes = options.max_message_bytes;
  impl_->registry.max_pending_bytes = options.max_pending_bytes;
  const std::string where = options.bind_address + ":" + std::to_string(options.port);
  beast::error_code error;
  const asio::ip::address address = asio::ip::make_address(options.bind_address, error);
  if (error) {
    throw std::runtime_error("bind address " + options.bind_address + ": " + error.message());
  }
  const tcp::endpoint endpoint(address, options.port);
  impl_->acceptor.open(endpoint.protocol(), error);
  if (!error) impl_->acceptor.set_option(asio::socket_base::reuse_address(true), error);
  if (!error) impl_->acceptor.bind(endpoint, error);
  if (!error) impl_->acceptor.listen(asio::socket_base::max_listen_connections, error);
  if (error) throw std::runtime_error("cannot listen on " + where + ": " + error.message());
  impl_->Accept();
  impl_->thread = std::thread([this] { impl_->io.run(); });
}

WebServer::~WebServer() {
  asio::post(impl_->io, [this] {
    beast::error_code ignored;
    impl_->acceptor.close(ignored);
    impl_->io.stop();
  });
  if (impl_->thread.joinable()) impl_->thread.join();
}

std::uint16_t WebServer::port() const { return impl_->acceptor.local_endpoint().port(); }

void WebServer::Send(std::uint64_t session, std::string text, bool ready) {
  auto shared = std::make_shared<const std::string>(std::move(text));
  asio::post(impl_->io, [this, session, shared, ready] {
    const auto it = impl_->registry.sessions.find(session);
    if (it == impl_->registry.sessions.end()) return;
    if (auto live = it->second.lock()) live->Queue(shared, ready);
  });
}

void WebServer::Broadcast(std::string text) {
  auto shared = std::make_shared<const std::string>(std::move(text));
  asio::post(impl_->io, [this, shared] {
    // Copied: Queue may drop a slow session from the registry.
    std::vector<std::shared_ptr<WsSession>> live;
    for (const auto& [id, weak] : impl_->registry.sessions) {
      if (auto session = weak.lock(); session && session->ready()) live.push_back(session);
    }
    for (const auto& session : live) session->Queue(shared, false);
  });
}

}  // namespace pena::services
