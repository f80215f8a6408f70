// -shprobe: the SH grid and the legacy grid sampled at one point, as the engine runtime samples them.
#include <cstdio>

#include "bspfile.h"
#include "file_io.h"
#include "sh_tools.h"

namespace q3::shtools {
namespace {

constexpr const char* kFaceNames[6] = {"+X", "-X", "+Y", "-Y", "+Z", "-Z"};

std::string rgbText(const float c[3]) {
    char text[96];
    std::snprintf(text, sizeof(text), "%9.5f %9.5f %9.5f", c[0], c[1], c[2]);
    return text;
}

// The same BSP without its SH grid, so that the runtime falls back to lump 15.
std::vector<uint8_t> withoutShGrid(std::span<const uint8_t> bspImage, const std::string& name) {
    bsp::Bsp b = bsp::parseBsp(bspImage, name, bsp::ReadOptions{true, false});
    bsp::detachShGrid(b);
    b.removeBspx(sh::kBspxLumpName);
    return bsp::serializeBsp(b, name);
}

}  // namespace

ProbeReport probeBsp(std::span<const uint8_t> bspImage, const float position[3], const std::string& name) {
    ProbeReport report;
    for (int i = 0; i < 3; ++i) report.position[i] = position[i];
    sh::GridRuntime runtime;
    if (std::string err = runtime.loadFromBsp(bspImage.data(), bspImage.size(), name); !err.empty())
        throw bsp::BspError(err);
    if (runtime.source() != sh::GridSource::Lump18 && runtime.source() != sh::GridSource::Bspx)
        throw bsp::BspError(name +
                            ": no SH light grid (neither lump 18 nor the BSPX lump LIGHTGRID_SH): run -light -sh");
    report.source = runtime.source();
    report.sh = runtime.sample(position);
    report.shFaces = sh::toAmbientCube(report.sh);

    const std::vector<uint8_t> legacyImage = withoutShGrid(bspImage, name);
    sh::GridRuntime legacy;
    if (std::string err = legacy.loadFromBsp(legacyImage.data(), legacyImage.size(), name); !err.empty())
        throw bsp::BspError(err);
    if (legacy.source() == sh::GridSource::Legacy) {
        report.hasLegacy = true;
        report.legacy = legacy.sample(position);
        report.legacyFaces = sh::toAmbientCube(report.legacy);
        report.legacyLighting = sh::toLegacyLighting(report.legacy);
    }

    sh::LightCache cache;
    if (std::string err = cache.loadFromBsp(bspImage.data(), bspImage.size(), name); !err.empty())
        throw bsp::BspError(err);
    if (!cache.lights().empty()) {
        report.hasWorldLights = true;
        report.cache = cache.query(position);
        report.cacheLights = cache.lights();
    }
    return report;
}

std::vector<std::string> formatProbeReport(const ProbeReport& r) {
    std::vector<std::string> lines;
    char text[256];
    std::snprintf(text, sizeof(text), "SH probe at (%g %g %g), grid from %s", r.position[0], r.position[1],
                  r.position[2], r.source == sh::GridSource::Bspx ? "BSPX LIGHTGRID_SH" : "lump 18");
    lines.emplace_back(text);
    lines.emplace_back("coefficients (R G B; 1.0 = legacy byte 255):");
    for (int i = 0; i < 9; ++i) lines.push_back("  c" + std::to_string(i) + " " + rgbText(r.sh.coeffs[i]));
    lines.emplace_back("irradiance towards      SH grid                          legacy grid");
    for (int f = 0; f < 6; ++f) {
        std::string line = std::string("  ") + kFaceNames[f] + "  " + rgbText(r.shFaces.face[f]);
        if (r.hasLegacy) line += "    " + rgbText(r.legacyFaces.face[f]);
        lines.push_back(line);
    }
    if (!r.hasLegacy) {
        lines.emplace_back("legacy grid: none (lump 15 empty)");
    } else {
        const sh::LegacyLighting& l = r.legacyLighting;
        std::snprintf(text, sizeof(text), "legacy grid: ambient %s, directed %s, direction (%.3f %.3f %.3f)",
                      rgbText(l.ambient).c_str(), rgbText(l.directed).c_str(), l.direction[0], l.direction[1],
                      l.direction[2]);
        lines.emplace_back(text);
    }
    if (!r.hasWorldLights) {
        lines.emplace_back("light cache: no WORLDLIGHTS lump (-light -worldlights)");
        return lines;
    }
    const sh::LightCacheResult& c = r.cache;
    std::snprintf(text, sizeof(text),
                  "light cache: %zu world lights; cluster %d: %d local, %u projected into the probe, %u hidden",
                  r.cacheLights.size(), c.cluster, c.localCount, c.projectedCount, c.occludedCount);
    lines.emplace_back(text);
    for (int i = 0; i < c.localCount; ++i) {
        const sh::WorldLight& l = r.cacheLights[c.local[i].index];
        const char* type = l.type == sh::WorldLightType::Sun ? "sun" : l.type == sh::WorldLightType::Spot ? "spot" : "point";
        const float* where = l.type == sh::WorldLightType::Sun ? l.direction.data() : l.origin.data();
        std::snprintf(text, sizeof(text), "  local %d: light %u, %s %s (%g %g %g), arriving %s", i + 1,
                      c.local[i].index, type, l.type == sh::WorldLightType::Sun ? "towards" : "at", where[0],
                      where[1], where[2], rgbText(c.local[i].arriving.data()).c_str());
        lines.emplace_back(text);
    }
    const sh::AmbientCube probeFaces = sh::toAmbientCube(c.probe);
    lines.emplace_back("  probe with the projected lights, irradiance towards:");
    for (int f = 0; f < 6; ++f) lines.push_back(std::string("    ") + kFaceNames[f] + "  " + rgbText(probeFaces.face[f]));
    return lines;
}

int runShProbeStage(const ShProbeOptions& options, const CommonOptions& common, Log& log) {
    if (!options.positionSet) throw cli::UsageError("-shprobe: no position (give X Y Z)");
    const std::string name = common.mapPath.string();
    const std::vector<uint8_t> bytes = readFileBytes(common.mapPath);
    const ProbeReport report = probeBsp(bytes, options.position, name);
    for (const std::string& line : formatProbeReport(report)) log.info(line);
    return 0;
}

}  // namespace q3::shtools
