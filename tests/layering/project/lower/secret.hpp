#pragma once
// A private header of the lower module.
namespace pena::lower {
inline int Secret() { return 2; }
}  // namespace pena::lower
