#include "light_styles.h"

#include <algorithm>
#include <cstring>
#include <map>
#include <set>

#include "color_pipeline.h"
#include "file_io.h"
#include "light_context.h"
#include "light_text.h"
#include "log.h"
#include "script.h"
#include "shader_info.h"
#include "vfs.h"

namespace q3::light {

// ---- MD4 (RFC 1320) ----

namespace {

uint32_t rotl(uint32_t x, int s) { return (x << s) | (x >> (32 - s)); }

void md4Block(std::array<uint32_t, 4>& state, const uint8_t* block) {
    uint32_t x[16];
    for (int i = 0; i < 16; ++i)
        x[i] = uint32_t(block[4 * i]) | uint32_t(block[4 * i + 1]) << 8 | uint32_t(block[4 * i + 2]) << 16 |
               uint32_t(block[4 * i + 3]) << 24;
    std::array<uint32_t, 4> v = state;
    // Each step updates one register from the other three; the updated register cycles a, d, c, b.
    auto step = [&v, &x](int round, int j, int k, int s) {
        const int ia = (4 - j % 4) % 4, ib = (ia + 1) % 4, ic = (ia + 2) % 4, id = (ia + 3) % 4;
        const uint32_t b = v[ib], c = v[ic], d = v[id];
        uint32_t f = 0;
        if (round == 0) f = (b & c) | (~b & d);
        else if (round == 1) f = ((b & c) | (b & d) | (c & d)) + 0x5A827999u;
        else f = (b ^ c ^ d) + 0x6ED9EBA1u;
        v[ia] = rotl(v[ia] + f + x[k], s);
    };
    constexpr int kShift[3][4] = {{3, 7, 11, 19}, {3, 5, 9, 13}, {3, 9, 11, 15}};
    constexpr int kOrder3[16] = {0, 8, 4, 12, 2, 10, 6, 14, 1, 9, 5, 13, 3, 11, 7, 15};
    for (int j = 0; j < 16; ++j) step(0, j, j, kShift[0][j % 4]);
    for (int j = 0; j < 16; ++j) step(1, j, (j % 4) * 4 + j / 4, kShift[1][j % 4]);
    for (int j = 0; j < 16; ++j) step(2, j, kOrder3[j], kShift[2][j % 4]);
    for (int i = 0; i < 4; ++i) state[i] += v[i];
}

}  // namespace

std::array<uint8_t, 16> md4Digest(std::string_view bytes) {
    std::array<uint32_t, 4> state{0x67452301u, 0xefcdab89u, 0x98badcfeu, 0x10325476u};
    const size_t whole = bytes.size() / 64 * 64;
    for (size_t at = 0; at < whole; at += 64) md4Block(state, reinterpret_cast<const uint8_t*>(bytes.data()) + at);
    // Tail: the remaining bytes, 0x80, zeros up to 56 mod 64, then the bit length (little-endian).
    std::vector<uint8_t> tail(bytes.begin() + static_cast<std::ptrdiff_t>(whole), bytes.end());
    tail.push_back(0x80);
    while (tail.size() % 64 != 56) tail.push_back(0);
    const uint64_t bits = uint64_t(bytes.size()) * 8;
    for (int i = 0; i < 8; ++i) tail.push_back(static_cast<uint8_t>(bits >> (8 * i)));
    for (size_t at = 0; at < tail.size(); at += 64) md4Block(state, tail.data() + at);
    std::array<uint8_t, 16> out{};
    for (int i = 0; i < 16; ++i) out[size_t(i)] = static_cast<uint8_t>(state[size_t(i / 4)] >> (8 * (i % 4)));
    return out;
}

std::string generatedShaderName(std::string_view mapName, std::string_view text) {
    static constexpr char kHex[] = "0123456789ABCDEF";
    std::string name(mapName);
    name += '/';
    for (uint8_t b : md4Digest(text)) {
        name += kHex[b >> 4];
        name += kHex[b & 15];
    }
    return name;
}

// ---- Shader text ----

namespace {

bool endsWithNoCase(std::string_view s, std::string_view suffix) {
    return s.size() >= suffix.size() && equalsNoCase(s.substr(s.size() - suffix.size()), suffix);
}

std::string withoutExtension(std::string_view name) {
    const size_t slash = name.find_last_of('/');
    const size_t dot = name.find_last_of('.');
    if (dot != std::string_view::npos && (slash == std::string_view::npos || dot > slash)) name = name.substr(0, dot);
    return std::string(name);
}

size_t findNoCase(std::string_view haystack, std::string_view needle) {
    if (needle.empty() || needle.size() > haystack.size()) return std::string_view::npos;
    for (size_t i = 0; i + needle.size() <= haystack.size(); ++i)
        if (equalsNoCase(haystack.substr(i, needle.size()), needle)) return i;
    return std::string_view::npos;
}

}  // namespace

std::optional<std::string> shaderScriptBody(std::string_view scriptText, int nameLine, std::string_view name) {
    Script script(scriptText, "shader script");
    constexpr std::string_view kQ3mapSuffix = ":q3map";
    while (script.next(true)) {
        if (script.line() < nameLine) continue;
        if (script.line() > nameLine) return std::nullopt;
        std::string token = script.token();
        const bool compilerOnly = token.size() > kQ3mapSuffix.size() && endsWithNoCase(token, kQ3mapSuffix);
        if (compilerOnly) token.resize(token.size() - kQ3mapSuffix.size());
        if (!equalsNoCase(withoutExtension(token), withoutExtension(name))) continue;
        if (!script.next(true) || script.token() != "{") return std::nullopt;

        std::string body;
        int depth = 0;
        int lastLine = -1;
        bool hasStages = false;
        auto append = [&](const std::string& t, int line) {
            const bool brace = t == "{" || t == "}";
            if (t == "}") --depth;
            if (brace || line != lastLine) {
                body += '\n';
                body.append(static_cast<size_t>(std::max(0, depth)), '\t');
                lastLine = brace ? -1 : line;  // the token after a brace starts a new line
            } else {
                body += ' ';
            }
            body += t;
            if (t == "{") ++depth;
        };
        append("{", script.line());
        while (depth > 0 && script.next(true)) {
            if (script.token().empty()) continue;
            if (script.token() == "{" && depth == 1) hasStages = true;
            append(script.token(), script.line());
        }
        if (depth > 0) return std::nullopt;  // unterminated: the parser dropped this shader too
        if (compilerOnly && !hasStages) return std::nullopt;
        body += '\n';
        return body;
    }
    return std::nullopt;
}

std::string defaultShaderBody(std::string_view shaderName) {
    return strCat("\n{ // Q3Map2 defaulted\n\t{\n\t\tmap $lightmap\n\t\trgbGen identity\n\t}\n\tq3map_styleMarker\n",
                  "\t{\n\t\tmap ", shaderName, ".tga\n\t\tblendFunc GL_DST_COLOR GL_ZERO\n\t\trgbGen identity\n\t}\n}\n");
}

StyleStageGens styleStageGens(const bsp::Entity* worldspawn, int style) {
    StyleStageGens gens;
    if (worldspawn) {
        if (const std::string* v = worldspawn->find(strCat("_style", style, "rgbgen"))) gens.rgbGen = *v;
        if (const std::string* v = worldspawn->find(strCat("_style", style, "alphagen"))) gens.alphaGen = *v;
    }
    if (gens.rgbGen.empty()) gens.rgbGen = std::string(kDefaultStyleRgbGen);
    return gens;
}

std::string styleStagesText(std::span<const StyleStage> stages, const bsp::Entity* worldspawn, bool depthFuncEqual) {
    std::string text = "\n\t// Q3Map2 custom lightstyle stage(s)\n";
    for (const StyleStage& stage : stages) {
        const StyleStageGens gens = styleStageGens(worldspawn, stage.style);
        text += strCat("\t{\n\t\tmap ", stage.lightmapPath, "\n\t\tblendFunc GL_SRC_ALPHA GL_ONE\n");
        if (depthFuncEqual) text += "\t\tdepthFunc equal\n";
        text += strCat("\t\trgbGen ", gens.rgbGen, " // style ", stage.style, "\n");
        if (!gens.alphaGen.empty()) text += strCat("\t\talphaGen ", gens.alphaGen, " // style ", stage.style, "\n");
        text += "\t\ttcGen lightmap\n\t}\n";
    }
    return text;
}

std::optional<std::string> generatedShaderText(std::string_view body, int styleMarker, std::string_view stages) {
    const std::string_view marker = styleMarker == 2 ? "q3map_styleMarker2" : "q3map_styleMarker";
    const size_t at = findNoCase(body, marker);
    if (at == std::string_view::npos) return std::nullopt;
    return strCat(body.substr(0, at), stages, body.substr(at + marker.size()));
}

std::filesystem::path generatedShaderFilePath(const std::filesystem::path& bspPath) {
    return (bspPath.parent_path() / ".." / "scripts" / ("q3map2_" + bspPath.stem().string() + ".shader"))
        .lexically_normal();
}

std::filesystem::path externalLightmapDir(const std::filesystem::path& bspPath, const std::string& lightmapDir) {
    return lightmapDir.empty() ? bspPath.parent_path() / bspPath.stem() : std::filesystem::path(lightmapDir);
}

// ---- Storing ----

namespace {

constexpr int kMaxStyle = 254;
constexpr size_t kMaxShaderName = 64;  // bsp::Shader::name, NUL included

std::string bspShaderName(const bsp::Shader& s) { return std::string(s.name, strnlen(s.name, sizeof(s.name))); }

// The styles of one block that survive the per-surface limit, as converted bytes.
struct BlockStyle {
    int style = 0;
    std::vector<Rgb8> texels;
    int page = -1;  // index among the styled pages
};

// Original shader text and marker of a BSP shader, as CustomShader sees them.
struct ShaderSource {
    std::string body;
    int styleMarker = 1;
};

ShaderSource shaderSource(const LightContext& ctx, const std::string& bspName) {
    const std::string name = withoutExtension(bspName);
    if (!ctx.shaderTable) return {defaultShaderBody(name), 1};
    const ShaderInfo& info = ctx.shaderTable->find(name);
    if (info.explicitScript && ctx.vfs) {
        if (std::optional<std::vector<uint8_t>> bytes = ctx.vfs->read(info.sourceFile)) {
            const std::string_view text(reinterpret_cast<const char*>(bytes->data()), bytes->size());
            if (std::optional<std::string> body = shaderScriptBody(text, info.sourceLine, info.name))
                return {std::move(*body), info.styleMarker};
        }
        return {defaultShaderBody(info.name), info.styleMarker};
    }
    return {defaultShaderBody(name), info.styleMarker};
}

// Index of a BSP shader of that name (case-insensitive), appended with `flagsFrom`'s flags if new.
int emitShader(bsp::Bsp& bsp, const std::string& name, const bsp::Shader& flagsFrom) {
    for (size_t i = 0; i < bsp.shaders.size(); ++i)
        if (equalsNoCase(bspShaderName(bsp.shaders[i]), name)) return static_cast<int>(i);
    bsp::Shader s{};
    std::strncpy(s.name, name.c_str(), sizeof(s.name) - 1);
    s.surfaceFlags = flagsFrom.surfaceFlags;
    s.contentFlags = flagsFrom.contentFlags;
    bsp.shaders.push_back(s);
    return static_cast<int>(bsp.shaders.size()) - 1;
}

void validate(const LightContext& ctx, std::span<const LightmapBlock> blocks, const PackedLightmaps& packed,
              const StyledLightmap& s) {
    const std::string file = ctx.bspPath.string();
    if (s.block < 0 || static_cast<size_t>(s.block) >= blocks.size() ||
        static_cast<size_t>(s.block) >= packed.placements.size())
        throw CompileError(strCat(file, ": styled lightmap names block ", s.block, " of ", blocks.size()));
    if (s.style < 1 || s.style > kMaxStyle)
        throw CompileError(strCat(file, ": styled lightmap of block ", s.block, " has invalid style ", s.style));
    const LightmapBlock& b = blocks[static_cast<size_t>(s.block)];
    if (s.width != b.width || s.height != b.height || s.color.size() != size_t(s.width) * size_t(s.height))
        throw CompileError(strCat(file, ": styled lightmap of block ", s.block, " is ", s.width, "x", s.height, " with ",
                                  s.color.size(), " luxels, its block is ", b.width, "x", b.height));
    for (int surfaceNum : b.surfaces)
        if (surfaceNum < 0 || static_cast<size_t>(surfaceNum) >= ctx.bsp.surfaces.size())
            throw CompileError(strCat(file, ": lightmap block ", s.block, " names surface ", surfaceNum, " of ",
                                      ctx.bsp.surfaces.size()));
}


constexpr std::string_view kShaderFileHeader = "// Shaders generated by the light stage for ";

// Removes lm_NNNN.tga from `first` on, up to the first missing number (q3map2's clean-up).
void removePagesFrom(const std::filesystem::path& dir, int first) {
    for (int n = first;; ++n) {
        std::error_code ec;
        if (!std::filesystem::remove(dir / externalLightmapName(n), ec)) break;
    }
}

// A run without styled light leaves neither the styled pages nor the generated shaders of an
// earlier run behind (only a shader file this stage wrote is removed).
void removeStaleStyleOutputs(const LightContext& ctx, int firstPage) {
    const std::filesystem::path dir = externalLightmapDir(ctx.bspPath, ctx.options.lightmapDir);
    removePagesFrom(dir, firstPage);
    const std::filesystem::path script = generatedShaderFilePath(ctx.bspPath);
    std::error_code ec;
    if (!std::filesystem::is_regular_file(script, ec)) return;
    const std::string text = readFileText(script);
    if (text.rfind(kShaderFileHeader, 0) == 0) std::filesystem::remove(script, ec);
}


// Per block: its styles that survive the per-surface limit, converted to bytes. A style's light
// given twice is summed; q3map2 sorts lights by style, so the lowest styles take the three slots.
std::map<int, std::vector<BlockStyle>> convertBlockStyles(const LightContext& ctx, std::span<const LightmapBlock> blocks,
                                                          const PackedLightmaps& packed,
                                                          std::vector<StyledLightmap>& styled, Log& log) {
    std::map<int, std::map<int, std::vector<Vec3>>> byBlock;
    for (StyledLightmap& s : styled) {
        std::vector<Vec3>& sum = byBlock[s.block][s.style];
        if (sum.empty()) {
            sum = std::move(s.color);
        } else {
            for (size_t i = 0; i < sum.size(); ++i) sum[i] += s.color[i];
        }
    }

    std::map<int, std::vector<BlockStyle>> out;
    for (auto& [blockIndex, styles] : byBlock) {
        const LightmapBlock& block = blocks[size_t(blockIndex)];
        const BlockPlacement& place = packed.placements[size_t(blockIndex)];
        if (place.solid || place.twinOf >= 0 || place.page < 0 || place.width != block.width ||
            place.height != block.height) {
            log.warning(strCat(ctx.bspPath.string(), ": lightmap block ", blockIndex,
                               " is stored solid or shared with another block: its styled light is not stored"));
            continue;
        }
        float brightness = 1;
        if (!block.surfaces.empty()) {
            const int shaderNum = ctx.bsp.surfaces[size_t(block.surfaces[0])].shaderNum;
            if (shaderNum >= 0 && size_t(shaderNum) < ctx.shaders.shaders.size())
                brightness = ctx.shaders.shaders[size_t(shaderNum)].lightmapBrightness;
        }
        std::vector<int> dropped;
        std::vector<BlockStyle> kept;
        for (auto& [style, color] : styles) {
            if (kept.size() + 1 >= size_t(kMaxSurfaceStyles)) {
                dropped.push_back(style);
                continue;
            }
            BlockStyle bs;
            bs.style = style;
            bs.texels.resize(color.size());
            bool lit = false;
            for (size_t i = 0; i < color.size(); ++i) {
                bs.texels[i] = colorToBytes(color[i], brightness, ctx.color);  // no minlight: style 0 only
                const bool used = block.used.empty() || block.used[i];
                lit = lit || (used && (bs.texels[i][0] | bs.texels[i][1] | bs.texels[i][2]) != 0);
            }
            if (lit) kept.push_back(std::move(bs));  // an all-black stage would add nothing
        }
        if (!dropped.empty()) {
            std::string list;
            for (int s : dropped) list += strCat(list.empty() ? "" : " ", s);
            log.warning(strCat("Hit per-surface style limit (", kMaxSurfaceStyles, ") on the lightmap of surface ",
                               block.surfaces.empty() ? -1 : block.surfaces[0], ": light of style ", list,
                               " dropped"));
        }
        if (!kept.empty()) out.emplace(blockIndex, std::move(kept));
    }
    return out;
}

// One styled page per (style-0 page, style), in that order; sets BlockStyle::page and draws every
// styled block at its style-0 block's texels.
std::vector<std::vector<uint8_t>> drawStyledPages(std::map<int, std::vector<BlockStyle>>& blockStyles,
                                                  std::span<const LightmapBlock> blocks,
                                                  const PackedLightmaps& packed) {
    std::map<std::pair<int, int>, int> pageOf;
    for (auto& [blockIndex, styles] : blockStyles)
        for (BlockStyle& bs : styles) pageOf.emplace(std::pair{packed.placements[size_t(blockIndex)].page, bs.style}, 0);
    int next = 0;
    for (auto& [key, page] : pageOf) page = next++;

    const size_t pageSize = size_t(packed.pageSize);
    std::vector<std::vector<uint8_t>> pages(pageOf.size(), std::vector<uint8_t>(pageSize * pageSize * 3, 0));
    for (auto& [blockIndex, styles] : blockStyles) {
        const LightmapBlock& block = blocks[size_t(blockIndex)];
        const BlockPlacement& place = packed.placements[size_t(blockIndex)];
        for (BlockStyle& bs : styles) {
            bs.page = pageOf.at({place.page, bs.style});
            std::vector<uint8_t>& rgb = pages[size_t(bs.page)];
            for (int y = 0; y < block.height; ++y)
                for (int x = 0; x < block.width; ++x) {
                    const size_t i = size_t(y) * size_t(block.width) + size_t(x);
                    if (!block.used.empty() && !block.used[i]) continue;  // may belong to an overlapping block
                    const size_t at = ((size_t(place.y) + size_t(y)) * pageSize + size_t(place.x) + size_t(x)) * 3;
                    std::copy(bs.texels[i].begin(), bs.texels[i].end(), rgb.begin() + std::ptrdiff_t(at));
                }
        }
    }
    return pages;
}

struct GeneratedShaders {
    std::vector<std::pair<std::string, std::string>> shaders;  // name, text; in order of first use
    size_t remappedSurfaces = 0;
};

// Remaps every surface of a styled block to "<map>/<MD4>" (one per original shader and list of
// (style, page)), adding the shader records to the BSP.
GeneratedShaders remapStyledSurfaces(LightContext& ctx, std::span<const LightmapBlock> blocks,
                                     const std::map<int, std::vector<BlockStyle>>& blockStyles,
                                     const std::string& mapName, int firstPage, Log& log) {
    const bsp::Entity* worldspawn = ctx.entities.empty() ? nullptr : &ctx.entities[0];
    GeneratedShaders out;
    std::set<std::string> written;
    std::map<std::pair<int, std::vector<std::pair<int, int>>>, int> remapOf;
    std::set<int> warnedNoMarker;
    for (const auto& [blockIndex, styles] : blockStyles) {
        std::vector<std::pair<int, int>> key;
        std::vector<StyleStage> stages;
        for (const BlockStyle& bs : styles) {
            key.emplace_back(bs.style, bs.page);
            stages.push_back({bs.style, strCat("maps/", mapName, "/", externalLightmapName(firstPage + bs.page))});
        }
        for (int surfaceNum : blocks[size_t(blockIndex)].surfaces) {
            bsp::Surface& surface = ctx.bsp.surfaces[size_t(surfaceNum)];
            const int original = surface.shaderNum;
            if (original < 0 || size_t(original) >= ctx.bsp.shaders.size()) continue;
            auto found = remapOf.find({original, key});
            if (found == remapOf.end()) {
                const std::string originalName = bspShaderName(ctx.bsp.shaders[size_t(original)]);
                const ShaderSource source = shaderSource(ctx, originalName);
                const std::string stageText = styleStagesText(stages, worldspawn, source.styleMarker == 2);
                const std::optional<std::string> text = generatedShaderText(source.body, source.styleMarker, stageText);
                int target = original;
                if (!text) {
                    if (warnedNoMarker.insert(original).second)
                        log.warning(strCat("shader ", originalName,
                                           " has no q3map_styleMarker: light styles on its surfaces are not drawn"));
                } else {
                    const std::string name = generatedShaderName(mapName, *text);
                    if (written.insert(name).second) out.shaders.emplace_back(name, *text);
                    const bsp::Shader flags = ctx.bsp.shaders[size_t(original)];
                    target = emitShader(ctx.bsp, name, flags);
                }
                found = remapOf.emplace(std::pair{original, key}, target).first;
            }
            if (found->second != original) ++out.remappedSurfaces;
            surface.shaderNum = found->second;
        }
    }
    return out;
}

void createFolder(const std::filesystem::path& dir) {
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec) throw FileError(strCat(dir.string(), ": cannot create the folder: ", ec.message()));
}

}  // namespace

void storeStyledLightmaps(LightContext& ctx, std::span<const LightmapBlock> blocks, const PackedLightmaps& packed,
                          std::vector<StyledLightmap> styled, Log& log) {
    const int firstPage = packed.needsExternalFiles() ? static_cast<int>(packed.pages.size()) : 0;
    const std::string mapName = ctx.bspPath.stem().string();
    if (!styled.empty() && mapName.size() + 1 + 32 >= kMaxShaderName)
        throw CompileError(strCat(ctx.bspPath.string(), ": map name '", mapName,
                                  "' is too long for generated style shader names (at most 30 characters)"));
    for (const StyledLightmap& s : styled) validate(ctx, blocks, packed, s);

    std::map<int, std::vector<BlockStyle>> blockStyles = convertBlockStyles(ctx, blocks, packed, styled, log);
    if (blockStyles.empty()) {
        removeStaleStyleOutputs(ctx, firstPage);
        return;
    }

    const std::vector<std::vector<uint8_t>> pages = drawStyledPages(blockStyles, blocks, packed);
    const std::filesystem::path dir = externalLightmapDir(ctx.bspPath, ctx.options.lightmapDir);
    createFolder(dir);
    for (size_t p = 0; p < pages.size(); ++p)
        writeFileAtomic(dir / externalLightmapName(firstPage + int(p)),
                        encodeLightmapTga(pages[p], packed.pageSize, packed.pageSize));
    removePagesFrom(dir, firstPage + int(pages.size()));  // pages of an earlier compile that nothing uses

    const GeneratedShaders generated = remapStyledSurfaces(ctx, blocks, blockStyles, mapName, firstPage, log);
    const std::filesystem::path script = generatedShaderFilePath(ctx.bspPath);
    if (generated.shaders.empty()) {
        removeStaleStyleOutputs(ctx, firstPage + int(pages.size()));
    } else {
        std::string file = strCat(kShaderFileHeader, mapName, ".bsp (light styles); replaced by every -light run.\n\n");
        for (const auto& [name, text] : generated.shaders) file += strCat(name, text, "\n");
        createFolder(script.parent_path());
        writeFileAtomic(script, file);
    }
    log.info(strCat(pages.size(), " styled lightmap pages written to ", dir.string(), ", ", generated.shaders.size(),
                    " style shaders to ", script.string(), " (", generated.remappedSurfaces, " surfaces)"));
}

}  // namespace q3::light
