#include "ipv4_address.hpp"

#include <arpa/inet.h>

#include <stdexcept>

namespace pena::gateway {

sockaddr_in Ipv4Address(const std::string& host, std::uint16_t port, const std::string& transport) {
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(port);
  if (inet_pton(AF_INET, host.c_str(), &address.sin_addr) != 1) {
    throw std::runtime_error(transport + " link: '" + host + "' is not an IPv4 address");
  }
  return address;
}

}  // namespace pena::gateway
