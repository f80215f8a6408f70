// Binary BSP inputs: the IBSP reader and validator, and the engine-side SH grid runtime.
#include "fuzz_entries.h"

#include "bspfile.h"
#include "sh_grid_lump.h"
#include "sh_grid_runtime.h"

#include <array>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

namespace q3::fuzz {

namespace {

const std::string kName = "fuzz.bsp";

// parseBsp without its built-in validation, then validateBsp on its own, so that the parser is
// exercised even on inputs the validator rejects. nullopt when the input was rejected cleanly.
std::optional<bsp::Bsp> readAndValidate(std::span<const uint8_t> bytes, bool force) {
    bsp::ReadOptions options;
    options.force = force;
    options.validate = false;
    bsp::Bsp parsed;
    try {
        parsed = bsp::parseBsp(bytes, kName, options);
    } catch (const bsp::BspError&) {
        return std::nullopt;
    }
    try {
        bsp::validateBsp(parsed, kName);
    } catch (const bsp::BspError&) {
        return std::nullopt;
    }
    return parsed;
}

std::vector<uint8_t> serializeOrViolate(const bsp::Bsp& b, const char* stage) {
    try {
        return bsp::serializeBsp(b, kName);
    } catch (const bsp::BspError& e) {
        throw PropertyViolation(std::string("a BSP the reader accepted cannot be written (") + stage + "): " + e.what());
    }
}

// A file the reader accepted must survive write -> read -> write unchanged.
void checkRoundTrip(const bsp::Bsp& accepted, bool force) {
    const std::vector<uint8_t> first = serializeOrViolate(accepted, "first write");
    std::optional<bsp::Bsp> reread = readAndValidate(first, force);
    if (!reread) {
        // Say why, through the library's own message.
        std::string why = "unknown";
        try {
            bsp::ReadOptions options;
            options.force = force;
            bsp::parseBsp(first, kName, options);
        } catch (const bsp::BspError& e) {
            why = e.what();
        }
        throw PropertyViolation("the written image of an accepted BSP is rejected: " + why);
    }
    if (serializeOrViolate(*reread, "second write") != first)
        throw PropertyViolation("BSP write -> read -> write is not stable");
}

}  // namespace

void fuzzBsp(std::span<const uint8_t> input, const FuzzContext&) {
    // Full reading with the default options: what the compiler stages do.
    try {
        bsp::parseBsp(input, kName);
    } catch (const bsp::BspError&) {
    }
    // The same with -force, then the split parse/validate path and the round trip.
    for (bool force : {false, true}) {
        if (std::optional<bsp::Bsp> accepted = readAndValidate(input, force)) {
            checkRoundTrip(*accepted, force);
            for (int lump = 0; lump < bsp::kMaxLumps; ++lump) bsp::lumpBytes(*accepted, lump);
            try {
                bsp::parseEntities(accepted->entities, kName);
            } catch (const bsp::BspError&) {
            }
        }
    }
}

void fuzzShRuntime(std::span<const uint8_t> input, const FuzzContext&) {
    sh::GridRuntime runtime;
    const std::string error = runtime.loadFromBsp(input.data(), input.size(), kName);
    if (!error.empty()) {
        if (runtime.source() != sh::GridSource::None)
            throw PropertyViolation("loadFromBsp reported an error but kept a grid: " + error);
        return;
    }
    const sh::GridSH& grid = runtime.grid();
    // Corners, centre and points well outside the grid (clamped to the border).
    std::vector<std::array<float, 3>> positions;
    for (int corner = 0; corner < 8; ++corner) {
        std::array<float, 3> p{};
        for (int axis = 0; axis < 3; ++axis) {
            const float extent = grid.size[axis] * float(grid.bounds[axis] > 0 ? grid.bounds[axis] - 1 : 0);
            p[axis] = grid.mins[axis] + ((corner >> axis) & 1 ? extent : 0.0f);
        }
        positions.push_back(p);
    }
    std::array<float, 3> centre{}, far{}, nearZero{};
    for (int axis = 0; axis < 3; ++axis) {
        centre[axis] = grid.mins[axis] + 0.5f * grid.size[axis] * float(grid.bounds[axis]);
        far[axis] = grid.mins[axis] - 1.0e6f;
        nearZero[axis] = 0.37f * float(axis + 1);
    }
    positions.push_back(centre);
    positions.push_back(far);
    positions.push_back(nearZero);

    const float normals[3][3] = {{0, 0, 1}, {1, 0, 0}, {0.6f, -0.8f, 0}};
    for (const std::array<float, 3>& p : positions) {
        const sh::GridPointSH sample = runtime.sample(p.data());
        for (const float* n : normals) {
            float rgb[3];
            sh::irradianceAt(sample, n, rgb);
        }
        sh::toAmbientCube(sample);
        sh::toLegacyLighting(sample);
    }

    // A decoded SH grid must encode back to a lump the codec accepts and decodes to the same grid.
    if (runtime.source() == sh::GridSource::Lump18 || runtime.source() == sh::GridSource::Bspx) {
        const std::vector<uint8_t> image = sh::encodeGridLump(grid);
        sh::GridSH decoded;
        std::string decodeError;
        if (!sh::decodeGridLump(image.data(), image.size(), decoded, decodeError))
            throw PropertyViolation("re-encoded SH grid is rejected: " + decodeError);
        if (decoded.points.size() != grid.points.size() ||
            std::memcmp(decoded.points.data(), grid.points.data(), grid.points.size() * sizeof(sh::GridPointSH)) != 0)
            throw PropertyViolation("SH grid encode -> decode changed the points");
    }
}

}  // namespace q3::fuzz
