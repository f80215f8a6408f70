// Shader images through the VFS, with q3map2's extension fallback and JPEG alpha companions.
#include "vfs_image.h"

#include <algorithm>

namespace q3 {

namespace {

std::string withoutExtension(std::string_view name) {
    const size_t slash = name.find_last_of("/\\");
    const size_t dot = name.find_last_of('.');
    if (dot == std::string_view::npos || (slash != std::string_view::npos && dot < slash)) return std::string(name);
    return std::string(name.substr(0, dot));
}

// Runs a decoder on a VFS file, naming the archive the file came from in its errors (the decoder
// only knows the VFS path).
template <class Decode>
auto fromVfs(const Vfs& vfs, const std::string& path, Decode decode) {
    try {
        return decode();
    } catch (const ImageError& error) {
        auto source = vfs.sourceOf(path);
        throw ImageError(std::string(error.what()) + (source ? " (from " + *source + ")" : ""));
    }
}

Image decodeFromVfs(const Vfs& vfs, const std::string& path, const std::vector<uint8_t>& bytes) {
    return fromVfs(vfs, path, [&] { return decodeImage(bytes, path); });
}

}  // namespace

std::vector<std::string> imageCandidates(std::string_view name) {
    std::vector<std::string> candidates;
    const std::string stem = withoutExtension(name);
    if (stem.empty()) return candidates;
    for (const char* ext : {".tga", ".png", ".jpg", ".jpeg"}) candidates.push_back(stem + ext);
    return candidates;
}

std::optional<LoadedImage> loadImage(const Vfs& vfs, std::string_view name) {
    for (const std::string& candidate : imageCandidates(name)) {
        auto bytes = vfs.read(candidate);
        if (!bytes) continue;
        LoadedImage loaded{candidate, decodeFromVfs(vfs, candidate, *bytes)};
        if (imageFormatFromName(candidate) == ImageFormat::Jpeg) {
            // JPEG has no alpha channel; q3map2 takes it from the blue channel of "<stem>_alpha.jpg".
            const std::string alphaName = withoutExtension(candidate) + "_alpha.jpg";
            if (auto alphaBytes = vfs.read(alphaName)) {
                Image alpha = decodeFromVfs(vfs, alphaName, *alphaBytes);
                if (alpha.width == loaded.image.width && alpha.height == loaded.image.height)
                    for (size_t i = 0; i + 3 < loaded.image.rgba.size(); i += 4) loaded.image.rgba[i + 3] = alpha.rgba[i + 2];
            }
        }
        return loaded;
    }
    return std::nullopt;
}

std::optional<ImageDimensions> loadImageDimensions(const Vfs& vfs, std::string_view name) {
    for (const std::string& candidate : imageCandidates(name))
        if (auto bytes = vfs.read(candidate))
            return fromVfs(vfs, candidate, [&] { return imageDimensions(*bytes, candidate); });
    return std::nullopt;
}

}  // namespace q3
