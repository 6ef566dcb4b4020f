#include "dds_endpoints.hpp"


namespace pena::services {

std::int64_t NowNs() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

Handle ToHandle(const eprosima::fastrtps::rtps::InstanceHandle_t& handle) {
  Handle bytes{};
  for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = handle.value[i];
  return bytes;
}

}  // namespace pena::services
