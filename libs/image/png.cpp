// PNG decoding and encoding with libpng. As in the JPEG decoder, libpng's fatal errors come back
// through longjmp; all C++ state is owned by a context created before setjmp.
// Decoding expands every colour type to 8-bit RGBA and, like q3map2, ignores gamma chunks.
#include "image.h"

#include <csetjmp>
#include <cstring>
#include <string>

#include <png.h>

namespace q3 {

namespace {

struct PngDecode {
    std::span<const uint8_t> bytes;
    size_t position = 0;
    png_structp png = nullptr;
    png_infop info = nullptr;
    std::vector<uint8_t> pixels;
    std::vector<png_bytep> rows;
    char message[256] = {};
    ~PngDecode() {
        if (png) png_destroy_read_struct(&png, info ? &info : nullptr, nullptr);
    }
};

void onPngError(png_structp png, png_const_charp text) {
    auto* decode = static_cast<PngDecode*>(png_get_error_ptr(png));
    std::snprintf(decode->message, sizeof decode->message, "%s", text ? text : "unknown error");
    png_longjmp(png, 1);
}

void onPngWarning(png_structp, png_const_charp) {}

void readFromMemory(png_structp png, png_bytep out, png_size_t length) {
    auto* decode = static_cast<PngDecode*>(png_get_io_ptr(png));
    if (decode->bytes.size() - decode->position < length) png_error(png, "file is truncated");
    std::memcpy(out, decode->bytes.data() + decode->position, length);
    decode->position += length;
}

// Deflate cannot expand data by more than about 1032:1; a header claiming more pixels than the file
// could hold is rejected before the picture is allocated.
constexpr size_t kMaxDeflateRatio = 1100;

// Returns false after a libpng error (message in decode.message).
bool runPngDecode(PngDecode& decode, int& width, int& height) {
    decode.png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &decode, onPngError, onPngWarning);
    if (!decode.png) {
        std::snprintf(decode.message, sizeof decode.message, "out of memory");
        return false;
    }
    if (setjmp(png_jmpbuf(decode.png))) return false;
    decode.info = png_create_info_struct(decode.png);
    if (!decode.info) png_error(decode.png, "out of memory");
    png_set_read_fn(decode.png, &decode, readFromMemory);
    png_set_user_limits(decode.png, kMaxImageDimension, kMaxImageDimension);
    png_read_info(decode.png, decode.info);

    const png_uint_32 w = png_get_image_width(decode.png, decode.info);
    const png_uint_32 h = png_get_image_height(decode.png, decode.info);
    const int colorType = png_get_color_type(decode.png, decode.info);
    const int bitDepth = png_get_bit_depth(decode.png, decode.info);
    const size_t rawBytes = size_t(png_get_rowbytes(decode.png, decode.info) + 1) * h;
    if (rawBytes > decode.bytes.size() * kMaxDeflateRatio + 65536)
        png_error(decode.png, "header size is impossible for the file's length");

    if (colorType == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(decode.png);
    if (colorType == PNG_COLOR_TYPE_GRAY && bitDepth < 8) png_set_expand_gray_1_2_4_to_8(decode.png);
    if (png_get_valid(decode.png, decode.info, PNG_INFO_tRNS)) png_set_tRNS_to_alpha(decode.png);
    if (bitDepth == 16) png_set_strip_16(decode.png);
    if (colorType == PNG_COLOR_TYPE_GRAY || colorType == PNG_COLOR_TYPE_GRAY_ALPHA) png_set_gray_to_rgb(decode.png);
    png_set_add_alpha(decode.png, 0xFF, PNG_FILLER_AFTER);  // no effect when alpha is already there
    png_set_interlace_handling(decode.png);
    png_read_update_info(decode.png, decode.info);
    if (png_get_rowbytes(decode.png, decode.info) != size_t(w) * 4)
        png_error(decode.png, "unexpected row layout after conversion");

    decode.pixels.resize(size_t(w) * h * 4);
    decode.rows.resize(h);
    for (png_uint_32 y = 0; y < h; ++y) decode.rows[y] = decode.pixels.data() + size_t(y) * w * 4;
    png_read_image(decode.png, decode.rows.data());
    png_read_end(decode.png, nullptr);
    width = int(w);
    height = int(h);
    return true;
}

}  // namespace

Image decodePng(std::span<const uint8_t> bytes, std::string_view name) {
    PngDecode decode;
    decode.bytes = bytes;
    int width = 0, height = 0;
    if (!runPngDecode(decode, width, height)) throw ImageError(std::string(name) + ": bad PNG: " + decode.message);
    Image image;
    image.width = width;
    image.height = height;
    image.rgba = std::move(decode.pixels);
    return image;
}

std::vector<uint8_t> encodePng(const Image& image, bool alpha) {
    if (image.empty() || image.rgba.size() != size_t(image.width) * image.height * 4)
        throw ImageError("encodePng: image of " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                         " cannot be written");
    std::vector<uint8_t> source;
    if (!alpha) {
        source.reserve(size_t(image.width) * image.height * 3);
        for (size_t i = 0; i < image.rgba.size(); i += 4)
            source.insert(source.end(), image.rgba.begin() + i, image.rgba.begin() + i + 3);
    }
    png_image description{};
    description.version = PNG_IMAGE_VERSION;
    description.width = png_uint_32(image.width);
    description.height = png_uint_32(image.height);
    description.format = alpha ? PNG_FORMAT_RGBA : PNG_FORMAT_RGB;
    const void* data = alpha ? static_cast<const void*>(image.rgba.data()) : source.data();

    png_alloc_size_t size = 0;
    if (!png_image_write_to_memory(&description, nullptr, &size, 0, data, 0, nullptr))
        throw ImageError(std::string("encodePng: ") + description.message);
    std::vector<uint8_t> out(size);
    if (!png_image_write_to_memory(&description, out.data(), &size, 0, data, 0, nullptr))
        throw ImageError(std::string("encodePng: ") + description.message);
    out.resize(size);
    return out;
}

}  // namespace q3
