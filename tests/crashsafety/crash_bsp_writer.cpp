// Helper of the crash-safety test: builds the large BSP of a seed, then writes it over TARGET with
// q3::bsp::writeBsp, COUNT times (0 = until killed). With "direct" it truncates and rewrites TARGET
// in place instead: the negative control showing that the test catches a non-atomic writer.
//
// Usage: crash_bsp_writer TARGET SEED COUNT [direct]
#include "bspfile.h"
#include "large_bsp.h"

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

int main(int argc, char** argv) {
    const bool direct = argc == 5 && std::string(argv[4]) == "direct";
    if (argc != 4 && !direct) {
        std::fprintf(stderr, "usage: %s TARGET SEED COUNT [direct]\n", argv[0]);
        return 2;
    }
    try {
        const q3::bsp::Bsp bsp = q3::test::makeLargeBsp(static_cast<uint32_t>(std::stoul(argv[2])));
        const unsigned long count = std::stoul(argv[3]);
        const std::vector<uint8_t> image = direct ? q3::bsp::serializeBsp(bsp) : std::vector<uint8_t>{};
        for (unsigned long i = 0; count == 0 || i < count; ++i) {
            if (!direct) {
                q3::bsp::writeBsp(argv[1], bsp);
                continue;
            }
            std::ofstream out(argv[1], std::ios::binary | std::ios::trunc);
            out.write(reinterpret_cast<const char*>(image.data()), std::streamsize(image.size()));
            out.flush();
            if (!out) throw std::runtime_error(std::string(argv[1]) + ": write failed");
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "ERROR: %s\n", e.what());
        return 1;
    }
    return 0;
}
