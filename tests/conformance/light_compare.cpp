// The comparison itself: per-surface lightmap means and their classes, vertex colours, and the
// assembly of the report (light_compare.h describes every figure).
#include "light_compare.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>

#include "light_compare_internal.h"

namespace q3::conformance {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr float kNearLightUnits = 128;
constexpr float kAreaLightUnits = 256;
constexpr double kShadowFraction = 0.25;
constexpr double kRepeatUnits = 2, kRepeatFraction = 0.05;
constexpr double kFullWeightArea = 4096;

double ratioOf(double ours, double reference) { return reference > 0 ? ours / reference : kNaN; }

// Same surfaces, same vertexes: anything else means the two files were not lit from one input.
void checkSameInput(const LitBsp& reference, const LitBsp& ours) {
    const bsp::Bsp& a = reference.bsp;
    const bsp::Bsp& b = ours.bsp;
    auto fail = [&](const std::string& what) {
        throw bsp::BspError(ours.name + ": not lit from the same input as " + reference.name + ": " + what);
    };
    if (a.surfaces.size() != b.surfaces.size())
        fail(std::to_string(b.surfaces.size()) + " surfaces, the reference has " + std::to_string(a.surfaces.size()));
    if (a.drawVerts.size() != b.drawVerts.size())
        fail(std::to_string(b.drawVerts.size()) + " vertexes, the reference has " + std::to_string(a.drawVerts.size()));
    for (size_t i = 0; i < a.surfaces.size(); ++i) {
        const bsp::Surface& x = a.surfaces[i];
        const bsp::Surface& y = b.surfaces[i];
        if (x.surfaceType != y.surfaceType || x.firstVert != y.firstVert || x.numVerts != y.numVerts ||
            x.numIndexes != y.numIndexes)
            fail("surface " + std::to_string(i) + " differs in type or vertex range");
    }
}

std::string shaderName(const bsp::Bsp& bsp, int shaderNum) {
    if (shaderNum < 0 || shaderNum >= int(bsp.shaders.size())) return "?";
    return std::string(bsp.shaders[shaderNum].name, strnlen(bsp.shaders[shaderNum].name, sizeof bsp.shaders[shaderNum].name));
}

double medianOf(std::vector<double> values) {
    if (values.empty()) return 0;
    const size_t mid = values.size() / 2;
    std::nth_element(values.begin(), values.begin() + mid, values.end());
    return values[mid];
}

// Surfaces within `units` of any surface whose shader emits area light.
std::vector<bool> nearAreaLights(const bsp::Bsp& bsp, const std::vector<detail::SurfaceShape>& shapes,
                                 const std::vector<bool>& shaderEmits) {
    std::vector<Bounds> emitters;
    for (size_t s = 0; s < bsp.surfaces.size(); ++s) {
        const int shader = bsp.surfaces[s].shaderNum;
        if (shader >= 0 && shader < int(shaderEmits.size()) && shaderEmits[shader] && !shapes[s].bounds.empty())
            emitters.push_back(shapes[s].bounds);
    }
    std::vector<bool> near(bsp.surfaces.size(), false);
    for (size_t s = 0; s < bsp.surfaces.size(); ++s)
        for (const Bounds& e : emitters)
            if (!shapes[s].bounds.empty() && detail::boundsDistance(shapes[s].bounds, e) <= kAreaLightUnits) {
                near[s] = true;
                break;
            }
    return near;
}

VertexFigures compareVertexColours(const bsp::Bsp& reference, const bsp::Bsp& ours) {
    VertexFigures v;
    std::vector<double> refLum, ourLum;
    for (const bsp::Surface& s : reference.surfaces) {
        if (s.lightmapNum != bsp::kLightmapByVertex || s.numVerts <= 0) continue;
        ++v.surfaces;
        for (int i = s.firstVert; i < s.firstVert + s.numVerts; ++i) {
            const uint8_t* a = reference.drawVerts[i].color;
            const uint8_t* b = ours.drawVerts[i].color;
            v.referenceSum += double(a[0]) + a[1] + a[2];
            v.oursSum += double(b[0]) + b[1] + b[2];
            refLum.push_back(0.299 * a[0] + 0.587 * a[1] + 0.114 * a[2]);
            ourLum.push_back(0.299 * b[0] + 0.587 * b[1] + 0.114 * b[2]);
            ++v.vertexes;
        }
    }
    v.ratio = ratioOf(v.oursSum, v.referenceSum);
    v.correlation = pearson(refLum, ourLum);
    return v;
}

}  // namespace

double pearson(const std::vector<double>& a, const std::vector<double>& b) {
    const size_t n = std::min(a.size(), b.size());
    if (n < 2) return kNaN;
    double ma = 0, mb = 0;
    for (size_t i = 0; i < n; ++i) {
        ma += a[i];
        mb += b[i];
    }
    ma /= double(n);
    mb /= double(n);
    double sab = 0, saa = 0, sbb = 0;
    for (size_t i = 0; i < n; ++i) {
        const double da = a[i] - ma, db = b[i] - mb;
        sab += da * db;
        saa += da * da;
        sbb += db * db;
    }
    if (saa <= 0 || sbb <= 0) return kNaN;
    return sab / std::sqrt(saa * sbb);
}

Comparison compareLitBsps(const LitBsp& reference, const LitBsp& ours, const LitBsp* reference2,
                          const ClassInputs& classes, const CompareOptions& options) {
    checkSameInput(reference, ours);
    Comparison out;
    out.referenceName = reference.name;
    out.oursName = ours.name;
    const bsp::Bsp& refBsp = reference.bsp;
    const int count = int(refBsp.surfaces.size());

    std::vector<SurfaceFigures> surfaces(count);
    std::vector<detail::SurfaceShape> shapes(count);
    LightmapFigures& lm = out.lightmaps;
    lm.referencePages = int(reference.pages.size());
    lm.oursPages = int(ours.pages.size());
    if (reference2) checkSameInput(reference, *reference2);
    std::vector<double> refMeans, ourMeans, repeatRefMeans, repeatOurMeans;
    double repeatRefTotal = 0, repeatOurTotal = 0;
    const detail::SolidTest solidTest(refBsp);
    const detail::SolidTest* solid = options.leaveOutHidden ? &solidTest : nullptr;
    for (int s = 0; s < count; ++s) {
        SurfaceFigures& f = surfaces[s];
        const SurfaceSample r = sampleSurface(reference, s, solid);
        const SurfaceSample o = sampleSurface(ours, s, solid);
        f.surface = s;
        f.shader = shaderName(refBsp, refBsp.surfaces[s].shaderNum);
        f.surfaceType = refBsp.surfaces[s].surfaceType;
        f.area = r.lit ? r.area : o.area;
        f.referenceLit = r.lit;
        f.oursLit = o.lit;
        f.referenceMean = r.mean;
        f.oursMean = o.mean;
        f.mismatch = std::fabs(o.mean - r.mean) / (r.mean + 8) * std::min(1.0, std::sqrt(f.area / kFullWeightArea));
        if (reference2) {
            const SurfaceSample r2 = sampleSurface(*reference2, s, solid);
            f.referenceRepeats =
                r2.lit == r.lit && std::fabs(r2.mean - r.mean) <= std::max(kRepeatUnits, kRepeatFraction * r.mean);
        }
        shapes[s] = detail::surfaceShape(refBsp, s);
        lm.referenceLit += r.lit;
        lm.oursLit += o.lit;
        lm.bothLit += r.lit && o.lit;
        lm.referenceOnly += r.lit && !o.lit;
        lm.oursOnly += o.lit && !r.lit;
        if (!r.lit) continue;
        if (r.hidden) {
            ++lm.hiddenSurfaces;
            f.hidden = true;
            continue;
        }
        lm.referenceTotal += r.mean;
        lm.oursTotal += o.mean;  // 0 when ours did not lightmap it
        refMeans.push_back(r.mean);
        ourMeans.push_back(o.mean);
        if (reference2 && f.referenceRepeats) {
            repeatRefTotal += r.mean;
            repeatOurTotal += o.mean;
            repeatRefMeans.push_back(r.mean);
            repeatOurMeans.push_back(o.mean);
        }
    }
    if (reference2) {
        lm.repeatable = int(repeatRefMeans.size());
        lm.repeatableRatio = ratioOf(repeatOurTotal, repeatRefTotal);
        lm.repeatableCorrelation = pearson(repeatRefMeans, repeatOurMeans);
    }
    lm.ratio = ratioOf(lm.oursTotal, lm.referenceTotal);
    lm.correlation = pearson(refMeans, ourMeans);
    lm.medianReference = medianOf(refMeans);

    // Classes over reference-lightmapped surfaces; with a second reference run, over the ones it
    // repeats (the reference's threads race on some surfaces, and a class must not follow that).
    std::vector<bool> areaLit, skyLit;
    if (classes.shadersKnown) {
        areaLit = nearAreaLights(refBsp, shapes, classes.shaderEmitsArea);
        if (classes.skyEmits) skyLit = detail::skyLitSurfaces(refBsp, classes.shaderIsSky);
        else skyLit.assign(count, false);
    }
    struct ClassRule {
        const char* name;
        bool measured;
        std::function<bool(int)> member;
    };
    const std::vector<ClassRule> rules = {
        {"planar", true, [&](int s) { return refBsp.surfaces[s].surfaceType == bsp::MST_PLANAR; }},
        {"patch", true, [&](int s) { return refBsp.surfaces[s].surfaceType == bsp::MST_PATCH; }},
        {"soup", true, [&](int s) { return refBsp.surfaces[s].surfaceType == bsp::MST_TRIANGLE_SOUP; }},
        {"near-light", classes.lightsKnown,
         [&](int s) {
             for (const Vec3& o : classes.lightOrigins)
                 if (!shapes[s].bounds.empty() && detail::pointBoundsDistance(o, shapes[s].bounds) <= kNearLightUnits)
                     return true;
             return false;
         }},
        {"shadow", true, [&](int s) { return surfaces[s].referenceMean < kShadowFraction * lm.medianReference; }},
        {"area-lit", classes.shadersKnown, [&](int s) { return areaLit[s]; }},
        {"sky-lit", classes.shadersKnown, [&](int s) { return skyLit[s]; }},
    };
    for (const ClassRule& rule : rules) {
        ClassFigures c;
        c.name = rule.name;
        c.measured = rule.measured;
        if (rule.measured)
            for (int s = 0; s < count; ++s) {
                if (!surfaces[s].referenceLit || surfaces[s].hidden || !rule.member(s)) continue;
                if (reference2 && !surfaces[s].referenceRepeats) continue;
                ++c.surfaces;
                c.referenceSum += surfaces[s].referenceMean * surfaces[s].area;
                c.oursSum += surfaces[s].oursMean * surfaces[s].area;
            }
        c.ratio = rule.measured ? ratioOf(c.oursSum, c.referenceSum) : kNaN;
        lm.classes.push_back(c);
    }
    if (!classes.lightsKnown) out.notes.push_back("near-light: no .map given and no light entity in the reference BSP");
    if (!classes.shadersKnown) out.notes.push_back("area-lit, sky-lit: no shader scripts given (--basepath)");
    else if (!classes.skyEmits) out.notes.push_back("sky-lit: no sky shader of this map emits light");
    if (lm.oursLit == 0) out.notes.push_back("ours wrote no lightmaps: every surface is vertex-lit or unlit");

    // One-sided surfaces first (a surface lightmapped by one side only is the plainest mismatch),
    // then by relative difference.
    std::vector<SurfaceFigures> ranked;
    for (const SurfaceFigures& f : surfaces)
        if ((f.referenceLit || f.oursLit) && !f.hidden) ranked.push_back(f);
    std::stable_sort(ranked.begin(), ranked.end(), [](const SurfaceFigures& a, const SurfaceFigures& b) {
        const bool oneSidedA = a.referenceLit != a.oursLit, oneSidedB = b.referenceLit != b.oursLit;
        if (oneSidedA != oneSidedB) return oneSidedA;
        return a.mismatch > b.mismatch;
    });
    if (int(ranked.size()) > options.worstCount) ranked.resize(std::max(0, options.worstCount));
    lm.worst = std::move(ranked);

    out.vertexes = compareVertexColours(refBsp, ours.bsp);
    out.grid = compareGrids(refBsp.lightGrid, ours.bsp.lightGrid, reference2 ? &reference2->bsp.lightGrid : nullptr);
    if (!reference2) out.notes.push_back("grid: no second reference run (--ref2): figures over all points only");
    else if (!out.grid.masked) out.notes.push_back("grid: the second reference run has another point count: no mask");
    if (!out.grid.countsMatch)
        out.notes.push_back("grid: point counts differ (reference " + std::to_string(out.grid.referencePoints) +
                            ", ours " + std::to_string(out.grid.oursPoints) + "): not compared");
    return out;
}

}  // namespace q3::conformance
