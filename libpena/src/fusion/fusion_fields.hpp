#pragma once
// The fields the fusion codec is made of: poses, segments, deltas, snapshots, annotations.
// Internal to the fusion module.

#include <optional>
#include <vector>

#include "byte_codec.hpp"
#include "pena/fusion/fusion_input.hpp"

namespace pena::fusion::detail {

void Put(ByteWriter& w, const geometry::Pose2& pose);
geometry::Pose2 GetPose(ByteReader& r);
void Put(ByteWriter& w, const std::optional<geometry::Pose2>& pose);
std::optional<geometry::Pose2> GetOptionalPose(ByteReader& r);
void Put(ByteWriter& w, const line_map::LineSegment& s);
line_map::LineSegment GetSegment(ByteReader& r);
void Put(ByteWriter& w, const std::vector<line_map::LineSegment>& list);
std::vector<line_map::LineSegment> GetSegments(ByteReader& r);
void Put(ByteWriter& w, const line_map::MapDelta& d);
line_map::MapDelta GetDelta(ByteReader& r);
void Put(ByteWriter& w, const line_map::MapSnapshot& s);
line_map::MapSnapshot GetSnapshot(ByteReader& r);
void Put(ByteWriter& w, const Annotation& a);
Annotation GetAnnotation(ByteReader& r);

}  // namespace pena::fusion::detail
