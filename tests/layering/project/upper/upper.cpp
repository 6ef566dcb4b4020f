#include "pena/upper/upper.hpp"

#include "pena/lower/lower.hpp"

namespace pena::upper {
int Upper() { return lower::Lower() + 1; }
}  // namespace pena::upper
