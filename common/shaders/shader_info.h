// What the compiler knows about one shader: its surfaceparms as Quake 3 content/surface flags plus
// every q3map_* directive that affects lighting, and the shader table that finds shaders by name.
//
// Behaviour follows q3map2 (shaders.cpp / game_quake3.h): a texture without a script is an
// "implicit" shader with default flags (solid) whose only image is the texture itself; among
// duplicate definitions the first one loaded wins (q3map2 searches its shader list from the start).
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "vec3.h"

namespace q3 {

// Quake 3 content flags (BSP brush and shader lumps), values of game_quake3.h / surfaceflags.h.
namespace contents {
inline constexpr uint32_t Solid = 0x1;
inline constexpr uint32_t Lava = 0x8;
inline constexpr uint32_t Slime = 0x10;
inline constexpr uint32_t Water = 0x20;
inline constexpr uint32_t Fog = 0x40;
inline constexpr uint32_t AreaPortal = 0x8000;
inline constexpr uint32_t PlayerClip = 0x10000;
inline constexpr uint32_t MonsterClip = 0x20000;
inline constexpr uint32_t Teleporter = 0x40000;
inline constexpr uint32_t JumpPad = 0x80000;
inline constexpr uint32_t ClusterPortal = 0x100000;
inline constexpr uint32_t DoNotEnter = 0x200000;
inline constexpr uint32_t BotClip = 0x400000;
inline constexpr uint32_t Origin = 0x1000000;
inline constexpr uint32_t Body = 0x2000000;
inline constexpr uint32_t Corpse = 0x4000000;
inline constexpr uint32_t Detail = 0x8000000;
inline constexpr uint32_t Structural = 0x10000000;
inline constexpr uint32_t Translucent = 0x20000000;
inline constexpr uint32_t Trigger = 0x40000000;
inline constexpr uint32_t NoDrop = 0x80000000;
}  // namespace contents

// Quake 3 surface flags.
namespace surfaceflags {
inline constexpr uint32_t NoDamage = 0x1;
inline constexpr uint32_t Slick = 0x2;
inline constexpr uint32_t Sky = 0x4;
inline constexpr uint32_t Ladder = 0x8;
inline constexpr uint32_t NoImpact = 0x10;
inline constexpr uint32_t NoMarks = 0x20;
inline constexpr uint32_t Flesh = 0x40;
inline constexpr uint32_t NoDraw = 0x80;
inline constexpr uint32_t Hint = 0x100;
inline constexpr uint32_t Skip = 0x200;
inline constexpr uint32_t NoLightmap = 0x400;
inline constexpr uint32_t PointLight = 0x800;
inline constexpr uint32_t MetalSteps = 0x1000;
inline constexpr uint32_t NoSteps = 0x2000;
inline constexpr uint32_t NonSolid = 0x4000;
inline constexpr uint32_t LightFilter = 0x8000;
inline constexpr uint32_t AlphaShadow = 0x10000;
inline constexpr uint32_t NoDLight = 0x20000;
inline constexpr uint32_t Dust = 0x40000;
inline constexpr uint32_t NoOb = 0x80000;  // quake3 game profile: bots' obstacle marker off
inline constexpr uint32_t VertexLit = PointLight | NoLightmap;
}  // namespace surfaceflags

// Compiler-side classification (q3map2's C_* flags); never written to a BSP.
namespace compileflags {
inline constexpr uint32_t Solid = 0x1;
inline constexpr uint32_t Translucent = 0x2;
inline constexpr uint32_t Structural = 0x4;
inline constexpr uint32_t Hint = 0x8;
inline constexpr uint32_t NoDraw = 0x10;
inline constexpr uint32_t LightGrid = 0x20;
inline constexpr uint32_t AlphaShadow = 0x40;
inline constexpr uint32_t LightFilter = 0x80;
inline constexpr uint32_t VertexLit = 0x100;
inline constexpr uint32_t Liquid = 0x200;
inline constexpr uint32_t Fog = 0x400;
inline constexpr uint32_t Sky = 0x800;
inline constexpr uint32_t Origin = 0x1000;
inline constexpr uint32_t AreaPortal = 0x2000;
inline constexpr uint32_t AntiPortal = 0x4000;
inline constexpr uint32_t Skip = 0x8000;
inline constexpr uint32_t NoMarks = 0x10000;
inline constexpr uint32_t Ob = 0x20000;  // surfaceparm ob: exempt from -noob
inline constexpr uint32_t Detail = 0x8000000;
}  // namespace compileflags

// One row of the surfaceparm table: flags to clear, then flags to set.
struct SurfaceParm {
    std::string_view name;
    uint32_t contents = 0, contentsClear = 0;
    uint32_t surface = 0, surfaceClear = 0;
    uint32_t compile = 0, compileClear = 0;
};

// The Quake 3 surfaceparm (case-insensitive) or nullptr when unknown. "default" is the row that
// resets a shader to solid.
const SurfaceParm* findSurfaceParm(std::string_view name);

struct ShaderInfo;
void applySurfaceParm(const SurfaceParm& parm, ShaderInfo& shader);
// False (shader unchanged) when the name is not a surfaceparm.
bool applySurfaceParm(std::string_view name, ShaderInfo& shader);

// q3map_sun / q3map_sunExt / sun.
struct ShaderSun {
    Vec3 color{1, 1, 1};        // normalised: largest component 1 (all zero gives white)
    float intensity = 0;        // as written (q3map2 "photons")
    float yawDegrees = 0;       // as written: 0 = east (+x), 90 = north (+y)
    float elevationDegrees = 0; // as written: 0 = horizon, 90 = straight up
    Vec3 direction{0, 0, 1};    // unit vector from the scene towards the sun
    float devianceDegrees = 0;  // q3map_sunExt angular jitter
    int samples = 1;            // q3map_sunExt sample count
    int style = 0;              // q3map_lightStyle in effect when the sun was declared
    float filterRadius = 0;     // q3map_lightmapFilterRadius "other" value in effect then
};

// q3map_skyLight value iterations [horizonMin horizonMax sampleColor].
struct ShaderSkyLight {
    float value = 0;      // clamped to >= 0
    int iterations = 2;   // clamped to >= 2
    int horizonMin = 0;   // degrees, clamped to -90..90
    int horizonMax = 90;  // degrees, clamped to -90..90
    bool sampleColor = true;  // colour the suns from the skyParms box images
};

// q3map_floodLight r g b distance intensity directionScale.
struct ShaderFloodLight {
    Vec3 color{1, 1, 1};  // normalised like sun colours
    float distance = 0;
    float intensity = 0;
    float directionScale = 0;
};

// q3map_foliage <model> <scale> <density> <odds> <inverseAlpha>: copies of a model scattered over
// the surface's upward-facing triangles, one chance per piece no longer than `density`.
struct ShaderFoliage {
    std::string model;
    float scale = 1;
    float density = 0;   // longest edge of the pieces a triangle is cut into
    float odds = 0;      // chance of a copy per piece, times the vertex alpha
    int inverseAlpha = 0;  // 0: alpha as is, 1: inverted, 2: ignored
};

// One step of q3map_colorGen / colorMod / rgbGen / rgbMod / alphaGen / alphaMod (q3map2's colorMod
// list): -bsp scales and offsets the vertex colour of the shader's surfaces, c' = mult * c + add,
// clamped to 0..255. The dot products use the vertex normal and `vector`; the Scale forms then
// map [lo, hi] to [0, 1].
struct ShaderColorMod {
    enum class Kind : uint8_t {
        None,    // an unknown method: changes nothing
        Volume,  // marks brushes whose volume applies the shader's other steps to vertexes inside
        ColorSet, AlphaSet, ColorScale, AlphaScale,
        ColorDotProduct, AlphaDotProduct, ColorDotProductScale, AlphaDotProductScale,
        ColorDotProduct2, AlphaDotProduct2, ColorDotProduct2Scale, AlphaDotProduct2Scale,
    };
    Kind kind = Kind::Volume;
    Vec3 vector;       // set / scale colour, or the dot product's vector
    float value = 0;   // alpha set / scale
    float lo = 0, hi = 1;  // dotProductScale range
};

struct ShaderInfo {
    std::string name;            // as written in the script (or the texture name), no extension
    bool explicitScript = false; // false: implicit shader made up for a texture without a script
    std::string sourceFile;      // script file that defined it (empty when implicit)
    int sourceLine = 0;

    uint32_t contentFlags = contents::Solid;
    uint32_t surfaceFlags = 0;
    uint32_t compileFlags = compileflags::Solid;

    // Lights emitted.
    std::vector<ShaderSun> suns;
    std::vector<ShaderSkyLight> skyLights;
    float surfaceLight = 0;                // q3map_surfacelight
    std::optional<Vec3> lightRGB;          // q3map_lightRGB, normalised (overrides the image colour)
    int lightSubdivide = 0;                // q3map_lightSubdivide; 0 = the light stage's default
    int lightStyle = 0;                    // q3map_lightStyle (0..255; 255 = none)
    float backsplashFraction = 0.05f;      // q3map_backsplash percent / 100
    float backsplashDistance = 23;         // q3map_backsplash distance
    bool backsplashSet = false;            // true when q3map_backsplash was written
    float bounceScale = 1;                 // q3map_bounce / q3map_bounceScale
    std::optional<ShaderFloodLight> floodLight;
    bool noFast = false;                   // q3map_noFast
    bool autosprite = false;               // deformVertexes autosprite(2): lights become point lights

    // Lightmap and vertex lighting.
    int lightmapSampleSize = 0;            // q3map_lightmapSampleSize; 0 = not set
    float lightmapSampleOffset = 1;        // q3map_lightmapSampleOffset
    float lightmapFilterRadius = 0;        // q3map_lightmapFilterRadius first value (this surface)
    float lightFilterRadius = 0;           // q3map_lightmapFilterRadius second value (its lights)
    int lightmapAxis = -1;                 // q3map_lightmapAxis: 0 x, 1 y, 2 z, -1 not forced
    int lightmapWidth = 0;                 // q3map_lightmapSize; 0 = the global size
    int lightmapHeight = 0;
    float lightmapBrightness = 1;          // product of q3map_lightmapBrightness/Gamma factors
    bool lightmapMergable = false;         // q3map_lightmapMergable
    bool nonplanar = false;                // q3map_nonplanar
    bool forceMeta = false;                // q3map_forceMeta
    bool indexed = false;                  // q3map_indexed / q3map_terrain: layered by an entity's _indexmap
    bool legacyTerrain = false;            // q3map_terrain: without q3map_tcGen, st from x and y
    bool clipModel = false;                // q3map_clipModel: misc_models with it get clip brushes
    float shadeAngleDegrees = 0;           // q3map_shadeAngle; 0 = no phong shading
    float vertexScale = 1;                 // product of q3map_vertexScale factors
    bool noVertexLight = false;            // q3map_noVertexLight
    bool forceSunlight = false;            // q3map_forceSunlight
    bool splotchFix = false;               // q3map_splotchFix
    bool noDirty = false;                  // q3map_noDirty
    int styleMarker = 0;                   // q3map_styleMarker = 1, q3map_styleMarker2 = 2
    bool twoSided = false;                 // cull none / disable / twosided

    // Images, as the script spells them: loading drops one extension and tries .tga, .png, .jpg
    // (q3map2's ImageLoad), so "x.blend.tga" is x.blend's image, not x's.
    // The light image as q3map2 derives it, in script order: q3map_lightImage (always wins);
    // skyParms sets <env>_up while no light image is known; the first stage image
    // (map/clampMap/animMap first frame, not $lightmap or *white) is taken only while neither a
    // light nor an editor image is known.
    std::string lightImage;
    std::string editorImage;      // qer_editorImage
    std::string normalImage;      // q3map_normalImage
    std::string firstStageImage;  // first stage image whatever came before it
    std::string skyParmsEnv;      // skyParms outer box name; empty for "-" or "full"
    bool hasStages = false;

    // q3map_deprecateShader: look-ups of this shader continue with that one.
    std::string deprecatedBy;

    // What -bsp reads besides the flags: how brush faces are textured, cut and fogged.
    float tessSize = 0;                 // tessSize / q3map_tessSize: faces cut on this grid; 0 = never
    bool fogParms = false;              // fogParms: brushes of this shader are fog volumes
    std::optional<Vec3> fogDir;         // q3map_fogDir: the fog's visible side faces against it
    bool globalTexture = false;         // q3map_globalTexture: no texture shift reduction or bias
    bool noClip = false;                // q3map_noClip: faces keep their whole winding
    bool noTJunc = false;               // q3map_notjunc
    bool noFog = false;                 // q3map_noFog
    bool polygonOffset = false;         // polygonOffset: never culled as hidden
    bool autosprite2 = false;           // deformVertexes autosprite2
    bool invert = false;                // q3map_invert: faces flipped
    float vertexOffset = 0;             // q3map_offset: vertices pushed along their normal
    int textureWidth = 0;               // q3map_textureSize; 0 = the image's size
    int textureHeight = 0;
    std::string implicitImage;          // implicitMap / implicitMask / implicitBlend image
    bool tcGen = false;                 // q3map_tcGen vector / ivector: st = (dot(s, p), dot(t, p))
    Vec3 tcGenVectors[2];
    std::string flareShader;            // q3map_flare / q3map_flareShader: flares of this surface (-flares)
    std::string backShader;             // q3map_backShader: a flipped copy with this shader
    std::string cloneShader;            // q3map_cloneShader: a copy with this shader
    std::string remapShader;            // q3map_remapShader: the BSP names this shader so instead
    std::vector<ShaderFoliage> foliage;  // q3map_foliage, in script order
    // q3map_tcMod translate/scale/rotate, composed in script order: s' = m[0] . (s, t, 1),
    // t' = m[1] . (s, t, 1); the identity when the shader has none.
    std::array<std::array<float, 3>, 3> tcMod{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
    std::vector<ShaderColorMod> colorMods;  // q3map_*Gen / q3map_*Mod steps, in script order

    // Brushes of this shader are colorMod volumes (its first colorMod step is `volume`).
    bool isColorModVolume() const { return !colorMods.empty() && colorMods.front().kind == ShaderColorMod::Kind::Volume; }
    bool isSky() const { return (compileFlags & compileflags::Sky) != 0; }
    bool isTranslucent() const { return (compileFlags & compileflags::Translucent) != 0; }
    bool isNoDraw() const { return (compileFlags & compileflags::NoDraw) != 0; }
    bool isVertexLit() const { return (compileFlags & compileflags::VertexLit) != 0; }
    bool isAlphaShadow() const { return (compileFlags & compileflags::AlphaShadow) != 0; }
    bool isLightFilter() const { return (compileFlags & compileflags::LightFilter) != 0; }
    bool isFog() const { return (compileFlags & compileflags::Fog) != 0; }

    // Images whose size scales brush face texture coordinates, in q3map2's order: editor image,
    // the shader name, the implicit image, the light image (the first that loads wins).
    std::vector<std::string> textureImageCandidates() const;
    // Images to try, in order, for the light colour and alpha/filter look-ups (q3map2's
    // LoadShaderImages): lightImage, then the editor image, then the shader name itself; the first
    // one that loads is the light image. Empty for nodraw shaders (q3map2 uses its white default).
    std::vector<std::string> lightImageCandidates() const;
};

// Default ShaderInfo for a texture without a script.
ShaderInfo makeImplicitShader(std::string_view textureName);

// Canonical form used for look-ups: lower case, '\' -> '/', extension removed.
std::string shaderKey(std::string_view name);

// Shaders by name. Filled once by the loader (single thread), then read concurrently.
class ShaderTable {
public:
    ShaderTable() = default;
    ShaderTable(ShaderTable&&) noexcept;
    ShaderTable& operator=(ShaderTable&&) noexcept;

    // Adds a script shader. Returns false, keeping the earlier one, when the name is already defined
    // (the first definition wins).
    bool add(ShaderInfo shader);
    // The same for a shader already on the heap whose shaderKey is known (made beside others).
    bool add(std::unique_ptr<ShaderInfo> shader, std::string key);
    void reserve(size_t shaders);

    // The script shader of that name (case-insensitive, extension ignored) or nullptr.
    const ShaderInfo* findExplicit(std::string_view name) const;
    // The script shader, or an implicit one made up (and kept) for the texture, named by
    // shaderKey(name) so that the result never depends on which spelling asked first. Follows
    // q3map_deprecateShader links (at most 16, as q3map2). Thread-safe; the reference stays valid
    // as long as the table.
    const ShaderInfo& find(std::string_view name) const;

    // Script shaders in the order they were added.
    const std::vector<std::unique_ptr<ShaderInfo>>& shaders() const { return shaders_; }
    size_t size() const { return shaders_.size(); }
    // How many later definitions were ignored because the name was already defined.
    int duplicateCount() const { return duplicates_; }

    // Script files loaded, in load order, and whether each was named by a shaderlist.txt.
    struct SourceFile {
        std::string path;       // e.g. "scripts/base_light.shader"
        bool inShaderList = false;
        int shaderCount = 0;
    };
    const std::vector<SourceFile>& files() const { return files_; }
    void addFile(SourceFile file) { files_.push_back(std::move(file)); }
    // True when a shaderlist.txt was found while loading.
    bool hasShaderList() const { return hasShaderList_; }
    void setHasShaderList(bool on) { hasShaderList_ = on; }

private:
    std::vector<std::unique_ptr<ShaderInfo>> shaders_;
    std::unordered_map<std::string, const ShaderInfo*> byName_;  // by shaderKey
    int duplicates_ = 0;
    std::vector<SourceFile> files_;
    bool hasShaderList_ = false;

    mutable std::mutex implicitMutex_;
    mutable std::map<std::string, std::unique_ptr<ShaderInfo>, std::less<>> implicit_;
};

}  // namespace q3
