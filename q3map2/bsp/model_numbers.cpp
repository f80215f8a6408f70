#include "model_numbers.h"

#include <cstdlib>

namespace q3::bspstage {
namespace {

bool hasGeometry(const BspEntity& e) { return !e.brushes.empty() || !e.patches.empty(); }

// The clone key, in q3map2's order of preference, or nullptr.
const std::string* cloneTarget(const BspEntity& e) {
    for (const char* key : {"_ins", "_instance", "_clone"})
        if (const std::string* v = e.source->find(key)) return v;
    return nullptr;
}

}  // namespace

void numberModels(LoadedMap& map, bool resolveClones, Log& log) {
    int next = 1;
    for (size_t i = 1; i < map.entities.size(); ++i) {
        BspEntity& e = map.entities[i];
        if (!hasGeometry(e) || (resolveClones && cloneTarget(e))) continue;
        e.model = "*" + std::to_string(next++);
    }
    if (!resolveClones) return;
    for (size_t i = 1; i < map.entities.size(); ++i) {
        BspEntity& clone = map.entities[i];
        const std::string* target = hasGeometry(clone) ? cloneTarget(clone) : nullptr;
        if (!target) continue;
        // q3map2 walks every entity, so the last one of that name wins.
        for (const BspEntity& parent : map.entities) {
            const std::string* name = parent.source->find("_clonename");
            if (!name || *name != *target) continue;
            const std::string model = !parent.model.empty() ? parent.model : parent.source->value("model");
            if (model.empty()) {
                log.warning("Cloned entity " + *name + " referenced entity without model");
                continue;
            }
            clone.model = "*" + std::to_string(std::atoi(model.c_str() + 1));
            clone.brushes.clear();
            clone.patches.clear();
        }
    }
}

}  // namespace q3::bspstage
