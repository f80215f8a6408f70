#include "srf_file.h"

#include <cmath>
#include <system_error>

#include "file_io.h"
#include "script.h"

namespace q3::light {

const SurfaceExtra& SurfaceExtras::forSurface(int surface) const {
    if (surface < 0 || size_t(surface) >= surfaces.size() || !present[surface]) return defaults;
    return surfaces[surface];
}

namespace {

// The value of `key` must follow on the same line.
double valueOnLine(Script& script, std::string_view key) {
    if (!script.next(false)) script.fail("missing value for " + std::string(key));
    double value = 0;
    if (!parseNumber(script.token(), value) || !std::isfinite(value))
        script.fail("expected a number for " + std::string(key) + ", found '" + script.token() + "'");
    return value;
}

int intOnLine(Script& script, std::string_view key) {
    const double value = valueOnLine(script, key);
    if (value != std::floor(value) || std::fabs(value) > 2147483647.0)
        script.fail("expected an integer for " + std::string(key) + ", found '" + script.token() + "'");
    return int(value);
}

// "( x y z )" as q3map2's Parse1DMatrix reads it.
Vec3 vectorOnLine(Script& script, std::string_view key) {
    if (!script.next(false) || script.token() != "(")
        script.fail("expected '(' after " + std::string(key));
    Vec3 v;
    for (int i = 0; i < 3; ++i) v[i] = float(valueOnLine(script, key));
    if (!script.next(false) || script.token() != ")")
        script.fail("expected ')' closing " + std::string(key));
    return v;
}

void parseField(Script& script, SurfaceExtra& se) {
    const std::string key = script.token();
    if (equalsNoCase(key, "shader")) {
        if (!script.next(false)) script.fail("missing value for shader");
        se.shader = script.token();
    } else if (equalsNoCase(key, "parent")) {
        se.parent = intOnLine(script, key);
    } else if (equalsNoCase(key, "entity")) {
        se.entity = intOnLine(script, key);
    } else if (equalsNoCase(key, "castShadows")) {
        se.castShadows = intOnLine(script, key);
    } else if (equalsNoCase(key, "receiveShadows")) {
        se.receiveShadows = intOnLine(script, key);
    } else if (equalsNoCase(key, "sampleSize")) {
        se.sampleSize = intOnLine(script, key);
        if (se.sampleSize < 0) script.fail("negative sampleSize " + std::to_string(se.sampleSize));
    } else if (equalsNoCase(key, "ambientColor")) {
        se.ambientColor = vectorOnLine(script, key);
    } else if (equalsNoCase(key, "longestCurve")) {
        se.longestCurve = float(valueOnLine(script, key));
    } else if (equalsNoCase(key, "lightmapAxis")) {
        se.lightmapAxis = vectorOnLine(script, key);
    }
    // Whatever else is on the line (unknown keys, extra values) is ignored, as q3map2 does.
    while (script.tokenAvailableOnLine()) script.next(false);
}

}  // namespace

SurfaceExtras parseSurfaceExtras(std::string_view text, const std::string& name, int defaultSampleSize) {
    SurfaceExtras extras;
    extras.loaded = true;
    extras.defaults.sampleSize = defaultSampleSize;
    Script script(text, name, true);
    while (script.next(true)) {
        SurfaceExtra* se = nullptr;
        if (equalsNoCase(script.token(), "default")) {
            se = &extras.defaults;
        } else {
            double number = 0;
            if (!parseNumber(script.token(), number) || number != std::floor(number))
                script.fail("expected a surface number or 'default', found '" + script.token() + "'");
            if (number < 0 || number > 0x1000000)
                script.fail("bogus surface number " + script.token());
            const size_t surface = size_t(number);
            if (surface >= extras.surfaces.size()) {
                // New blocks start from the defaults read so far, as in q3map2.
                extras.surfaces.resize(surface + 1, extras.defaults);
                extras.present.resize(surface + 1, false);
            }
            extras.present[surface] = true;
            se = &extras.surfaces[surface];
        }
        if (!script.next(true) || script.token() != "{") script.fail("{ not found");
        for (;;) {
            if (!script.next(true)) script.fail("unexpected end of file, } not found");
            if (script.token() == "}") break;
            parseField(script, *se);
        }
    }
    return extras;
}

SurfaceExtras loadSurfaceExtras(const std::filesystem::path& path, int defaultSampleSize) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) {
        SurfaceExtras missing;
        missing.defaults.sampleSize = defaultSampleSize;
        return missing;
    }
    return parseSurfaceExtras(readFileText(path), path.string(), defaultSampleSize);
}

}  // namespace q3::light
