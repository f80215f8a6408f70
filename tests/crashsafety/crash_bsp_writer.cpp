// Helper of the crash-safety test: builds the large BSP of a seed, then writes it over TARGET with
// q3::bsp::writeBsp, COUNT times (0 = until killed).
//
// Usage: crash_bsp_writer TARGET SEED COUNT
#include "bspfile.h"
#include "large_bsp.h"

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

int main(int argc, char** argv) {
    if (argc != 4) {
        std::fprintf(stderr, "usage: %s TARGET SEED COUNT\n", argv[0]);
        return 2;
    }
    try {
        const q3::bsp::Bsp bsp = q3::test::makeLargeBsp(static_cast<uint32_t>(std::stoul(argv[2])));
        const unsigned long count = std::stoul(argv[3]);
        for (unsigned long i = 0; count == 0 || i < count; ++i) q3::bsp::writeBsp(argv[1], bsp);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "ERROR: %s\n", e.what());
        return 1;
    }
    return 0;
}
