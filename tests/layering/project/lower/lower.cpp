#include "pena/lower/lower.hpp"

#include "secret.hpp"

namespace pena::lower {
int Lower() { return Secret() - 1; }
}  // namespace pena::lower
