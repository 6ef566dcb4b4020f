// What a browser sends pena-console (services/console/browser_request.cpp): one WebSocket text
// message parsed into a command or refused with an error naming the field; never an exception.
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "browser_request.hpp"
#include "fuzz_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const pena::services::BrowserRequest request =
      pena::services::ParseBrowserRequest(pena::fuzz::AsText(data, size));
  if (!request.ok() && request.error().empty()) std::abort();
  return 0;
}
