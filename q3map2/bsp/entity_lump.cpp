#include "entity_lump.h"

#include <cstdio>

#include "script.h"

namespace q3::bspstage {
namespace {

bool isTrue(const bsp::Entity& e, std::string_view key) {
    const std::string* v = e.find(key);
    return v && std::atoi(v->c_str()) != 0;
}

std::string formatOrigin(const DVec3& o) {
    char text[128];
    std::snprintf(text, sizeof text, "%f %f %f", float(o.x), float(o.y), float(o.z));
    return text;
}

}  // namespace

std::string commandLineValue(const std::string& previous, const std::vector<std::string>& stageArgs) {
    std::string out = previous;
    if (!out.empty()) out += "; ";
    out += "-bsp";
    for (const std::string& arg : stageArgs) {
        out += ' ';
        for (char c : arg)
            if (c != '\\' && c != '"' && c != ';' && static_cast<unsigned char>(c) >= ' ') out += c;
    }
    return out;
}

std::vector<bsp::Entity> bspEntities(const LoadedMap& map, const EntityLumpOptions& options) {
    std::vector<bsp::Entity> out;
    bool keepLights = options.keepLights, keepModels = options.keepModels;
    for (size_t i = 0; i < map.entities.size(); ++i) {
        const BspEntity& e = map.entities[i];
        bsp::Entity entity;
        for (const auto& [key, value] : e.source->pairs)
            if (!key.empty() && !value.empty()) entity.pairs.emplace_back(key, value);
        if (i == 0) {
            if (options.recordCommandLine) {
                entity.set("_q3map2_cmdline", commandLineValue(entity.value("_q3map2_cmdline"), options.stageArgs));
                entity.set("_q3map2_version", options.version);
            }
            if (options.keepLights) entity.set("_keepLights", "1");
            if (options.keepModels) entity.set("_keepModels", "1");
            keepLights = isTrue(entity, "_keepLights");
            keepModels = isTrue(entity, "_keepModels");
        } else {
            if (e.hasOriginBrush) entity.set("origin", formatOrigin(e.origin));
            if (!e.model.empty()) entity.set("model", e.model);
        }
        const std::string_view classname = entity.classname();
        if (i > 0 && !keepLights && classname.size() >= 5 && equalsNoCase(classname.substr(0, 5), "light")) continue;
        if ((equalsNoCase(classname, "misc_model") && !keepModels) || equalsNoCase(classname, "_decal") ||
            equalsNoCase(classname, "_skybox"))
            continue;
        out.push_back(std::move(entity));
    }
    return out;
}

}  // namespace q3::bspstage
