#pragma once
// How every options struct refuses a value: std::invalid_argument with
// "<scope>.<field> must be <rule>, got <value>", so a wrong config names the option, its rule and
// unit, and what it got, whichever module checks it (ground rule 4).

#include <sstream>
#include <stdexcept>
#include <string_view>

namespace pena {

inline void RequireOption(bool ok, std::string_view scope, std::string_view field,
                          std::string_view rule, double value) {
  if (ok) return;
  std::ostringstream message;
  message << scope << '.' << field << " must be " << rule << ", got " << value;
  throw std::invalid_argument(message.str());
}

}  // namespace pena
