#include "draw_surface.h"

namespace q3::bspstage {

std::string_view surfaceKindName(SurfaceKind kind) {
    switch (kind) {
        case SurfaceKind::Bad: return "ESurfaceType::Bad";
        case SurfaceKind::Face: return "ESurfaceType::Face";
        case SurfaceKind::Patch: return "ESurfaceType::Patch";
        case SurfaceKind::Triangles: return "ESurfaceType::Triangles";
        case SurfaceKind::Flare: return "ESurfaceType::Flare";
        case SurfaceKind::Foliage: return "ESurfaceType::Foliage";
        case SurfaceKind::ForcedMeta: return "ESurfaceType::ForcedMeta";
        case SurfaceKind::Meta: return "ESurfaceType::Meta";
        case SurfaceKind::Foghull: return "ESurfaceType::Foghull";
        case SurfaceKind::Decal: return "ESurfaceType::Decal";
        case SurfaceKind::Shader: return "ESurfaceType::Shader";
    }
    return "ESurfaceType::Bad";
}

}  // namespace q3::bspstage
