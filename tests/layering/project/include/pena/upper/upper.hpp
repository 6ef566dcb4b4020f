#pragma once
// The upper module's public function.
namespace pena::upper {
int Upper();
}  // namespace pena::upper
