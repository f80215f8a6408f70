// Format detection and the format-independent decode entry point.
#include "image.h"

#include <algorithm>
#include <string>

#include "ascii_case.h"

namespace q3 {

namespace {

std::string lowerExtension(std::string_view name) {
    size_t slash = name.find_last_of("/\\");
    size_t dot = name.find_last_of('.');
    if (dot == std::string_view::npos || (slash != std::string_view::npos && dot < slash)) return {};
    return toLower(name.substr(dot + 1));
}

}  // namespace

ImageFormat imageFormatFromName(std::string_view name) {
    std::string ext = lowerExtension(name);
    if (ext == "tga") return ImageFormat::Tga;
    if (ext == "jpg" || ext == "jpeg") return ImageFormat::Jpeg;
    if (ext == "png") return ImageFormat::Png;
    return ImageFormat::Unknown;
}

ImageFormat sniffImageFormat(std::span<const uint8_t> bytes) {
    static constexpr uint8_t kPngSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
    if (bytes.size() >= 8 && std::equal(kPngSignature, kPngSignature + 8, bytes.begin())) return ImageFormat::Png;
    if (bytes.size() >= 3 && bytes[0] == 0xFF && bytes[1] == 0xD8 && bytes[2] == 0xFF) return ImageFormat::Jpeg;
    return ImageFormat::Unknown;
}

Image decodeImage(std::span<const uint8_t> bytes, std::string_view name) {
    // Content wins over the name: games ship JPEGs named .tga and the other way round.
    ImageFormat format = sniffImageFormat(bytes);
    if (format == ImageFormat::Unknown) format = imageFormatFromName(name);
    switch (format) {
        case ImageFormat::Png: return decodePng(bytes, name);
        case ImageFormat::Jpeg: return decodeJpeg(bytes, name);
        case ImageFormat::Tga: return decodeTga(bytes, name);
        case ImageFormat::Unknown: break;
    }
    throw ImageError(std::string(name) + ": unknown image format (not TGA, JPEG or PNG)");
}

ImageDimensions imageDimensions(std::span<const uint8_t> bytes, std::string_view name) {
    ImageFormat format = sniffImageFormat(bytes);
    if (format == ImageFormat::Unknown) format = imageFormatFromName(name);
    if (format == ImageFormat::Jpeg) return jpegDimensions(bytes, name);
    const Image image = decodeImage(bytes, name);
    return {image.width, image.height};
}

}  // namespace q3
