// The SH light grid lump (BSP lump 18 of version 47, or the BSPX lump "LIGHTGRID_SH"):
// a 40-byte header followed by 108-byte points, little-endian. See docs/sh-grid-format.md.
// Dependency-free: engines can take this header and its .cpp as they are.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace q3::sh {

constexpr size_t kGridHeaderBytes = 40;
constexpr size_t kGridPointBytes = 108;
constexpr const char* kBspxLumpName = "LIGHTGRID_SH";

struct GridPointSH {
    float coeffs[9][3];  // coefficient-major: coeffs[i] = {R, G, B}
};
static_assert(sizeof(GridPointSH) == kGridPointBytes);

struct GridSH {
    float mins[3] = {0, 0, 0};
    float size[3] = {0, 0, 0};
    int32_t bounds[3] = {0, 0, 0};
    std::vector<GridPointSH> points;  // index x + y*bx + z*bx*by
};

// Checks a lump image: header present, bounds positive, numPoints == bx*by*bz,
// length == 40 + 108*numPoints, every float finite, cell size positive.
// Returns an empty string when valid, else one line saying what is wrong.
std::string checkGridLump(const uint8_t* data, size_t size);

// Decodes a lump image (calls checkGridLump first). Returns false and sets `error` when invalid.
bool decodeGridLump(const uint8_t* data, size_t size, GridSH& out, std::string& error);
std::vector<uint8_t> encodeGridLump(const GridSH& grid);

// A lump image filled in place: the header is written when it is made and each point is encoded
// straight into its 108 bytes, so a grid being built is held once, already in its file form.
// release() hands the bytes over (to a BSP) without copying them.
class GridLumpImage {
public:
    GridLumpImage() = default;
    GridLumpImage(GridLumpImage&&) noexcept = default;
    GridLumpImage& operator=(GridLumpImage&&) noexcept = default;
    GridLumpImage(const GridLumpImage&) = delete;  // a grid is held once: copies are spelled encode(decode())
    GridLumpImage& operator=(const GridLumpImage&) = delete;
    // Header for the given lattice, every point zero.
    GridLumpImage(const float mins[3], const float size[3], const int32_t bounds[3]);
    static GridLumpImage encode(const GridSH& grid);

    size_t numPoints() const { return numPoints_; }
    std::array<int32_t, 3> bounds() const { return bounds_; }
    GridPointSH point(size_t index) const;
    void setPoint(size_t index, const GridPointSH& point);
    const std::vector<uint8_t>& bytes() const { return bytes_; }
    GridSH decode() const;
    // The lump image, moved out; the object is left empty (no points).
    std::vector<uint8_t> release();

private:
    void start(const float mins[3], const float size[3], const int32_t bounds[3], size_t count);

    std::vector<uint8_t> bytes_;
    std::array<int32_t, 3> bounds_{};
    size_t numPoints_ = 0;
};

}  // namespace q3::sh
