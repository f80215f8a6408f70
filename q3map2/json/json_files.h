// File and member names of the JSON folder: q3map2's, plus ours for what q3map2 has no file for.
#pragma once

namespace q3::json::files {

constexpr const char* kShaders = "shaders.json";
constexpr const char* kModels = "models.json";
constexpr const char* kPlanes = "planes.json";
constexpr const char* kLeafs = "leafs.json";
constexpr const char* kNodes = "nodes.json";
constexpr const char* kLeafSurfaces = "LeafSurfaces.json";
constexpr const char* kLeafBrushes = "LeafBrushes.json";
constexpr const char* kBrushes = "Brushes.json";
constexpr const char* kBrushSides = "BrushSides.json";
constexpr const char* kDrawVerts = "DrawVert.json";
constexpr const char* kDrawSurfaces = "DrawSurfaces.json";
constexpr const char* kFogs = "fogs.json";
constexpr const char* kDrawIndexes = "DrawIndexes.json";
constexpr const char* kVisBytes = "VisBytes.json";
constexpr const char* kLightBytes = "LightBytes.json";
constexpr const char* kEntities = "entities.json";
constexpr const char* kGridPoints = "GridPoints.json";
// Ours.
constexpr const char* kGridPointsSH = "GridPointsSH.json";
constexpr const char* kHeader = "Header.json";              // version, lump entries, SH carrier
constexpr const char* kAdvertisements = "Advertisements.json";
constexpr const char* kLump17Bytes = "Lump17Bytes.json";    // lump 17 that is not advertisement records
constexpr const char* kBspxLumps = "BSPXLumps.json";
constexpr const char* kEntityText = "EntityText.json";      // exact entity lump, when it is not canonical
constexpr const char* kLightmapImages = "LightmapImages.json";

}  // namespace q3::json::files
