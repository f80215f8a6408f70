// Every .map source of openarena-oacmp1 parses, and its entity, brush, patch and light counts agree
// with an independent plain-text scan of the editor's "// entity N" / "// brush N" comments.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cmath>
#include <map>
#include <sstream>
#include <string>

#include "file_io.h"
#include "map_file.h"
#include "script.h"
#include "texture_projection.h"
#include "test_data.h"

using namespace q3;
using namespace q3::map;

namespace {

struct TextCounts {
    int entities = 0;                    // highest "// entity N" + 1
    std::map<int, int> primitives;       // "// brush N" lines per entity
    int patches = 0;                     // lines reading patchDef2 / patchDef3
    int lights = 0;                      // "classname" "light..." lines
    int faces = 0;                       // brush face lines: "( x y z ) ( ..." not "( ( ..."
};

std::string trim(const std::string& line) {
    size_t begin = line.find_first_not_of(" \t\r");
    size_t end = line.find_last_not_of(" \t\r");
    return begin == std::string::npos ? std::string() : line.substr(begin, end - begin + 1);
}

// Radiant writes "// entity N" before each entity (sometimes not before the first) and
// "// brush N" before each brush or patch.
TextCounts scanComments(const std::string& text) {
    TextCounts counts;
    std::istringstream in(text);
    std::string raw;
    int current = 0;
    int highest = -1;
    while (std::getline(in, raw)) {
        const std::string line = trim(raw);
        if (line.rfind("// entity ", 0) == 0) {
            current = std::stoi(line.substr(10));
            highest = std::max(highest, current);
        } else if (line.rfind("// brush ", 0) == 0) {
            ++counts.primitives[current];
            highest = std::max(highest, current);
        } else if (line == "patchDef2" || line == "patchDef3") {
            ++counts.patches;
        } else if (line.rfind("\"classname\" \"light", 0) == 0) {
            ++counts.lights;
        } else if (line.rfind("( ", 0) == 0 && line.rfind("( (", 0) != 0 && line.find(" ) ( ") != std::string::npos) {
            ++counts.faces;
        }
    }
    counts.entities = highest + 1;
    return counts;
}

}  // namespace

TEST(MapRealData, EveryOacmpSourceParsesWithMatchingCounts) {
    const auto sources = q3::test::oacmpMapSources();
    ASSERT_EQ(sources.size(), 13u);
    int totalBrushes = 0, totalPatches = 0, totalLights = 0;
    for (const auto& path : sources) {
        SCOPED_TRACE(path.filename().string());
        const std::string text = readFileText(path);
        const TextCounts expected = scanComments(text);
        MapFile map;
        ASSERT_NO_THROW(map = parseMap(text, path.filename().string()));

        ASSERT_GT(expected.entities, 0);
        EXPECT_EQ(int(map.entities.size()), expected.entities);
        EXPECT_EQ(map.entities.at(0).classname(), "worldspawn");
        int patches = 0, brushes = 0, faces = 0;
        for (const MapEntity& e : map.entities) {
            const auto it = expected.primitives.find(e.number);
            const int commented = it == expected.primitives.end() ? 0 : it->second;
            EXPECT_EQ(e.primitiveCount(), commented) << "entity " << e.number << " (" << e.classname() << ")";
            patches += int(e.patches.size());
            brushes += int(e.brushes.size());
            for (const MapBrush& b : e.brushes) {
                faces += int(b.faces.size());
                EXPECT_GE(b.faces.size(), 4u) << "entity " << e.number << " brush line " << b.line;
                for (const BrushFace& f : b.faces) EXPECT_FALSE(f.texture.empty());
            }
            for (const MapPatch& p : e.patches) {
                EXPECT_EQ(p.control.size(), size_t(p.width) * p.height);
                EXPECT_EQ(p.width % 2, 1);
                EXPECT_EQ(p.height % 2, 1);
            }
        }
        EXPECT_EQ(patches, expected.patches);
        EXPECT_EQ(faces, expected.faces);
        const std::vector<const MapEntity*> lights = lightEntities(map);
        EXPECT_EQ(int(lights.size()), expected.lights);
        EXPECT_GT(lights.size(), 0u);
        for (const MapEntity* light : lights) {
            Vec3 origin;
            EXPECT_TRUE(light->origin(origin)) << "light entity " << light->number << " has no usable origin";
        }
        totalBrushes += brushes;
        totalPatches += patches;
        totalLights += int(lights.size());
    }
    // The whole set is large; these floors guard against a scan and a parser that both see nothing.
    EXPECT_GT(totalBrushes, 10000);
    EXPECT_GT(totalPatches, 2000);
    EXPECT_GT(totalLights, 1000);
}

TEST(MapRealData, FacePlanesAndTextureAxesOfRealBrushesAreValid) {
    // Editor brushes are built from integer-ish points: no face may be degenerate.
    for (const auto& path : q3::test::oacmpMapSources()) {
        SCOPED_TRACE(path.filename().string());
        MapFile map = loadMap(path);
        int invalid = 0, faces = 0;
        for (const MapEntity& e : map.entities)
            for (const MapBrush& b : e.brushes)
                for (const BrushFace& f : b.faces) {
                    ++faces;
                    if (!f.planeValid) ++invalid;
                    else {
                        const double n2 = f.plane.normal[0] * f.plane.normal[0] + f.plane.normal[1] * f.plane.normal[1] +
                                          f.plane.normal[2] * f.plane.normal[2];
                        EXPECT_NEAR(n2, 1.0, 1e-9);
                        for (const Vec3& p : f.points) {
                            const double d = f.plane.normal[0] * p.x + f.plane.normal[1] * p.y + f.plane.normal[2] * p.z;
                            EXPECT_NEAR(d, f.plane.dist, 1e-3);
                        }
                        // The texture axes must span the face: their cross product is not parallel to it.
                        const TextureVecs tv = textureVectors(f, f.plane, {64, 64});
                        const double* a = tv.vecs[0];
                        const double* b = tv.vecs[1];
                        const double c[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
                        const double along = c[0] * f.plane.normal[0] + c[1] * f.plane.normal[1] + c[2] * f.plane.normal[2];
                        EXPECT_GT(std::fabs(along), 1e-9) << "face on line " << f.line;
                    }
                }
        EXPECT_GT(faces, 0);
        EXPECT_EQ(invalid, 0);
    }
}

TEST(MapRealData, DamagedRealFileFailsCleanly) {
    // Truncations and byte damage of a real file: each either still parses or gives one ScriptError
    // naming the file and a line inside it; nothing else escapes.
    const auto sources = q3::test::oacmpMapSources();
    ASSERT_FALSE(sources.empty());
    const std::string original = readFileText(sources.front());
    const int lines = int(std::count(original.begin(), original.end(), '\n')) + 1;
    uint32_t seed = 12345;
    auto nextRandom = [&seed]() {
        seed = seed * 1664525u + 1013904223u;
        return seed >> 8;
    };
    const char replacements[] = {'{', '}', '(', ')', '"', 'x', ' ', '\n', '9', '/'};
    int failures = 0;
    for (int attempt = 0; attempt < 120; ++attempt) {
        std::string damaged = original;
        if (attempt < 40) {
            damaged.resize(size_t(nextRandom()) % original.size());
        } else {
            for (int k = 0; k < 3; ++k)
                damaged[size_t(nextRandom()) % damaged.size()] = replacements[nextRandom() % sizeof replacements];
        }
        try {
            parseMap(damaged, "damaged.map");
        } catch (const ScriptError& e) {
            ++failures;
            const std::string message = e.what();
            ASSERT_EQ(message.rfind("damaged.map:", 0), 0u) << message;
            const int line = std::stoi(message.substr(12));
            EXPECT_GE(line, 1);
            EXPECT_LE(line, lines);
            EXPECT_EQ(message.find('\n'), std::string::npos) << message;
        }
    }
    EXPECT_GT(failures, 40);  // truncations alone nearly always break the last entity
}
