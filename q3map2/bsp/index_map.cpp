#include "index_map.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <optional>

#include "bsp_brushes.h"
#include "image.h"
#include "index_map_formats.h"
#include "log.h"
#include "map_file.h"
#include "script.h"
#include "vfs.h"

namespace q3::bspstage {
namespace {

// A float scaled to pixels, truncated as C converts it; values no int holds give the first pixel,
// as the x86 conversion q3map2 relies on does (a zero-sized entity axis divides by zero).
int truncatedPixel(float v, int size) {
    if (!std::isfinite(v) || v >= 2147483648.0f || v < -2147483648.0f) return 0;
    return std::clamp(int(v), 0, size - 1);
}

// The first of `keys` with a non-empty value (q3map2 drops empty pairs when it reads the map).
const std::string* firstKey(const map::MapEntity& e, std::initializer_list<const char*> keys) {
    for (const char* k : keys)
        if (const std::string* v = e.find(k); v && !v->empty()) return v;
    return nullptr;
}

std::string entityName(const map::MapEntity& e) {
    return "Entity " + std::to_string(e.number) + " (" + std::string(e.classname()) + ")";
}

std::string extensionOf(const std::string& file) {
    const size_t dot = file.find_last_of('.');
    const size_t slash = file.find_last_of("/\\");
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return {};
    return file.substr(dot + 1);
}

// q3map2 splits the list at every single space, so two spaces in a row give a 0 between them.
void parseOffsets(const std::string& text, IndexMap& out) {
    size_t start = 0;
    for (int i = 0; i < kMaxIndexMapLayers && start < text.size(); ++i) {
        size_t space = text.find(' ', start);
        if (space == std::string::npos) space = text.size();
        out.offsets[size_t(i)] = float(std::atof(text.substr(start, space - start).c_str()));
        start = space + 1;
    }
}

// The entity's bounds as q3map2 SetEntityBounds takes them: its brushes and patch control points,
// each axis replaced by the "min" / "max" keys when given.
Bounds entityBounds(const map::MapEntity& e, const LoadedMap& map) {
    Bounds b;
    for (const BspEntity& be : map.entities) {
        for (const Brush& brush : be.brushes)
            if (brush.mapEntityNum == e.number && !brush.bounds.empty()) {
                b.add(brush.bounds.mins.toFloat());
                b.add(brush.bounds.maxs.toFloat());
            }
        for (const PatchRef& p : be.patches)
            if (p.mapEntityNum == e.number)
                for (const map::PatchControl& c : p.patch->control) b.add(c.xyz);
    }
    if (const std::string* v = e.find("min"); v && !v->empty()) b.mins = parseVectorKey(*v).toFloat();
    if (const std::string* v = e.find("max"); v && !v->empty()) b.maxs = parseVectorKey(*v).toFloat();
    return b;
}

bool hasPrimitives(const map::MapEntity& e, const LoadedMap& map) {
    for (const BspEntity& be : map.entities) {
        for (const Brush& brush : be.brushes)
            if (brush.mapEntityNum == e.number) return true;
        for (const PatchRef& p : be.patches)
            if (p.mapEntityNum == e.number) return true;
    }
    return false;
}

// The layer of every pixel: the red channel spread over the layers, as q3map2 reads a TGA.
std::vector<uint8_t> layersFromRed(const Image& image, int layers) {
    std::vector<uint8_t> out(size_t(image.width) * size_t(image.height));
    for (size_t i = 0; i < out.size(); ++i) {
        const int layer = int(image.rgba[i * 4]) * layers / 256;
        out[i] = uint8_t(std::min(layer, layers - 1));
    }
    return out;
}

// A palette image's indexes are the layers themselves, the ones past the last layer taking it.
std::vector<uint8_t> layersFromIndexes(std::vector<uint8_t> indexes, int layers) {
    for (uint8_t& i : indexes) i = uint8_t(std::min(int(i), layers - 1));
    return indexes;
}

std::optional<IndexMap> loadIndexMap(const map::MapEntity& e, const LoadedMap& map, const Vfs* vfs, Log& log) {
    const std::string* file = firstKey(e, {"_indexmap", "alphamap"});
    if (!file || !hasPrimitives(e, map)) return std::nullopt;
    const std::string who = entityName(e) + ": index map \"" + *file + "\"";
    const std::string ignored = ", the entity is not layered";
    const std::string* layers = firstKey(e, {"_layers", "layers"});
    if (!layers) {
        log.warning(who + " has no \"_layers\" or \"layers\" key" + ignored);
        return std::nullopt;
    }
    IndexMap im;
    im.file = *file;
    im.layers = std::atoi(layers->c_str());
    if (im.layers < 1 || im.layers > kMaxIndexMapLayers) {
        log.warning(who + " has " + std::to_string(im.layers) + " layers, not 1 to " +
                    std::to_string(kMaxIndexMapLayers) + ignored);
        return std::nullopt;
    }
    const std::string* shader = firstKey(e, {"_shader", "shader"});
    if (!shader) {
        log.warning(who + " has no \"_shader\" or \"shader\" key" + ignored);
        return std::nullopt;
    }
    im.baseShader = *shader;
    const std::string ext = extensionOf(*file);
    const bool palette = equalsNoCase(ext, "pcx") || equalsNoCase(ext, "bmp");
    if (!palette && !equalsNoCase(ext, "tga") && !equalsNoCase(ext, "png")) {
        log.warning(who + ": only .tga, .png, .pcx and .bmp index maps are read" + ignored);
        return std::nullopt;
    }
    if (!vfs) throw CompileError(who + ": no game file system to read it from");
    const std::optional<std::vector<uint8_t>> bytes = vfs->read(*file);
    if (!bytes) throw CompileError(who + " not found in the game folders");
    try {
        if (palette) {
            PaletteIndexes image = equalsNoCase(ext, "pcx") ? decodePcxIndexes(*bytes, *file)
                                                            : decodeBmpIndexes(*bytes, *file);
            im.width = image.width;
            im.height = image.height;
            im.pixels = layersFromIndexes(std::move(image.pixels), im.layers);
        } else {
            const Image image = decodeImage(*bytes, *file);
            im.width = image.width;
            im.height = image.height;
            im.pixels = layersFromRed(image, im.layers);
        }
    } catch (const ImageError& err) {
        throw CompileError(who + ": " + err.what());
    }
    if (im.width < 2 || im.height < 2) {
        log.warning(who + " is smaller than 2x2 pixels" + ignored);
        return std::nullopt;
    }
    if (const std::string* offsets = firstKey(e, {"_offsets", "offsets"})) parseOffsets(*offsets, im);
    im.bounds = entityBounds(e, map);
    log.debug(entityName(e) + " has shader index map \"" + *file + "\"");
    return im;
}

}  // namespace

uint8_t IndexMap::layerAt(const Vec3& point) const {
    const Vec3 size = bounds.maxs - bounds.mins;
    const float s = (point.x - bounds.mins.x) / size.x;
    const float t = (bounds.maxs.y - point.y) / size.y;
    const int x = truncatedPixel(s * float(width), width);
    const int y = truncatedPixel(t * float(height), height);
    return pixels[size_t(y) * size_t(width) + size_t(x)];
}

LayeredVertices IndexMap::layer(std::span<const Vec3> points) const {
    LayeredVertices v;
    std::vector<uint8_t> index;
    for (const Vec3& p : points) index.push_back(layerAt(p));
    if (index.empty()) return v;
    v.lowest = *std::min_element(index.begin(), index.end());
    v.highest = *std::max_element(index.begin(), index.end());
    for (uint8_t i : index) {
        v.alpha.push_back(i < v.highest ? 0 : 255);
        v.zOffset.push_back(offsets[i]);
    }
    return v;
}

std::string IndexMap::layerShaderName(const LayeredVertices& v) const {
    std::string name = "textures/" + baseShader + "_" + std::to_string(v.lowest);
    if (v.lowest != v.highest) name += "to" + std::to_string(v.highest);
    return name;
}

std::vector<std::unique_ptr<IndexMap>> loadIndexMaps(const map::MapFile& file, const LoadedMap& map, const Vfs* vfs,
                                                     Log& log) {
    std::vector<std::unique_ptr<IndexMap>> out(file.entities.size());
    for (size_t i = 0; i < file.entities.size(); ++i)
        if (std::optional<IndexMap> im = loadIndexMap(file.entities[i], map, vfs, log))
            out[i] = std::make_unique<IndexMap>(std::move(*im));
    return out;
}

}  // namespace q3::bspstage
