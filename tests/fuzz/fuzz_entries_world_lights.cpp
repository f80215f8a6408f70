// The WORLDLIGHTS codec under fuzzing: any input is accepted or rejected with a one-line error;
// accepted lumps re-encode to the same bytes and every record evaluates to finite light.
#include <cmath>

#include "fuzz_entries.h"
#include "world_lights.h"

namespace q3::fuzz {

void fuzzWorldLights(std::span<const uint8_t> input, const FuzzContext&) {
    std::vector<sh::WorldLight> lights;
    std::string error;
    const bool accepted = sh::decodeWorldLights(input.data(), input.size(), lights, error);
    if (!accepted) {
        if (error.empty() || error.find('\n') != std::string::npos || !error.starts_with("WORLDLIGHTS: "))
            throw PropertyViolation("a rejected lump without a one-line WORLDLIGHTS error: " + error);
        return;
    }
    const std::vector<uint8_t> again = sh::encodeWorldLights(lights);
    if (!std::equal(again.begin(), again.end(), input.begin(), input.end()))
        throw PropertyViolation("decode -> encode changed an accepted WORLDLIGHTS lump");
    const std::array<float, 3> normals[] = {{0, 0, 1}, {1, 0, 0}, {0, -1, 0}};
    for (const sh::WorldLight& light : lights)
        for (const std::array<float, 3>& offset : {std::array<float, 3>{0, 0, 0}, {8, -3, 2}, {-500, 200, 40}}) {
            const std::array<float, 3> p{light.origin[0] + offset[0], light.origin[1] + offset[1],
                                         light.origin[2] + offset[2]};
            for (const auto& n : normals)
                for (float v : sh::evaluateWorldLight(light, p, n))
                    if (!std::isfinite(v)) throw PropertyViolation("a valid WORLDLIGHTS record evaluates to a non-finite value");
        }
}

}  // namespace q3::fuzz
