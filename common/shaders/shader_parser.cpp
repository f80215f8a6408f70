#include "shader_parser.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <unordered_map>

#include "script.h"
#include "shader_math.h"

namespace q3 {
namespace {

// q3map_* directives q3map2 understands that no stage of this compiler uses yet. They are
// recognised so that they are not mistaken for q3map_<surfaceparm>; their arguments are skipped
// with the rest of the line.
constexpr std::array<std::string_view, 7> kIgnoredQ3mapDirectives = {
    "q3map_surfacemodel", "q3map_fur",           "q3map_patchShadows",
    "q3map_vertexShadows", "q3map_noVertexShadows", "q3map_clipModel", "q3map_material",
};

bool isIgnoredQ3mapDirective(std::string_view token) {
    return std::any_of(kIgnoredQ3mapDirectives.begin(), kIgnoredQ3mapDirectives.end(),
                       [&](std::string_view d) { return equalsNoCase(d, token); });
}

bool startsWithNoCase(std::string_view s, std::string_view prefix) {
    return s.size() >= prefix.size() && equalsNoCase(s.substr(0, prefix.size()), prefix);
}


// Reads one shader script. Holds the tokenizer and the shader being filled; no state survives a
// call to parseShaderScript.
class ShaderScriptParser {
public:
    ShaderScriptParser(std::string_view text, const std::string& fileName, Log& log, const ShaderTable* earlier)
        : script_(text, fileName), fileName_(fileName), log_(log), earlier_(earlier) {}

    std::vector<ShaderInfo> parse() {
        std::vector<ShaderInfo> shaders;
        while (script_.next(true)) {
            std::string name = script_.token();
            const int nameLine = script_.line();
            if (!script_.tokenWasQuoted() && (name == "{" || name == "}"))
                script_.fail("expected a shader name, found '" + name + "'");
            // "name:q3map" defines a compiler-only variant of "name".
            constexpr std::string_view kQ3mapSuffix = ":q3map";
            if (name.size() > kQ3mapSuffix.size() &&
                equalsNoCase(std::string_view(name).substr(name.size() - kQ3mapSuffix.size()), kQ3mapSuffix))
                name.resize(name.size() - kQ3mapSuffix.size());

            if (!script_.next(true)) script_.fail("shader '" + name + "' has no body: expected '{' after its name");
            if (script_.token() != "{" || script_.tokenWasQuoted())
                script_.fail("shader '" + name + "': expected '{' after the shader name, found '" + script_.token() + "'");

            ShaderInfo shader;
            shader.name = name;
            shader.explicitScript = true;
            shader.sourceFile = fileName_;
            shader.sourceLine = nameLine;
            shaders_ = &shaders;
            if (!parseBody(shader)) break;  // end of file reached inside the shader
            firstByKey_.emplace(shaderKey(shader.name), shaders.size());  // an earlier one keeps its slot
            shaders.push_back(std::move(shader));
        }
        return shaders;
    }

private:
    // Returns false (after a warning) when the file ends before the closing brace.
    bool parseBody(ShaderInfo& shader) {
        while (true) {
            if (!script_.next(true)) return unterminated(shader, "the body");
            const std::string& token = script_.token();
            if (!script_.tokenWasQuoted() && token == "}") return true;
            if (!script_.tokenWasQuoted() && token == "{") {
                if (!parseStage(shader)) return unterminated(shader, "a stage");
                continue;
            }
            parseDirective(shader, std::string(token));
            skipRestOfLine();
        }
    }

    bool unterminated(const ShaderInfo& shader, const char* what) {
        log_.warning(fileName_ + ":" + std::to_string(script_.line()) + ": end of file inside " + what +
                     " of shader '" + shader.name + "' (line " + std::to_string(shader.sourceLine) +
                     "): missing '}', shader ignored");
        return false;
    }

    void skipRestOfLine() {
        while (script_.tokenAvailableOnLine()) script_.next(false);
    }

    // A stage: only its images matter. Returns false at end of file.
    bool parseStage(ShaderInfo& shader) {
        shader.hasStages = true;
        while (true) {
            if (!script_.next(true)) return false;
            const std::string token = script_.token();
            if (script_.tokenWasQuoted()) continue;
            if (token == "}") return true;
            const bool animated = equalsNoCase(token, "animMap") || equalsNoCase(token, "clampAnimMap");
            if (animated || equalsNoCase(token, "map") || equalsNoCase(token, "clampMap") ||
                equalsNoCase(token, "mapComp") || equalsNoCase(token, "mapNoComp")) {
                if (animated) argToken(shader, token);  // frequency
                std::string image = argToken(shader, token);
                if (image.empty() || image[0] == '$' || image[0] == '*') continue;
                if (shader.firstStageImage.empty()) shader.firstStageImage = image;
                if (shader.lightImage.empty() && shader.editorImage.empty()) shader.lightImage = image;
            }
        }
    }

    std::string where() const { return fileName_ + ":" + std::to_string(script_.line()); }

    // The next token on the directive's line; a missing one is fatal as in q3map2.
    std::string argToken(const ShaderInfo& shader, std::string_view directive) {
        if (!script_.next(false))
            script_.fail("missing argument for '" + std::string(directive) + "' in shader '" + shader.name + "'");
        return script_.token();
    }

    // Numbers are read like atof (q3map2): a malformed one yields its leading numeric part, else 0,
    // with a warning.
    double argNumber(const ShaderInfo& shader, std::string_view directive) {
        std::string token = argToken(shader, directive);
        double value = 0;
        if (parseNumber(token, value)) return value;
        const char* begin = token.data();
        const char* end = token.data() + token.size();
        if (begin != end && *begin == '+') ++begin;
        auto result = std::from_chars(begin, end, value);
        if (result.ec != std::errc() || !std::isfinite(value)) value = 0;
        log_.warning(where() + ": shader '" + shader.name + "': bad number '" + token + "' for '" +
                     std::string(directive) + "', read as " + std::to_string(value));
        return value;
    }

    float argFloat(const ShaderInfo& shader, std::string_view directive) {
        return static_cast<float>(argNumber(shader, directive));
    }

    // atoi semantics: the fraction is dropped.
    int argInt(const ShaderInfo& shader, std::string_view directive) {
        double v = argNumber(shader, directive);
        v = std::clamp(std::trunc(v), -2147483648.0, 2147483647.0);
        return static_cast<int>(v);
    }

    Vec3 argVec3(const ShaderInfo& shader, std::string_view directive) {
        Vec3 v;
        v.x = argFloat(shader, directive);
        v.y = argFloat(shader, directive);
        v.z = argFloat(shader, directive);
        return v;
    }

    // Surfaceparms implied by other directives (always in the table).
    static void applyParm(ShaderInfo& shader, std::string_view parm) { applySurfaceParm(parm, shader); }

    void parseDirective(ShaderInfo& shader, const std::string& token) {
        auto is = [&](std::string_view name) { return equalsNoCase(token, name); };

        if (is("surfaceparm")) {
            std::string parm = argToken(shader, token);
            if (!applySurfaceParm(parm, shader))
                log_.warning(where() + ": shader '" + shader.name + "': unknown surfaceparm '" + parm + "'");
        } else if (is("cull")) {
            std::string mode = argToken(shader, token);
            if (equalsNoCase(mode, "none") || equalsNoCase(mode, "disable") || equalsNoCase(mode, "twosided"))
                shader.twoSided = true;
        } else if (is("deformVertexes")) {
            std::string kind = argToken(shader, token);
            if (startsWithNoCase(kind, "autosprite")) {
                // Autosprites become point lights and are detail, as in q3map2.
                shader.autosprite = true;
                if (equalsNoCase(kind, "autosprite2")) shader.autosprite2 = true;
                applyParm(shader, "detail");
            }
        } else if (is("qer_editorImage")) {
            shader.editorImage = argToken(shader, token);
        } else if (is("q3map_normalImage")) {
            shader.normalImage = argToken(shader, token);
        } else if (is("q3map_lightImage")) {
            shader.lightImage = argToken(shader, token);
        } else if (is("skyParms")) {
            std::string env = argToken(shader, token);
            if (env != "-" && !equalsNoCase(env, "full")) {
                shader.skyParmsEnv = env;
                if (shader.lightImage.empty()) shader.lightImage = env + "_up";
            }
            argToken(shader, token);  // cloud height
            argToken(shader, token);  // inner box
        } else if (is("sun") || is("q3map_sun") || is("q3map_sunExt")) {
            parseSun(shader, token, is("q3map_sunExt"));
        } else if (is("tessSize")) {
            shader.tessSize = argFloat(shader, token);
        } else if (is("fogParms")) {
            shader.fogParms = true;
        } else if (is("polygonOffset")) {
            shader.polygonOffset = true;
        } else if (is("implicitMap") || is("implicitMask") || is("implicitBlend")) {
            std::string image = argToken(shader, token);
            shader.implicitImage = image == "-" ? shader.name : image;
        } else if (startsWithNoCase(token, "q3map_")) {
            parseQ3mapDirective(shader, token);
        }
        // Anything else (stage-independent engine directives, editor keys, "light", ...) matters to
        // neither -bsp nor -light.
    }

    void parseSun(ShaderInfo& shader, const std::string& token, bool extended) {
        ShaderSun sun;
        sun.style = shader.lightStyle;
        sun.color = normalizeShaderColor(argVec3(shader, token));
        sun.intensity = argFloat(shader, token);
        sun.yawDegrees = argFloat(shader, token);
        sun.elevationDegrees = argFloat(shader, token);
        sun.direction = sunDirectionFromAngles(sun.yawDegrees, sun.elevationDegrees);
        sun.filterRadius = shader.lightFilterRadius;
        if (extended && script_.tokenAvailableOnLine()) {
            sun.devianceDegrees = argFloat(shader, token);
            sun.samples = argInt(shader, token);
        }
        shader.suns.push_back(sun);
        applyParm(shader, "sky");
    }

    void parseQ3mapDirective(ShaderInfo& shader, const std::string& token) {
        auto is = [&](std::string_view name) { return equalsNoCase(token, name); };

        if (is("q3map_baseShader")) {
            inheritBaseShader(shader, argToken(shader, token));
        } else if (is("q3map_deprecateShader")) {
            shader.deprecatedBy = argToken(shader, token);
        } else if (is("q3map_bounce") || is("q3map_bounceScale")) {
            shader.bounceScale = argFloat(shader, token);
        } else if (is("q3map_skyLight")) {
            ShaderSkyLight sky;
            sky.value = std::max(0.0f, argFloat(shader, token));
            sky.iterations = std::max(2, argInt(shader, token));
            if (script_.tokenAvailableOnLine()) {
                sky.horizonMin = std::clamp(argInt(shader, token), -90, 90);
                if (script_.tokenAvailableOnLine()) {
                    sky.horizonMax = std::clamp(argInt(shader, token), -90, 90);
                    if (script_.tokenAvailableOnLine()) sky.sampleColor = argInt(shader, token) != 0;
                }
            }
            shader.skyLights.push_back(sky);
        } else if (is("q3map_surfaceLight")) {
            shader.surfaceLight = argFloat(shader, token);
        } else if (is("q3map_lightStyle")) {
            shader.lightStyle = std::clamp(argInt(shader, token), 0, 255);
        } else if (is("q3map_lightRGB")) {
            shader.lightRGB = normalizeShaderColor(argVec3(shader, token));
        } else if (is("q3map_lightSubdivide")) {
            shader.lightSubdivide = argInt(shader, token);
        } else if (is("q3map_backsplash")) {
            shader.backsplashFraction = argFloat(shader, token) * 0.01f;
            shader.backsplashDistance = argFloat(shader, token);
            shader.backsplashSet = true;
        } else if (is("q3map_floodLight")) {
            ShaderFloodLight flood;
            flood.color = argVec3(shader, token);
            flood.distance = argFloat(shader, token);
            flood.intensity = argFloat(shader, token);
            flood.directionScale = argFloat(shader, token);
            flood.color = normalizeShaderColor(flood.color);
            shader.floodLight = flood;
        } else if (is("q3map_noDirty")) {
            shader.noDirty = true;
        } else if (is("q3map_lightmapSampleSize")) {
            shader.lightmapSampleSize = argInt(shader, token);
        } else if (is("q3map_lightmapSampleOffset")) {
            shader.lightmapSampleOffset = argFloat(shader, token);
        } else if (is("q3map_lightmapFilterRadius")) {
            shader.lightmapFilterRadius = argFloat(shader, token);
            shader.lightFilterRadius = argFloat(shader, token);
        } else if (is("q3map_lightmapAxis")) {
            std::string axis = argToken(shader, token);
            if (equalsNoCase(axis, "x")) shader.lightmapAxis = 0;
            else if (equalsNoCase(axis, "y")) shader.lightmapAxis = 1;
            else if (equalsNoCase(axis, "z")) shader.lightmapAxis = 2;
            else {
                log_.warning(where() + ": shader '" + shader.name + "': unknown lightmap axis '" + axis + "'");
                shader.lightmapAxis = -1;
            }
        } else if (is("q3map_lightmapSize")) {
            int width = argInt(shader, token);
            int height = argInt(shader, token);
            auto powerOfTwo = [](int v) { return v >= 0 && (v & (v - 1)) == 0; };
            if (powerOfTwo(width) && powerOfTwo(height)) {
                shader.lightmapWidth = width;
                shader.lightmapHeight = height;
            } else {
                log_.warning(where() + ": shader '" + shader.name + "': lightmap size " + std::to_string(width) + "x" +
                             std::to_string(height) + " is not a power of two, using the global size");
                shader.lightmapWidth = shader.lightmapHeight = 0;
            }
        } else if (is("q3map_lightmapBrightness") || is("q3map_lightmapGamma")) {
            shader.lightmapBrightness *= argFloat(shader, token);
            if (shader.lightmapBrightness < 0) shader.lightmapBrightness = 1;
        } else if (is("q3map_vertexScale")) {
            shader.vertexScale *= argFloat(shader, token);
        } else if (is("q3map_noVertexLight")) {
            shader.noVertexLight = true;
        } else if (is("q3map_terrain")) {
            // Team Arena terrain: indexed, unclipped, non-planar meta surfaces with full normal
            // smoothing and (without a q3map_tcGen) a texture projected from above.
            shader.legacyTerrain = true;
            shader.indexed = true;
            shader.noClip = true;
            shader.noTJunc = true;
            shader.nonplanar = true;
            shader.forceMeta = true;
            shader.shadeAngleDegrees = 179.0f;
        } else if (is("q3map_indexed")) {
            shader.indexed = true;
        } else if (is("q3map_forceMeta")) {
            shader.forceMeta = true;
        } else if (is("q3map_clipModel")) {
            shader.clipModel = true;
        } else if (is("q3map_nonplanar")) {
            shader.nonplanar = true;
        } else if (is("q3map_shadeAngle")) {
            shader.shadeAngleDegrees = argFloat(shader, token);
        } else if (is("q3map_lightmapMergable")) {
            shader.lightmapMergable = true;
        } else if (is("q3map_noFast")) {
            shader.noFast = true;
        } else if (is("q3map_splotchFix")) {
            shader.splotchFix = true;
        } else if (is("q3map_forceSunlight")) {
            shader.forceSunlight = true;
        } else if (is("q3map_onlyVertexLighting")) {
            applyParm(shader, "pointlight");
        } else if (is("q3map_styleMarker")) {
            shader.styleMarker = 1;
        } else if (is("q3map_styleMarker2")) {
            shader.styleMarker = 2;
        } else if (is("q3map_tessSize")) {
            shader.tessSize = argFloat(shader, token);
        } else if (is("q3map_fogDir")) {
            shader.fogDir = argVec3(shader, token);
        } else if (is("q3map_globalTexture")) {
            shader.globalTexture = true;
        } else if (is("q3map_noClip")) {
            shader.noClip = true;
        } else if (is("q3map_notjunc")) {
            shader.noTJunc = true;
        } else if (is("q3map_noFog")) {
            shader.noFog = true;
        } else if (is("q3map_invert")) {
            shader.invert = true;
        } else if (is("q3map_offset")) {
            shader.vertexOffset = argFloat(shader, token);
        } else if (is("q3map_textureSize")) {
            shader.textureWidth = argInt(shader, token);
            shader.textureHeight = argInt(shader, token);
        } else if (is("q3map_flare") || is("q3map_flareShader")) {
            shader.flareShader = argToken(shader, token);
        } else if (is("q3map_backShader")) {
            shader.backShader = argToken(shader, token);
        } else if (is("q3map_cloneShader")) {
            shader.cloneShader = argToken(shader, token);
        } else if (is("q3map_remapShader")) {
            shader.remapShader = argToken(shader, token);
        } else if (is("q3map_foliage")) {
            ShaderFoliage& f = shader.foliage.emplace_back();
            f.model = argToken(shader, token);
            f.scale = argFloat(shader, token);
            f.density = argFloat(shader, token);
            f.odds = argFloat(shader, token);
            f.inverseAlpha = argInt(shader, token);
        } else if (is("q3map_tcMod")) {
            parseTcMod(shader, token);
        } else if (is("q3map_tcGen")) {
            parseTcGen(shader, token);
        } else if (is("q3map_colorGen") || is("q3map_colorMod") || is("q3map_rgbGen") || is("q3map_rgbMod") ||
                   is("q3map_alphaGen") || is("q3map_alphaMod")) {
            parseColorMod(shader, token, is("q3map_alphaGen") || is("q3map_alphaMod"));
        } else if (isIgnoredQ3mapDirective(token)) {
            // Not lighting related.
        } else if (!applySurfaceParm(std::string_view(token).substr(6), shader)) {
            log_.warning(where() + ": shader '" + shader.name + "': unknown directive '" + token + "'");
        }
    }

    // q3map_tcMod translate|shift|offset s t, scale s t, rotate degrees: each one composes into the
    // shader's matrix as q3map2 does (a rotation applies before what came earlier).
    void parseTcMod(ShaderInfo& shader, const std::string& token) {
        const std::string method = argToken(shader, token);
        auto& m = shader.tcMod;
        if (equalsNoCase(method, "translate") || equalsNoCase(method, "shift") || equalsNoCase(method, "offset")) {
            m[0][2] += argFloat(shader, token);
            m[1][2] += argFloat(shader, token);
        } else if (equalsNoCase(method, "scale")) {
            m[0][0] *= argFloat(shader, token);
            m[1][1] *= argFloat(shader, token);
        } else if (equalsNoCase(method, "rotate")) {
            const double radians = double(argFloat(shader, token)) / 180 * 3.14159265358979323846;
            const float c = float(std::cos(radians)), s = float(std::sin(radians));
            const float r[3][3] = {{c, -s, 0}, {s, c, 0}, {0, 0, 1}};
            const auto old = m;
            for (int i = 0; i < 3; ++i)
                for (int j = 0; j < 3; ++j) m[i][j] = old[i][0] * r[0][j] + old[i][1] * r[1][j] + old[i][2] * r[2][j];
        } else {
            log_.warning(where() + ": shader '" + shader.name + "': unknown q3map_tcMod method '" + method + "'");
        }
    }

    // A parenthesised list of numbers, "( a b c )".
    std::vector<float> argList(const ShaderInfo& shader, const std::string& token, size_t count) {
        if (argToken(shader, token) != "(") script_.fail(token + " in shader '" + shader.name + "': expected '('");
        std::vector<float> values;
        for (size_t i = 0; i < count; ++i) values.push_back(argFloat(shader, token));
        if (argToken(shader, token) != ")") script_.fail(token + " in shader '" + shader.name + "': expected ')'");
        return values;
    }

    // q3map_[color|rgb|alpha][Gen|Mod] <method> <parameters>: one step appended to the shader's
    // colorMod list; an unknown method still takes its place in the list and changes nothing, as in
    // q3map2.
    void parseColorMod(ShaderInfo& shader, const std::string& token, bool alpha) {
        using Kind = ShaderColorMod::Kind;
        ShaderColorMod& cm = shader.colorMods.emplace_back();
        cm.kind = Kind::Volume;
        const std::string method = argToken(shader, token);
        auto is = [&](std::string_view name) { return equalsNoCase(method, name); };
        auto vector = [&](size_t count) {
            const std::vector<float> v = argList(shader, token, count);
            cm.vector = {v[0], v[1], v[2]};
            if (count == 5) {
                cm.lo = v[3];
                cm.hi = v[4];
            }
        };
        if (alpha && (is("set") || is("const"))) {
            cm.kind = Kind::AlphaSet;
            cm.value = argFloat(shader, token);
        } else if (is("set") || is("const")) {
            cm.kind = Kind::ColorSet;
            vector(3);
        } else if (alpha && is("scale")) {
            cm.kind = Kind::AlphaScale;
            cm.value = argFloat(shader, token);
        } else if (is("scale")) {
            cm.kind = Kind::ColorScale;
            vector(3);
        } else if (is("dotProduct")) {
            cm.kind = alpha ? Kind::AlphaDotProduct : Kind::ColorDotProduct;
            vector(3);
        } else if (is("dotProductScale")) {
            cm.kind = alpha ? Kind::AlphaDotProductScale : Kind::ColorDotProductScale;
            vector(5);
        } else if (is("dotProduct2")) {
            cm.kind = alpha ? Kind::AlphaDotProduct2 : Kind::ColorDotProduct2;
            vector(3);
        } else if (is("dotProduct2scale")) {
            cm.kind = alpha ? Kind::AlphaDotProduct2Scale : Kind::ColorDotProduct2Scale;
            vector(5);
        } else if (!is("volume")) {
            cm.kind = Kind::None;  // kept in the list with no effect, as q3map2 does
            log_.warning(where() + ": shader '" + shader.name + "': unknown " + token + " method '" + method + "'");
        }
    }

    // q3map_tcGen vector ( sx sy sz ) ( tx ty tz ), or ivector with the reciprocals of each part.
    void parseTcGen(ShaderInfo& shader, const std::string& token) {
        const std::string method = argToken(shader, token);
        const bool inverse = equalsNoCase(method, "ivector");
        if (!inverse && !equalsNoCase(method, "vector")) {
            log_.warning(where() + ": shader '" + shader.name + "': unknown q3map_tcGen method '" + method + "'");
            shader.tcGen = true;
            shader.tcGenVectors[0] = shader.tcGenVectors[1] = Vec3{0, 0, 0};
            return;
        }
        for (Vec3& v : shader.tcGenVectors) {
            const std::vector<float> read = argList(shader, token, 3);
            v = {read[0], read[1], read[2]};
            if (inverse)
                for (float* c : {&v.x, &v.y, &v.z}) *c = *c != 0 ? 1.0f / *c : 0.0f;
        }
        shader.tcGen = true;
    }

    // q3map_baseShader: start over from a copy of another shader (earlier in this file, else in the
    // table, else an implicit shader), keeping this shader's identity.
    void inheritBaseShader(ShaderInfo& shader, const std::string& baseName) {
        const ShaderInfo* base = nullptr;
        if (const auto it = firstByKey_.find(shaderKey(baseName)); it != firstByKey_.end())
            base = &(*shaders_)[it->second];
        if (!base && earlier_) base = earlier_->findExplicit(baseName);
        ShaderInfo copy = base ? *base : makeImplicitShader(baseName);
        copy.name = shader.name;
        copy.explicitScript = true;
        copy.sourceFile = shader.sourceFile;
        copy.sourceLine = shader.sourceLine;
        copy.hasStages = copy.hasStages || shader.hasStages;
        shader = std::move(copy);
    }

    Script script_;
    const std::string& fileName_;
    Log& log_;
    const ShaderTable* earlier_;
    const std::vector<ShaderInfo>* shaders_ = nullptr;
    // Index in *shaders_ of the first shader of this file with each shaderKey, so that long
    // q3map_baseShader chains do not rescan the file for every link.
    std::unordered_map<std::string, size_t> firstByKey_;
};

}  // namespace

std::vector<ShaderInfo> parseShaderScript(std::string_view text, const std::string& fileName, Log& log,
                                          const ShaderTable* earlier) {
    return ShaderScriptParser(text, fileName, log, earlier).parse();
}

}  // namespace q3
