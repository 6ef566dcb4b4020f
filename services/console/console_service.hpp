#pragma once
// pena-console: the command post's live view in a browser (docs/console.md). A thin DDS adapter:
// the constructor creates the participant, readers of poses, statuses, the global map,
// annotations and operator corrections, the operator-correction and annotation writers, then
// the web server (web_server.hpp). Listener and web callbacks only enqueue; Run() is the one
// worker that owns the picture (console_picture.hpp): it applies samples, answers browsers (a
// snapshot when they connect, deltas every tick) and turns the operator's validated gestures
// into pena_dds::OperatorCorrection and pena_dds::Annotation samples.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <variant>

#include "browser_request.hpp"
#include "console_picture.hpp"
#include "dds_endpoints.hpp"
#include "dds_participant.hpp"
#include "pena_dds/entityPubSubTypes.h"
#include "pena_dds/global_mapPubSubTypes.h"
#include "pena_dds/operatorPubSubTypes.h"
#include "web_server.hpp"
#include "work_queue.hpp"

namespace pena::services {

// pena-console's options.
struct ConsoleOptions {
  DdsOptions dds;
  WebServerOptions web;
  PictureOptions picture;
  std::string operator_id = "operator";  // author of this console's corrections (<= 16 chars)
  double tick_s = 0.05;                  // wall seconds between deltas to the browsers
  double max_origin_distance_m = 3.0;    // a rotation origin farther from the entity's trail
                                         // is refused (it names no moment of its trajectory)
  double duration_s = 0.0;               // wall seconds to run; 0 = until SIGINT/SIGTERM
  std::filesystem::path port_file;       // if given: the bound port is written there
};

// Throws std::invalid_argument naming the field and its unit.
void ValidateConsoleOptions(const ConsoleOptions& options);

// Counts per run.
struct ConsoleSummary {
  long samples = 0;
  long browsers = 0;
  long requests = 0;
  long refused = 0;
  long corrections_sent = 0;
  long annotations_sent = 0;
  long deltas_sent = 0;
};

class ConsoleService {
 public:
  // Throws DdsError, std::invalid_argument (options) or std::runtime_error (cannot listen).
  explicit ConsoleService(ConsoleOptions options);
  ~ConsoleService();
  ConsoleService(const ConsoleService&) = delete;
  ConsoleService& operator=(const ConsoleService&) = delete;

  // The port the web server listens on.
  std::uint16_t port() const { return web_->port(); }
  // Runs until the duration passed or a stop signal.
  ConsoleSummary Run();

 private:
  struct BrowserOpen {
    std::uint64_t session;
  };
  struct BrowserMessage {
    std::uint64_t session;
    std::string text;
  };
  struct BrowserClose {
    std::uint64_t session;
  };
  struct LinkHealthEvent {
    pena_dds::LinkHealth sample;
  };
  struct PoseEvent {
    pena_dds::EntityPose sample;
    SampleMeta meta;
  };
  using Event = std::variant<PoseEvent, pena_dds::EntityStatus, pena_dds::GlobalMapDelta,
                             pena_dds::GlobalMapSnapshot, pena_dds::Annotation,
                             pena_dds::OperatorCorrection, LinkHealthEvent, BrowserOpen,
                             BrowserMessage, BrowserClose>;
  template <class PubSubType>
  typename Reader<PubSubType>::SampleCallback Enqueue();

  void Handle(const PoseEvent& pose);
  void Handle(const pena_dds::EntityStatus& sample);
  void Handle(const pena_dds::GlobalMapDelta& sample);
  void Handle(const pena_dds::GlobalMapSnapshot& sample);
  void Handle(const pena_dds::Annotation& sample);
  void Handle(const pena_dds::OperatorCorrection& sample);
  void Handle(const LinkHealthEvent& health);
  void Handle(const BrowserOpen& open);
  void Handle(const BrowserMessage& message);
  void Handle(const BrowserClose& close);
  void Rotate(std::uint64_t session, std::int64_t req, const RotateRequest& rotate);
  void Translate(std::uint64_t session, std::int64_t req, const TranslateRequest& translate);
  void Undo(std::uint64_t session, std::int64_t req, const UndoRequest& undo);
  void MoveMark(std::uint64_t session, std::int64_t req, const MoveMarkRequest& move);
  // The moment of the entity's trail nearest `point_m`, or the problem (naming `field`).
  std::variant<ConsolePicture::Nearest, std::string> MomentAt(const std::string& entity_id,
                                                              const Eigen::Vector2d& point_m,
                                                              const std::string& field) const;
  // Publishes an operator correction and answers the browser.
  void Send(std::uint64_t session, std::int64_t req, pena_dds::OperatorCorrection& sample,
            const std::string& done);
  void Annotate(std::uint64_t session, std::int64_t req, const AnnotateRequest& annotate);
  void Retract(std::uint64_t session, std::int64_t req, const RetractRequest& retract);
  // Publishes a new or changed annotation and answers the browser.
  void Publish(std::uint64_t session, std::int64_t req, const AnnotationRecord& record,
               const std::string& done);
  // Answers an error; nothing was applied.
  void Refuse(std::uint64_t session, std::int64_t req, const std::string& problem);
  // "<operator>/<n>", n = the run's start in wall seconds * 100000 + a count: unique across
  // runs (the operator topics are durable) and decimal, as the link packs annotation ids.
  std::string NextId();
  void Flush();
  // Answers a browser's request: an error names what was wrong, nothing is applied.
  void Reply(std::uint64_t session, std::int64_t req, const std::string& type,
             const std::string& text, const std::string& correction_id = {});

  ConsoleOptions options_;
  ConsolePicture picture_;
  ConsoleSummary summary_;
  std::uint64_t next_seq_ = 1;
  // Wall seconds at start: this run's ids differ from an earlier run's.
  std::uint64_t run_start_s_ = 0;
  WorkQueue<Event> inbox_;
  Participant participant_;
  Writer<pena_dds::OperatorCorrectionPubSubType> correction_writer_;
  Writer<pena_dds::AnnotationPubSubType> annotation_writer_;
  Reader<pena_dds::EntityPosePubSubType> pose_reader_;
  Reader<pena_dds::EntityStatusPubSubType> status_reader_;
  Reader<pena_dds::GlobalMapDeltaPubSubType> delta_reader_;
  Reader<pena_dds::GlobalMapSnapshotPubSubType> snapshot_reader_;
  Reader<pena_dds::AnnotationPubSubType> annotation_reader_;
  Reader<pena_dds::OperatorCorrectionPubSubType> correction_reader_;
  Reader<pena_dds::LinkHealthPubSubType> link_health_reader_;
  // Last: destroyed first, so no callback reaches a half-destroyed service.
  std::unique_ptr<WebServer> web_;
};

}  // namespace pena::services
