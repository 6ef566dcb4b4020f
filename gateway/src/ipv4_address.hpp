#pragma once
// The socket address both link transports (UDP, TCP) bind and send to.

#include <netinet/in.h>

#include <cstdint>
#include <string>

namespace pena::gateway {

// An IPv4 socket address from dotted text and a port; throws naming `transport` and the text.
sockaddr_in Ipv4Address(const std::string& host, std::uint16_t port, const std::string& transport);

}  // namespace pena::gateway
