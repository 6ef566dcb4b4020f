#pragma once
// Every PeNa DDS topic: its name and the QoS profiles of its writers and readers
// (deploy/dds/pena-qos.xml). Types, rates and QoS are listed in docs/dds.md.

namespace pena::services {

// A topic and the XML profile names its endpoints are created with.
struct TopicSpec {
  const char* name;
  const char* writer_profile;
  const char* reader_profile;
};

namespace topics {
// pena_dds::EntityPose, keyed by entity, at scan rate.
inline constexpr TopicSpec kPose{"pena/entity/pose", "pena_pose_writer", "pena_pose_reader"};
// pena_dds::EntityStatus heartbeat.
inline constexpr TopicSpec kStatus{"pena/entity/status", "pena_status_writer",
                                   "pena_status_reader"};
// pena_dds::LineMapDelta, an entity's line-map changes.
inline constexpr TopicSpec kLineMapDelta{"pena/entity/line_map_delta",
                                         "pena_line_map_delta_writer",
                                         "pena_line_map_delta_reader"};
// pena_dds::LineMapSnapshot, an entity's whole line map (on request and at the end).
inline constexpr TopicSpec kLineMapSnapshot{"pena/entity/line_map_snapshot",
                                            "pena_line_map_snapshot_writer",
                                            "pena_line_map_snapshot_reader"};
// pena_dds::ReferenceScan, at reference changes.
inline constexpr TopicSpec kReferenceScan{"pena/entity/reference_scan",
                                          "pena_reference_scan_writer",
                                          "pena_reference_scan_reader"};
// pena_dds::Correction, fusion -> entity.
inline constexpr TopicSpec kCorrection{"pena/fusion/correction", "pena_correction_writer",
                                       "pena_correction_reader"};
// pena_dds::GlobalMapDelta, fusion -> everyone.
inline constexpr TopicSpec kGlobalMapDelta{"pena/fusion/global_map_delta",
                                           "pena_global_map_delta_writer",
                                           "pena_global_map_delta_reader"};
// pena_dds::GlobalMapSnapshot, fusion -> late joiners.
inline constexpr TopicSpec kGlobalMapSnapshot{"pena/fusion/global_map_snapshot",
                                              "pena_global_map_snapshot_writer",
                                              "pena_global_map_snapshot_reader"};
// pena_dds::OperatorCorrection.
inline constexpr TopicSpec kOperatorCorrection{"pena/operator/correction",
                                               "pena_operator_writer", "pena_operator_reader"};
// pena_dds::Annotation.
inline constexpr TopicSpec kAnnotation{"pena/annotation", "pena_operator_writer",
                                       "pena_operator_reader"};
// pena_dds::LinkHealth, pena-gateway -> the operator's console.
inline constexpr TopicSpec kLinkHealth{"pena/gateway/link_health", "pena_status_writer",
                                       "pena_status_reader"};
// pena_dds::SyncRequest: "send me your snapshot".
inline constexpr TopicSpec kSyncRequest{"pena/sync_request", "pena_sync_request_writer",
                                        "pena_sync_request_reader"};
}  // namespace topics

// The map_id of the one global map on kGlobalMapDelta / kGlobalMapSnapshot, and the target_id
// a SyncRequest for it names.
inline constexpr const char* kGlobalMapId = "global";

}  // namespace pena::services
