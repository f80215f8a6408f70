// Light styles for Quake 3 IBSP maps. An IBSP surface holds a single lightmap, so the light of
// switchable styles (1..254) goes to external pages maps/<map>/lm_NNNN.tga, drawn by extra shader
// stages that the compiler generates: each lit surface is remapped to a shader
// "<map>/<MD4 of its text>" whose text is the original shader with its q3map_styleMarker replaced
// by one additive `tcGen lightmap` stage per style, all written to scripts/q3map2_<map>.shader.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "bspfile.h"
#include "lightmap_pack.h"
#include "vec3.h"

namespace q3 {
class Log;
}

namespace q3::light {

struct LightContext;

// Styles a lightmapped surface can carry: style 0 plus three others (q3map2 MAX_LIGHTMAPS).
inline constexpr int kMaxSurfaceStyles = 4;
// rgbGen of a generated style stage when worldspawn has no _style<N>rgbgen.
inline constexpr std::string_view kDefaultStyleRgbGen = "wave noise 0.5 1 0 5.37";

// Light of one style (1..254) on one raw lightmap: same size and luxel grid as its style-0 block.
struct StyledLightmap {
    int block = -1;            // index of the style-0 LightmapBlock in `blocks` / packed.placements
    int style = 0;
    int width = 0, height = 0; // BSP luxels (block.width x block.height)
    std::vector<Vec3> color;   // linear light, row-major, same scale as style 0 before colorToBytes
};

// Writes the styled lightmaps of an IBSP map: external pages maps/<map>/lm_NNNN.tga numbered after
// the style-0 pages (each styled block at the same texel position as its style-0 block, so that
// `tcGen lightmap` addresses both), the generated shader file, and remaps the surfaces of those
// blocks to generated shaders added to ctx.bsp.shaders. Called after applyPackedLightmaps.
// `blocks`/`packed` are the style-0 blocks and their placement (lightmap_pack.h).
//
// Call it on every IBSP -light run, even with no styled light: a run without any removes the
// styled pages and the generated shader file that an earlier run left.
// Details: external style-0 pages must already be on disk (writeExternalLightmaps removes the files
// numbered after its own pages); a block keeps its three lowest styles ("Hit per-surface style
// limit" warning for the others); a styled lightmap that converts to all-black bytes is dropped; a
// script shader without q3map_styleMarker[2] keeps its surfaces (q3map2 behaviour, with a warning).
void storeStyledLightmaps(LightContext& ctx, std::span<const LightmapBlock> blocks,
                          const PackedLightmaps& packed, std::vector<StyledLightmap> styled, Log& log);

// ---- Building blocks (pure functions) ----

// MD4 digest (RFC 1320) of `bytes`; q3map2 names generated shaders by the MD4 of their text.
std::array<uint8_t, 16> md4Digest(std::string_view bytes);
// "<mapName>/" followed by the 32 upper-case hex digits of md4Digest(text).
std::string generatedShaderName(std::string_view mapName, std::string_view text);

// The body of shader `name` (defined on line `nameLine` of `scriptText`) as q3map2 keeps it for
// generated shaders: every token re-emitted, tokens of one line joined by spaces, each line on a
// new line indented by its brace depth, braces on lines of their own, then a final newline
// ("\n{\n\tq3map_styleMarker\n\t{\n\t\tmap $lightmap\n\t}\n}\n"). nullopt when the shader is not
// found there, or when it is a stageless "name:q3map" variant (q3map2 keeps no text for those).
std::optional<std::string> shaderScriptBody(std::string_view scriptText, int nameLine, std::string_view name);
// The text q3map2 assumes for a shader without a script: a lightmap stage, the style marker, then
// the texture `shaderName`.tga multiplied in.
std::string defaultShaderBody(std::string_view shaderName);

// One generated stage: the styled page (as the engine loads it, "maps/<map>/lm_0003.tga") of one style.
struct StyleStage {
    int style = 0;
    std::string lightmapPath;
};
// rgbGen / alphaGen of the stages of `style`: worldspawn _style<N>rgbgen (default
// kDefaultStyleRgbGen when missing or empty) and _style<N>alphagen (none when missing or empty).
struct StyleStageGens {
    std::string rgbGen;
    std::string alphaGen;
};
StyleStageGens styleStageGens(const bsp::Entity* worldspawn, int style);
// The text that replaces the style marker: a comment line, then per stage `map <page>`,
// `blendFunc GL_SRC_ALPHA GL_ONE`, `depthFunc equal` (q3map_styleMarker2), rgbGen, alphaGen,
// `tcGen lightmap`.
std::string styleStagesText(std::span<const StyleStage> stages, const bsp::Entity* worldspawn, bool depthFuncEqual);
// `body` with its first q3map_styleMarker (styleMarker 0/1) or q3map_styleMarker2 (2), compared
// without case, replaced by `stages`; nullopt when the marker is absent.
std::optional<std::string> generatedShaderText(std::string_view body, int styleMarker, std::string_view stages);

// Where q3map2 writes generated shaders of a map: <bsp folder>/../scripts/q3map2_<map>.shader.
std::filesystem::path generatedShaderFilePath(const std::filesystem::path& bspPath);
// Folder of the external lightmap pages: -lightmapdir, else the BSP path without extension.
std::filesystem::path externalLightmapDir(const std::filesystem::path& bspPath, const std::string& lightmapDir);

}  // namespace q3::light
