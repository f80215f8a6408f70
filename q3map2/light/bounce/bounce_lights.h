// Radiosity emitters for -bounce (q3map2 RadCreateDiffuseLights): every lit surface is chopped into
// pieces, and each piece becomes an area light coloured by the light it received in the previous
// pass times its own texture colour. Pure: surfaces in, lights out, in a fixed order.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "lights.h"
#include "vec3.h"

namespace q3::light {

// A vertex of an emitting surface: world position, unit normal, texture st, and lightmap
// coordinate in BSP luxels of the surface's lightmap (0..width, 0..height).
struct BounceVertex {
    Vec3 xyz;
    Vec3 normal;
    std::array<float, 2> st{};
    std::array<float, 2> lm{};
};

// One lit surface of one style, ready to emit: its triangles and this pass's light on it.
struct BounceSurface {
    int surfaceNum = -1;
    const LightingShader* shader = nullptr;  // sky/nodraw/trans/autosprite/fog/twoSided, subdivide
    float shaderBounceScale = 1;             // q3map_bounceScale (ShaderInfo::bounceScale)
    const LightImage* image = nullptr;       // texture for the colour; nullptr = use `averageColor`
    Vec3 averageColor{1, 1, 1};              // 0..1
    std::vector<BounceVertex> verts;
    std::vector<uint32_t> triangles;  // index triples into verts
    int style = 0;
    int width = 0, height = 0;  // lightmap size in BSP luxels; 0 = vertex lit (`vertexLight`)
    std::vector<Vec3> luxels;   // this pass's light, legacy units (0..255+), row-major
    std::vector<uint8_t> lit;   // per luxel: 0 = unmapped/unlit (skipped); empty = all lit
    // Vertex-lit surfaces (no lightmap): this pass's light per vertex of `verts`, legacy units.
    std::vector<Vec3> vertexLight;
};

struct BounceSettings {
    float bounceScale = 0.25f;  // -bouncescale
    float colorRatio = 1;       // -bouncecolorratio (0 = grey texture, 1 = full texture colour)
    float falloffTolerance = 1;
    bool fast = false;      // -fastbounce or -fast
    bool noStyles = false;  // -nostyles: every emitter lights style 0
};

// q3map2's constants of the radiosity emitters (light_bounce.cpp).
inline constexpr float kBounceDefaultSubdivide = 256;  // diffuseSubdivide
inline constexpr float kBounceMinSubdivide = 64;       // minDiffuseSubdivide
inline constexpr float kBounceMaxGradient = 0.75f;     // RADIOSITY_MAX_GRADIENT
inline constexpr float kBounceValue = 500;             // RADIOSITY_VALUE
inline constexpr float kBounceMinColor = 0.0001f;      // RADIOSITY_MIN
inline constexpr float kBounceClipEpsilon = 0.125f;    // RADIOSITY_CLIP_EPSILON
inline constexpr int kBounceMaxSamples = 150;          // MAX_SAMPLES of RadSample

// Whether a surface of this shader re-emits light at all: a positive q3map_bounceScale and none of
// sky, autosprite, nodraw or surfaceparm trans.
bool surfaceBounces(const LightingShader* shader, float shaderBounceScale);

// A point of an emitter piece: the surface's vertex attributes interpolated at the cuts, with the
// vertex light of a vertex-lit surface.
struct BouncePieceVertex {
    BounceVertex vertex;
    Vec3 light;  // legacy units; read only without a lightmap
};

// Average colour (0..1 per channel, not normalised) and per-channel gradient ((max - min) * max)
// of a winding piece of `surface`, sampled like q3map2 RadSample. `samples` is how many lit
// samples were taken (0: colour and gradient are zero).
struct BounceSample {
    Vec3 color;
    Vec3 gradient;
    int samples = 0;
};
BounceSample sampleBouncePiece(const BounceSurface& surface, std::span<const BouncePieceVertex> winding,
                               float colorRatio);

// The emitters of one bounce pass, in surface order then piece order (deterministic; surfaces
// are processed in parallel). Throws CompileError when a surface's luxel arrays do not match its
// lightmap size or a triangle index is out of range.
std::vector<Light> createBounceLights(std::span<const BounceSurface> surfaces, const BounceSettings& settings);

// q3map2 -dump: the emitters as a .map text of light entities (classname light, light = int(add),
// origin %.0f, _color %.3f), to be written as <map>_bounce_NNN.map by the caller.
std::string bounceLightsAsMap(std::span<const Light> lights);

}  // namespace q3::light
