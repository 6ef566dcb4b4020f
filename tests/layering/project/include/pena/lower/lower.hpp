#pragma once
// The lower module's public function.
namespace pena::lower {
int Lower();
}  // namespace pena::lower
