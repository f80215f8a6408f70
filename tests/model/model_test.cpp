// The misc_model library: MD3 read natively, other formats through Assimp with q3map2's settings,
// shader and skin names. Every model here is written by the test.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>

#include "model.h"
#include "model_test_files.h"

namespace q3::model {
namespace {

// A reader over files held in memory, recording what was asked for.
struct MemoryFiles {
    std::map<std::string, std::string> files;
    std::vector<std::string> asked;

    FileReader reader() {
        return [this](const std::string& path) -> std::optional<std::vector<uint8_t>> {
            asked.push_back(path);
            const auto it = files.find(path);
            if (it == files.end()) return std::nullopt;
            return std::vector<uint8_t>(it->second.begin(), it->second.end());
        };
    }
};

std::set<std::array<float, 3>> positions(const Surface& s) {
    std::set<std::array<float, 3>> out;
    for (const Vertex& v : s.verts) out.insert({v.xyz.x, v.xyz.y, v.xyz.z});
    return out;
}

// One quad (OBJ is Y up: it stands in the file's XZ plane) and one triangle, two materials.
const char* kQuadObj =
    "mtllib quad.mtl\n"
    "v 0 0 0\nv 32 0 0\nv 32 0 -32\nv 0 0 -32\n"
    "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
    "usemtl crate\nf 1/1 2/2 3/3 4/4\n"
    "usemtl textures/x/trim\nf 1/1 4/4 3/3\n";
const char* kQuadMtl = "newmtl crate\nKd 1 1 1\nmap_Kd crate.tga\nnewmtl textures/x/trim\nKd 1 1 1\nmap_Kd t.tga\n";

TEST(ImportModel, ObjTurnedZUpWithFlippedTextureRowsAndMtlShaders) {
    MemoryFiles files;
    files.files = {{"models/test/quad.obj", kQuadObj}, {"models/test/quad.mtl", kQuadMtl}};
    const std::vector<Surface> surfaces = loadModel("models/test/quad.obj", files.reader(), {});
    ASSERT_EQ(surfaces.size(), 2u);
    EXPECT_EQ(surfaces[0].shader, "models/test/crate");      // bare texture name: the model's folder
    EXPECT_EQ(surfaces[1].shader, "textures/x/trim");        // named like a game shader: kept
    EXPECT_NE(std::find(files.asked.begin(), files.asked.end(), "models/test/quad.mtl"), files.asked.end());
    // Identical corners joined: 4 vertices, 2 triangles; (x, y, z) became (x, -z, y).
    ASSERT_EQ(surfaces[0].verts.size(), 4u);
    EXPECT_EQ(surfaces[0].indexes.size(), 6u);
    EXPECT_EQ(positions(surfaces[0]), (std::set<std::array<float, 3>>{{0, 0, 0}, {32, 0, 0}, {32, 32, 0}, {0, 32, 0}}));
    for (const Vertex& v : surfaces[0].verts) {
        EXPECT_NEAR(v.normal.z, 1.0f, 1e-6) << "generated normal faces +Z";
        // vt (u, v) becomes (u, 1 - v): the corner at file (32, 0, -32) had vt (1, 1).
        if (v.xyz == Vec3{32, 32, 0}) EXPECT_EQ(v.st[1], 0.0f);
        if (v.xyz == Vec3{0, 0, 0}) EXPECT_EQ(v.st[1], 1.0f);
        EXPECT_EQ(v.color[0], 1.0f) << "no vertex colours: white";
    }
    // Winding flipped: with Z up, the first triangle turns clockwise seen from above (+Z).
    const Surface& s = surfaces[0];
    const Vec3 a = s.verts[size_t(s.indexes[0])].xyz, b = s.verts[size_t(s.indexes[1])].xyz, c = s.verts[size_t(s.indexes[2])].xyz;
    EXPECT_LT(cross(b - a, c - a).z, 0.0f);
}

TEST(ImportModel, PlyVertexColoursAndAMaterialWithoutName) {
    MemoryFiles files;
    files.files["models/p/tri.ply"] =
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
        "property uchar red\nproperty uchar green\nproperty uchar blue\nelement face 1\n"
        "property list uchar int vertex_indices\nend_header\n0 0 0 255 0 0\n8 0 0 0 255 0\n0 8 0 0 0 51\n3 0 1 2\n";
    const std::vector<Surface> surfaces = loadModel("models/p/tri.ply", files.reader(), {});
    ASSERT_EQ(surfaces.size(), 1u);
    EXPECT_EQ(surfaces[0].shader, "models/p/");  // no material name: the model's folder alone
    ASSERT_EQ(surfaces[0].verts.size(), 3u);
    std::set<std::array<float, 3>> colours;
    for (const Vertex& v : surfaces[0].verts) colours.insert({v.color[0], v.color[1], v.color[2]});
    EXPECT_EQ(colours, (std::set<std::array<float, 3>>{{1, 0, 0}, {0, 1, 0}, {0, 0, 0.2f}}));
}

TEST(ImportModel, LargeMeshesSplitAtTheVertexLimit) {
    // 40 separate triangles (120 distinct corners) with a limit of 30 vertices.
    std::string obj;
    for (int t = 0; t < 40; ++t)
        obj += "v " + std::to_string(t * 10) + " 0 0\nv " + std::to_string(t * 10 + 5) + " 0 0\nv " +
               std::to_string(t * 10) + " 5 0\n";
    for (int t = 0; t < 40; ++t)
        obj += "f " + std::to_string(3 * t + 1) + " " + std::to_string(3 * t + 2) + " " + std::to_string(3 * t + 3) + "\n";
    MemoryFiles files;
    files.files["m.obj"] = obj;
    const std::vector<Surface> surfaces = loadModel("m.obj", files.reader(), {0, 30});
    ASSERT_GE(surfaces.size(), 4u);
    size_t triangles = 0;
    for (const Surface& s : surfaces) {
        EXPECT_LE(s.verts.size(), 30u);
        triangles += s.indexes.size() / 3;
    }
    EXPECT_EQ(triangles, 40u);
}

TEST(ImportModel, MissingBrokenAndUnknownFilesAreOneLineErrors) {
    MemoryFiles files;
    files.files["models/b/broken.obj"] = "v 0 0 0\nf 1 7 9\n";  // corners that do not exist
    files.files["models/b/noise.xyz123"] = "not a model";
    files.files["models/b/short.md3"] = std::string(50, '\0');
    files.files["models/b/noise.md3"] = std::string(400, 'x');
    for (const char* name : {"models/b/missing.obj", "models/b/broken.obj", "models/b/noise.xyz123",
                             "models/b/short.md3", "models/b/missing.md3", "models/b/noise.md3"}) {
        try {
            loadModel(name, files.reader(), {});
            ADD_FAILURE() << name << " loaded";
        } catch (const ModelError& e) {
            const std::string what = e.what();
            EXPECT_EQ(what.rfind(name, 0), 0u) << what;  // names the file first
            EXPECT_EQ(what.find('\n'), std::string::npos) << what;
        }
    }
}

TEST(Md3Model, CornersJoinedAndShaderFoundBesideTheModel) {
    // Vertex 3 repeats vertex 1: joined.
    auto bytes = test::md3Image({{0, 0, 0}, {64, 0, 0}, {0, 64, 0}, {64, 0, 0}}, {{0, 2, 1}, {2, 3, 0}},
                                {{{0, 0}}, {{1, 0}}, {{0, 1}}, {{1, 0}}});
    MemoryFiles files;
    files.files["models/test/box.MD3"] = std::string(bytes.begin(), bytes.end());
    {
        const std::vector<Surface> surfaces = loadModel("models/test/box.MD3", files.reader(), {});
        ASSERT_EQ(surfaces.size(), 1u);
        // The MD3 names "models/test/skin.tga"; the reader keeps its file name, found beside the model.
        EXPECT_EQ(surfaces[0].shader, "models/test/skin");
        ASSERT_EQ(surfaces[0].verts.size(), 3u);
        EXPECT_EQ(positions(surfaces[0]), (std::set<std::array<float, 3>>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}));
        EXPECT_EQ(surfaces[0].indexes.size(), 6u);
        for (const Vertex& v : surfaces[0].verts) EXPECT_NEAR(v.normal.z, 1.0f, 1e-6);
        // Texture rows as stored (the reader flips them, FlipUVs flips them back).
        for (const Vertex& v : surfaces[0].verts)
            if (v.xyz == Vec3{0, 1, 0}) EXPECT_EQ(v.st[1], 1.0f);
    }
    EXPECT_THROW(loadModel("models/test/box.MD3", files.reader(), {1, 999}), ModelError) << "one frame only";
}

TEST(ModelNames, ImportedShaderNames) {
    const std::string model = "models/m/thing.ase";
    EXPECT_EQ(importedShaderName("mat", "wood.tga", model), "models/m/wood");
    EXPECT_EQ(importedShaderName("mat", "", model), "models/m/mat");
    EXPECT_EQ(importedShaderName("textures/a/b", "c.tga", model), "textures/a/b");
    EXPECT_EQ(importedShaderName("models\\a\\b.tga", "c.tga", model), "models/a/b");
    EXPECT_EQ(importedShaderName("m", "textures\\gothic\\wall.jpg", model), "textures/gothic/wall");
    EXPECT_EQ(importedShaderName("m", "C:\\q3\\baseq3\\textures\\base\\floor.tga", model), "textures/base/floor");
    EXPECT_EQ(importedShaderName("m", "/home/me/q3/Models/x/y.png", model), "Models/x/y");
    EXPECT_EQ(importedShaderName("m", "../../art/rock.tga", model), "models/m/rock");
    EXPECT_EQ(importedShaderName("m", "dir.v2/rock", model), "dir.v2/rock");  // a dot in a folder is no extension
}

TEST(ModelNames, SkinFilesAndTheirLines) {
    EXPECT_EQ(skinFileName("models/players/sarge/head.md3", "roderic"), "models/players/sarge/head_roderic.skin");
    EXPECT_EQ(skinFileName("models/relics/relic.md3", "14"), "models/relics/relic.md3_14.skin");
    const std::vector<SkinRemap> remaps =
        parseSkin("replace models/a/b textures/c/d\r\nh_head,models/players/x/head.tga\n"
                  "  tag_torso ,\nbad line\n,empty\nu_body , textures/e/f\r");
    std::vector<std::pair<std::string, std::string>> pairs;
    for (const SkinRemap& r : remaps) pairs.emplace_back(r.from, r.to);
    EXPECT_EQ(pairs, (std::vector<std::pair<std::string, std::string>>{
                         {"models/a/b", "textures/c/d"}, {"h_head", "models/players/x/head.tga"}, {"u_body", "textures/e/f"}}));
}

TEST(ImportModel, KnowsTheFormatsQ3map2Reads) {
    for (const char* ext : {".obj", ".ase", ".lwo", ".3ds", ".fbx", ".dae", ".ply", ".md2", ".mdl", ".ms3d", ".x", ".ac"})
        EXPECT_TRUE(importerReads(ext)) << ext;
    EXPECT_FALSE(importerReads(".xyz123"));
}

}  // namespace
}  // namespace q3::model
