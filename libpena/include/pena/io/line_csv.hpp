#pragma once
// Line maps and floor plans as CSV: header "id,x1,y1,x2,y2" (metres), more columns may follow.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "pena/geometry/segment2.hpp"

namespace pena::io {

// One row: a segment with its id; `extra` holds any further columns verbatim (comma-joined).
struct LineRow {
  std::int64_t id = 0;
  geometry::Segment2 segment;
  std::string extra;
};

// Writes the header "id,x1,y1,x2,y2" plus `extra_header` (e.g. ",wall_id") and one row per line,
// coordinates with millimetre precision.
void WriteLineCsv(const std::filesystem::path& path, const std::vector<LineRow>& rows,
                  const std::string& extra_header = "");
// Reads a line CSV; throws InputError naming the line for a bad header or row.
std::vector<LineRow> ReadLineCsv(const std::filesystem::path& path);

}  // namespace pena::io
