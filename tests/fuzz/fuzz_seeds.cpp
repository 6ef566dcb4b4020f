// fuzz_seeds: writes the binary seeds of the corpus (corpus/<target>/seed-*) from real encoder
// output: a short native mission log, line-map codec bytes, a synthetic team's link frames
// (plain, as envelopes, sealed) and CDR samples of the DDS types. The text seeds (CARMEN, TUM,
// relations, CSV, SVG, DXF, configs, browser requests) are hand-written files beside them.
// usage: fuzz_seeds CORPUS_DIR
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <fastdds/rtps/common/SerializedPayload.h>

#include "link_pair.hpp"
#include "pena/gateway/dds_convert.hpp"
#include "pena/gateway/synthetic_team.hpp"
#include "pena/io/line_map_codec.hpp"
#include "pena/io/mission_log.hpp"
#include "pena/line_map/line_map.hpp"
#include "pena_dds/correctionPubSubTypes.h"
#include "pena_dds/entityPubSubTypes.h"
#include "pena_dds/global_mapPubSubTypes.h"
#include "pena_dds/line_mapPubSubTypes.h"
#include "pena_dds/operatorPubSubTypes.h"
#include "pena_dds/scanPubSubTypes.h"
#include "to_dds.hpp"

namespace fs = std::filesystem;
using namespace pena;

namespace {

fs::path corpus;

void Put(const std::string& target, const std::string& name, const std::string& bytes) {
  fs::create_directories(corpus / target);
  std::ofstream(corpus / target / ("seed-" + name), std::ios::binary) << bytes;
}

// Walls worth a snapshot and a delta (whole millimetres: what LineMap output carries).
std::vector<line_map::LineSegment> Walls(int count, double y_m) {
  std::vector<line_map::LineSegment> walls(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) {
    auto& wall = walls[static_cast<std::size_t>(i)];
    wall.segment.start_m = {4.0 * i, y_m};
    wall.segment.end_m = {4.0 * i + 3.0, y_m};
    wall.support_cells = 40;
    wall.observations = 5;
  }
  return walls;
}

void MissionLog() {
  const fs::path path = fs::temp_directory_path() / "pena-fuzz-seed.penalog";
  {
    io::MissionLogHeader header;
    header.mission = "seed";
    header.entity_id = "ff1";
    header.laser = {-1.5, 0.5, 30.0, 0.01, 1};
    io::MissionLogWriter writer(path, header);
    sensors::LaserScan scan;
    scan.stamp_s = 0.1;
    scan.geometry = header.laser;
    scan.ranges_m = {1.0f, 2.0f, sensors::LaserScan::kNoReturn, 3.5f, 4.0f, 2.5f, 1.5f};
    writer.Write(scan);
    writer.Write(sensors::GyroSample{0.11, 0.2});
    writer.Write(sensors::CompassSample{0.12, 1.0});
    writer.Write(sensors::StrideSample{0.13, 0.7});
    writer.Write(sensors::WheelOdometry{0.14, {1.0, 2.0, 0.3}, 0.5, 0.1});
    writer.Close();
  }
  std::ifstream in(path, std::ios::binary);
  Put("fuzz_mission_log", "five-records", std::string(std::istreambuf_iterator<char>(in), {}));
  fs::remove(path);
}

void LineMapCodec() {
  line_map::LineMap map;
  const line_map::MapDelta first = map.Integrate(Walls(3, 0.0), "ff1");
  const line_map::MapDelta second = map.Integrate(Walls(2, 0.5), "ff2");
  Put("fuzz_line_map_codec", "delta", std::string(1, '\0') + io::EncodeDelta(first));
  Put("fuzz_line_map_codec", "delta-2", std::string(1, '\0') + io::EncodeDelta(second));
  Put("fuzz_line_map_codec", "snapshot", std::string(1, '\1') + io::EncodeSnapshot(map.Snapshot()));
}

std::string Chunk(const std::string& payload) {
  std::string out;
  out.push_back(static_cast<char>(payload.size() >> 8));
  out.push_back(static_cast<char>(payload.size()));
  return out + payload;
}

void Link() {
  using namespace gateway;
  testing::LinkPair pair(testing::Endpoint(1), testing::Endpoint(2), testing::IdealLink(),
                         testing::IdealLink());
  SyntheticTeamOptions options;
  options.alarm_period_s = 2.0;
  SyntheticTeam team(options);
  line_map::LineMap global;
  pair.near.Offer(MapChange{"global", global.Integrate(Walls(60, 0.0), "global"), false});
  while (pair.now_s < 6.0) {
    for (DomainItem& item : team.Advance(pair.now_s)) pair.near.Offer(std::move(item));
    pair.Step(0.01);
  }
  LinkKey key;
  for (std::size_t i = 0; i < key.bytes.size(); ++i) key.bytes[i] = static_cast<std::uint8_t>(i + 1);
  SealOptions seal_options;
  seal_options.sender_id = 1;
  LinkSeal seal(key, seal_options);
  std::string session;
  int n = 0;
  for (const auto& [t, frame] : pair.sent_forward) {
    if (n >= 12) break;
    const std::string name = std::to_string(n++);
    Put("fuzz_link_frame", name, frame);
    Put("fuzz_link_open", "sealed-" + name, std::string(1, '\0') + seal.Seal(frame, 1.7e9 + t));
    session += Chunk(DecodeFrame(frame).payload);
    if (n % 4 == 0) {
      Put("fuzz_link_session", name, session);
      session.clear();
    }
  }
  Put("fuzz_link_open", "round-trip", std::string(1, '\1') + pair.sent_forward.front().second);
}

template <class PubSubType>
std::string Cdr(typename PubSubType::type sample) {
  PubSubType type;
  eprosima::fastrtps::rtps::SerializedPayload_t payload(type.getSerializedSizeProvider(&sample)());
  type.serialize(&sample, &payload);
  return std::string(reinterpret_cast<const char*>(payload.data), payload.length);
}

void Dds() {
  line_map::LineMap map;
  const line_map::MapDelta delta = map.Integrate(Walls(3, 0.0), "ff1");
  const line_map::MapSnapshot snapshot = map.Snapshot();
  Put("fuzz_from_dds", "line-map-delta",
      std::string(1, '\0') + Cdr<pena_dds::LineMapDeltaPubSubType>(services::ToDdsLineMapDelta(delta, "ff1", 1.0)));
  Put("fuzz_from_dds", "line-map-snapshot",
      std::string(1, '\1') + Cdr<pena_dds::LineMapSnapshotPubSubType>(services::ToDdsLineMapSnapshot(snapshot, "ff1", 1.0)));
  // The global map as pena-fusion publishes it: walls with their support (who saw them, error sd).
  line_map::MapDelta global = delta;
  for (std::size_t i = 0; i < global.added.size(); ++i) {
    global.added[i].seen_by_entities = static_cast<std::uint32_t>(i + 1);
    global.added[i].error_sd_m = line_map::Quantise(0.04 * static_cast<double>(i + 1), line_map::kErrorSdQuantumM);
  }
  Put("fuzz_from_dds", "global-map-delta",
      std::string(1, '\2') + Cdr<pena_dds::GlobalMapDeltaPubSubType>(services::ToDdsGlobalMapDelta(global, "global", 1.0)));
  Put("fuzz_line_map_codec", "global-delta", std::string(1, '\0') + io::EncodeDelta(global));
  pena_dds::Correction correction;
  correction.schema_version(pena_dds::SCHEMA_VERSION);
  correction.entity_id("ff1");
  correction.kind(pena_dds::CORRECTION_MAP_FROM_ODOM);
  correction.confidence(1.0);
  Put("fuzz_from_dds", "correction", std::string(1, '\4') + Cdr<pena_dds::CorrectionPubSubType>(correction));
  Put("fuzz_dds_convert", "correction", std::string(1, '\2') + Cdr<pena_dds::CorrectionPubSubType>(correction));

  gateway::PoseUpdate pose;
  pose.entity = "ff1";
  pose.world_from_body = {1.0, 2.0, 0.5};
  pose.position_sd_m = 0.2;
  Put("fuzz_dds_convert", "pose",
      std::string(1, '\0') + Cdr<pena_dds::EntityPosePubSubType>(gateway::PoseToDds(pose, 7)));
  pena_dds::Annotation annotation;
  annotation.schema_version(pena_dds::SCHEMA_VERSION);
  annotation.annotation_id("ff1/3");
  annotation.author_id("ff1");
  annotation.kind(pena_dds::ANNOTATION_VICTIM_FOUND);
  Put("fuzz_dds_convert", "annotation", std::string(1, '\1') + Cdr<pena_dds::AnnotationPubSubType>(annotation));
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: fuzz_seeds CORPUS_DIR\n");
    return 2;
  }
  corpus = argv[1];
  MissionLog();
  LineMapCodec();
  Link();
  Dds();
  return 0;
}
