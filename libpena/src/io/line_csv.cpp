// Line maps and floor plans as CSV: "id,x1,y1,x2,y2[,extra...]" (metres).
#include "pena/io/line_csv.hpp"

#include <cmath>
#include <string_view>

#include "gz_line_reader.hpp"
#include "pena/io/input_error.hpp"
#include "text_fields.hpp"
#include "text_writer.hpp"

namespace pena::io {
namespace {

constexpr std::string_view kHeader = "id,x1,y1,x2,y2";
constexpr int kMillimetreDecimals = 3;

std::string_view Trimmed(std::string_view text) {
  const std::size_t first = text.find_first_not_of(" \t");
  if (first == std::string_view::npos) return {};
  const std::size_t last = text.find_last_not_of(" \t");
  return text.substr(first, last - first + 1);
}

double Coordinate(const std::filesystem::path& path, std::size_t line, std::string_view field,
                  const char* name) {
  const std::optional<double> value = detail::ParseDouble(Trimmed(field));
  if (!value || !std::isfinite(*value)) {
    throw InputError(path, line, std::string(name) + " '" + std::string(field) +
                                     "' is not a finite number (metres)");
  }
  return *value;
}

LineRow ParseRow(const std::filesystem::path& path, std::size_t line, std::string_view text) {
  const std::vector<std::string_view> fields = detail::SplitAt(text, ',');
  if (fields.size() < 5) {
    throw InputError(path, line,
                     "expected at least 5 columns (id,x1,y1,x2,y2), found " +
                         std::to_string(fields.size()));
  }
  LineRow row;
  const std::optional<std::int64_t> id = detail::ParseInt64(Trimmed(fields[0]));
  if (!id) throw InputError(path, line, "id '" + std::string(fields[0]) + "' is not an integer");
  row.id = *id;
  row.segment.start_m = {Coordinate(path, line, fields[1], "x1"),
                         Coordinate(path, line, fields[2], "y1")};
  row.segment.end_m = {Coordinate(path, line, fields[3], "x2"),
                       Coordinate(path, line, fields[4], "y2")};
  // Everything after the fifth comma, verbatim.
  std::size_t position = std::string_view::npos;
  std::size_t from = 0;
  for (int commas = 0; commas < 5; ++commas) {
    position = text.find(',', from);
    if (position == std::string_view::npos) break;
    from = position + 1;
  }
  if (position != std::string_view::npos) row.extra = std::string(text.substr(position + 1));
  return row;
}

}  // namespace

void WriteLineCsv(const std::filesystem::path& path, const std::vector<LineRow>& rows,
                  const std::string& extra_header) {
  detail::TextWriter out(path);
  out.Put(std::string(kHeader) + extra_header + "\n");
  for (const LineRow& row : rows) {
    std::string line = std::to_string(row.id);
    for (double value : {row.segment.start_m.x(), row.segment.start_m.y(), row.segment.end_m.x(),
                         row.segment.end_m.y()}) {
      line += ',';
      line += detail::FormatFixed(value, kMillimetreDecimals);
    }
    if (!row.extra.empty()) line += "," + row.extra;
    out.Put(line + "\n");
  }
  out.Close();
}

std::vector<LineRow> ReadLineCsv(const std::filesystem::path& path) {
  detail::GzLineReader reader(path);
  std::string line;
  if (!reader.ReadLine(line)) throw InputError(path, 1, "empty file: expected header id,x1,y1,x2,y2");
  const std::vector<std::string_view> header = detail::SplitAt(line, ',');
  const std::vector<std::string_view> expected = detail::SplitAt(kHeader, ',');
  bool header_ok = header.size() >= expected.size();
  for (std::size_t i = 0; header_ok && i < expected.size(); ++i) {
    header_ok = Trimmed(header[i]) == expected[i];
  }
  if (!header_ok) {
    throw InputError(path, 1, "expected header starting id,x1,y1,x2,y2, found '" + line + "'");
  }
  std::vector<LineRow> rows;
  while (reader.ReadLine(line)) {
    if (Trimmed(line).empty()) continue;
    rows.push_back(ParseRow(path, reader.line_number(), line));
  }
  return rows;
}

}  // namespace pena::io
