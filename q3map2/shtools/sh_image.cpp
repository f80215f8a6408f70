// -shimage: the probes of one height of the SH grid as shaded spheres seen from above.
#include <algorithm>
#include <cmath>

#include "file_io.h"
#include "sh_tools.h"

namespace q3::shtools {
namespace {

constexpr int kMaxPictureSide = 8192;
constexpr uint8_t kBackground = 32;

}  // namespace

uint8_t toDisplay(float irradiance, float exposure) {
    const double mapped = 1.0 - std::exp(-double(exposure) * std::max(0.0f, irradiance));
    return static_cast<uint8_t>(std::lround(255.0 * std::pow(mapped, 1.0 / 2.2)));
}

std::vector<DiscPixel> sphereDisc(int cell) {
    std::vector<DiscPixel> out;
    const float radius = 0.5f * float(cell) - 0.5f;
    for (int py = 0; py < cell; ++py)
        for (int px = 0; px < cell; ++px) {
            const float u = (float(px) + 0.5f - 0.5f * float(cell)) / radius;
            const float v = -(float(py) + 0.5f - 0.5f * float(cell)) / radius;
            const float r2 = u * u + v * v;
            if (r2 > 1.0f) continue;
            out.push_back({px, py, {u, v, std::sqrt(1.0f - r2)}});
        }
    return out;
}

float middleHeight(const sh::GridSH& grid) {
    return grid.mins[2] + 0.5f * float(std::max(0, grid.bounds[2] - 1)) * grid.size[2];
}

Image renderProbeImage(const sh::GridRuntime& runtime, float z, int probePixels, float exposure) {
    const sh::GridSH& grid = runtime.grid();
    const int bx = std::max(1, grid.bounds[0]), by = std::max(1, grid.bounds[1]);
    const int cell = std::clamp(std::min(probePixels, kMaxPictureSide / std::max(bx, by)), 1, 256);
    Image image;
    image.width = bx * cell;
    image.height = by * cell;
    image.rgba.assign(size_t(image.width) * size_t(image.height) * 4, kBackground);
    for (size_t i = 3; i < image.rgba.size(); i += 4) image.rgba[i] = 255;

    const std::vector<DiscPixel> disc = sphereDisc(cell);
    for (int y = 0; y < by; ++y)
        for (int x = 0; x < bx; ++x) {
            const float position[3] = {grid.mins[0] + float(x) * grid.size[0],
                                       grid.mins[1] + float(y) * grid.size[1], z};
            const sh::GridPointSH probe = runtime.sample(position);
            const int left = x * cell;
            const int top = (by - 1 - y) * cell;  // north (+Y) up
            for (const DiscPixel& d : disc) {
                float rgb[3];
                sh::irradianceAt(probe, d.normal, rgb);
                uint8_t* texel = image.texel(left + d.x, top + d.y);
                for (int ch = 0; ch < 3; ++ch) texel[ch] = toDisplay(rgb[ch], exposure);
            }
        }
    return image;
}

int runShImageStage(const ShImageOptions& options, const CommonOptions& common, Log& log) {
    if (options.output.empty()) throw cli::UsageError("-shimage: no output file (give OUT.png)");
    const std::string name = common.mapPath.string();
    const std::vector<uint8_t> bytes = readFileBytes(common.mapPath);
    sh::GridRuntime runtime;
    if (std::string err = runtime.loadFromBsp(bytes.data(), bytes.size(), name); !err.empty()) throw FileError(err);
    if (runtime.source() != sh::GridSource::Lump18 && runtime.source() != sh::GridSource::Bspx)
        throw FileError(name + ": no SH light grid (neither lump 18 nor the BSPX lump LIGHTGRID_SH): run -light -sh");
    const float z = options.heightSet ? options.height : middleHeight(runtime.grid());
    const Image image = renderProbeImage(runtime, z, options.probePixels, options.exposure);
    writeFileAtomic(options.output, encodePng(image, false));
    log.info("wrote " + options.output + " (" + std::to_string(image.width) + " x " + std::to_string(image.height) +
             ", probes at z " + std::to_string(z) + ")");
    return 0;
}

}  // namespace q3::shtools
