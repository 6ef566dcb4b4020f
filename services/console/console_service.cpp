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
                         Enqueue<pena_dds::OperatorCorrectionPubSubType>()),
      link_health_reader_(participant_, topics::kLinkHealth,
                          [this](pena_dds::LinkHealth&& sample, const SampleMeta& /*meta*/) {
                            inbox_.Push(Event(LinkHealthEvent{std::move(sample)}));
                          }) {
  // The topic is durable: a run's ids differ from an earlier run's.
  run_start_s_ = static_cast<std::uint64_t>(NowNs() / 1'000'000'000);
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

void ConsoleService::Handle(const LinkHealthEvent& health) {
  ++summary_.samples;
  picture_.OnLinkHealth(ToPicture(health.sample, NowNs()));
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
        } else if constexpr (std::is_same_v<T, TranslateRequest>) {
          Translate(message.session, request.req, command);
        } else if constexpr (std::is_same_v<T, UndoRequest>) {
          Undo(message.session, request.req, command);
        } else if constexpr (std::is_same_v<T, AnnotateRequest>) {
          Annotate(message.session, request.req, command);
        } else if constexpr (std::is_same_v<T, MoveMarkRequest>) {
          MoveMark(message.session, request.req, command);
        } else {
          Retract(message.session, request.req, command);
        }
      },
      request.command());
}

std::string ConsoleService::NextId() {
  constexpr std::uint64_t kPerRun = 100'000;
  if (next_seq_ >= kPerRun) throw std::length_error("this console run has used all its ids; restart it");
  return options_.operator_id + "/" + std::to_string(run_start_s_ * kPerRun + next_seq_++);
}

std::variant<ConsolePicture::Nearest, std::string> ConsoleService::MomentAt(
    const std::string& entity_id, const Eigen::Vector2d& point_m, const std::string& field) const {
  if (!picture_.HasEntity(entity_id)) {
    return field.substr(0, field.find('.')) + ".entity: unknown entity '" + entity_id + "'";
  }
  const auto nearest = picture_.NearestTrailPose(entity_id, point_m);
  if (!nearest) return entity_id + ": no trajectory yet to correct";
  if (nearest->distance_m > options_.max_origin_distance_m) {
    return field + ": " + Num(nearest->distance_m) + " m from " + entity_id +
           "'s trajectory (at most " + Num(options_.max_origin_distance_m) + " m)";
  }
  return *nearest;
}

void ConsoleService::Send(std::uint64_t session, std::int64_t req,
                          pena_dds::OperatorCorrection& sample, const std::string& done) {
  const std::string correction_id = sample.correction_id().to_string();
  if (!correction_writer_.Write(sample)) {
    Refuse(session, req, correction_id + ": DDS refused the correction");
    return;
  }
  ++summary_.corrections_sent;
  spdlog::info("{} sent {}: {}", options_.operator_id, correction_id, done);
  Reply(session, req, "ack", done + " sent", correction_id);
}

void ConsoleService::Rotate(std::uint64_t session, std::int64_t req, const RotateRequest& rotate) {
  const auto moment = MomentAt(rotate.entity_id, rotate.origin_m, "rotate.origin");
  if (const auto* problem = std::get_if<std::string>(&moment)) {
    Refuse(session, req, *problem);
    return;
  }
  if ((rotate.wrong_m - rotate.origin_m).norm() < 0.1 ||
      (rotate.correct_m - rotate.origin_m).norm() < 0.1) {
    Refuse(session, req, "rotate " + rotate.entity_id +
                             ": the wrong and correct direction points must be at least 0.1 m "
                             "from the origin");
    return;
  }
  const double stamp_s = std::get<ConsolePicture::Nearest>(moment).stamp_s;
  const double angle_deg =
      localisation::CorrectionTransform(localisation::RotationCorrection{
          stamp_s, rotate.origin_m, rotate.wrong_m, rotate.correct_m})
          .theta_rad * 180.0 / M_PI;
  const std::uint64_t seq = next_seq_;
  pena_dds::OperatorCorrection sample =
      ToDdsRotation(rotate, stamp_s, options_.operator_id, NextId(), seq);
  Send(session, req, sample,
       "rotation of " + rotate.entity_id + " by " + Num(angle_deg) + " deg from " +
           Num(stamp_s) + " s");
}

void ConsoleService::Translate(std::uint64_t session, std::int64_t req,
                               const TranslateRequest& translate) {
  const auto moment = MomentAt(translate.entity_id, translate.point_m, "translate.point");
  if (const auto* problem = std::get_if<std::string>(&moment)) {
    Refuse(session, req, *problem);
    return;
  }
  const double stamp_s = std::get<ConsolePicture::Nearest>(moment).stamp_s;
  const Eigen::Vector2d shift = translate.correct_m - translate.point_m;
  const std::uint64_t seq = next_seq_;
  pena_dds::OperatorCorrection sample =
      ToDdsTranslation(translate, stamp_s, options_.operator_id, NextId(), seq);
  Send(session, req, sample,
       "translation of " + translate.entity_id + " by (" + Num(shift.x()) + ", " +
           Num(shift.y()) + ") m from " + Num(stamp_s) + " s");
}

void ConsoleService::Undo(std::uint64_t session, std::int64_t req, const UndoRequest& undo) {
  const CorrectionRecord* undone = picture_.FindCorrection(undo.correction_id);
  if (undone == nullptr || !undone->geometry || undone->kind == "undo") {
    Refuse(session, req, "undo.id: no rotation or translation '" + undo.correction_id + "' listed");
    return;
  }
  if (picture_.LastInForce(undone->entity_id) != undone) {
    Refuse(session, req, "undo.id: '" + undo.correction_id + "' is not the last correction of " +
                             undone->entity_id + " in force (undo goes from the last one)");
    return;
  }
  const std::uint64_t seq = next_seq_;
  pena_dds::OperatorCorrection sample = ToDdsUndo(*undone, options_.operator_id, NextId(), seq);
  Send(session, req, sample, "undo of " + undone->kind + " " + undo.correction_id + " of " +
                                 undone->entity_id);
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
  for (const Eigen::Vector2d& corner : annotate.outline_m) {
    record.outline.emplace_back(corner.x(), corner.y());
  }
  const std::string shape =
      record.outline.empty() ? "" : " (" + std::to_string(record.outline.size()) + " corners)";
  Publish(session, req, record, "marked " + annotate.kind + shape + " at " + Num(record.x_m) +
                                    ", " + Num(record.y_m));
}

void ConsoleService::MoveMark(std::uint64_t session, std::int64_t req, const MoveMarkRequest& move) {
  const AnnotationRecord* known = picture_.FindAnnotation(move.annotation_id);
  if (known == nullptr || known->retracted) {
    Refuse(session, req, "move_mark.id: no mark '" + move.annotation_id + "' to move");
    return;
  }
  AnnotationRecord record = *known;
  const double dx = move.position_m.x() - record.x_m, dy = move.position_m.y() - record.y_m;
  record.x_m += dx;
  record.y_m += dy;
  for (auto& [x, y] : record.outline) {
    x += dx;
    y += dy;
  }
  Publish(session, req, record, "moved " + record.kind + " " + record.annotation_id + " to " +
                                    Num(record.x_m) + ", " + Num(record.y_m));
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
