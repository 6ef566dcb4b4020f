// Which server library carries the console's deltas best: pena-console's Boost.Beast WebSocket
// server (web_server.cpp) against cpp-httplib with server-sent events, the alternative Debian 12
// packages. A server process publishes the poses of N simulated entities at R Hz (one message
// per pose, the size of the console's pose deltas, stamped with CLOCK_MONOTONIC when made) to
// B browsers; the parent process plays the browsers and takes each message's age on arrival.
// Prints latency p50/p90/p99/max, the server's CPU time and peak resident memory; asserts
// nothing (docs/console.md, "The server library").
//
//   bench_web_server [--server beast|httplib-sse|both] [--entities 50] [--hz 4]
//                    [--browsers 4] [--seconds 20]
#include <httplib.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <boost/asio/connect.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/websocket.hpp>
#include <chrono>
#include <cinttypes>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <fstream>
#include <memory>
#include <mutex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "web_server.hpp"

namespace {

std::int64_t MonotonicNs() {
  timespec now{};
  clock_gettime(CLOCK_MONOTONIC, &now);
  return static_cast<std::int64_t>(now.tv_sec) * 1'000'000'000 + now.tv_nsec;
}

struct Options {
  std::string server = "both";
  int entities = 50;
  double hz = 4.0;
  int browsers = 4;
  double seconds = 20.0;
};

// One pose delta as the console sends it (about 200 bytes of JSON), with the making time.
std::string PoseMessage(int entity, std::uint64_t seq) {
  char text[320];
  std::snprintf(text, sizeof text,
                "{\"type\":\"delta\",\"made_ns\":%" PRId64 ",\"seq\":%" PRIu64
                ",\"poses\":[{\"id\":\"sim%03d\",\"stamp_s\":%.3f,\"x\":%.3f,\"y\":%.3f,"
                "\"theta\":%.4f,\"cov\":[0.0123,0.0011,0.0011,0.0234],\"state\":\"tracking\"}]}",
                MonotonicNs(), seq, entity, static_cast<double>(seq) * 0.25, 0.01 * entity,
                0.02 * static_cast<double>(seq), 0.001 * static_cast<double>(seq));
  return text;
}

// Calls publish(text) for entities x hz messages a second, evenly spaced, until stop.
template <typename Publish>
void RunEntities(const Options& options, const std::atomic<bool>& stop, Publish publish) {
  const auto period = std::chrono::nanoseconds(
      static_cast<std::int64_t>(1e9 / (options.hz * options.entities)));
  auto next = std::chrono::steady_clock::now();
  std::uint64_t seq = 0;
  while (!stop.load()) {
    publish(PoseMessage(static_cast<int>(seq % static_cast<std::uint64_t>(options.entities)), seq));
    ++seq;
    next += period;
    std::this_thread::sleep_until(next);
  }
}

std::atomic<bool> g_stop{false};
void OnSignal(int) { g_stop.store(true); }

// The child: serves until SIGTERM. Writes its port to `port_pipe`.
int ServeBeast(const Options& options, int port_pipe) {
  std::unique_ptr<pena::services::WebServer> server;
  pena::services::WebServerCallbacks callbacks;
  // A connecting browser gets its "snapshot" and then the deltas, as in pena-console.
  callbacks.on_open = [&server](std::uint64_t session) {
    server->Send(session, "{\"type\":\"snapshot\"}", true);
  };
  callbacks.on_message = [](std::uint64_t, std::string) {};
  callbacks.on_close = [](std::uint64_t) {};
  pena::services::WebServerOptions server_options;
  server_options.port = 0;
  server = std::make_unique<pena::services::WebServer>(server_options, callbacks);
  const std::uint16_t port = server->port();
  if (write(port_pipe, &port, sizeof port) != sizeof port) return 1;
  RunEntities(options, g_stop, [&server](std::string text) { server->Broadcast(std::move(text)); });
  return 0;
}

// cpp-httplib: GET /events is a text/event-stream; each browser's stream waits on its own queue.
struct SseHub {
  struct Client {
    std::deque<std::string> queue;
    bool closed = false;
  };
  std::mutex mutex;
  std::condition_variable ready;
  std::vector<std::shared_ptr<Client>> clients;

  void Broadcast(const std::string& text) {
    const std::lock_guard<std::mutex> lock(mutex);
    for (const auto& client : clients) client->queue.push_back("data: " + text + "\n\n");
    ready.notify_all();
  }
};

int ServeHttplibSse(const Options& options, int port_pipe) {
  httplib::Server server;
  SseHub hub;
  server.Get("/events", [&hub](const httplib::Request&, httplib::Response& response) {
    auto client = std::make_shared<SseHub::Client>();
    {
      const std::lock_guard<std::mutex> lock(hub.mutex);
      client->queue.push_back("data: {\"type\":\"snapshot\"}\n\n");
      hub.clients.push_back(client);
    }
    response.set_chunked_content_provider(
        "text/event-stream",
        [&hub, client](std::size_t, httplib::DataSink& sink) {
          std::string batch;
          {
            std::unique_lock<std::mutex> lock(hub.mutex);
            hub.ready.wait_for(lock, std::chrono::milliseconds(200),
                               [&] { return !client->queue.empty() || g_stop.load(); });
            while (!client->queue.empty()) {
              batch += client->queue.front();
              client->queue.pop_front();
            }
          }
          if (g_stop.load()) return false;
          return batch.empty() || sink.write(batch.data(), batch.size());
        },
        [&hub, client](bool) {
          const std::lock_guard<std::mutex> lock(hub.mutex);
          std::erase(hub.clients, client);
        });
  });
  const int port = server.bind_to_any_port("127.0.0.1");
  if (port <= 0) return 1;
  std::thread listener([&server] { server.listen_after_bind(); });
  const std::uint16_t port16 = static_cast<std::uint16_t>(port);
  if (write(port_pipe, &port16, sizeof port16) != sizeof port16) return 1;
  RunEntities(options, g_stop, [&hub](const std::string& text) { hub.Broadcast(text); });
  hub.ready.notify_all();
  server.stop();
  listener.join();
  return 0;
}

// What one browser saw: message ages in microseconds.
struct Received {
  std::vector<std::int64_t> age_us;
  std::string error;
};

// The age of a message carrying "made_ns":N, or -1.
std::int64_t AgeUs(std::string_view text, std::int64_t now_ns) {
  const auto at = text.find("\"made_ns\":");
  if (at == std::string_view::npos) return -1;
  return (now_ns - std::strtoll(text.data() + at + 10, nullptr, 10)) / 1000;
}

void ReadWebSocket(std::uint16_t port, const std::atomic<bool>& stop, Received& out) {
  namespace beast = boost::beast;
  try {
    boost::asio::io_context io;
    boost::asio::ip::tcp::resolver resolver(io);
    beast::websocket::stream<boost::asio::ip::tcp::socket> ws(io);
    boost::asio::connect(ws.next_layer(), resolver.resolve("127.0.0.1", std::to_string(port)));
    ws.handshake("127.0.0.1", "/ws");
    beast::flat_buffer buffer;
    while (!stop.load()) {
      ws.read(buffer);
      const std::int64_t now_ns = MonotonicNs();
      const std::string text = beast::buffers_to_string(buffer.data());
      buffer.consume(buffer.size());
      if (const std::int64_t age = AgeUs(text, now_ns); age >= 0) out.age_us.push_back(age);
    }
  } catch (const std::exception& error) {
    if (!stop.load()) out.error = error.what();
  }
}

void ReadEventStream(std::uint16_t port, const std::atomic<bool>& stop, Received& out) {
  httplib::Client client("127.0.0.1", port);
  client.set_read_timeout(5, 0);
  std::string pending;
  const auto result = client.Get("/events", [&](const char* data, std::size_t size) {
    const std::int64_t now_ns = MonotonicNs();
    pending.append(data, size);
    for (auto end = pending.find("\n\n"); end != std::string::npos; end = pending.find("\n\n")) {
      if (const std::int64_t age = AgeUs(std::string_view(pending).substr(0, end), now_ns);
          age >= 0) {
        out.age_us.push_back(age);
      }
      pending.erase(0, end + 2);
    }
    return !stop.load();
  });
  if (!result && !stop.load()) out.error = httplib::to_string(result.error());
}

// utime + stime in seconds and VmHWM in KiB of a process.
std::pair<double, long> CpuAndPeakMemory(pid_t pid) {
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string line;
  std::getline(stat, line);
  std::istringstream fields(line.substr(line.rfind(')') + 2));
  std::string field;
  unsigned long long utime = 0, stime = 0;
  for (int i = 3; fields >> field; ++i) {
    if (i == 14) utime = std::stoull(field);
    if (i == 15) {
      stime = std::stoull(field);
      break;
    }
  }
  long peak_kib = -1;
  std::ifstream status("/proc/" + std::to_string(pid) + "/status");
  while (std::getline(status, line)) {
    if (line.rfind("VmHWM:", 0) == 0) peak_kib = std::atol(line.c_str() + 6);
  }
  return {static_cast<double>(utime + stime) / static_cast<double>(sysconf(_SC_CLK_TCK)),
          peak_kib};
}

double Percentile(std::vector<std::int64_t> sorted, double p) {
  if (sorted.empty()) return 0.0;
  const auto at = static_cast<std::size_t>(p * static_cast<double>(sorted.size() - 1) + 0.5);
  return static_cast<double>(sorted[at]) / 1000.0;
}

int Measure(const Options& options, const std::string& server) {
  int pipe_fds[2];
  if (pipe(pipe_fds) != 0) return 1;
  const pid_t child = fork();
  if (child < 0) return 1;
  if (child == 0) {
    close(pipe_fds[0]);
    signal(SIGTERM, OnSignal);
    _exit(server == "beast" ? ServeBeast(options, pipe_fds[1])
                            : ServeHttplibSse(options, pipe_fds[1]));
  }
  close(pipe_fds[1]);
  std::uint16_t port = 0;
  if (read(pipe_fds[0], &port, sizeof port) != sizeof port) {
    std::fprintf(stderr, "bench_web_server: the %s server did not start\n", server.c_str());
    return 1;
  }
  close(pipe_fds[0]);
  std::atomic<bool> stop{false};
  std::vector<Received> received(static_cast<std::size_t>(options.browsers));
  std::vector<std::thread> browsers;
  for (Received& out : received) {
    browsers.emplace_back([&, port] {
      if (server == "beast") {
        ReadWebSocket(port, stop, out);
      } else {
        ReadEventStream(port, stop, out);
      }
    });
  }
  // One second of warm-up (connections, first allocations), then the measured window.
  std::this_thread::sleep_for(std::chrono::seconds(1));
  for (Received& out : received) out.age_us.clear();
  const auto [cpu0_s, unused] = CpuAndPeakMemory(child);
  std::this_thread::sleep_for(std::chrono::duration<double>(options.seconds));
  const auto [cpu1_s, peak_kib] = CpuAndPeakMemory(child);
  stop.store(true);
  kill(child, SIGTERM);
  for (std::thread& browser : browsers) browser.join();
  int status = 0;
  waitpid(child, &status, 0);

  std::vector<std::int64_t> ages;
  std::size_t errors = 0;
  for (const Received& out : received) {
    ages.insert(ages.end(), out.age_us.begin(), out.age_us.end());
    if (!out.error.empty()) {
      ++errors;
      std::fprintf(stderr, "bench_web_server: %s browser: %s\n", server.c_str(), out.error.c_str());
    }
  }
  std::sort(ages.begin(), ages.end());
  const double expected = options.entities * options.hz * options.seconds * options.browsers;
  std::printf("%-12s %3d entities x %.0f Hz, %d browsers, %.0f s: %zu messages (%.1f %% of sent), "
              "age p50 %.2f ms, p90 %.2f ms, p99 %.2f ms, max %.2f ms; server CPU %.2f s "
              "(%.1f %% of a core), peak RSS %.1f MiB%s\n",
              server.c_str(), options.entities, options.hz, options.browsers, options.seconds,
              ages.size(), 100.0 * static_cast<double>(ages.size()) / expected,
              Percentile(ages, 0.5), Percentile(ages, 0.9), Percentile(ages, 0.99),
              Percentile(ages, 1.0), cpu1_s - cpu0_s, 100.0 * (cpu1_s - cpu0_s) / options.seconds,
              static_cast<double>(peak_kib) / 1024.0, errors ? ", BROWSER ERRORS" : "");
  return errors ? 1 : 0;
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string flag = argv[i];
    const char* value = argv[i + 1];
    if (flag == "--server") {
      options.server = value;
    } else if (flag == "--entities") {
      options.entities = std::atoi(value);
    } else if (flag == "--hz") {
      options.hz = std::atof(value);
    } else if (flag == "--browsers") {
      options.browsers = std::atoi(value);
    } else if (flag == "--seconds") {
      options.seconds = std::atof(value);
    } else {
      std::fprintf(stderr, "bench_web_server: unknown option %s\n", argv[i]);
      return 2;
    }
  }
  if (options.entities < 1 || !(options.hz > 0.0) || options.browsers < 1 ||
      !(options.seconds > 0.0) ||
      (options.server != "beast" && options.server != "httplib-sse" && options.server != "both")) {
    std::fprintf(stderr, "bench_web_server: --server beast|httplib-sse|both, --entities >= 1, "
                         "--hz > 0, --browsers >= 1, --seconds > 0\n");
    return 2;
  }
  int status = 0;
  for (const std::string server : {"beast", "httplib-sse"}) {
    if (options.server == server || options.server == "both") status |= Measure(options, server);
  }
  return status;
}
