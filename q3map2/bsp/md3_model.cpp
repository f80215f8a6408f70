#include "md3_model.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <stdexcept>
#include <tuple>

namespace q3::bspstage {
namespace {

class Reader {
public:
    Reader(std::span<const uint8_t> bytes, const std::string& fileName) : bytes_(bytes), fileName_(fileName) {}

    template <class T>
    T at(size_t offset) const {
        if (offset + sizeof(T) > bytes_.size() || offset + sizeof(T) < offset)
            fail("offset " + std::to_string(offset) + " is past the end of the file");
        T value;
        std::memcpy(&value, bytes_.data() + offset, sizeof(T));
        return value;
    }
    std::string text(size_t offset, size_t size) const {
        if (offset + size > bytes_.size()) fail("a name is past the end of the file");
        const char* begin = reinterpret_cast<const char*>(bytes_.data() + offset);
        return std::string(begin, strnlen(begin, size));
    }
    [[noreturn]] void fail(const std::string& what) const { throw std::runtime_error(fileName_ + ": " + what); }

private:
    std::span<const uint8_t> bytes_;
    const std::string& fileName_;
};

// The normal of an MD3 vertex: latitude and longitude bytes, scaled as the model importer q3map2
// uses does (3.141926 / 128 per step).
Vec3 decodeNormal(uint16_t packed) {
    const float scale = 3.141926f / 128.0f;
    const float lat = float((packed >> 8) & 0xff) * scale;
    const float lng = float(packed & 0xff) * scale;
    return {std::cos(lat) * std::sin(lng), std::sin(lat) * std::sin(lng), std::cos(lng)};
}

}  // namespace

std::vector<ModelSurface> parseMd3(std::span<const uint8_t> bytes, int frame, const std::string& fileName) {
    const Reader r(bytes, fileName);
    if (bytes.size() < 108 || std::memcmp(bytes.data(), "IDP3", 4) != 0) r.fail("not an MD3 model (no IDP3 header)");
    if (r.at<int32_t>(4) != 15) r.fail("MD3 version " + std::to_string(r.at<int32_t>(4)) + ", expected 15");
    const int32_t numFrames = r.at<int32_t>(76);
    const int32_t numSurfaces = r.at<int32_t>(84);
    const int32_t ofsSurfaces = r.at<int32_t>(100);
    if (numFrames < 1 || numSurfaces < 0 || ofsSurfaces < 0) r.fail("bad frame or surface counts");
    frame = std::clamp(frame, 0, numFrames - 1);

    std::vector<ModelSurface> out;
    size_t ofs = size_t(ofsSurfaces);
    for (int s = 0; s < numSurfaces; ++s) {
        ModelSurface surface;
        surface.name = r.text(ofs + 4, 64);
        const int32_t surfaceFrames = r.at<int32_t>(ofs + 72);
        const int32_t numShaders = r.at<int32_t>(ofs + 76);
        const int32_t numVerts = r.at<int32_t>(ofs + 80);
        const int32_t numTriangles = r.at<int32_t>(ofs + 84);
        const int32_t ofsTriangles = r.at<int32_t>(ofs + 88);
        const int32_t ofsShaders = r.at<int32_t>(ofs + 92);
        const int32_t ofsSt = r.at<int32_t>(ofs + 96);
        const int32_t ofsXyz = r.at<int32_t>(ofs + 100);
        const int32_t ofsEnd = r.at<int32_t>(ofs + 104);
        if (numVerts < 0 || numTriangles < 0 || ofsEnd <= 0 || surfaceFrames < 1)
            r.fail("surface " + std::to_string(s) + " has bad counts");
        if (numShaders > 0) surface.shader = r.text(ofs + size_t(ofsShaders), 64);
        const int surfaceFrame = std::min(frame, surfaceFrames - 1);
        // The importer keeps one vertex per distinct corner (same position and normal, texture
        // coordinates within 1e-5, whichever file vertex it came from), in the order the triangles
        // use them.
        using Key = std::tuple<int16_t, int16_t, int16_t, uint16_t>;
        std::map<Key, std::vector<int>> seen;
        for (int t = 0; t < numTriangles; ++t) {
            for (int c = 0; c < 3; ++c) {
                const int32_t index = r.at<int32_t>(ofs + size_t(ofsTriangles) + size_t(t) * 12 + size_t(c) * 4);
                if (index < 0 || index >= numVerts)
                    r.fail("surface " + surface.name + ": triangle " + std::to_string(t) + " uses vertex " +
                           std::to_string(index) + " of " + std::to_string(numVerts));
                const size_t xyz = ofs + size_t(ofsXyz) + (size_t(surfaceFrame) * size_t(numVerts) + size_t(index)) * 8;
                const size_t st = ofs + size_t(ofsSt) + size_t(index) * 8;
                const Key key{r.at<int16_t>(xyz), r.at<int16_t>(xyz + 2), r.at<int16_t>(xyz + 4), r.at<uint16_t>(xyz + 6)};
                const float s0 = r.at<float>(st), s1 = r.at<float>(st + 4);
                std::vector<int>& sameCorner = seen[key];
                int found = -1;
                for (int candidate : sameCorner) {
                    const float ds = surface.verts[size_t(candidate)].st[0] - s0;
                    const float dt = surface.verts[size_t(candidate)].st[1] - s1;
                    if (ds * ds + dt * dt < 1e-10f) {
                        found = candidate;
                        break;
                    }
                }
                if (found < 0) {
                    ModelVertex v;
                    v.xyz = {float(std::get<0>(key)) / 64.0f, float(std::get<1>(key)) / 64.0f, float(std::get<2>(key)) / 64.0f};
                    v.normal = decodeNormal(std::get<3>(key));
                    v.st[0] = s0;
                    v.st[1] = s1;
                    found = int(surface.verts.size());
                    sameCorner.push_back(found);
                    surface.verts.push_back(v);
                }
                surface.indexes.push_back(found);
            }
        }
        out.push_back(std::move(surface));
        ofs += size_t(ofsEnd);
    }
    return out;
}

}  // namespace q3::bspstage
