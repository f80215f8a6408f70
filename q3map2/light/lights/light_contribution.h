// How much light one Light sends to one sample: a luxel/vertex (point + normal) or a grid point
// (point only). q3map2's formulas (LightContributionToSample / LightContributionToPoint) for the
// q3map2 model, the formula of specs/light-models.md for the controlled model, PVS culling, fast
// envelopes and occlusion through the TraceScene.
#pragma once

#include <optional>
#include <span>
#include <vector>

#include "form_factor.h"
#include "light_types.h"
#include "lights.h"
#include "trace_scene.h"
#include "vec3.h"

namespace q3::light {

class TraceScene;
class BspTree;
class SkyVisibility;

struct ContributionSettings {
    bool faster = false;        // -faster: area lights as inverse square
    bool lightAngleHL = false;  // -lightanglehl: half-Lambert angle term
    bool sunOnly = false;       // -sunonly
    float ignoreNear = 0;       // occluders closer than this to the sample are ignored
    bool forceFast = false;     // -fast (or -fastgrid for grid points): every light uses its envelope
};

// Where and how a luxel or vertex receives light.
struct SamplePoint {
    Vec3 origin;
    Vec3 normal;
    int cluster = -1;        // -1 = unknown (no PVS culling)
    bool twoSided = false;   // cull none surfaces are lit from both sides
};

// Read-only services shared by every sample; `scene` nullptr = no occlusion (-notrace),
// `tree` nullptr = no PVS culling, `skies` nullptr = no culling of suns by sky visibility.
struct LightingEnv {
    const TraceScene* scene = nullptr;
    const BspTree* tree = nullptr;
    const SkyVisibility* skies = nullptr;
    ContributionSettings settings;
    // When set (with a scene), shadow rays are not traced one by one: each contribution's ray is
    // appended here and the contribution returned unoccluded; the caller traces the batch
    // (TraceScene::traceBatch) and multiplies each contribution by its ray's transmission.
    std::vector<ShadowRay>* deferredRays = nullptr;
    // Shadow groups that may block this receiver's rays (TraceScene::receiverMask).
    uint32_t rayMask = kAllShadowGroups;
    // The caller knows that no segment from its receivers to the lights it asks about enters
    // structural solid (BspTree::hullClearOfSolid), so rays skip that walk.
    bool clearOfSolid = false;
};

// Whether area light `light` surely lights no luxel or grid point inside `box`, so a caller may
// skip the box at once: the box lies behind a one-sided emitter, or the per-point
// formFactorUpperBound test, taken over the whole box (with room for the push of points near the
// emitter's plane), finds no more than the -fast tolerance. `receiverNormal`, when every point of
// the box is a sample with that normal, also bounds the receiver's cosine.
bool areaLightSurelyDarkIn(const Light& light, const Bounds& box, const ContributionSettings& settings,
                           const Vec3* receiverNormal = nullptr);

// Whether the visibility data rule out any light of `light` at a point of `cluster`: a cluster that
// cannot see the light's cluster, or a sun whose sky the cluster cannot see.
bool pvsCulled(const Light& light, int cluster, const LightingEnv& env);

// Controlled-model terms (specs/light-models.md).
float controlledFalloff(const ControlledParams& p, float distance);
float controlledCone(const ControlledParams& p, Vec3 spotAxis, Vec3 towardsLight);
float controlledIncidence(const ControlledParams& p, float cosine);

// Light reaching a luxel or vertex; nullopt when none does.
std::optional<LightContribution> lightToSample(const Light& light, const SamplePoint& sample, const LightingEnv& env);
// Light reaching a grid point (no surface, no angle term).
std::optional<LightContribution> lightToGridPoint(const Light& light, Vec3 origin, int cluster,
                                                  const LightingEnv& env);
// The same with the light's lightEnvelope already known (loops over many samples ask once).
std::optional<LightContribution> lightToSample(const Light& light, const SamplePoint& sample, const LightingEnv& env,
                                               float envelope);
std::optional<LightContribution> lightToGridPoint(const Light& light, Vec3 origin, int cluster,
                                                  const LightingEnv& env, float envelope);

// Whether lightToSamples takes `light` for `env`: a point, spot or area light of q3map2's model
// that lights surfaces, with shadow rays deferred (env.deferredRays and a scene) and no -sunonly.
bool samplesBatchable(const Light& light, const LightingEnv& env);
// lightToSample for the samples points[i], i in `which` (all set), of one light that
// samplesBatchable takes: out[i] (and dirs[i] when given) receives each contribution before
// occlusion and is left alone where there is none; the index of each deferred ray's sample is
// appended to `traced`, in the order of the rays. One PVS lookup serves a run of samples in one
// cluster.
void lightToSamples(const Light& light, const LightingEnv& env, float envelope,
                    std::span<const std::optional<SamplePoint>> points, std::span<const uint32_t> which,
                    std::span<Vec3> out, Vec3* dirs, std::vector<size_t>& traced);

// The same for grid points (lightToGridPoint): for the points origins[p], p in `which`, of a light
// that gridPointsBatchable takes (any but a sun or a controlled light), out[p] receives each
// contribution before occlusion and rayOf[p] the index of its deferred ray; both are left alone
// where there is none.
bool gridPointsBatchable(const Light& light, const LightingEnv& env);
void lightToGridPoints(const Light& light, const LightingEnv& env, float envelope, std::span<const Vec3> origins,
                       std::span<const int> clusters, std::span<const uint32_t> which,
                       std::span<std::optional<LightContribution>> out, std::span<int32_t> rayOf);

// Every contribution of `lights` to a sample / grid point, in light order.
void gatherSampleLight(std::span<const Light> lights, const SamplePoint& sample, const LightingEnv& env,
                       std::vector<LightContribution>& out);
void gatherGridLight(std::span<const Light> lights, Vec3 origin, int cluster, const LightingEnv& env,
                     std::vector<LightContribution>& out);

}  // namespace q3::light
