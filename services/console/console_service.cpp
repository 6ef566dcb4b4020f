#include "console_service.hpp"

#include <spdlog/spdlog.h>

#include <cmath>
#include <fstream>
#include <stdexcept>

#include "console_conversions.hpp"
#include "from_dds.hpp"
#include "signals.hpp"
#include "topics.hpp"

namespace pena::services {
namespace {

using nlohmann::json;

void Require(bool ok, const std::string& message) {
  if (!ok) throw std::invalid_argument(message);
}

std::string Num(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2f", value);
  return text;
}

}  // namespace

void ValidateConsoleOptions(const ConsoleOptions& options) {
  Require(!options.web.bind_address.empty(), "bind address must be given (e.g. 127.0.0.1)");
  Require(!options.operator_id.empty() && options.operator_id.size() <= 16,
          "operator_id must be 1 to 16 characters, got '" + options.operator_id + "'");
  Require(options.tick_s > 0.0 && options.tick_s <= 5.0,
          "tick_s must be in (0, 5] s, got " + std::to_string(options.tick_s));
  Require(options.max_origin_distance_m > 0.0,
          "max_origin_distance_m must be > 0 m, got " +
              std::to_string(options.max_origin_distance_m));
  Require(options.picture.stale_after_s > 0.0,
          "stale_after_s must be > 0 s, got " + std::to_string(options.picture.stale_after_s));
  Require(options.picture.trail_points >= 2, "trail_points must be >= 2");
  Require(options.duration_s >= 0.0, "duration_s must be >= 0 s (0 = until a signal)");
}

template <class PubSubType>
typename Reader<PubSubType>::SampleCallback ConsoleService::Enqueue() {
  return [this](typename PubSubType::type&& sample, const SampleMeta& /*meta*/) {
    inbox_.Push(Event(std::move(sample)));
  };
}

ConsoleService::ConsoleService(ConsoleOptions options)
    : options_((ValidateConsoleOptions(options), std::move(options))),
      picture_(options_.picture),
      participant_(options_.dds, "pena-console"),
      correction_writer_(participant_, topics::kOperatorCorrection),
      annotation_writer_(participant_, topics::kAnnotation),
      pose_reader_(participant_, topics::kPose,
                   [this](pena_dds::EntityPose&& sample, const SampleMeta& meta) {
                     inbox_.Push(Event(PoseEvent{std::move(sample), meta}));
                   }),
      status_reader_(participant_, topics::kStatus, Enqueue<pena_dds::EntityStatusPubSubType>()),
      delta_reader_(participant_, topics::kGlobalMapDelta,
                    Enqueue<pena_dds::GlobalMapDeltaPubSubType>()),
      snapshot_reader_(participant_, topics::kGlobalMapSnapshot,
                       Enqueue<pena_dds::GlobalMapSnapshotPubSubType>()),
      annotation_reader_(participant_, topics::kAnnotation,
                         Enqueue<pena_dds::AnnotationPubSubType>()),
      correction_reader_(participant_, topics::kOperatorCorrection,
                         Enqueue<pena_dds::OperatorCorrectionPubSubType>()) {
  // The topic is durable: a run's ids "<operator>/<start s>-<n>" differ from an earlier run's.
  run_id_ = std::to_string(NowNs() / 1'000'000'000);
  WebServerCallbacks callbacks;
  callbacks.on_open = [this](std::uint64_t session) { inbox_.Push(Event(BrowserOpen{session})); };
  callbacks.on_message = [this](std::uint64_t session, std::string text) {
    inbox_.Push(Event(BrowserMessage{session, std::move(text)}));
  };
  callbacks.on_close = [this](std::uint64_t session) {
    inbox_.Push(Event(BrowserClose{session}));
  };
  web_ = std::make_unique<WebServer>(options_.web, std::move(callbacks));
  if (!options_.port_file.empty()) {
    std::ofstream out(options_.port_file);
    out << web_->port() << '\n';
    if (!out) throw std::invalid_argument("port_file: cannot write " + options_.port_file.string());
  }
}

ConsoleService::~ConsoleService() { web_.reset(); }

ConsoleSummary ConsoleService::Run() {
  const std::int64_t tick_ns = static_cast<std::int64_t>(options_.tick_s * 1e9);
  const std::int64_t end_ns = options_.duration_s > 0.0
                                  ? NowNs() + static_cast<std::int64_t>(options_.duration_s * 1e9)
                                  : INT64_MAX;
  std::int64_t next_tick_ns = NowNs() + tick_ns;
  while (!StopRequested() && NowNs() < end_ns) {
    const std::int64_t wait_ns = std::max<std::int64_t>(0, next_tick_ns - NowNs());
    if (std::optional<Event> event = inbox_.PopFor(std::chrono::nanoseconds(wait_ns))) {
      try {
        std::visit([this](const auto& e) { Handle(e); }, *event);
      } catch (const std::exception& error) {
        // Another schema version or a malformed sample: dropped, the console goes on.
        spdlog::warn("sample dropped: {}", error.what());
      }
    }
    if (NowNs() >= next_tick_ns) {
      Flush();
      next_tick_ns = NowNs() + tick_ns;
    }
  }
  return summary_;
}

void ConsoleService::Flush() {
  if (std::optional<json> delta = picture_.TakeDelta(NowNs())) {
    web_->Broadcast(delta->dump());
    ++summary_.deltas_sent;
  }
}

void ConsoleService::Handle(const PoseEvent& pose) {
  ++summary_.samples;
  picture_.OnPose(ToPicture(pose.sample, pose.meta.reception_time_ns, pose.meta.source_time_ns));
}

void ConsoleService::Handle(const pena_dds::EntityStatus& sample) {
  ++summary_.samples;
  picture_.OnStatus(ToPicture(sample, NowNs()));
}

void ConsoleService::Handle(const pena_dds::GlobalMapDelta& sample) {
  ++summary_.samples;
  if (sample.map_id() != kGlobalMapId) return;
  picture_.OnMapDelta(FromDds(sample));
}

void ConsoleService::Handle(const pena_dds::GlobalMapSnapshot& sample) {
  ++summary_.samples;
  if (sample.map_id() != kGlobalMapId) return;
  picture_.OnMapSnapshot(FromDds(sample));
}

void ConsoleService::Handle(const pena_dds::Annotation& sample) {
  ++summary_.samples;
  picture_.OnAnnotation(ToPicture(sample));
}

void ConsoleService::Handle(const pena_dds::OperatorCorrection& sample) {
  ++summary_.samples;
  picture_.OnCorrection(ToPicture(sample));
}

void ConsoleService::Handle(const BrowserOpen& open) {
  ++summary_.browsers;
  // Everyone else first gets what changed, so the snapshot and the next delta fit together.
  Flush();
  json snapshot = picture_.Snapshot(NowNs());
  snapshot["operator"] = options_.operator_id;
  web_->Send(open.session, snapshot.dump(), /*ready=*/true);
  spdlog::info("browser {} connected: snapshot of {} entities, map version {}", open.session,
               picture_.entity_count(), picture_.map_version());
}

void ConsoleService::Handle(const BrowserClose& close) {
  spdlog::info("browser {} disconnected", close.session);
}

void ConsoleService::Reply(std::uint64_t session, std::int64_t req, const std::string& type,
                           const std::string& text, const std::string& correction_id) {
  json reply = {{"type", type}, {"req", req}, {"message", text}};
  if (!correction_id.empty()) reply["correction_id"] = correction_id;
  web_->Send(session, reply.dump());
}

void ConsoleService::Handle(const BrowserMessage& message) {
  ++summary_.requests;
  const BrowserRequest request = ParseBrowserRequest(message.text);
  if (!request.ok()) {
    Refuse(message.session, request.req, request.error());
    return;
  }
  std::visit(
      [&](const auto& command) {
        using T = std::decay_t<decltype(command)>;
        if constexpr (std::is_same_v<T, PingRequest>) {
          Reply(message.session, request.req, "pong", "");
        } else if constexpr (std::is_same_v<T, RotateRequest>) {
          Rotate(message.session, request.req, command);
        } else if constexpr (std::is_same_v<T, AnnotateRequest>) {
          Annotate(message.session, request.req, command);
        } else {
          Retract(message.session, request.req, command);
        }
      },
      request.command());
}

std::string ConsoleService::NextId() {
  return options_.operator_id + "/" + run_id_ + "-" + std::to_string(next_seq_++);
}

void ConsoleService::Rotate(std::uint64_t session, std::int64_t req, const RotateRequest& rotate) {
  const std::string who = "rotate " + rotate.entity_id;
  std::string problem;
  const auto nearest = picture_.NearestTrailPose(rotate.entity_id, rotate.origin_m);
  if (!picture_.HasEntity(rotate.entity_id)) {
    problem = "rotate.entity: unknown entity '" + rotate.entity_id + "'";
  } else if (!nearest) {
    problem = who + ": no trajectory yet to rotate";
  } else if (nearest->distance_m > options_.max_origin_distance_m) {
    problem = "rotate.origin: " + Num(nearest->distance_m) + " m from " + rotate.entity_id +
              "'s trajectory (at most " + Num(options_.max_origin_distance_m) + " m)";
  } else if ((rotate.wrong_m - rotate.origin_m).norm() < 0.1 ||
             (rotate.correct_m - rotate.origin_m).norm() < 0.1) {
    problem = who + ": the wrong and correct direction points must be at least 0.1 m from the "
                    "origin";
  }
  if (!problem.empty()) {
    Refuse(session, req, problem);
    return;
  }
  const std::uint64_t seq = next_seq_;
  const std::string correction_id = NextId();
  pena_dds::OperatorCorrection sample =
      ToDdsRotation(rotate, nearest->stamp_s, options_.operator_id, correction_id, seq);
  if (!correction_writer_.Write(sample)) {
    Refuse(session, req, who + ": DDS refused the correction");
    return;
  }
  ++summary_.corrections_sent;
  const double angle_deg =
      localisation::CorrectionTransform(localisation::RotationCorrection{
          nearest->stamp_s, rotate.origin_m, rotate.wrong_m, rotate.correct_m})
          .theta_rad * 180.0 / M_PI;
  spdlog::info("{} sent {}: rotate {} by {:.2f} deg about ({:.2f}, {:.2f}) from {:.2f} s",
               options_.operator_id, correction_id, rotate.entity_id, angle_deg,
               rotate.origin_m.x(), rotate.origin_m.y(), nearest->stamp_s);
  Reply(session, req, "ack",
        "rotation of " + rotate.entity_id + " by " + Num(angle_deg) + " deg from " +
            Num(nearest->stamp_s) + " s sent",
        correction_id);
}

void ConsoleService::Annotate(std::uint64_t session, std::int64_t req,
                              const AnnotateRequest& annotate) {
  AnnotationRecord record;
  record.annotation_id = NextId();
  record.author_id = options_.operator_id;
  record.kind = annotate.kind;
  record.stamp_s = picture_.latest_stamp_s();  // mission time as far as the console knows it
  record.x_m = annotate.position_m.x();
  record.y_m = annotate.position_m.y();
  record.radius_m = annotate.radius_m;
  record.text = annotate.text;
  Publish(session, req, record, "marked " + annotate.kind + " at " + Num(record.x_m) + ", " +
                                    Num(record.y_m));
}

void ConsoleService::Retract(std::uint64_t session, std::int64_t req,
                             const RetractRequest& retract) {
  const AnnotationRecord* known = picture_.FindAnnotation(retract.annotation_id);
  if (known == nullptr || known->retracted) {
    Refuse(session, req, "retract.id: no mark '" + retract.annotation_id + "' to retract");
    return;
  }
  AnnotationRecord record = *known;
  record.retracted = true;
  Publish(session, req, record, "retracted " + record.kind + " " + record.annotation_id);
}

void ConsoleService::Publish(std::uint64_t session, std::int64_t req,
                             const AnnotationRecord& record, const std::string& done) {
  pena_dds::Annotation sample;
  try {
    sample = ToDdsAnnotation(record);
  } catch (const std::exception& error) {
    Refuse(session, req, error.what());
    return;
  }
  if (!annotation_writer_.Write(sample)) {
    Refuse(session, req, "DDS refused the annotation");
    return;
  }
  ++summary_.annotations_sent;
  spdlog::info("{} sent {}: {}", options_.operator_id, record.annotation_id, done);
  Reply(session, req, "ack", done, record.annotation_id);
}

void ConsoleService::Refuse(std::uint64_t session, std::int64_t req, const std::string& problem) {
  ++summary_.refused;
  spdlog::warn("browser {}: request refused: {}", session, problem);
  Reply(session, req, "error", problem);
}

}  // namespace pena::services
