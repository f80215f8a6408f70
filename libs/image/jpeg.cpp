// JPEG decoding with libjpeg-turbo. libjpeg reports fatal errors through a callback that must not
// return; it jumps back to the decode call with longjmp. Only C data lives in the frames it skips,
// and everything C++ is owned by a context created before setjmp, so nothing leaks.
#include "image.h"

#include <csetjmp>
#include <cstdio>
#include <string>

#include <jerror.h>
#include <jpeglib.h>

namespace q3 {

namespace {

struct JpegErrorContext {
    jpeg_error_mgr manager;  // first member: libjpeg hands back a pointer to it
    std::jmp_buf jump;
    char message[JMSG_LENGTH_MAX] = {};
};

void onJpegError(j_common_ptr cinfo) {
    auto* context = reinterpret_cast<JpegErrorContext*>(cinfo->err);
    cinfo->err->format_message(cinfo, context->message);
    std::longjmp(context->jump, 1);
}

// Benign warnings (stray bytes between markers) are ignored; running out of data or hitting a
// marker inside the compressed data is fatal, since libjpeg would pad the rest of the picture.
void onJpegMessage(j_common_ptr cinfo, int level) {
    if (level >= 0) return;
    const int code = cinfo->err->msg_code;
    if (code == JWRN_JPEG_EOF || code == JWRN_HIT_MARKER || code == JWRN_MUST_RESYNC) onJpegError(cinfo);
}

struct JpegDecode {
    jpeg_decompress_struct info{};
    JpegErrorContext error;
    std::vector<uint8_t> pixels;  // RGBA, or CMYK before conversion
    bool created = false;
    ~JpegDecode() {
        if (created) jpeg_destroy_decompress(&info);
    }
};

// Adobe writes CMYK inverted; converting with the stored values as they are gives the right RGB.
void cmykToRgba(std::vector<uint8_t>& pixels) {
    for (size_t i = 0; i + 3 < pixels.size(); i += 4) {
        const unsigned k = pixels[i + 3];
        for (int c = 0; c < 3; ++c) pixels[i + c] = uint8_t(pixels[i + c] * k / 255);
        pixels[i + 3] = 255;
    }
}

// Returns false after a libjpeg error, with the message in decode.error.message. With headerOnly
// the size is read from the header and no pixel is decoded.
bool runJpegDecode(JpegDecode& decode, std::span<const uint8_t> bytes, int& width, int& height, bool& cmyk,
                   std::string& limitMessage, bool headerOnly = false) {
    decode.info.err = jpeg_std_error(&decode.error.manager);
    decode.error.manager.error_exit = onJpegError;
    decode.error.manager.emit_message = onJpegMessage;
    if (setjmp(decode.error.jump)) return false;
    jpeg_create_decompress(&decode.info);
    decode.created = true;
    jpeg_mem_src(&decode.info, bytes.data(), static_cast<unsigned long>(bytes.size()));
    jpeg_read_header(&decode.info, TRUE);
    if (decode.info.image_width > unsigned(kMaxImageDimension) ||
        decode.info.image_height > unsigned(kMaxImageDimension)) {
        limitMessage = "size " + std::to_string(decode.info.image_width) + "x" +
                       std::to_string(decode.info.image_height) + " exceeds " + std::to_string(kMaxImageDimension);
        return true;
    }
    if (headerOnly) {
        width = int(decode.info.image_width);
        height = int(decode.info.image_height);
        return true;
    }
    cmyk = decode.info.jpeg_color_space == JCS_CMYK || decode.info.jpeg_color_space == JCS_YCCK;
    decode.info.out_color_space = cmyk ? JCS_CMYK : JCS_EXT_RGBA;
    jpeg_start_decompress(&decode.info);
    width = int(decode.info.output_width);
    height = int(decode.info.output_height);
    const size_t rowBytes = size_t(width) * 4;
    // Rows are appended as they arrive so that a truncated file with a huge header fails before
    // the whole picture is allocated.
    while (decode.info.output_scanline < decode.info.output_height) {
        const size_t offset = decode.pixels.size();
        decode.pixels.resize(offset + rowBytes);
        JSAMPROW row = decode.pixels.data() + offset;
        jpeg_read_scanlines(&decode.info, &row, 1);
    }
    jpeg_finish_decompress(&decode.info);
    return true;
}

}  // namespace

ImageDimensions jpegDimensions(std::span<const uint8_t> bytes, std::string_view name) {
    JpegDecode decode;
    ImageDimensions d;
    bool cmyk = false;
    std::string limitMessage;
    if (!runJpegDecode(decode, bytes, d.width, d.height, cmyk, limitMessage, true))
        throw ImageError(std::string(name) + ": bad JPEG: " + decode.error.message);
    if (!limitMessage.empty()) throw ImageError(std::string(name) + ": bad JPEG: " + limitMessage);
    if (d.width <= 0 || d.height <= 0) throw ImageError(std::string(name) + ": bad JPEG: empty picture");
    return d;
}

Image decodeJpeg(std::span<const uint8_t> bytes, std::string_view name) {
    JpegDecode decode;
    int width = 0, height = 0;
    bool cmyk = false;
    std::string limitMessage;
    if (!runJpegDecode(decode, bytes, width, height, cmyk, limitMessage))
        throw ImageError(std::string(name) + ": bad JPEG: " + decode.error.message);
    if (!limitMessage.empty()) throw ImageError(std::string(name) + ": bad JPEG: " + limitMessage);
    if (width <= 0 || height <= 0 || decode.pixels.size() != size_t(width) * height * 4)
        throw ImageError(std::string(name) + ": bad JPEG: incomplete picture");
    if (cmyk) cmykToRgba(decode.pixels);
    Image image;
    image.width = width;
    image.height = height;
    image.rgba = std::move(decode.pixels);
    return image;
}

}  // namespace q3
