// -json -unpack: one file per lump, in q3map2's layout.
#include "flag_names.h"
#include "json_files.h"
#include "json_stage.h"
#include "json_writer.h"
#include "world_lights_json.h"

#include "file_io.h"
#include "image.h"
#include "sh_grid_lump.h"
#include "world_lights.h"

#include <cstring>

namespace q3::json {
namespace fs = std::filesystem;

namespace {

// Helpers shared by the record writers ------------------------------------------------------------

void writeMinMax(Writer& w, const float* mins, const float* maxs) {
    w.key("minmax");
    w.startObject();
    w.key("mins");
    w.floats(mins, 3);
    w.key("maxs");
    w.floats(maxs, 3);
    w.endObject();
}

void writeMinMax(Writer& w, const int32_t* mins, const int32_t* maxs) {
    w.key("minmax");
    w.startObject();
    w.key("mins");
    w.integers(mins, 3);
    w.key("maxs");
    w.integers(maxs, 3);
    w.endObject();
}

// The name stored in a fixed 64-byte field, and the full field as hex when bytes after the
// terminating NUL are not zero (some compilers leave garbage there; keeping it makes the round
// trip exact).
void writeName(Writer& w, const char* key, const char (&field)[64]) {
    size_t len = strnlen(field, sizeof(field));
    w.key(key);
    w.string(std::string_view(field, len));
    bool junk = false;
    for (size_t i = len; i < sizeof(field); ++i) junk |= field[i] != 0;
    if (junk) {
        static const char digits[] = "0123456789abcdef";
        std::string hex;
        for (unsigned char c : field) {
            hex += digits[c >> 4];
            hex += digits[c & 15];
        }
        w.key("nameBytes");
        w.string(hex);
    }
}

// {"Prefix#i": {"Num": v}, ...}: q3map2's form for plain integer and byte lumps.
template <typename T>
void numFile(Writer& w, const char* prefix, const T* values, size_t count) {
    w.startObject();
    for (size_t i = 0; i < count; ++i) {
        w.indexedKey(prefix, i);
        w.startObject();
        w.key("Num");
        w.integer(static_cast<int64_t>(values[i]));
        w.endObject();
        w.drain();
    }
    w.endObject();
}

template <typename Record, typename Fn>
void recordFile(Writer& w, const char* prefix, const std::vector<Record>& records, Fn writeRecord) {
    w.startObject();
    for (size_t i = 0; i < records.size(); ++i) {
        w.indexedKey(prefix, i);
        writeRecord(w, records[i]);
        w.drain();
    }
    w.endObject();
}

// Lump writers --------------------------------------------------------------------------------------

void shadersFile(Writer& out, const bsp::Bsp& bsp) {
    recordFile(out, "shader", bsp.shaders, [](Writer& w, const bsp::Shader& s) {
        w.startObject();
        writeName(w, "shader", s.name);
        w.key("surfaceFlags");
        writeFlags(w, static_cast<uint32_t>(s.surfaceFlags), quake3Flags().surface);
        w.key("contentFlags");
        writeFlags(w, static_cast<uint32_t>(s.contentFlags), quake3Flags().content);
        w.endObject();
    });
}

void modelsFile(Writer& out, const bsp::Bsp& bsp) {
    recordFile(out, "model", bsp.models, [](Writer& w, const bsp::Model& m) {
        w.startObject();
        writeMinMax(w, m.mins, m.maxs);
        w.key("firstBSPSurface"); w.integer(m.firstSurface);
        w.key("numBSPSurfaces"); w.integer(m.numSurfaces);
        w.key("firstBSPBrush"); w.integer(m.firstBrush);
        w.key("numBSPBrushes"); w.integer(m.numBrushes);
        w.endObject();
    });
}

void planesFile(Writer& out, const bsp::Bsp& bsp) {
    recordFile(out, "plane", bsp.planes, [](Writer& w, const bsp::Plane& p) {
        float v[4] = {p.normal[0], p.normal[1], p.normal[2], p.dist};
        w.floats(v, 4);
    });
}

void leafsFile(Writer& out, const bsp::Bsp& bsp) {
    recordFile(out, "leaf", bsp.leafs, [](Writer& w, const bsp::Leaf& l) {
        w.startObject();
        w.key("cluster"); w.integer(l.cluster);
        w.key("area"); w.integer(l.area);
        writeMinMax(w, l.mins, l.maxs);
        w.key("firstBSPLeafSurface"); w.integer(l.firstLeafSurface);
        w.key("numBSPLeafSurfaces"); w.integer(l.numLeafSurfaces);
        w.key("firstBSPLeafBrush"); w.integer(l.firstLeafBrush);
        w.key("numBSPLeafBrushes"); w.integer(l.numLeafBrushes);
        w.endObject();
    });
}

void nodesFile(Writer& out, const bsp::Bsp& bsp) {
    recordFile(out, "node", bsp.nodes, [](Writer& w, const bsp::Node& n) {
        w.startObject();
        w.key("planeNum"); w.integer(n.planeNum);
        w.key("children"); w.integers(n.children, 2);
        writeMinMax(w, n.mins, n.maxs);
        w.endObject();
    });
}

void brushesFile(Writer& out, const bsp::Bsp& bsp) {
    recordFile(out, "Brush", bsp.brushes, [](Writer& w, const bsp::Brush& b) {
        w.startObject();
        w.key("firstSide"); w.integer(b.firstSide);
        w.key("numSides"); w.integer(b.numSides);
        w.key("shaderNum"); w.integer(b.shaderNum);
        w.endObject();
    });
}

void brushSidesFile(Writer& out, const bsp::Bsp& bsp) {
    recordFile(out, "BrushSide", bsp.brushSides, [](Writer& w, const bsp::BrushSide& s) {
        w.startObject();
        w.key("planeNum"); w.integer(s.planeNum);
        w.key("shaderNum"); w.integer(s.shaderNum);
        w.key("surfaceNum"); w.integer(-1);  // Raven BSPs only; q3map2 writes -1 for Quake 3
        w.endObject();
    });
}

// q3map2 writes draw verts and surfaces in its four-style superset form; Quake 3 uses style 0.
void drawVertsFile(Writer& out, const bsp::Bsp& bsp) {
    recordFile(out, "DrawVert", bsp.drawVerts, [](Writer& w, const bsp::DrawVert& v) {
        static const float zero2[2] = {0, 0};
        static const uint8_t zero4[4] = {0, 0, 0, 0};
        w.startObject();
        w.key("xyz"); w.floats(v.xyz, 3);
        w.key("st"); w.floats(v.st, 2);
        w.key("lightmap");
        w.startArray();
        w.floats(v.lightmap, 2);
        for (int i = 1; i < 4; ++i) w.floats(zero2, 2);
        w.endArray();
        w.key("normal"); w.floats(v.normal, 3);
        w.key("color");
        w.startArray();
        w.integers(v.color, 4);
        for (int i = 1; i < 4; ++i) w.integers(zero4, 4);
        w.endArray();
        w.endObject();
    });
}

void drawSurfacesFile(Writer& out, const bsp::Bsp& bsp) {
    recordFile(out, "DrawSurface", bsp.surfaces, [](Writer& w, const bsp::Surface& s) {
        const int32_t styles[4] = {0, 255, 255, 255};
        const int32_t lmNum[4] = {s.lightmapNum, bsp::kLightmapByVertex, bsp::kLightmapByVertex, bsp::kLightmapByVertex};
        const int32_t lmX[4] = {s.lightmapX, 0, 0, 0};
        const int32_t lmY[4] = {s.lightmapY, 0, 0, 0};
        w.startObject();
        w.key("shaderNum"); w.integer(s.shaderNum);
        w.key("fogNum"); w.integer(s.fogNum);
        w.key("surfaceType"); w.integer(s.surfaceType);
        w.key("firstVert"); w.integer(s.firstVert);
        w.key("numVerts"); w.integer(s.numVerts);
        w.key("firstIndex"); w.integer(s.firstIndex);
        w.key("numIndexes"); w.integer(s.numIndexes);
        w.key("lightmapStyles"); w.integers(styles, 4);
        w.key("vertexStyles"); w.integers(styles, 4);
        w.key("lightmapNum"); w.integers(lmNum, 4);
        w.key("lightmapX"); w.integers(lmX, 4);
        w.key("lightmapY"); w.integers(lmY, 4);
        w.key("lightmapWidth"); w.integer(s.lightmapWidth);
        w.key("lightmapHeight"); w.integer(s.lightmapHeight);
        w.key("lightmapOrigin"); w.floats(s.lightmapOrigin, 3);
        w.key("lightmapVecs");
        w.startArray();
        for (const auto& vec : s.lightmapVecs) w.floats(vec, 3);
        w.endArray();
        w.key("patchWidth"); w.integer(s.patchWidth);
        w.key("patchHeight"); w.integer(s.patchHeight);
        w.endObject();
    });
}

void fogsFile(Writer& out, const bsp::Bsp& bsp) {
    recordFile(out, "fog", bsp.fogs, [](Writer& w, const bsp::Fog& f) {
        w.startObject();
        writeName(w, "shader", f.shader);
        w.key("brushNum"); w.integer(f.brushNum);
        w.key("visibleSide"); w.integer(f.visibleSide);
        w.endObject();
    });
}

void gridPointsFile(Writer& out, const bsp::Bsp& bsp) {
    recordFile(out, "GridPoint", bsp.lightGrid, [](Writer& w, const bsp::GridPoint& p) {
        static const uint8_t zero3[3] = {0, 0, 0};
        const int32_t styles[4] = {0, 255, 255, 255};
        w.startObject();
        w.key("ambient");
        w.startArray();
        w.integers(p.ambient, 3);
        for (int i = 1; i < 4; ++i) w.integers(zero3, 3);
        w.endArray();
        w.key("directed");
        w.startArray();
        w.integers(p.directed, 3);
        for (int i = 1; i < 4; ++i) w.integers(zero3, 3);
        w.endArray();
        w.key("styles"); w.integers(styles, 4);
        w.key("latLong"); w.integers(p.latLong, 2);
        w.endObject();
    });
}

void entitiesFile(Writer& w, const std::vector<bsp::Entity>& entities) {
    w.startObject();
    for (size_t i = 0; i < entities.size(); ++i) {
        w.indexedKey("entity", i);
        w.startObject();
        for (const auto& [key, value] : entities[i].pairs) {
            w.key("KeyValue");
            w.startArray();
            w.string(key);
            w.string(value);
            w.endArray();
        }
        w.endObject();
    }
    w.endObject();
}

void entityTextFile(Writer& w, const std::string& text) {
    w.startObject();
    w.key("text");
    w.string(text);
    w.endObject();
}

void advertisementsFile(Writer& out, const std::vector<uint8_t>& lump) {
    std::vector<bsp::Advertisement> ads(lump.size() / sizeof(bsp::Advertisement));
    if (!ads.empty()) std::memcpy(ads.data(), lump.data(), ads.size() * sizeof(bsp::Advertisement));
    recordFile(out, "advertisement", ads, [](Writer& w, const bsp::Advertisement& a) {
        w.startObject();
        w.key("cellId"); w.integer(a.cellId);
        w.key("normal"); w.floats(a.normal, 3);
        w.key("rect");
        w.startArray();
        for (const auto& corner : a.rect) w.floats(corner, 3);
        w.endArray();
        writeName(w, "model", a.model);
        w.endObject();
    });
}

void shGridFile(Writer& w, const sh::GridSH& grid) {
    w.startObject();
    w.key("header");
    w.startObject();
    w.key("gridMins"); w.floats(grid.mins, 3);
    w.key("gridSize"); w.floats(grid.size, 3);
    w.key("gridBounds"); w.integers(grid.bounds, 3);
    w.endObject();
    w.key("points");
    w.startArray();
    for (const sh::GridPointSH& p : grid.points) {
        w.startArray();
        for (const auto& rgb : p.coeffs) w.floats(rgb, 3);
        w.endArray();
    }
    w.endArray();
    w.endObject();
}

sh::GridSH decodeShGrid(const std::vector<uint8_t>& bytes, const std::string& where) {
    sh::GridSH grid;
    std::string error;
    if (!sh::decodeGridLump(bytes.data(), bytes.size(), grid, error)) throw bsp::BspError(where + ": " + error);
    return grid;
}

// BSPX lumps in file order; the SH grid's entry points at GridPointsSH.json so its position is kept.
void bspxFile(Writer& w, const bsp::Bsp& bsp) {
    w.startObject();
    for (size_t i = 0; i < bsp.bspx.size(); ++i) {
        const bsp::BspxLump& lump = bsp.bspx[i];
        w.indexedKey("BSPXLump", i);
        w.startObject();
        w.key("name");
        w.string(lump.name);
        if (lump.name == sh::kBspxLumpName) {
            w.key("file");
            w.string(files::kGridPointsSH);
        } else if (lump.name == sh::kWorldLightsLumpName) {
            writeWorldLightsMember(w, lump.data, "BSPX " + lump.name);
        } else {
            w.key("bytes");
            w.integers(lump.data.data(), static_cast<int>(lump.data.size()));
        }
        w.endObject();
    }
    w.endObject();
}

void headerFile(Writer& w, const bsp::Bsp& bsp, const char* shCarrier) {
    w.startObject();
    w.key("ident"); w.string("IBSP");
    w.key("version"); w.integer(bsp.version);
    w.key("lumpEntries"); w.integer(bsp.headerLumps);
    w.key("shGrid"); w.string(shCarrier);
    w.endObject();
}

// Lightmap pages as PNG files, listed in LightmapImages.json.
void lightmapImagesFile(Writer& w, const bsp::Bsp& bsp, const fs::path& folder) {
    const int pageBytes = bsp::kLightmapPageBytes;
    size_t pages = bsp.lightmaps.size() / pageBytes;
    fs::create_directories(folder / "lightmaps");
    w.startObject();
    w.key("pageWidth"); w.integer(128);
    w.key("pageHeight"); w.integer(128);
    w.key("pages");
    w.startArray();
    for (size_t p = 0; p < pages; ++p) {
        char name[64];
        std::snprintf(name, sizeof(name), "lightmaps/lm_%04zu.png", p);
        Image page;
        page.width = 128;
        page.height = 128;
        page.rgba.resize(128 * 128 * 4);
        const uint8_t* src = bsp.lightmaps.data() + p * pageBytes;
        for (int i = 0; i < 128 * 128; ++i) {
            page.rgba[i * 4 + 0] = src[i * 3 + 0];
            page.rgba[i * 4 + 1] = src[i * 3 + 1];
            page.rgba[i * 4 + 2] = src[i * 3 + 2];
            page.rgba[i * 4 + 3] = 255;
        }
        writeFileAtomic(folder / name, encodePng(page, /*alpha=*/false));
        w.string(name);
    }
    w.endArray();
    w.endObject();
}

}  // namespace

void unpackBsp(const bsp::Bsp& bsp, const fs::path& folder, const JsonOptions& options, Log& log) {
    fs::create_directories(folder);
    // Each file streams through a temporary that replaces the old file only when complete.
    auto write = [&](const char* name, auto&& writeBody) {
        log.info("Writing " + (folder / name).string());
        AtomicFileWriter file(folder / name);
        Writer w(&file);
        writeBody(w);
        w.finish();
        file.commit();
    };
    std::string bspName = folder.string() + ".bsp";

    write(files::kShaders, [&](Writer& w) { shadersFile(w, bsp); });
    write(files::kModels, [&](Writer& w) { modelsFile(w, bsp); });
    write(files::kPlanes, [&](Writer& w) { planesFile(w, bsp); });
    write(files::kLeafs, [&](Writer& w) { leafsFile(w, bsp); });
    write(files::kNodes, [&](Writer& w) { nodesFile(w, bsp); });
    write(files::kLeafSurfaces, [&](Writer& w) { numFile(w, "LeafSurface", bsp.leafSurfaces.data(), bsp.leafSurfaces.size()); });
    write(files::kLeafBrushes, [&](Writer& w) { numFile(w, "LeafBrush", bsp.leafBrushes.data(), bsp.leafBrushes.size()); });
    write(files::kBrushes, [&](Writer& w) { brushesFile(w, bsp); });
    write(files::kBrushSides, [&](Writer& w) { brushSidesFile(w, bsp); });
    write(files::kDrawVerts, [&](Writer& w) { drawVertsFile(w, bsp); });
    write(files::kDrawSurfaces, [&](Writer& w) { drawSurfacesFile(w, bsp); });
    write(files::kFogs, [&](Writer& w) { fogsFile(w, bsp); });
    write(files::kDrawIndexes, [&](Writer& w) { numFile(w, "DrawIndex", bsp.drawIndexes.data(), bsp.drawIndexes.size()); });
    write(files::kVisBytes, [&](Writer& w) { numFile(w, "VisByte", bsp.visibility.data(), bsp.visibility.size()); });

    bool pagesAsImages = options.lightmapImages && bsp.lightmaps.size() % bsp::kLightmapPageBytes == 0;
    if (options.lightmapImages && !pagesAsImages)
        log.warning(bspName + ": lightmap lump is not a whole number of 128x128 pages; writing LightBytes.json instead");
    if (pagesAsImages) {
        write(files::kLightmapImages, [&](Writer& w) { lightmapImagesFile(w, bsp, folder); });
    } else {
        write(files::kLightBytes, [&](Writer& w) { numFile(w, "LightByte", bsp.lightmaps.data(), bsp.lightmaps.size()); });
    }

    std::vector<bsp::Entity> entities = bsp::parseEntities(bsp.entities, bspName);
    write(files::kEntities, [&](Writer& w) { entitiesFile(w, entities); });
    if (bsp::unparseEntities(entities) != bsp.entities)
        write(files::kEntityText, [&](Writer& w) { entityTextFile(w, bsp.entities); });
    write(files::kGridPoints, [&](Writer& w) { gridPointsFile(w, bsp); });

    // What q3map2 has no file for.
    const char* shCarrier = "none";
    if (!bsp.shGrid.empty()) {
        shCarrier = "lump18";
        sh::GridSH grid = decodeShGrid(bsp.shGrid, bspName + ": lightgrid_sh");
        write(files::kGridPointsSH, [&](Writer& w) { shGridFile(w, grid); });
    } else if (const bsp::BspxLump* lump = bsp.findBspx(sh::kBspxLumpName)) {
        shCarrier = "bspx";
        sh::GridSH grid = decodeShGrid(lump->data, bspName + ": BSPX " + lump->name);
        write(files::kGridPointsSH, [&](Writer& w) { shGridFile(w, grid); });
    }
    write(files::kHeader, [&](Writer& w) { headerFile(w, bsp, shCarrier); });
    if (!bsp.lump17.empty()) {
        if (bsp.lump17.size() % sizeof(bsp::Advertisement) == 0)
            write(files::kAdvertisements, [&](Writer& w) { advertisementsFile(w, bsp.lump17); });
        else
            write(files::kLump17Bytes, [&](Writer& w) { numFile(w, "Lump17Byte", bsp.lump17.data(), bsp.lump17.size()); });
    }
    if (!bsp.bspx.empty()) write(files::kBspxLumps, [&](Writer& w) { bspxFile(w, bsp); });
}

}  // namespace q3::json
