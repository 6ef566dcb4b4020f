// ROS map_server maps: a P5 PGM and a yaml of metadata (http://wiki.ros.org/map_server).
#include "pena/io/ros_map.hpp"

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>

#include "gz_line_reader.hpp"
#include "pena/io/input_error.hpp"
#include "text_fields.hpp"
#include "text_writer.hpp"

namespace pena::io {
namespace {

constexpr std::uint8_t kPgmOccupied = 0;
constexpr std::uint8_t kPgmFree = 254;
constexpr std::uint8_t kPgmUnknown = 205;  // what map_saver writes for unknown cells
constexpr int kMaxPgmSide = 100000;

std::string_view Trimmed(std::string_view text) {
  const std::size_t first = text.find_first_not_of(" \t\r");
  if (first == std::string_view::npos) return {};
  return text.substr(first, text.find_last_not_of(" \t\r") - first + 1);
}

void ValidateImage(const grid::GridImage& image) {
  if (image.occupancy.empty() || image.occupancy.type() != CV_8UC1) {
    throw std::invalid_argument("ROS map: occupancy must be a non-empty CV_8UC1 image");
  }
  if (!std::isfinite(image.resolution_m) || image.resolution_m <= 0.0) {
    throw std::invalid_argument("ROS map: resolution_m must be finite and > 0 m, got " +
                                std::to_string(image.resolution_m));
  }
  if (!image.origin_m.allFinite()) throw std::invalid_argument("ROS map: origin_m must be finite");
}

std::uint8_t TrinaryPgmPixel(std::uint8_t occupancy) {
  const double probability = occupancy / 255.0;
  if (probability > kRosOccupiedThreshold) return kPgmOccupied;
  if (probability < kRosFreeThreshold) return kPgmFree;
  return kPgmUnknown;
}

void WritePgm(const std::filesystem::path& path, const grid::GridImage& image) {
  const cv::Mat& occupancy = image.occupancy;
  std::string bytes = "P5\n# PeNa occupancy grid, " + detail::FormatExact(image.resolution_m) +
                      " m/pix\n" + std::to_string(occupancy.cols) + " " +
                      std::to_string(occupancy.rows) + "\n255\n";
  // Both GridImage and map_server put the largest y in row 0, so rows are written as they are.
  for (int row = 0; row < occupancy.rows; ++row) {
    const auto* pixels = occupancy.ptr<std::uint8_t>(row);
    for (int col = 0; col < occupancy.cols; ++col)
      bytes += static_cast<char>(TrinaryPgmPixel(pixels[col]));
  }
  errno = 0;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  out.close();
  if (!out) {
    const int saved = errno;
    throw std::runtime_error(path.string() + ": cannot write" +
                             (saved != 0 ? std::string(": ") + std::strerror(saved) : ""));
  }
}

void WriteYaml(const std::filesystem::path& path, const std::string& image_name,
               const grid::GridImage& image) {
  detail::TextWriter out(path);
  out.Put("image: " + image_name + "\n");
  out.Put("resolution: " + detail::FormatExact(image.resolution_m) + "\n");
  out.Put("origin: [" + detail::FormatExact(image.origin_m.x()) + ", " +
          detail::FormatExact(image.origin_m.y()) + ", 0.0]\n");
  out.Put("negate: 0\n");
  out.Put("occupied_thresh: " + detail::FormatExact(kRosOccupiedThreshold) + "\n");
  out.Put("free_thresh: " + detail::FormatExact(kRosFreeThreshold) + "\n");
  out.Put("mode: trinary\n");
  out.Close();
}

// The yaml's "key: value" lines with their line numbers; nested yaml is not part of the format.
struct YamlEntry {
  std::string value;
  std::size_t line = 0;
};
using YamlEntries = std::map<std::string, YamlEntry, std::less<>>;

YamlEntries ReadYamlEntries(const std::filesystem::path& path) {
  detail::GzLineReader reader(path);
  YamlEntries entries;
  std::string text;
  while (reader.ReadLine(text)) {
    std::string_view line = text;
    line = Trimmed(line.substr(0, line.find('#')));
    if (line.empty()) continue;
    const std::size_t colon = line.find(':');
    if (colon == std::string_view::npos) {
      throw InputError(path, reader.line_number(), "expected 'key: value', got '" + text + "'");
    }
    entries[std::string(Trimmed(line.substr(0, colon)))] = {
        std::string(Trimmed(line.substr(colon + 1))), reader.line_number()};
  }
  return entries;
}

const YamlEntry& Require(const std::filesystem::path& path, const YamlEntries& entries,
                         std::string_view key) {
  const auto found = entries.find(key);
  if (found == entries.end()) throw InputError(path, 0, "missing field '" + std::string(key) + "'");
  return found->second;
}

double Number(const std::filesystem::path& path, std::size_t line, std::string_view text,
              const std::string& what) {
  const std::optional<double> value = detail::ParseDouble(Trimmed(text));
  if (!value || !std::isfinite(*value)) {
    throw InputError(path, line, what + " '" + std::string(text) + "' is not a finite number");
  }
  return *value;
}

double OptionalNumber(const std::filesystem::path& path, const YamlEntries& entries,
                      std::string_view key, double fallback) {
  const auto found = entries.find(key);
  if (found == entries.end()) return fallback;
  return Number(path, found->second.line, found->second.value, std::string(key));
}

Eigen::Vector2d ParseOrigin(const std::filesystem::path& path, const YamlEntry& entry) {
  const std::string_view text = entry.value;
  if (text.size() < 2 || text.front() != '[' || text.back() != ']') {
    throw InputError(path, entry.line, "origin must read [x, y, yaw] (metres, radians)");
  }
  const auto fields = detail::SplitAt(text.substr(1, text.size() - 2), ',');
  if (fields.size() != 3) throw InputError(path, entry.line, "origin must hold 3 numbers");
  if (Number(path, entry.line, fields[2], "origin yaw") != 0.0) {
    throw InputError(path, entry.line, "origin yaw must be 0 (rotated maps are not supported)");
  }
  return {Number(path, entry.line, fields[0], "origin x"),
          Number(path, entry.line, fields[1], "origin y")};
}

std::filesystem::path ImagePath(const std::filesystem::path& yaml_path, const YamlEntry& entry) {
  std::string_view name = entry.value;
  if (name.size() >= 2 && (name.front() == '"' || name.front() == '\'') &&
      name.back() == name.front()) {
    name = name.substr(1, name.size() - 2);
  }
  if (name.empty()) throw InputError(yaml_path, entry.line, "image is empty");
  const std::filesystem::path image(name);
  return image.is_absolute() ? image : yaml_path.parent_path() / image;
}

// Reads the next PGM header number, skipping whitespace and '#' comments.
int PgmHeaderNumber(const std::filesystem::path& path, const std::string& bytes, std::size_t& at,
                    const char* what) {
  while (at < bytes.size()) {
    if (bytes[at] == '#') {
      at = bytes.find('\n', at);
      if (at == std::string::npos) at = bytes.size();
    } else if (std::isspace(static_cast<unsigned char>(bytes[at])) != 0) {
      ++at;
    } else {
      break;
    }
  }
  long value = 0;
  const std::size_t start = at;
  while (at < bytes.size() && std::isdigit(static_cast<unsigned char>(bytes[at])) != 0 &&
         value <= kMaxPgmSide) {
    value = value * 10 + (bytes[at++] - '0');
  }
  if (at == start || value < 1 || value > kMaxPgmSide) {
    throw InputError(
        path, 0,
        std::string("PGM ") + what + " must be an integer in 1.." + std::to_string(kMaxPgmSide));
  }
  return static_cast<int>(value);
}

cv::Mat ReadPgm(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, "cannot open");
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (bytes.rfind("P5", 0) != 0) throw InputError(path, 0, "not a binary PGM (P5)");
  std::size_t at = 2;
  const int width = PgmHeaderNumber(path, bytes, at, "width");
  const int height = PgmHeaderNumber(path, bytes, at, "height");
  const int max_value = PgmHeaderNumber(path, bytes, at, "maxval");
  if (max_value > 255) throw InputError(path, 0, "16-bit PGM (maxval > 255) is not supported");
  ++at;  // the single whitespace after maxval
  const std::size_t count = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  if (at > bytes.size() || bytes.size() - at < count) {
    throw InputError(path, 0, "truncated: expected " + std::to_string(count) + " pixels");
  }
  cv::Mat image(height, width, CV_8UC1);
  for (std::size_t i = 0; i < count; ++i) {
    const long value = static_cast<unsigned char>(bytes[at + i]) * 255L / max_value;
    image.data[i] = static_cast<std::uint8_t>(std::min(value, 255L));
  }
  return image;
}

}  // namespace

void WriteRosMap(const std::filesystem::path& path_stem, const grid::GridImage& image) {
  ValidateImage(image);
  // Appending, not replace_extension, so a stem like "run.2" keeps its dot.
  const std::filesystem::path pgm_path = path_stem.string() + ".pgm";
  WritePgm(pgm_path, image);
  WriteYaml(path_stem.string() + ".yaml", pgm_path.filename().string(), image);
}

grid::GridImage ReadRosMap(const std::filesystem::path& yaml_path) {
  const YamlEntries entries = ReadYamlEntries(yaml_path);
  const auto mode = entries.find("mode");
  if (mode != entries.end() && mode->second.value == "raw") {
    throw InputError(yaml_path, mode->second.line, "mode raw is not supported (trinary, scale)");
  }
  grid::GridImage image;
  const YamlEntry& resolution = Require(yaml_path, entries, "resolution");
  image.resolution_m = Number(yaml_path, resolution.line, resolution.value, "resolution");
  if (image.resolution_m <= 0.0)
    throw InputError(yaml_path, resolution.line, "resolution must be > 0 m");
  image.origin_m = ParseOrigin(yaml_path, Require(yaml_path, entries, "origin"));
  const bool negate = OptionalNumber(yaml_path, entries, "negate", 0.0) != 0.0;
  const double occupied =
      OptionalNumber(yaml_path, entries, "occupied_thresh", kRosOccupiedThreshold);
  const double free_thresh = OptionalNumber(yaml_path, entries, "free_thresh", kRosFreeThreshold);
  const cv::Mat pgm = ReadPgm(ImagePath(yaml_path, Require(yaml_path, entries, "image")));
  image.occupancy = cv::Mat(pgm.size(), CV_8UC1);
  // map_server's trinary reading (scale mode is read the same way, losing its grey levels).
  for (std::size_t i = 0; i < pgm.total(); ++i) {
    const double darkness = (255.0 - pgm.data[i]) / 255.0;
    const double probability = negate ? 1.0 - darkness : darkness;
    image.occupancy.data[i] = probability > occupied ? 255 : probability < free_thresh ? 0 : 128;
  }
  return image;
}

}  // namespace pena::io
