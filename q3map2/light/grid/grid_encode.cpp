#include "grid_encode.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "log.h"
#include "script.h"

namespace q3::light {

Vec3 parseGridSize(std::string_view value, const std::string& where) {
    if (value.find_first_not_of(" \t") == std::string_view::npos) return kDefaultGridSize;
    Vec3 size;
    int count = 0;
    size_t pos = 0;
    while (pos < value.size()) {
        pos = value.find_first_not_of(" \t", pos);
        if (pos == std::string_view::npos) break;
        size_t end = value.find_first_of(" \t", pos);
        if (end == std::string_view::npos) end = value.size();
        double number = 0;
        if (count >= 3 || !parseNumber(value.substr(pos, end - pos), number) || !std::isfinite(number))
            throw CompileError(where + ": gridsize \"" + std::string(value) + "\" is not three numbers");
        size[count++] = float(number);
        pos = end;
    }
    if (count != 3) throw CompileError(where + ": gridsize \"" + std::string(value) + "\" is not three numbers");
    return size;
}

std::string GridLayout::sizeKeyValue() const {
    char text[96];
    std::snprintf(text, sizeof(text), "%.0f %.0f %.0f", size.x, size.y, size.z);
    return text;
}

std::array<int, 3> GridLayout::pointCoords(int index) const {
    const int bx = bounds[0], by = bounds[1];
    return {index % bx, (index / bx) % by, index / (bx * by)};
}

Vec3 GridLayout::pointOrigin(int index) const {
    const auto c = pointCoords(index);
    return {mins.x + float(c[0]) * size.x, mins.y + float(c[1]) * size.y, mins.z + float(c[2]) * size.z};
}

constexpr float kGridWorldLimit = float(1 << 20);

GridLayout computeGridLayout(Vec3 requestedSize, Vec3 worldMins, Vec3 worldMaxs) {
    GridLayout layout;
    layout.requestedSize = requestedSize;
    for (int i = 0; i < 3; ++i) layout.size[i] = std::max(8.0f, std::floor(requestedSize[i]));

    for (int axis = 0;; axis = (axis + 1) % 3) {
        // Same float arithmetic as the engines (R_LoadLightGrid) so the point count matches theirs.
        long long points = 1;
        for (int i = 0; i < 3; ++i) {
            const float g = layout.size[i];
            // Far beyond any engine's world size; keeps the counts below in range for absurd input.
            const float lo = std::clamp(worldMins[i], -kGridWorldLimit, kGridWorldLimit);
            const float hi = std::clamp(worldMaxs[i], -kGridWorldLimit, kGridWorldLimit);
            layout.mins[i] = g * std::ceil(lo / g);
            const float max = g * std::floor(hi / g);
            // An empty world (maxs below mins) gives no points rather than a negative count.
            layout.bounds[i] = std::max(0, int((max - layout.mins[i]) / g + 1.0f));
            points *= layout.bounds[i];
        }
        if (points <= kMaxGridPoints) break;
        layout.size[axis] += kGridGrowStep;
        ++layout.growSteps;
    }
    return layout;
}

GridLayout computeGridLayout(Vec3 requestedSize, const bsp::Bsp& bsp) {
    if (bsp.models.empty()) return computeGridLayout(requestedSize, Vec3{}, Vec3{});
    const bsp::Model& world = bsp.models[0];
    return computeGridLayout(requestedSize, Vec3::fromArray(world.mins), Vec3::fromArray(world.maxs));
}

GridSample accumulateGridSample(std::span<const LightContribution> contributions, Vec3 baseAmbient,
                                const GridOptions& options) {
    constexpr int kMaxStyles = 4;
    constexpr int kNoStyle = -1;

    Vec3 dirSum;
    for (const LightContribution& c : contributions) dirSum += c.direction * length(c.color);
    const Vec3 primary = normalize(dirSum);

    std::array<int, kMaxStyles> styles{0, kNoStyle, kNoStyle, kNoStyle};
    std::array<Vec3, kMaxStyles> ambient;
    std::array<Vec3, kMaxStyles> directed;
    ambient.fill(baseAmbient);
    int numStyles = 1;

    const float gD = options.directionality, gAD = options.ambientDirectionality;
    for (const LightContribution& c : contributions) {
        // Map cos = 1 to gridDirectionality and cos = 0 to gridAmbientDirectionality.
        const float d = std::max(0.0f, gAD + dot(c.direction, primary) * (gD - gAD));
        int slot = 0;
        while (slot < numStyles && styles[slot] != c.style) ++slot;
        if (slot >= numStyles) {
            if (numStyles < kMaxStyles) {
                styles[numStyles] = c.style;
                slot = numStyles++;
            } else {
                slot = 0;  // too many styles: fold into the base style
            }
        }
        directed[slot] += c.color * d;
        // Keeps the total average: ambient + 0.25*sum(directed) == 0.25*sum(contributions).
        ambient[slot] += c.color * (0.25f * (1.0f - d));
    }
    return {ambient[0], directed[0], primary};
}

bsp::GridPoint encodeGridPoint(const GridSample& sample, const GridOptions& options, const ColorOptions& color) {
    bsp::GridPoint point{};
    const Vec3 ambient = vmax(sample.ambient, options.minLight);
    const Rgb8 a = colorToBytes(ambient, options.scale * options.ambientScale, color);
    const Rgb8 d = colorToBytes(sample.directed, options.scale, color);
    const bool ambientZero = a[0] + a[1] + a[2] == 0;
    const bool directedZero = d[0] + d[1] + d[2] == 0;
    for (int i = 0; i < 3; ++i) {
        // The engines skip points whose ambient is zero; keep useful points alive.
        point.ambient[i] = (ambientZero && !directedZero) ? 1 : a[i];
        point.directed[i] = d[i];
    }
    const auto latLong = normalToLatLong(sample.direction);
    point.latLong[0] = latLong[0];
    point.latLong[1] = latLong[1];
    return point;
}

std::array<uint8_t, 2> normalToLatLong(Vec3 n) {
    if (n.x == 0.0f && n.y == 0.0f) return {uint8_t(n.z > 0.0f ? 0 : 128), 0};
    constexpr double kRadToDeg = 180.0 / kPiD;
    constexpr double kDegToByte = double(255.0f / 360.0f);
    const int a = int(std::atan2(double(n.y), double(n.x)) * kRadToDeg * kDegToByte) & 0xff;
    const int b = int(std::acos(std::clamp(double(n.z), -1.0, 1.0)) * kRadToDeg * kDegToByte) & 0xff;
    return {uint8_t(b), uint8_t(a)};
}

Vec3 latLongToNormal(std::array<uint8_t, 2> bytes) {
    constexpr double kByteToRad = 2.0 * kPiD / 256.0;
    const double lng = bytes[0] * kByteToRad;
    const double lat = bytes[1] * kByteToRad;
    return {float(std::cos(lat) * std::sin(lng)), float(std::sin(lat) * std::sin(lng)), float(std::cos(lng))};
}

}  // namespace q3::light
