// The three ways of lighting a moving model (see lightcache_compare.h).
#include "lightcache_compare.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "file_io.h"
#include "light_contribution.h"
#include "light_stage.h"
#include "sh_tools.h"
#include "world_lights_export.h"

namespace q3::light::cachetest {
namespace {

namespace fs = std::filesystem;

CommonOptions commonFor(const MapInputs& in, const fs::path& bsp, const std::string& commandLine) {
    CommonOptions common;
    common.mapPath = bsp;
    common.basePaths = in.basePaths;
    common.fsGame = in.fsGame;
    common.threads = 2;
    common.commandLine = commandLine;
    return common;
}

LightOptions fastGridOptions() {
    LightOptions options;
    options.fast = true;
    options.noLightmaps = true;  // models are lit by the grid and the lights only
    options.sh = true;
    options.worldLights = true;
    return options;
}

// Lights a copy of the input in its own folder; the written file's bytes, empty on failure.
std::vector<uint8_t> lightCopy(const MapInputs& in, const fs::path& dir, const LightOptions& options,
                               const std::string& commandLine) {
    fs::create_directories(dir / "maps");
    const fs::path bsp = dir / "maps" / in.bsp.filename();
    fs::copy_file(in.bsp, bsp, fs::copy_options::overwrite_existing);
    fs::copy_file(in.mapSource, fs::path(bsp).replace_extension(".map"), fs::copy_options::overwrite_existing);
    Log log(false);
    if (runLightStage(options, commonFor(in, bsp, commandLine), log) != 0) return {};
    return readFileBytes(bsp);
}

std::array<float, 3> arr(Vec3 v) { return {v.x, v.y, v.z}; }

Vec3 irradiance(const sh::GridPointSH& probe, Vec3 n) {
    const float normal[3] = {n.x, n.y, n.z};
    float rgb[3];
    sh::irradianceAt(probe, normal, rgb);
    return {rgb[0], rgb[1], rgb[2]};
}

}  // namespace

std::vector<Vec3> fibonacciNormals(int count) {
    std::vector<Vec3> out;
    const double golden = M_PI * (3 - std::sqrt(5.0));
    for (int k = 0; k < count; ++k) {
        const double z = 1 - (2 * k + 1) / double(count);
        const double r = std::sqrt(1 - z * z);
        out.push_back({float(r * std::cos(golden * k)), float(r * std::sin(golden * k)), float(z)});
    }
    return out;
}

LitMap::LitMap(const MapInputs& in, const fs::path& work) {
    fs::remove_all(work);
    const std::vector<uint8_t> withLights = lightCopy(in, work / "full", fastGridOptions(), "-light -fast -nolm -sh -worldlights");
    LightOptions leftOut = fastGridOptions();
    leftOut.shNoWorldLights = true;
    cacheBytes_ = lightCopy(in, work / "cache", leftOut, "-light -fast -nolm -shnoworldlights");
    if (withLights.empty() || cacheBytes_.empty()) {
        error_ = in.bsp.string() + ": -light failed";
        return;
    }
    error_ = fullGrid_.loadFromBsp(withLights.data(), withLights.size(), "full");
    if (error_.empty()) error_ = cache_.loadFromBsp(cacheBytes_.data(), cacheBytes_.size(), "cache");
    if (!error_.empty()) return;

    Log log(false);
    ctx_.options = leftOut;
    loadLightInputs(ctx_, commonFor(in, work / "cache" / "maps" / in.bsp.filename(), "-light"), log);
    buildSurfaceGeometry(ctx_);
    buildScene(ctx_);
    createLights(ctx_, log);
    const WorldLightSettings settings = worldLightSettings(ctx_.options);
    for (const Light& light : ctx_.lights)
        if (worldLightRecord(light, settings)) listed_.push_back(&light);
    env_ = surfaceLightingEnv(ctx_);
    env_.settings.forceFast = true;
    if (ctx_.scene) env_.rayMask = ctx_.scene->receiverMask(1);
}

bool LitMap::open(Vec3 p) const { return ctx_.tree->clusterForPoint(p) >= 0 && !ctx_.tree->pointInSolid(p); }

float LitMap::nearestLocalLight(Vec3 p) const {
    float best = INFINITY;
    for (const sh::WorldLight& l : cache_.lights())
        if (l.type != sh::WorldLightType::Sun) best = std::min(best, length(p - Vec3{l.origin[0], l.origin[1], l.origin[2]}));
    return best;
}

std::vector<Vec3> LitMap::bruteForceDirect(Vec3 p, const std::vector<Vec3>& normals) const {
    std::vector<Vec3> out(normals.size());
    const int cluster = ctx_.tree->clusterForPoint(p);
    for (const Light* light : listed_) {
        const std::optional<LightContribution> c = lightToGridPoint(*light, p, cluster, env_);
        if (!c) continue;
        for (size_t k = 0; k < normals.size(); ++k) {
            const float cosine = dot(normals[k], c->direction);
            const float incidence = light->controlled && light->type != LightType::Sun
                                        ? controlledIncidence(*light->controlled, cosine)
                                        : std::max(0.f, cosine);
            out[k] += c->color * (incidence / 255.0f * ctx_.options.gridScale);
        }
    }
    return out;
}

LitMap::Irradiance LitMap::irradianceAt(Vec3 p, const std::vector<Vec3>& normals) const {
    const float at[3] = {p.x, p.y, p.z};
    const sh::GridPointSH full = fullGrid_.sample(at);
    const sh::GridPointSH rest = cache_.grid().sample(at);
    const sh::LightCacheResult r = cache_.query(at);
    Irradiance out;
    out.bruteForce = bruteForceDirect(p, normals);
    for (size_t k = 0; k < normals.size(); ++k) {
        out.bruteForce[k] += irradiance(rest, normals[k]);
        out.shAlone.push_back(irradiance(full, normals[k]));
        Vec3 cached = irradiance(r.probe, normals[k]);
        for (int i = 0; i < r.localCount; ++i) {
            const auto v = sh::evaluateWorldLight(cache_.lights()[r.local[i].index], arr(p), arr(normals[k]));
            cached += Vec3{v[0], v[1], v[2]};
        }
        out.withCache.push_back(cached);
    }
    return out;
}

LitMap::Errors LitMap::errorsAt(Vec3 p, const std::vector<Vec3>& normals) const {
    const Irradiance e = irradianceAt(p, normals);
    Errors out;
    for (size_t k = 0; k < normals.size(); ++k)
        for (int c = 0; c < 3; ++c) {
            out.shAlone += std::fabs(e.shAlone[k][c] - e.bruteForce[k][c]);
            out.withCache += std::fabs(e.withCache[k][c] - e.bruteForce[k][c]);
            out.truthScale += std::fabs(e.bruteForce[k][c]);
        }
    const double n = double(std::max<size_t>(1, normals.size()));
    out.shAlone /= n;
    out.withCache /= n;
    out.truthScale /= n;
    return out;
}

Image renderPathPicture(const LitMap& map, const std::vector<Vec3>& positions, int cell, float exposure) {
    constexpr uint8_t kBackground = 32;
    Image image;
    image.width = int(positions.size()) * cell;
    image.height = 3 * cell;
    image.rgba.assign(size_t(image.width) * size_t(image.height) * 4, kBackground);
    for (size_t i = 3; i < image.rgba.size(); i += 4) image.rgba[i] = 255;
    // The disc's pixels and their sphere normals, the same for every cell.
    const std::vector<shtools::DiscPixel> disc = shtools::sphereDisc(cell);
    std::vector<Vec3> normals;
    for (const shtools::DiscPixel& d : disc) normals.push_back({d.normal[0], d.normal[1], d.normal[2]});
    for (size_t col = 0; col < positions.size(); ++col) {
        const LitMap::Irradiance e = map.irradianceAt(positions[col], normals);
        const std::vector<Vec3>* rows[3] = {&e.bruteForce, &e.shAlone, &e.withCache};
        for (int row = 0; row < 3; ++row)
            for (size_t k = 0; k < disc.size(); ++k) {
                uint8_t* texel = image.texel(int(col) * cell + disc[k].x, row * cell + disc[k].y);
                for (int ch = 0; ch < 3; ++ch) texel[ch] = shtools::toDisplay((*rows[row])[k][ch], exposure);
            }
    }
    return image;
}

}  // namespace q3::light::cachetest
