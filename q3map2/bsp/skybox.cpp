#include "skybox.h"

#include <cstdio>

#include "script.h"

namespace q3::bspstage {

std::optional<ModelTransform> skyboxTransform(const std::vector<BspEntity>& entities) {
    std::optional<ModelTransform> out;
    for (size_t i = 1; i < entities.size(); ++i) {
        const BspEntity& e = entities[i];
        if (!e.isPointEntity() || !equalsNoCase(e.classname, "_skybox") || !e.source) continue;
        const map::MapEntity& source = *e.source;
        Vec3 origin{0, 0, 0};
        std::sscanf(source.value("origin").c_str(), "%f %f %f", &origin.x, &origin.y, &origin.z);
        // _scale: three factors, or one for all axes; 64 when missing.
        Vec3 scale = Vec3::splat(64);
        if (const std::string* s = source.find("_scale")) {
            Vec3 three;
            if (std::sscanf(s->c_str(), "%f %f %f", &three.x, &three.y, &three.z) == 3)
                scale = three;
            else if (float one; std::sscanf(s->c_str(), "%f", &one) == 1)
                scale = Vec3::splat(one);
        }
        float pitch = 0, yaw = 0, roll = 0;
        if (const std::string* a = source.find("angles"))
            std::sscanf(a->c_str(), "%f %f %f", &pitch, &yaw, &roll);
        else if (const std::string* a = source.find("angle"))
            std::sscanf(a->c_str(), "%f", &yaw);
        out = ModelTransform::skybox(origin, pitch, yaw, roll, scale);
    }
    return out;
}

DrawSurface skyboxCopy(const DrawSurface& ds, const ModelTransform& transform) {
    DrawSurface copy = ds;
    for (bsp::DrawVert& v : copy.verts) transform.point(xyzOf(v)).toArray(v.xyz);
    copy.planeNormal = {0, 0, 0};
    copy.skybox = false;
    copy.skyboxCopy = true;
    copy.parentSurface = ds.outputNum;
    copy.outputNum = -1;
    return copy;
}

}  // namespace q3::bspstage
