// A large, valid BSP whose bytes depend only on a seed: the content the crash-safety helper writes
// and the test compares against.
#pragma once

#include "bspfile.h"

#include <cstdint>

namespace q3::test {

// About 12 MB: 160 lightmap pages and 100 000 vertices of pseudo-random data, a few shaders and
// planes, and an entity lump naming the seed. Different seeds give different bytes everywhere.
bsp::Bsp makeLargeBsp(uint32_t seed);

}  // namespace q3::test
