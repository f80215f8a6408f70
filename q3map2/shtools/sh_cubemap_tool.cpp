// -shcubemap: six face images -> L2 SH radiance and irradiance, printed as nine RGB coefficients each.
// The face order and orientation are those of sh_cubemap.h; texel bytes are read as linear values
// (byte / 255, times -scale).
#include <cstdio>

#include "file_io.h"
#include "sh_cubemap.h"
#include "sh_tools.h"

namespace q3::shtools {
namespace {

constexpr size_t kFaceCount = 6;

std::string rgbText(const double c[3]) {
    char text[96];
    std::snprintf(text, sizeof(text), "%12.6f %12.6f %12.6f", c[0], c[1], c[2]);
    return text;
}

}  // namespace

const cli::OptionTable<ShCubemapOptions>& shCubemapOptionTable() {
    using O = ShCubemapOptions;
    static const cli::OptionTable<O> table = {
        cli::floatValue<O>({"-scale"}, &O::scale, cli::Range::positive(),
                           "Radiance of a texel = byte / 255 * F (e.g. 255 gives legacy light units)",
                           cli::kImplemented),
    };
    return table;
}

sh::CubeFaceImage toCubeFace(const Image& image, float scale, const std::string& name, const char* faceName) {
    if (image.width != image.height || image.width <= 0)
        throw FileError(name + ": face " + faceName + " is " + std::to_string(image.width) + " x " +
                        std::to_string(image.height) + " texels, a cubemap face must be square");
    sh::CubeFaceImage face;
    face.size = image.width;
    face.texels.resize(size_t(image.width) * size_t(image.height));
    const double k = double(scale) / 255.0;
    for (size_t i = 0; i < face.texels.size(); ++i)
        face.texels[i] = {image.rgba[4 * i] * k, image.rgba[4 * i + 1] * k, image.rgba[4 * i + 2] * k};
    return face;
}

sh::Cubemap loadCubemap(const std::array<std::string, 6>& files, float scale) {
    sh::Cubemap faces;
    for (size_t f = 0; f < kFaceCount; ++f) {
        const std::vector<uint8_t> bytes = readFileBytes(files[f]);
        const Image image = decodeImage(bytes, files[f]);
        faces[f] = toCubeFace(image, scale, files[f], sh::cubeFaceName(sh::CubeFace(f)));
    }
    const int size = faces[0].size;
    for (size_t f = 1; f < kFaceCount; ++f)
        if (faces[f].size != size)
            throw FileError(files[f] + ": face " + sh::cubeFaceName(sh::CubeFace(f)) + " is " +
                            std::to_string(faces[f].size) + " texels wide but face +X (" + files[0] + ") is " +
                            std::to_string(size));
    return faces;
}

CubemapReport projectCubemapFiles(const std::array<std::string, 6>& files, float scale) {
    const sh::Cubemap faces = loadCubemap(files, scale);
    CubemapReport report;
    report.faceSize = faces[0].size;
    if (std::string err = sh::projectCubemap(faces, report.radiance); !err.empty()) throw FileError(files[0] + ": " + err);
    report.irradiance = sh::convolveRadianceToIrradiance(report.radiance);
    return report;
}

std::vector<std::string> formatCubemapReport(const CubemapReport& r) {
    std::vector<std::string> lines;
    lines.push_back("cubemap of 6 x " + std::to_string(r.faceSize) + " x " + std::to_string(r.faceSize) +
                    " texels (faces +X -X +Y -Y +Z -Z, BSP axes, Z up)");
    lines.emplace_back("radiance coefficients (R G B):");
    for (int i = 0; i < sh::kCoeffCount; ++i) lines.push_back("  L" + std::to_string(i) + " " + rgbText(r.radiance.c[i]));
    lines.emplace_back("irradiance coefficients (R G B; the lump 18 form, evaluate with max(0, sum c_i Y_i(n))):");
    for (int i = 0; i < sh::kCoeffCount; ++i) lines.push_back("  E" + std::to_string(i) + " " + rgbText(r.irradiance.c[i]));
    return lines;
}

int runShCubemapCommand(std::span<const std::string> stageArgs, const cli::ParseContext& context, Log& log) {
    if (stageArgs.size() < kFaceCount)
        throw cli::UsageError("-shcubemap: expected six face images: -shcubemap [options] PX NX PY NY PZ NZ");
    ShCubemapOptions options;
    const size_t optionCount = stageArgs.size() - kFaceCount;
    for (size_t f = 0; f < kFaceCount; ++f) {
        const std::string& file = stageArgs[optionCount + f];
        if (file.empty() || file[0] == '-')
            throw cli::UsageError("-shcubemap: expected six face images at the end, got \"" + file + "\"");
        options.faces[f] = file;
    }
    cli::parseOptions(shCubemapOptionTable(), stageArgs.first(optionCount), context, options);
    for (const std::string& line : formatCubemapReport(projectCubemapFiles(options.faces, options.scale)))
        log.info(line);
    return 0;
}

}  // namespace q3::shtools
