// Codec of the SH light grid lump. Bytes are assembled explicitly so the file format stays
// little-endian whatever the host byte order.
#include "sh_grid_lump.h"

#include "le_bytes.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace q3::sh {
namespace {

using le::readF32;
using le::readI32;
using le::readU32;
using le::writeF32;
using le::writeU32;

const char* axisName(int axis) { return axis == 0 ? "x" : axis == 1 ? "y" : "z"; }

}  // namespace

std::string checkGridLump(const uint8_t* data, size_t size) {
    if (data == nullptr && size != 0) return "SH grid lump: no data";
    if (size < kGridHeaderBytes)
        return "SH grid lump: " + std::to_string(size) + " bytes is shorter than its " +
               std::to_string(kGridHeaderBytes) + "-byte header";
    for (int axis = 0; axis < 3; ++axis) {
        const float mins = readF32(data + 4 * axis);
        const float cell = readF32(data + 12 + 4 * axis);
        if (!std::isfinite(mins))
            return std::string("SH grid lump: gridMins ") + axisName(axis) + " is not finite";
        if (!std::isfinite(cell) || !(cell > 0.0f))
            return std::string("SH grid lump: gridSize ") + axisName(axis) + " = " +
                   std::to_string(cell) + " is not a positive finite cell size";
    }
    int64_t expectedPoints = 1;
    for (int axis = 0; axis < 3; ++axis) {
        const int32_t bound = readI32(data + 24 + 4 * axis);
        if (bound <= 0)
            return std::string("SH grid lump: gridBounds ") + axisName(axis) + " = " +
                   std::to_string(bound) + " is not positive";
        expectedPoints *= bound;  // at most (2^31)^3 < 2^93: checked against 2^31 after each step
        if (expectedPoints > INT32_MAX)
            return "SH grid lump: gridBounds multiply to more than 2^31 points";
    }
    const int32_t numPoints = readI32(data + 36);
    if (numPoints != expectedPoints)
        return "SH grid lump: numPoints " + std::to_string(numPoints) + " != gridBounds product " +
               std::to_string(expectedPoints);
    const uint64_t expectedBytes = kGridHeaderBytes + uint64_t(kGridPointBytes) * uint64_t(expectedPoints);
    if (uint64_t(size) != expectedBytes)
        return "SH grid lump: length " + std::to_string(size) + " != 40 + 108 * " +
               std::to_string(expectedPoints) + " = " + std::to_string(expectedBytes);
    const uint8_t* coeffs = data + kGridHeaderBytes;
    const size_t floatCount = size_t(expectedPoints) * 27;
    for (size_t i = 0; i < floatCount; ++i) {
        if (!std::isfinite(readF32(coeffs + 4 * i)))
            return "SH grid lump: point " + std::to_string(i / 27) + " coefficient " +
                   std::to_string((i % 27) / 3) + " channel " + std::to_string(i % 3) +
                   " is not finite";
    }
    return {};
}

namespace {

GridPointSH readPoint(const uint8_t* p) {
    GridPointSH point;
    for (int i = 0; i < 9; ++i)
        for (int c = 0; c < 3; ++c, p += 4) point.coeffs[i][c] = readF32(p);
    return point;
}

}  // namespace

bool decodeGridLump(const uint8_t* data, size_t size, GridSH& out, std::string& error) {
    error = checkGridLump(data, size);
    if (!error.empty()) return false;
    GridSH grid;
    for (int axis = 0; axis < 3; ++axis) {
        grid.mins[axis] = readF32(data + 4 * axis);
        grid.size[axis] = readF32(data + 12 + 4 * axis);
        grid.bounds[axis] = readI32(data + 24 + 4 * axis);
    }
    const size_t numPoints = size_t(readI32(data + 36));
    grid.points.resize(numPoints);
    for (size_t i = 0; i < numPoints; ++i) grid.points[i] = readPoint(data + kGridHeaderBytes + kGridPointBytes * i);
    out = std::move(grid);
    return true;
}

std::vector<uint8_t> encodeGridLump(const GridSH& grid) { return GridLumpImage::encode(grid).release(); }

GridLumpImage::GridLumpImage(const float mins[3], const float size[3], const int32_t bounds[3]) {
    size_t count = 1;
    for (int axis = 0; axis < 3; ++axis) count *= size_t(std::max(0, bounds[axis]));
    start(mins, size, bounds, count);
}

void GridLumpImage::start(const float mins[3], const float size[3], const int32_t bounds[3], size_t count) {
    numPoints_ = count;
    for (int axis = 0; axis < 3; ++axis) bounds_[axis] = bounds[axis];
    bytes_.assign(kGridHeaderBytes + kGridPointBytes * count, 0);  // 0.0f is four zero bytes
    uint8_t* p = bytes_.data();
    for (int axis = 0; axis < 3; ++axis) {
        writeF32(p + 4 * axis, mins[axis]);
        writeF32(p + 12 + 4 * axis, size[axis]);
        writeU32(p + 24 + 4 * axis, uint32_t(bounds[axis]));
    }
    writeU32(p + 36, uint32_t(count));
}

GridLumpImage GridLumpImage::encode(const GridSH& grid) {
    GridLumpImage image;  // numPoints is the points held, whatever the bounds say (checkGridLump reports a mismatch)
    image.start(grid.mins, grid.size, grid.bounds, grid.points.size());
    for (size_t i = 0; i < grid.points.size(); ++i) image.setPoint(i, grid.points[i]);
    return image;
}

GridPointSH GridLumpImage::point(size_t index) const {
    return readPoint(bytes_.data() + kGridHeaderBytes + kGridPointBytes * index);
}

void GridLumpImage::setPoint(size_t index, const GridPointSH& point) {
    uint8_t* p = bytes_.data() + kGridHeaderBytes + kGridPointBytes * index;
    for (int i = 0; i < 9; ++i)
        for (int c = 0; c < 3; ++c, p += 4) writeF32(p, point.coeffs[i][c]);
}

GridSH GridLumpImage::decode() const {
    GridSH grid;
    for (int axis = 0; axis < 3; ++axis) {
        grid.mins[axis] = readF32(bytes_.data() + 4 * axis);
        grid.size[axis] = readF32(bytes_.data() + 12 + 4 * axis);
        grid.bounds[axis] = bounds_[axis];
    }
    grid.points.resize(numPoints_);
    for (size_t i = 0; i < numPoints_; ++i) grid.points[i] = point(i);
    return grid;
}

std::vector<uint8_t> GridLumpImage::release() {
    numPoints_ = 0;
    bounds_ = {};
    std::vector<uint8_t> out;
    out.swap(bytes_);
    return out;
}

}  // namespace q3::sh
