// The comparison as JSON (for scripts) and as a short text summary (for people).
#include <cmath>
#include <cstdio>
#include <sstream>

#include "light_compare.h"

namespace q3::conformance {
namespace {

std::string number(double v) {
    if (!std::isfinite(v)) return "null";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", v);
    return buf;
}

std::string quoted(const std::string& s) {
    std::string out = "\"";
    for (char c : s) {
        if (c == '"' || c == '\\') out += '\\';
        if (static_cast<unsigned char>(c) < 0x20) {
            char buf[8];
            std::snprintf(buf, sizeof buf, "\\u%04x", c);
            out += buf;
            continue;
        }
        out += c;
    }
    return out + "\"";
}

const char* typeName(int type) {
    switch (type) {
        case bsp::MST_PLANAR: return "planar";
        case bsp::MST_PATCH: return "patch";
        case bsp::MST_TRIANGLE_SOUP: return "soup";
        case bsp::MST_FLARE: return "flare";
        default: return "bad";
    }
}

std::string gridStatsJson(const GridStats& g) {
    std::ostringstream o;
    o << "{\"points\": " << g.points << ", \"ambientRatio\": " << number(g.ambientRatio)
      << ", \"directedRatio\": " << number(g.directedRatio) << ", \"ambientCorrelation\": " << number(g.ambientCorrelation)
      << ", \"directedCorrelation\": " << number(g.directedCorrelation) << ", \"directionPoints\": " << g.directionPoints
      << ", \"directionFraction\": " << number(g.directionFraction) << "}";
    return o.str();
}

// "1.0123 (+1.2 %)" or "n/a".
std::string ratioText(double r) {
    if (!std::isfinite(r)) return "n/a";
    char buf[48];
    std::snprintf(buf, sizeof buf, "%.4f (%+.1f %%)", r, (r - 1) * 100);
    return buf;
}

std::string fixed(double v, int digits = 4) {
    if (!std::isfinite(v)) return "n/a";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.*f", digits, v);
    return buf;
}

}  // namespace

std::string toJson(const Comparison& c) {
    const LightmapFigures& lm = c.lightmaps;
    std::ostringstream o;
    o << "{\n  \"reference\": " << quoted(c.referenceName) << ",\n  \"ours\": " << quoted(c.oursName) << ",\n";
    o << "  \"lightmaps\": {\"referencePages\": " << lm.referencePages << ", \"oursPages\": " << lm.oursPages
      << ", \"referenceLit\": " << lm.referenceLit << ", \"oursLit\": " << lm.oursLit << ", \"bothLit\": " << lm.bothLit
      << ", \"referenceOnly\": " << lm.referenceOnly << ", \"oursOnly\": " << lm.oursOnly
      << ",\n    \"referenceTotal\": " << number(lm.referenceTotal) << ", \"oursTotal\": " << number(lm.oursTotal)
      << ", \"ratio\": " << number(lm.ratio) << ", \"correlation\": " << number(lm.correlation)
      << ", \"medianReference\": " << number(lm.medianReference) << ",\n    \"repeatable\": " << lm.repeatable << ", \"hiddenSurfaces\": " << lm.hiddenSurfaces
      << ", \"repeatableRatio\": " << number(lm.repeatable >= 0 ? lm.repeatableRatio : NAN)
      << ", \"repeatableCorrelation\": " << number(lm.repeatable >= 0 ? lm.repeatableCorrelation : NAN)
      << ",\n    \"classes\": [";
    for (size_t i = 0; i < lm.classes.size(); ++i) {
        const ClassFigures& k = lm.classes[i];
        o << (i ? ",\n      " : "\n      ") << "{\"name\": " << quoted(k.name) << ", \"measured\": "
          << (k.measured ? "true" : "false") << ", \"surfaces\": " << k.surfaces << ", \"referenceSum\": "
          << number(k.referenceSum) << ", \"oursSum\": " << number(k.oursSum) << ", \"ratio\": " << number(k.ratio) << "}";
    }
    o << "],\n    \"worst\": [";
    for (size_t i = 0; i < lm.worst.size(); ++i) {
        const SurfaceFigures& w = lm.worst[i];
        o << (i ? ",\n      " : "\n      ") << "{\"surface\": " << w.surface << ", \"shader\": " << quoted(w.shader)
          << ", \"type\": \"" << typeName(w.surfaceType) << "\", \"area\": " << number(w.area)
          << ", \"referenceLit\": " << (w.referenceLit ? "true" : "false") << ", \"oursLit\": "
          << (w.oursLit ? "true" : "false") << ", \"referenceRepeats\": " << (w.referenceRepeats ? "true" : "false")
          << ", \"referenceMean\": " << number(w.referenceMean)
          << ", \"oursMean\": " << number(w.oursMean) << "}";
    }
    o << "]},\n";
    const VertexFigures& v = c.vertexes;
    o << "  \"vertexes\": {\"surfaces\": " << v.surfaces << ", \"vertexes\": " << v.vertexes << ", \"referenceSum\": "
      << number(v.referenceSum) << ", \"oursSum\": " << number(v.oursSum) << ", \"ratio\": " << number(v.ratio)
      << ", \"correlation\": " << number(v.correlation) << "},\n";
    const GridFigures& g = c.grid;
    o << "  \"grid\": {\"referencePoints\": " << g.referencePoints << ", \"oursPoints\": " << g.oursPoints
      << ", \"countsMatch\": " << (g.countsMatch ? "true" : "false") << ", \"masked\": " << (g.masked ? "true" : "false")
      << ",\n    \"all\": " << gridStatsJson(g.all) << ",\n    \"agreed\": "
      << (g.masked ? gridStatsJson(g.agreed) : std::string("null")) << "},\n";
    o << "  \"notes\": [";
    for (size_t i = 0; i < c.notes.size(); ++i) o << (i ? ", " : "") << quoted(c.notes[i]);
    o << "]\n}\n";
    return o.str();
}

std::string toText(const Comparison& c, int worstShown) {
    const LightmapFigures& lm = c.lightmaps;
    std::ostringstream o;
    o << "reference " << c.referenceName << "\nours      " << c.oursName << "\n\n";
    o << "lightmaps: pages reference " << lm.referencePages << ", ours " << lm.oursPages << "; surfaces lightmapped: "
      << "reference " << lm.referenceLit << ", ours " << lm.oursLit << ", both " << lm.bothLit << ", reference only "
      << lm.referenceOnly << ", ours only " << lm.oursOnly << "\n";
    o << "  total ratio " << ratioText(lm.ratio) << ", per-surface correlation " << fixed(lm.correlation)
      << ", median reference mean " << fixed(lm.medianReference, 1) << "\n";
    if (lm.hiddenSurfaces > 0)
        o << "  " << lm.hiddenSurfaces << " surfaces lie entirely against solid and are left out (texels against solid are, everywhere)\n";
    if (lm.repeatable >= 0)
        o << "  over the " << lm.repeatable << " surfaces the second reference run repeats: ratio "
          << ratioText(lm.repeatableRatio) << ", correlation " << fixed(lm.repeatableCorrelation) << "\n";
    for (const ClassFigures& k : lm.classes) {
        char line[160];
        if (!k.measured) std::snprintf(line, sizeof line, "    %-11s not measured\n", k.name.c_str());
        else
            std::snprintf(line, sizeof line, "    %-11s %5d surfaces  ratio %s\n", k.name.c_str(), k.surfaces,
                          ratioText(k.ratio).c_str());
        o << line;
    }
    const VertexFigures& v = c.vertexes;
    o << "vertex colours (" << v.surfaces << " vertex-lit surfaces, " << v.vertexes << " vertexes): ratio "
      << ratioText(v.ratio) << ", correlation " << fixed(v.correlation) << "\n";
    const GridFigures& g = c.grid;
    o << "grid: points reference " << g.referencePoints << ", ours " << g.oursPoints << "\n";
    auto gridLine = [&](const char* label, const GridStats& s) {
        o << "  " << label << " (" << s.points << " points): ambient " << ratioText(s.ambientRatio) << " corr "
          << fixed(s.ambientCorrelation) << "; directed " << ratioText(s.directedRatio) << " corr "
          << fixed(s.directedCorrelation) << "; direction within 15 deg " << fixed(s.directionFraction * 100, 1)
          << " % of " << s.directionPoints << "\n";
    };
    if (g.countsMatch) {
        if (g.masked) gridLine("agreed", g.agreed);
        gridLine("all   ", g.all);
    }
    for (const std::string& note : c.notes) o << "note: " << note << "\n";
    if (!lm.worst.empty() && worstShown > 0) {
        o << "\nworst surfaces (surface, type, area, shader: reference mean -> ours mean; ~ the reference does not "
             "repeat it):\n";
        for (int i = 0; i < std::min<int>(worstShown, int(lm.worst.size())); ++i) {
            const SurfaceFigures& w = lm.worst[i];
            char line[320];
            std::snprintf(line, sizeof line, "  %6d %-6s %9.0f  %-48s %7s -> %-7s%s\n", w.surface,
                          typeName(w.surfaceType), w.area, w.shader.c_str(),
                          w.referenceLit ? fixed(w.referenceMean, 1).c_str() : "unlit",
                          w.oursLit ? fixed(w.oursMean, 1).c_str() : "unlit", w.referenceRepeats ? "" : " ~");
            o << line;
        }
    }
    return o.str();
}

}  // namespace q3::conformance
