#include "pena/lower/internal/secret.hpp"
#include "pena/upper/upper.hpp"

int main() { return pena::upper::Upper() + pena::lower::Secret() == 4 ? 0 : 1; }
