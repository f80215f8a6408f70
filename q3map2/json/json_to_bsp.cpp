// -json -pack: the folder back into a BSP. Every value is checked where it is read, so an error
// in a hand-edited file names the file, line, column and the field.
#include "flag_names.h"
#include "json_error.h"
#include "json_files.h"
#include "json_stage.h"
#include "json_value.h"
#include "num_file.h"
#include "world_lights_json.h"

#include "file_io.h"
#include "image.h"
#include "sh_grid_lump.h"
#include "world_lights.h"

#include <cstring>
#include <limits>

namespace q3::json {
namespace fs = std::filesystem;

namespace {

std::string recordName(const char* prefix, size_t i) { return std::string(prefix) + "#" + std::to_string(i); }

class FolderReader {
public:
    FolderReader(fs::path folder, Log& log) : folder_(std::move(folder)), log_(log) {}

    bool has(const char* name) const { return fs::exists(folder_ / name); }

    std::string text(const char* name) const {
        fs::path path = folder_ / name;
        if (!fs::exists(path)) throw JsonError(path.string() + ": missing file");
        log_.debug("Loading " + path.string());
        return readFileText(path);
    }

    Document document(const char* name) const { return parseDocument((folder_ / name).string(), text(name)); }

    std::vector<int64_t> numbers(const char* name, int64_t lo, int64_t hi) const {
        return readNumFile((folder_ / name).string(), text(name), lo, hi);
    }

    const fs::path& folder() const { return folder_; }

private:
    fs::path folder_;
    Log& log_;
};

void readFloats(const Value& v, float* out, size_t n, const std::string& context) {
    v.asArray(n, context);
    for (size_t i = 0; i < n; ++i) out[i] = v.items[i].asFloat(context);
}

template <typename T>
void readInts(const Value& v, T* out, size_t n, const std::string& context) {
    v.asArray(n, context);
    for (size_t i = 0; i < n; ++i) out[i] = static_cast<T>(v.items[i].asInt(context));
}

void readBytes(const Value& v, uint8_t* out, size_t n, const std::string& context) {
    v.asArray(n, context);
    for (size_t i = 0; i < n; ++i) out[i] = v.items[i].asByte(context);
}

// First element of q3map2's four-style arrays ([[...], [...], [...], [...]]): Quake 3 keeps style 0.
const Value& styleZero(const Value& v, const std::string& context) {
    if (!v.isArray() || v.items.empty()) v.fail(context, "expected an array of 4 styles");
    return v.items[0];
}

int32_t styleZeroInt(const Value& v, const std::string& context) { return styleZero(v, context).asInt(context); }

void readName(const Value& record, const char* key, char (&field)[64], const std::string& context) {
    const Value& nameValue = record.member(key, context);
    const std::string& name = nameValue.asString(context + "." + key);
    if (name.size() >= sizeof(field)) nameValue.fail(context + "." + key, "name is longer than 63 characters");
    std::memset(field, 0, sizeof(field));
    if (const Value* bytes = record.findMember("nameBytes")) {
        const std::string& hex = bytes->asString(context + ".nameBytes");
        if (hex.size() != 128) bytes->fail(context + ".nameBytes", "expected 128 hexadecimal digits");
        for (size_t i = 0; i < 64; ++i) {
            auto digit = [&](char c) -> int {
                if (c >= '0' && c <= '9') return c - '0';
                if (c >= 'a' && c <= 'f') return c - 'a' + 10;
                if (c >= 'A' && c <= 'F') return c - 'A' + 10;
                bytes->fail(context + ".nameBytes", "expected hexadecimal digits");
            };
            field[i] = static_cast<char>(digit(hex[2 * i]) * 16 + digit(hex[2 * i + 1]));
        }
        // The name member wins when it was edited.
        if (std::string_view(field, strnlen(field, 64)) == name) return;
        std::memset(field, 0, sizeof(field));
    }
    std::memcpy(field, name.data(), name.size());
}

void readMinMax(const Value& record, float* mins, float* maxs, const std::string& context) {
    const Value& mm = record.member("minmax", context);
    readFloats(mm.member("mins", context), mins, 3, context + ".minmax.mins");
    readFloats(mm.member("maxs", context), maxs, 3, context + ".minmax.maxs");
}

void readMinMax(const Value& record, int32_t* mins, int32_t* maxs, const std::string& context) {
    const Value& mm = record.member("minmax", context);
    readInts(mm.member("mins", context), mins, 3, context + ".minmax.mins");
    readInts(mm.member("maxs", context), maxs, 3, context + ".minmax.maxs");
}

template <typename Record, typename Fn>
std::vector<Record> readRecords(const Document& doc, const char* prefix, Fn readRecord) {
    const Value& root = doc.root.asObject(doc.source->name);
    std::vector<Record> out(root.items.size());
    for (size_t i = 0; i < root.items.size(); ++i) {
        std::memset(&out[i], 0, sizeof(Record));
        readRecord(root.items[i], out[i], recordName(prefix, i));
    }
    return out;
}

// Reference checks, reported at the member that holds the bad index ------------------------------

void checkIndex(const Value& record, const char* key, int64_t value, int64_t count, bool allowMinusOne,
                const std::string& context, const char* target) {
    if ((allowMinusOne && value == -1) || (value >= 0 && value < count)) return;
    record.member(key, context).fail(context + "." + key, std::to_string(value) + " is out of range (" + target +
                                                              " has " + std::to_string(count) + ")");
}

void checkRange(const Value& record, const char* firstKey, int64_t first, int64_t num, int64_t count,
                const std::string& context, const char* target) {
    if (first >= 0 && num >= 0 && first + num <= count) return;
    record.member(firstKey, context).fail(context + "." + firstKey,
                                          "range " + std::to_string(first) + "+" + std::to_string(num) +
                                              " is out of range (" + target + " has " + std::to_string(count) + ")");
}

// Lumps -------------------------------------------------------------------------------------------

// The record files whose values are still needed after reading, for reference checks that report
// positions. The two largest files (draw verts, grid points) are read and released on their own.
struct Folder {
    Document shaders, models, planes, leafs, nodes, brushes, brushSides, drawSurfaces, fogs, entities;
};

void readShaders(bsp::Bsp& bsp, const Document& doc, const JsonOptions& options) {
    FlagReadOptions flagOptions{options.useFlagNames, options.skipFlags};
    bsp.shaders = readRecords<bsp::Shader>(doc, "shader", [&](const Value& r, bsp::Shader& s, const std::string& c) {
        readName(r, "shader", s.name, c);
        s.surfaceFlags = static_cast<int32_t>(readFlags(r.member("surfaceFlags", c), quake3Flags().surface, flagOptions, c + ".surfaceFlags"));
        s.contentFlags = static_cast<int32_t>(readFlags(r.member("contentFlags", c), quake3Flags().content, flagOptions, c + ".contentFlags"));
    });
}

void readGeometry(bsp::Bsp& bsp, const Folder& f) {
    bsp.models = readRecords<bsp::Model>(f.models, "model", [](const Value& r, bsp::Model& m, const std::string& c) {
        readMinMax(r, m.mins, m.maxs, c);
        m.firstSurface = r.member("firstBSPSurface", c).asInt(c + ".firstBSPSurface");
        m.numSurfaces = r.member("numBSPSurfaces", c).asInt(c + ".numBSPSurfaces");
        m.firstBrush = r.member("firstBSPBrush", c).asInt(c + ".firstBSPBrush");
        m.numBrushes = r.member("numBSPBrushes", c).asInt(c + ".numBSPBrushes");
    });
    bsp.planes = readRecords<bsp::Plane>(f.planes, "plane", [](const Value& r, bsp::Plane& p, const std::string& c) {
        float v[4];
        readFloats(r, v, 4, c);
        p = {{v[0], v[1], v[2]}, v[3]};
    });
    bsp.leafs = readRecords<bsp::Leaf>(f.leafs, "leaf", [](const Value& r, bsp::Leaf& l, const std::string& c) {
        l.cluster = r.member("cluster", c).asInt(c + ".cluster");
        l.area = r.member("area", c).asInt(c + ".area");
        readMinMax(r, l.mins, l.maxs, c);
        l.firstLeafSurface = r.member("firstBSPLeafSurface", c).asInt(c + ".firstBSPLeafSurface");
        l.numLeafSurfaces = r.member("numBSPLeafSurfaces", c).asInt(c + ".numBSPLeafSurfaces");
        l.firstLeafBrush = r.member("firstBSPLeafBrush", c).asInt(c + ".firstBSPLeafBrush");
        l.numLeafBrushes = r.member("numBSPLeafBrushes", c).asInt(c + ".numBSPLeafBrushes");
    });
    bsp.nodes = readRecords<bsp::Node>(f.nodes, "node", [](const Value& r, bsp::Node& n, const std::string& c) {
        n.planeNum = r.member("planeNum", c).asInt(c + ".planeNum");
        readInts(r.member("children", c), n.children, 2, c + ".children");
        readMinMax(r, n.mins, n.maxs, c);
    });
    bsp.brushes = readRecords<bsp::Brush>(f.brushes, "Brush", [](const Value& r, bsp::Brush& b, const std::string& c) {
        b.firstSide = r.member("firstSide", c).asInt(c + ".firstSide");
        b.numSides = r.member("numSides", c).asInt(c + ".numSides");
        b.shaderNum = r.member("shaderNum", c).asInt(c + ".shaderNum");
    });
    bsp.brushSides = readRecords<bsp::BrushSide>(f.brushSides, "BrushSide", [](const Value& r, bsp::BrushSide& s, const std::string& c) {
        s.planeNum = r.member("planeNum", c).asInt(c + ".planeNum");
        s.shaderNum = r.member("shaderNum", c).asInt(c + ".shaderNum");
    });
    bsp.surfaces = readRecords<bsp::Surface>(f.drawSurfaces, "DrawSurface", [](const Value& r, bsp::Surface& s, const std::string& c) {
        s.shaderNum = r.member("shaderNum", c).asInt(c + ".shaderNum");
        s.fogNum = r.member("fogNum", c).asInt(c + ".fogNum");
        s.surfaceType = r.member("surfaceType", c).asInt(c + ".surfaceType");
        s.firstVert = r.member("firstVert", c).asInt(c + ".firstVert");
        s.numVerts = r.member("numVerts", c).asInt(c + ".numVerts");
        s.firstIndex = r.member("firstIndex", c).asInt(c + ".firstIndex");
        s.numIndexes = r.member("numIndexes", c).asInt(c + ".numIndexes");
        s.lightmapNum = styleZeroInt(r.member("lightmapNum", c), c + ".lightmapNum");
        s.lightmapX = styleZeroInt(r.member("lightmapX", c), c + ".lightmapX");
        s.lightmapY = styleZeroInt(r.member("lightmapY", c), c + ".lightmapY");
        s.lightmapWidth = r.member("lightmapWidth", c).asInt(c + ".lightmapWidth");
        s.lightmapHeight = r.member("lightmapHeight", c).asInt(c + ".lightmapHeight");
        readFloats(r.member("lightmapOrigin", c), s.lightmapOrigin, 3, c + ".lightmapOrigin");
        const Value& vecs = r.member("lightmapVecs", c).asArray(3, c + ".lightmapVecs");
        for (int i = 0; i < 3; ++i) readFloats(vecs.items[i], s.lightmapVecs[i], 3, c + ".lightmapVecs");
        s.patchWidth = r.member("patchWidth", c).asInt(c + ".patchWidth");
        s.patchHeight = r.member("patchHeight", c).asInt(c + ".patchHeight");
    });
    bsp.fogs = readRecords<bsp::Fog>(f.fogs, "fog", [](const Value& r, bsp::Fog& g, const std::string& c) {
        readName(r, "shader", g.shader, c);
        g.brushNum = r.member("brushNum", c).asInt(c + ".brushNum");
        g.visibleSide = r.member("visibleSide", c).asInt(c + ".visibleSide");
    });
}

void readDrawVerts(bsp::Bsp& bsp, const Document& doc) {
    bsp.drawVerts = readRecords<bsp::DrawVert>(doc, "DrawVert", [](const Value& r, bsp::DrawVert& v, const std::string& c) {
        readFloats(r.member("xyz", c), v.xyz, 3, c + ".xyz");
        readFloats(r.member("st", c), v.st, 2, c + ".st");
        readFloats(styleZero(r.member("lightmap", c), c + ".lightmap"), v.lightmap, 2, c + ".lightmap");
        readFloats(r.member("normal", c), v.normal, 3, c + ".normal");
        readBytes(styleZero(r.member("color", c), c + ".color"), v.color, 4, c + ".color");
    });
}

// GridPoints.json is the largest file: streamed, record by record.
void readGridPoints(bsp::Bsp& bsp, const FolderReader& folder) {
    std::string text = folder.text(files::kGridPoints);
    readFlatRecords((folder.folder() / files::kGridPoints).string(), text, [&](const FlatRecord& r) -> std::string {
        bsp::GridPoint p{};
        // Quake 3 keeps style 0: the first 3 of ambient/directed (q3map2 writes 4 styles of 3).
        struct Field {
            const char* key;
            uint8_t* out;
            size_t used, minimum;
        } fields[] = {{"ambient", p.ambient, 3, 3}, {"directed", p.directed, 3, 3}, {"latLong", p.latLong, 2, 2}};
        for (const Field& f : fields) {
            const std::vector<int64_t>* values = r.find(f.key);
            if (!values) return r.name + ": missing member \"" + f.key + "\"";
            if (values->size() < f.minimum)
                return r.name + "." + f.key + ": expected at least " + std::to_string(f.minimum) + " numbers, found " +
                       std::to_string(values->size());
            for (size_t i = 0; i < f.used; ++i) {
                int64_t v = (*values)[i];
                if (v < 0 || v > 255)
                    return r.name + "." + f.key + ": byte value " + std::to_string(v) + " is out of range 0..255";
                f.out[i] = static_cast<uint8_t>(v);
            }
        }
        bsp.lightGrid.push_back(p);
        return {};
    });
}

// Index checks that need several lumps; done where the values still know their source position.
void checkReferences(const bsp::Bsp& bsp, const Folder& f) {
    const int64_t shaders = bsp.shaders.size(), planes = bsp.planes.size(), verts = bsp.drawVerts.size(),
                  indexes = bsp.drawIndexes.size(), sides = bsp.brushSides.size(),
                  brushes = bsp.brushes.size(), surfaces = bsp.surfaces.size(), nodes = bsp.nodes.size(),
                  leafs = bsp.leafs.size(), leafSurfaces = bsp.leafSurfaces.size(), leafBrushes = bsp.leafBrushes.size();
    for (size_t i = 0; i < bsp.surfaces.size(); ++i) {
        const bsp::Surface& s = bsp.surfaces[i];
        const Value& r = f.drawSurfaces.root.items[i];
        std::string c = recordName("DrawSurface", i);
        checkIndex(r, "shaderNum", s.shaderNum, shaders, false, c, "shaders.json");
        checkRange(r, "firstVert", s.firstVert, s.numVerts, verts, c, "DrawVert.json");
        checkRange(r, "firstIndex", s.firstIndex, s.numIndexes, indexes, c, "DrawIndexes.json");
    }
    for (size_t i = 0; i < bsp.brushes.size(); ++i) {
        const Value& r = f.brushes.root.items[i];
        std::string c = recordName("Brush", i);
        checkRange(r, "firstSide", bsp.brushes[i].firstSide, bsp.brushes[i].numSides, sides, c, "BrushSides.json");
        checkIndex(r, "shaderNum", bsp.brushes[i].shaderNum, shaders, false, c, "shaders.json");
    }
    for (size_t i = 0; i < bsp.brushSides.size(); ++i) {
        const Value& r = f.brushSides.root.items[i];
        std::string c = recordName("BrushSide", i);
        checkIndex(r, "planeNum", bsp.brushSides[i].planeNum, planes, false, c, "planes.json");
        checkIndex(r, "shaderNum", bsp.brushSides[i].shaderNum, shaders, false, c, "shaders.json");
    }
    for (size_t i = 0; i < bsp.models.size(); ++i) {
        const Value& r = f.models.root.items[i];
        std::string c = recordName("model", i);
        checkRange(r, "firstBSPSurface", bsp.models[i].firstSurface, bsp.models[i].numSurfaces, surfaces, c, "DrawSurfaces.json");
        checkRange(r, "firstBSPBrush", bsp.models[i].firstBrush, bsp.models[i].numBrushes, brushes, c, "Brushes.json");
    }
    for (size_t i = 0; i < bsp.nodes.size(); ++i) {
        const Value& r = f.nodes.root.items[i];
        std::string c = recordName("node", i);
        checkIndex(r, "planeNum", bsp.nodes[i].planeNum, planes, false, c, "planes.json");
        for (int32_t child : bsp.nodes[i].children) {
            if (child >= 0) checkIndex(r, "children", child, nodes, false, c, "nodes.json");
            else checkIndex(r, "children", -(int64_t(child) + 1), leafs, false, c, "leafs.json");
        }
    }
    for (size_t i = 0; i < bsp.leafs.size(); ++i) {
        const Value& r = f.leafs.root.items[i];
        std::string c = recordName("leaf", i);
        checkRange(r, "firstBSPLeafSurface", bsp.leafs[i].firstLeafSurface, bsp.leafs[i].numLeafSurfaces, leafSurfaces, c, "LeafSurfaces.json");
        checkRange(r, "firstBSPLeafBrush", bsp.leafs[i].firstLeafBrush, bsp.leafs[i].numLeafBrushes, leafBrushes, c, "LeafBrushes.json");
    }
    for (size_t i = 0; i < bsp.fogs.size(); ++i)
        checkIndex(f.fogs.root.items[i], "brushNum", bsp.fogs[i].brushNum, brushes, false, recordName("fog", i), "Brushes.json");
}

template <typename T>
std::vector<T> narrow(const std::vector<int64_t>& values) {
    return std::vector<T>(values.begin(), values.end());
}

std::string readEntities(const FolderReader& folder, const Document& doc) {
    std::vector<bsp::Entity> entities;
    const Value& root = doc.root.asObject(doc.source->name);
    for (size_t i = 0; i < root.items.size(); ++i) {
        std::string c = recordName("entity", i);
        const Value& e = root.items[i].asObject(c);
        bsp::Entity entity;
        for (size_t k = 0; k < e.items.size(); ++k) {
            if (e.keys[k] != "KeyValue") e.items[k].fail(c, "unexpected member \"" + e.keys[k] + "\" (expected \"KeyValue\")");
            const Value& kv = e.items[k].asArray(2, c + ".KeyValue");
            entity.pairs.emplace_back(kv.items[0].asString(c + ".KeyValue"), kv.items[1].asString(c + ".KeyValue"));
        }
        entities.push_back(std::move(entity));
    }
    std::string text = bsp::unparseEntities(entities);
    // The exact original text is used when the entities were not edited.
    if (folder.has(files::kEntityText)) {
        Document exact = folder.document(files::kEntityText);
        const std::string& original = exact.root.member("text", "EntityText").asString("EntityText.text");
        std::vector<bsp::Entity> parsed = bsp::parseEntities(original, exact.source->name);
        if (bsp::unparseEntities(parsed) == text) return original;
    }
    return text;
}

sh::GridSH readShGrid(const Document& doc) {
    const Value& root = doc.root.asObject(doc.source->name);
    const Value& header = root.member("header", "GridPointsSH");
    sh::GridSH grid;
    readFloats(header.member("gridMins", "header"), grid.mins, 3, "header.gridMins");
    readFloats(header.member("gridSize", "header"), grid.size, 3, "header.gridSize");
    readInts(header.member("gridBounds", "header"), grid.bounds, 3, "header.gridBounds");
    const Value& points = root.member("points", "GridPointsSH");
    if (!points.isArray()) points.fail("points", "expected an array");
    int64_t expected = 1;
    for (int32_t b : grid.bounds) {
        if (b <= 0) header.member("gridBounds", "header").fail("header.gridBounds", "bounds must be positive");
        expected *= b;
    }
    if (expected != static_cast<int64_t>(points.size()))
        points.fail("points", "count " + std::to_string(points.size()) + " does not match gridBounds (" +
                                  std::to_string(expected) + " points)");
    grid.points.resize(points.size());
    for (size_t i = 0; i < points.size(); ++i) {
        std::string c = "points[" + std::to_string(i) + "]";
        const Value& p = points.items[i].asArray(9, c);
        for (int k = 0; k < 9; ++k) readFloats(p.items[k], grid.points[i].coeffs[k], 3, c);
    }
    return grid;
}

std::vector<uint8_t> readLightmapImages(const FolderReader& folder) {
    Document doc = folder.document(files::kLightmapImages);
    const Value& root = doc.root.asObject(doc.source->name);
    int32_t w = root.member("pageWidth", "LightmapImages").asInt("pageWidth");
    int32_t h = root.member("pageHeight", "LightmapImages").asInt("pageHeight");
    if (w != 128 || h != 128) root.member("pageWidth", "LightmapImages").fail("pageWidth", "pages must be 128x128");
    const Value& pages = root.member("pages", "LightmapImages");
    if (!pages.isArray()) pages.fail("pages", "expected an array of file names");
    std::vector<uint8_t> bytes;
    for (size_t p = 0; p < pages.size(); ++p) {
        std::string c = "pages[" + std::to_string(p) + "]";
        const std::string& name = pages.items[p].asString(c);
        fs::path path = folder.folder() / name;
        Image image;
        try {
            image = decodeImage(readFileBytes(path), path.string());
        } catch (const std::exception& e) {
            pages.items[p].fail(c, e.what());
        }
        if (image.width != 128 || image.height != 128)
            pages.items[p].fail(c, path.string() + " is " + std::to_string(image.width) + "x" +
                                       std::to_string(image.height) + ", expected 128x128");
        for (int i = 0; i < 128 * 128; ++i)
            for (int k = 0; k < 3; ++k) bytes.push_back(image.rgba[i * 4 + k]);
    }
    return bytes;
}

void readExtras(bsp::Bsp& bsp, const FolderReader& folder, const std::string& shCarrier) {
    if (folder.has(files::kAdvertisements)) {
        Document doc = folder.document(files::kAdvertisements);
        auto ads = readRecords<bsp::Advertisement>(doc, "advertisement", [](const Value& r, bsp::Advertisement& a, const std::string& c) {
            a.cellId = r.member("cellId", c).asInt(c + ".cellId");
            readFloats(r.member("normal", c), a.normal, 3, c + ".normal");
            const Value& rect = r.member("rect", c).asArray(4, c + ".rect");
            for (int i = 0; i < 4; ++i) readFloats(rect.items[i], a.rect[i], 3, c + ".rect");
            readName(r, "model", a.model, c);
        });
        bsp.lump17.resize(ads.size() * sizeof(bsp::Advertisement));
        if (!ads.empty()) std::memcpy(bsp.lump17.data(), ads.data(), bsp.lump17.size());
    } else if (folder.has(files::kLump17Bytes)) {
        bsp.lump17 = narrow<uint8_t>(folder.numbers(files::kLump17Bytes, 0, 255));
    }

    std::vector<uint8_t> shBytes;
    if (folder.has(files::kGridPointsSH)) shBytes = sh::encodeGridLump(readShGrid(folder.document(files::kGridPointsSH)));
    bool shInBspx = !shBytes.empty() && shCarrier == "bspx";
    if (!shBytes.empty() && !shInBspx) bsp.shGrid = shBytes;

    if (folder.has(files::kBspxLumps)) {
        Document doc = folder.document(files::kBspxLumps);
        const Value& root = doc.root.asObject(doc.source->name);
        for (size_t i = 0; i < root.items.size(); ++i) {
            std::string c = recordName("BSPXLump", i);
            const Value& r = root.items[i].asObject(c);
            const std::string& name = r.member("name", c).asString(c + ".name");
            if (name.empty() || name.size() > 23) r.member("name", c).fail(c + ".name", "BSPX lump names have 1 to 23 characters");
            if (name == sh::kBspxLumpName) {
                if (!shInBspx) r.fail(c, std::string("lists ") + files::kGridPointsSH + " but the SH grid is not carried in BSPX");
                bsp.setBspx(name, shBytes);
                shInBspx = false;
                continue;
            }
            if (name == sh::kWorldLightsLumpName) {
                bsp.setBspx(name, readWorldLightsMember(r.member("lights", c), c + ".lights"));
                continue;
            }
            const Value& bytes = r.member("bytes", c);
            if (!bytes.isArray()) bytes.fail(c + ".bytes", "expected an array of bytes");
            std::vector<uint8_t> data(bytes.size());
            for (size_t k = 0; k < bytes.size(); ++k) data[k] = bytes.items[k].asByte(c + ".bytes");
            bsp.setBspx(name, std::move(data));
        }
    }
    if (shInBspx) bsp.setBspx(sh::kBspxLumpName, shBytes);
}

}  // namespace

bsp::Bsp packFolder(const fs::path& folderPath, const JsonOptions& options, Log& log) {
    if (!fs::is_directory(folderPath)) throw JsonError(folderPath.string() + ": no such folder to pack");
    FolderReader folder(folderPath, log);
    bsp::Bsp bsp;

    std::string shCarrier = "none";
    if (folder.has(files::kHeader)) {
        Document header = folder.document(files::kHeader);
        const Value& root = header.root.asObject("Header");
        const Value& version = root.member("version", "Header");
        bsp.version = version.asInt("Header.version");
        if (bsp.version != bsp::kVersionQ3 && bsp.version != bsp::kVersionQL)
            version.fail("Header.version", "version must be 46 or 47");
        const Value& entries = root.member("lumpEntries", "Header");
        bsp.headerLumps = entries.asInt("Header.lumpEntries");
        if (bsp.headerLumps < 17 || bsp.headerLumps > 19) entries.fail("Header.lumpEntries", "must be 17, 18 or 19");
        if (const Value* carrier = root.findMember("shGrid")) shCarrier = carrier->asString("Header.shGrid");
    } else if (folder.has(files::kGridPointsSH)) {
        // A folder without our header but with an SH grid: the v47 layout of the SH grid spec.
        bsp.version = bsp::kVersionQL;
        bsp.headerLumps = 19;
    }

    readDrawVerts(bsp, folder.document(files::kDrawVerts));
    readGridPoints(bsp, folder);
    Folder f{folder.document(files::kShaders),    folder.document(files::kModels),     folder.document(files::kPlanes),
             folder.document(files::kLeafs),      folder.document(files::kNodes),      folder.document(files::kBrushes),
             folder.document(files::kBrushSides), folder.document(files::kDrawSurfaces), folder.document(files::kFogs),
             folder.document(files::kEntities)};
    readShaders(bsp, f.shaders, options);
    readGeometry(bsp, f);
    constexpr int64_t kIntMin = std::numeric_limits<int32_t>::min(), kIntMax = std::numeric_limits<int32_t>::max();
    bsp.leafSurfaces = narrow<int32_t>(folder.numbers(files::kLeafSurfaces, kIntMin, kIntMax));
    bsp.leafBrushes = narrow<int32_t>(folder.numbers(files::kLeafBrushes, kIntMin, kIntMax));
    bsp.drawIndexes = narrow<int32_t>(folder.numbers(files::kDrawIndexes, kIntMin, kIntMax));
    bsp.visibility = narrow<uint8_t>(folder.numbers(files::kVisBytes, 0, 255));
    if (folder.has(files::kLightmapImages)) bsp.lightmaps = readLightmapImages(folder);
    else bsp.lightmaps = narrow<uint8_t>(folder.numbers(files::kLightBytes, 0, 255));
    bsp.entities = readEntities(folder, f.entities);
    readExtras(bsp, folder, shCarrier);
    if (!bsp.shGrid.empty() && (bsp.version != bsp::kVersionQL || bsp.headerLumps != 19)) {
        bsp.version = bsp::kVersionQL;
        bsp.headerLumps = 19;
    }
    checkReferences(bsp, f);
    bsp::validateBsp(bsp, folderPath.string());
    return bsp;
}

}  // namespace q3::json
