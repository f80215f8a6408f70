// What the C interfaces of libs/sh share: copying an error line into the caller's buffer and
// loading a handle from a BSP image without letting an exception cross into C.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <new>
#include <string>

namespace q3::sh::capi {

// Copies `message` into `error` (truncated, always terminated); nothing when there is no buffer.
inline void writeError(char* error, size_t errorSize, const std::string& message) {
    if (error == nullptr || errorSize == 0) return;
    const size_t n = std::min(message.size(), errorSize - 1);
    std::memcpy(error, message.data(), n);
    error[n] = '\0';
}

// A new Handle whose `load(handle, bsp, size)` returned an empty string, else nullptr with the
// error (or "out of memory loading WHAT" / "unexpected failure loading WHAT") in `error`.
template <typename Handle, typename Load>
Handle* loadHandle(const unsigned char* bsp, size_t size, char* error, size_t errorSize, const char* what, Load load) {
    try {
        auto* handle = new Handle;
        const std::string err = load(*handle, bsp, size);
        if (!err.empty()) {
            writeError(error, errorSize, err);
            delete handle;
            return nullptr;
        }
        writeError(error, errorSize, "");
        return handle;
    } catch (const std::bad_alloc&) {
        writeError(error, errorSize, std::string("out of memory loading ") + what);
    } catch (...) {
        writeError(error, errorSize, std::string("unexpected failure loading ") + what);
    }
    return nullptr;
}

}  // namespace q3::sh::capi
