// The lumps the world structure fills, against q3map2 2.5.17n's BSP of the same .map: nodes
// (plane values, children, bounds), leafs (cluster, area, bounds, leaf brush lists), brushes and
// sides (shader names and flags, plane values), models (brush ranges, world bounds) and the entity
// lump text.
//
// Planes are compared by value, not index: q3map2 creates planes for planar patches before the
// world tree, which shifts the indices of later planes. Node and leaf bounds must be equal. Brush
// model bounds are not compared: q3map2 grows them with the vertices of their draw surfaces, which
// do not exist here yet.
//
// Known differences:
// - edge bevels: on some brushes q3map2 adds the same edge bevels in another order (reported, not
//   failed; distances may differ by one float step, so they are matched within 0.02), and on a
//   few (at most 0.5 % of the brushes) one bevel differs or is missing. Which edge q3map2 visits
//   first is not understood yet; collision does not depend on the order.
// - side shaders: q3map2 re-points a side to the shader of the draw surface made from it
//   (FixBrushSides); without draw surfaces ours keep their own (at most 0.05 % of the sides).
// Everything else must match.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include "bsp_reference.h"
#include "log.h"
#include "map_file.h"
#include "reference_fixture.h"
#include "structure_emit.h"
#include "test_data.h"

namespace q3::bspstage {
namespace {

namespace fs = std::filesystem;

// Differences by kind, with the first few of each so that a failure shows where things went apart.
struct Differences {
    struct Kind {
        int count = 0;
        std::vector<std::string> examples;
    };
    std::map<std::string, Kind> kinds;
    void add(const std::string& kind, const std::string& what) {
        Kind& k = kinds[kind];
        if (++k.count <= 8) k.examples.push_back(what);
    }
    void add(const std::string& what) { add("structure", what); }
    int count(const std::string& kind) const {
        auto it = kinds.find(kind);
        return it == kinds.end() ? 0 : it->second.count;
    }
    std::string report(const std::string& kind) const {
        std::ostringstream s;
        s << count(kind) << " " << kind << " differences";
        if (auto it = kinds.find(kind); it != kinds.end())
            for (const std::string& d : it->second.examples) s << "\n  " << d;
        return s.str();
    }
};

bool samePlane(const bsp::Plane& a, const bsp::Plane& b) {
    for (int i = 0; i < 3; ++i)
        if (std::fabs(a.normal[i] - b.normal[i]) > 1e-5f) return false;
    return std::fabs(a.dist - b.dist) <= 1e-3f;
}

bool sameBounds(const int32_t* a, const int32_t* b) { return std::equal(a, a + 3, b); }

std::string shaderName(const bsp::Bsp& b, int index) { return b.shaders.at(size_t(index)).name; }

void compareNodesAndLeafs(const bsp::Bsp& ours, const bsp::Bsp& ref, Differences& d) {
    if (ours.nodes.size() != ref.nodes.size()) d.add("nodes " + std::to_string(ours.nodes.size()) + " / " + std::to_string(ref.nodes.size()));
    for (size_t i = 0; i < std::min(ours.nodes.size(), ref.nodes.size()); ++i) {
        const bsp::Node &a = ours.nodes[i], &b = ref.nodes[i];
        if (!samePlane(ours.planes.at(size_t(a.planeNum)), ref.planes.at(size_t(b.planeNum))))
            d.add("node " + std::to_string(i) + " plane");
        if (a.children[0] != b.children[0] || a.children[1] != b.children[1]) d.add("node " + std::to_string(i) + " children");
        if (!sameBounds(a.mins, b.mins) || !sameBounds(a.maxs, b.maxs)) d.add("node " + std::to_string(i) + " bounds");
    }
    if (ours.leafs.size() != ref.leafs.size()) d.add("leafs " + std::to_string(ours.leafs.size()) + " / " + std::to_string(ref.leafs.size()));
    for (size_t i = 0; i < std::min(ours.leafs.size(), ref.leafs.size()); ++i) {
        const bsp::Leaf &a = ours.leafs[i], &b = ref.leafs[i];
        const std::string leaf = "leaf " + std::to_string(i);
        if (a.cluster != b.cluster || a.area != b.area)
            d.add(leaf + " cluster/area " + std::to_string(a.cluster) + "/" + std::to_string(a.area) + " vs " +
                  std::to_string(b.cluster) + "/" + std::to_string(b.area));
        if (!sameBounds(a.mins, b.mins) || !sameBounds(a.maxs, b.maxs)) d.add(leaf + " bounds");
        const std::vector<int32_t> la(ours.leafBrushes.begin() + a.firstLeafBrush,
                                      ours.leafBrushes.begin() + a.firstLeafBrush + a.numLeafBrushes);
        const std::vector<int32_t> lb(ref.leafBrushes.begin() + b.firstLeafBrush,
                                      ref.leafBrushes.begin() + b.firstLeafBrush + b.numLeafBrushes);
        if (la != lb) d.add(leaf + " brushes");
    }
}

bool isBevel(const bsp::Bsp& b, const bsp::BrushSide& side) { return shaderName(b, side.shaderNum) == "noshader"; }

bool sameBevelPlane(const bsp::Plane& a, const bsp::Plane& b) {
    for (int i = 0; i < 3; ++i)
        if (std::fabs(a.normal[i] - b.normal[i]) > 1e-5f) return false;
    return std::fabs(a.dist - b.dist) <= 0.02f;
}

// Sides 0-5 and the brush's own sides must match in order; edge bevels only as a set (see the
// file comment). Returns true when the edge bevels match but in another order.
bool compareBrushSides(const bsp::Bsp& ours, const bsp::Bsp& ref, const bsp::Brush& a, const bsp::Brush& b,
                       const std::string& brush, Differences& d) {
    std::vector<bsp::Plane> bevelsA, bevelsB;
    for (int k = 0; k < a.numSides; ++k) {
        const bsp::BrushSide& sa = ours.brushSides.at(size_t(a.firstSide + k));
        const bsp::BrushSide& sb = ref.brushSides.at(size_t(b.firstSide + k));
        const bsp::Plane &pa = ours.planes.at(size_t(sa.planeNum)), &pb = ref.planes.at(size_t(sb.planeNum));
        if (k >= 6 && isBevel(ours, sa) && isBevel(ref, sb)) {
            bevelsA.push_back(pa);
            bevelsB.push_back(pb);
            continue;
        }
        if (!samePlane(pa, pb)) d.add(brush + " side " + std::to_string(k) + " plane");
        const bsp::Shader &ha = ours.shaders.at(size_t(sa.shaderNum)), &hb = ref.shaders.at(size_t(sb.shaderNum));
        if (std::string(ha.name) != hb.name || ha.surfaceFlags != hb.surfaceFlags || ha.contentFlags != hb.contentFlags)
            d.add("side shader", brush + " side " + std::to_string(k) + " " + ha.name + " vs " + hb.name);
    }
    bool reordered = false, missing = false;
    for (size_t k = 0; k < bevelsA.size(); ++k) {
        if (sameBevelPlane(bevelsA[k], bevelsB[k])) continue;
        reordered = true;
        auto match = std::find_if(bevelsB.begin(), bevelsB.end(), [&](const bsp::Plane& p) { return sameBevelPlane(bevelsA[k], p); });
        missing |= match == bevelsB.end();
    }
    if (missing) d.add("edge bevel", brush + ": an edge bevel of ours is not among q3map2's");
    return reordered && !missing;
}

// Returns the number of brushes whose edge bevels come in another order.
int compareBrushes(const bsp::Bsp& ours, const bsp::Bsp& ref, Differences& d) {
    if (ours.brushes.size() != ref.brushes.size()) d.add("brushes " + std::to_string(ours.brushes.size()) + " / " + std::to_string(ref.brushes.size()));
    int reordered = 0;
    for (size_t i = 0; i < std::min(ours.brushes.size(), ref.brushes.size()); ++i) {
        const bsp::Brush &a = ours.brushes[i], &b = ref.brushes[i];
        const std::string brush = "brush " + std::to_string(i);
        if (shaderName(ours, a.shaderNum) != shaderName(ref, b.shaderNum))
            d.add(brush + " shader " + shaderName(ours, a.shaderNum) + " vs " + shaderName(ref, b.shaderNum));
        if (a.numSides != b.numSides) {
            d.add("edge bevel", brush + " sides " + std::to_string(a.numSides) + " / " + std::to_string(b.numSides));
            continue;
        }
        if (compareBrushSides(ours, ref, a, b, brush, d)) ++reordered;
    }
    return reordered;
}

void compareModels(const bsp::Bsp& ours, const bsp::Bsp& ref, Differences& d) {
    if (ours.models.size() != ref.models.size()) d.add("models " + std::to_string(ours.models.size()) + " / " + std::to_string(ref.models.size()));
    for (size_t i = 0; i < std::min(ours.models.size(), ref.models.size()); ++i) {
        const bsp::Model &a = ours.models[i], &b = ref.models[i];
        if (a.firstBrush != b.firstBrush || a.numBrushes != b.numBrushes) d.add("model " + std::to_string(i) + " brushes");
        if (i == 0)
            for (int k = 0; k < 3; ++k)
                if (std::fabs(a.mins[k] - b.mins[k]) > 1 || std::fabs(a.maxs[k] - b.maxs[k]) > 1) d.add("world bounds");
    }
}

class StructureEmit : public conformance::ReferenceTest<fs::path> {};

TEST_P(StructureEmit, LumpsMatchQ3map2) {
    const fs::path mapSource = GetParam();
    const std::string name = mapSource.stem().string();
    const fs::path folder = test::referenceCompile(reference(), mapSource);
    const bsp::Bsp ref = bsp::readBsp(folder / (name + ".bsp"));

    Log log(false);
    const map::MapFile file = map::loadMap(mapSource);
    LoadedMap map = loadMapForBsp(file, test::openArenaShaders(), {}, log);
    WorldStructure world = buildWorldStructure(map, {}, log);
    EntityLumpOptions entityOptions;
    entityOptions.stageArgs = {"-meta"};
    const bsp::Bsp ours = emitStructure(map, world, test::openArenaShaders(), entityOptions);
    EXPECT_NO_THROW(bsp::validateBsp(ours, name));

    Differences d;
    compareNodesAndLeafs(ours, ref, d);
    const int reorderedBevels = compareBrushes(ours, ref, d);
    compareModels(ours, ref, d);
    if (ours.entities != ref.entities) d.add("entity lump text");
    std::printf("%-10s nodes %5zu / %5zu  leafs %5zu / %5zu  brushes %5zu / %5zu  sides %6zu / %6zu  leafbrushes %6zu / %6zu  "
                "(ours / q3map2); edge bevels in another order on %d brushes\n",
                name.c_str(), ours.nodes.size(), ref.nodes.size(), ours.leafs.size(), ref.leafs.size(), ours.brushes.size(),
                ref.brushes.size(), ours.brushSides.size(), ref.brushSides.size(), ours.leafBrushes.size(),
                ref.leafBrushes.size(), reorderedBevels);
    EXPECT_EQ(d.count("structure"), 0) << d.report("structure");
    // Tolerances (see the file comment): edge bevels on 0.5 % of the brushes, side shaders on
    // 0.05 % of the sides (at least 2 and 1 of them).
    EXPECT_LE(d.count("edge bevel"), std::max<int>(2, int(ref.brushes.size() / 200))) << d.report("edge bevel");
    EXPECT_LE(d.count("side shader"), std::max<int>(1, int(ref.brushSides.size() / 2000))) << d.report("side shader");
}

std::string mapName(const ::testing::TestParamInfo<fs::path>& info) { return info.param.stem().string(); }

INSTANTIATE_TEST_SUITE_P(Oacmp, StructureEmit, ::testing::ValuesIn(q3::test::oacmpMapSourcesForRegistration()), mapName);

}  // namespace
}  // namespace q3::bspstage
