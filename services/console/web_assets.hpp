#pragma once
// The console page's files (services/console/web/), compiled into the binary at build time by
// embed_web_assets.cmake: nothing is fetched from anywhere at run time.

#include <string_view>

namespace pena::services {

// One served file.
struct WebAsset {
  std::string_view path;          // "/index.html"
  std::string_view content_type;  // "text/html; charset=utf-8"
  std::string_view body;
};

// The asset served at `path`, or nullptr.
const WebAsset* FindWebAsset(std::string_view path);

}  // namespace pena::services
