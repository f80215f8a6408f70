#include "lightmap_export.h"

#include <cmath>
#include <cstdio>

#include "file_io.h"
#include "light_context.h"
#include "light_text.h"
#include "lightmap_pack.h"

namespace q3::light {

std::string exportedLightmapName(int index, const std::string& extension) {
    char name[64];
    std::snprintf(name, sizeof(name), "lightmap_%04d.%s", index, extension.c_str());
    return name;
}

std::filesystem::path lightmapExportDir(const std::filesystem::path& bspPath) {
    std::filesystem::path dir = bspPath;
    dir.replace_extension();
    return dir;
}

std::vector<std::span<const uint8_t>> lumpPages(const bsp::Bsp& bsp, const std::string& fileName, int size) {
    const size_t pageBytes = static_cast<size_t>(size) * static_cast<size_t>(size) * 3;
    if (bsp.lightmaps.size() % pageBytes != 0)
        throw bsp::BspError(strCat(fileName, ": lightmap lump is ", bsp.lightmaps.size(),
                                   " bytes, not a whole number of ", size, "x", size, " pages"));
    std::vector<std::span<const uint8_t>> pages;
    for (size_t at = 0; at < bsp.lightmaps.size(); at += pageBytes)
        pages.emplace_back(bsp.lightmaps.data() + at, pageBytes);
    return pages;
}

Image pagePicture(std::span<const uint8_t> rgb, int size) {
    Image picture;
    picture.width = picture.height = size;
    picture.rgba.resize(static_cast<size_t>(size) * static_cast<size_t>(size) * 4);
    for (int row = 0; row < size; ++row)
        for (int x = 0; x < size; ++x) {
            const uint8_t* in = &rgb[(static_cast<size_t>(row) * static_cast<size_t>(size) + static_cast<size_t>(x)) * 3];
            uint8_t* out = picture.texel(x, size - 1 - row);
            out[0] = in[0];
            out[1] = in[1];
            out[2] = in[2];
            out[3] = 255;
        }
    return picture;
}

std::vector<uint8_t> pageFromPicture(const Image& picture, int size, const std::string& name) {
    if (picture.width != size || picture.height != size)
        throw ImageError(strCat(name, ": lightmap page is ", picture.width, "x", picture.height, ", expected ", size,
                                "x", size));
    std::vector<uint8_t> rgb(static_cast<size_t>(size) * static_cast<size_t>(size) * 3);
    for (int row = 0; row < size; ++row)
        for (int x = 0; x < size; ++x) {
            const uint8_t* in = picture.texel(x, size - 1 - row);
            uint8_t* out = &rgb[(static_cast<size_t>(row) * static_cast<size_t>(size) + static_cast<size_t>(x)) * 3];
            out[0] = in[0];
            out[1] = in[1];
            out[2] = in[2];
        }
    return rgb;
}

std::vector<std::filesystem::path> exportLightmapPages(const bsp::Bsp& bsp, const std::filesystem::path& dir,
                                                       const std::string& fileName) {
    const auto pages = lumpPages(bsp, fileName);
    std::vector<std::filesystem::path> written;
    if (pages.empty()) return written;
    std::filesystem::create_directories(dir);
    for (size_t i = 0; i < pages.size(); ++i) {
        const std::filesystem::path path = dir / exportedLightmapName(static_cast<int>(i));
        writeFileAtomic(path, encodeTga(pagePicture(pages[i], kGameLightmapSize), false));
        written.push_back(path);
    }
    return written;
}

int importLightmapPages(bsp::Bsp& bsp, const std::filesystem::path& dir, const std::string& fileName, Log& log) {
    const size_t count = lumpPages(bsp, fileName).size();
    const size_t pageBytes = static_cast<size_t>(kGameLightmapSize) * kGameLightmapSize * 3;
    int replaced = 0;
    for (size_t i = 0; i < count; ++i) {
        std::filesystem::path path = dir / exportedLightmapName(static_cast<int>(i), "tga");
        if (!std::filesystem::exists(path)) path = dir / exportedLightmapName(static_cast<int>(i), "png");
        if (!std::filesystem::exists(path)) {
            log.warning(strCat("no ", exportedLightmapName(static_cast<int>(i), "tga"), " or .png in ", dir.string(),
                               ": lightmap page ", i, " kept"));
            continue;
        }
        const std::vector<uint8_t> bytes = readFileBytes(path);
        const Image picture = decodeImage(bytes, path.string());
        const std::vector<uint8_t> rgb = pageFromPicture(picture, kGameLightmapSize, path.string());
        std::copy(rgb.begin(), rgb.end(), bsp.lightmaps.begin() + static_cast<std::ptrdiff_t>(i * pageBytes));
        ++replaced;
    }
    return replaced;
}

Image lightmapAtlas(std::span<const std::vector<uint8_t>> pages, int pageSize) {
    Image atlas;
    if (pages.empty() || pageSize <= 0) return atlas;
    const int n = static_cast<int>(pages.size());
    const int columns = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(n))));
    const int rows = (n + columns - 1) / columns;
    atlas.width = columns * pageSize;
    atlas.height = rows * pageSize;
    if (atlas.width > kMaxImageDimension || atlas.height > kMaxImageDimension)
        throw CompileError(strCat("lightmap atlas of ", n, " pages of ", pageSize, "x", pageSize, " would be ",
                                  atlas.width, "x", atlas.height, " pixels, more than ", kMaxImageDimension));
    atlas.rgba.assign(static_cast<size_t>(atlas.width) * static_cast<size_t>(atlas.height) * 4, 0);
    for (int p = 0; p < n; ++p) {
        const std::vector<uint8_t>& page = pages[static_cast<size_t>(p)];
        const int ox = (p % columns) * pageSize, oy = (p / columns) * pageSize;
        for (int y = 0; y < pageSize; ++y)
            for (int x = 0; x < pageSize; ++x) {
                const size_t at = (static_cast<size_t>(y) * static_cast<size_t>(pageSize) + static_cast<size_t>(x)) * 3;
                uint8_t* out = atlas.texel(ox + x, oy + y);
                if (at + 2 < page.size()) {
                    out[0] = page[at];
                    out[1] = page[at + 1];
                    out[2] = page[at + 2];
                }
                out[3] = 255;
            }
    }
    // Cells with no page stay black but opaque.
    for (size_t i = 3; i < atlas.rgba.size(); i += 4) atlas.rgba[i] = 255;
    return atlas;
}

void exportPackedLightmaps(const LightContext& ctx, const PackedLightmaps& packed, Log& log) {
    const LightOptions& o = ctx.options;
    if (o.exportLightmaps) {
        if (ctx.bsp.lightmaps.empty()) {
            log.warning("-export: no lightmap data in the BSP (external lightmaps are already pictures)");
        } else {
            const std::filesystem::path dir = lightmapExportDir(ctx.bspPath);
            const auto written = exportLightmapPages(ctx.bsp, dir, ctx.bspPath.string());
            log.info(strCat(written.size(), " lightmap pages exported to ", dir.string()));
        }
    }
    if (!o.lightmapAtlas.empty()) {
        const Image atlas = lightmapAtlas(packed.pages, packed.pageSize);
        if (atlas.empty()) {
            log.warning(strCat("-lightmapatlas: no lightmap pages, ", o.lightmapAtlas, " not written"));
        } else {
            writeFileAtomic(o.lightmapAtlas, encodePng(atlas, false));
            log.info(strCat("lightmap atlas (", packed.pages.size(), " pages, ", atlas.width, "x", atlas.height,
                            ") written to ", o.lightmapAtlas));
        }
    }
}

namespace {
std::filesystem::path stageBspPath(const CommonOptions& common) {
    std::filesystem::path path = common.mapPath;
    path.replace_extension(".bsp");
    return path;
}
}  // namespace

int runExportStage(const CommonOptions& common, Log& log) {
    const std::filesystem::path bspPath = stageBspPath(common);
    const bsp::Bsp bsp = bsp::readBsp(bspPath, bsp::ReadOptions{common.force, true});
    if (bsp.lightmaps.empty()) {
        log.warning(strCat(bspPath.string(), ": no lightmap data to export"));
        return 0;
    }
    const std::filesystem::path dir = lightmapExportDir(bspPath);
    const auto written = exportLightmapPages(bsp, dir, bspPath.string());
    for (const auto& path : written) log.info(strCat("wrote ", path.string()));
    return 0;
}

int runImportStage(const CommonOptions& common, Log& log) {
    const std::filesystem::path bspPath = stageBspPath(common);
    bsp::Bsp bsp = bsp::readBsp(bspPath, bsp::ReadOptions{common.force, true});
    if (bsp.lightmaps.empty()) {
        log.warning(strCat(bspPath.string(), ": no lightmap data to import into"));
        return 0;
    }
    const std::filesystem::path dir = lightmapExportDir(bspPath);
    const int replaced = importLightmapPages(bsp, dir, bspPath.string(), log);
    bsp::writeBsp(bspPath, bsp);
    log.info(strCat(replaced, " lightmap pages imported from ", dir.string(), " into ", bspPath.string()));
    return 0;
}

const cli::OptionTable<PictureStageOptions>& pictureStageOptionTable() {
    static const cli::OptionTable<PictureStageOptions> table;
    return table;
}

}  // namespace q3::light
