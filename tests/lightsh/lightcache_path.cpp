// lightcachepath: a PNG of a straight path through a map, one column per position and three rows:
// brute force, the SH grid alone, the SH grid plus the light cache (lightcache_compare.h); prints
// each position's mean error of the two against brute force.
//   lightcachepath MAP.bsp MAP.map OUT.png X1 Y1 Z1 X2 Y2 Z2 [POSITIONS [BASEPATH GAME]]
#include <cstdio>
#include <cstdlib>
#include <string>

#include "file_io.h"
#include "lightcache_compare.h"

namespace {

bool number(const char* text, float& out) {
    char* end = nullptr;
    out = std::strtof(text, &end);
    return end != text && *end == 0 && std::isfinite(out);
}

}  // namespace

int main(int argc, char** argv) {
    using namespace q3;
    using namespace q3::light::cachetest;
    if (argc != 10 && argc != 11 && argc != 13) {
        std::fprintf(stderr, "usage: lightcachepath MAP.bsp MAP.map OUT.png X1 Y1 Z1 X2 Y2 Z2 [POSITIONS [BASEPATH GAME]]\n");
        return 2;
    }
    float c[6];
    for (int i = 0; i < 6; ++i)
        if (!number(argv[4 + i], c[i])) {
            std::fprintf(stderr, "lightcachepath: coordinate \"%s\" is not a number\n", argv[4 + i]);
            return 2;
        }
    const int count = argc >= 11 ? std::atoi(argv[10]) : 32;
    if (count < 2 || count > 512) {
        std::fprintf(stderr, "lightcachepath: positions must be 2..512\n");
        return 2;
    }
    MapInputs in{argv[1], argv[2], {}, ""};
    if (argc == 13) {
        in.basePaths.push_back(argv[11]);
        in.fsGame = argv[12];
    }
    try {
        const LitMap map(in, std::filesystem::temp_directory_path() / "lightcachepath");
        if (!map.error().empty()) {
            std::fprintf(stderr, "lightcachepath: %s\n", map.error().c_str());
            return 1;
        }
        const Vec3 from{c[0], c[1], c[2]}, to{c[3], c[4], c[5]};
        std::vector<Vec3> positions;
        for (int i = 0; i < count; ++i) positions.push_back(from + (to - from) * (float(i) / float(count - 1)));
        const std::vector<Vec3> normals = fibonacciNormals(48);
        double alone = 0, cached = 0;
        for (const Vec3& p : positions) {
            const LitMap::Errors e = map.errorsAt(p, normals);
            alone += e.shAlone;
            cached += e.withCache;
            std::printf("%8.1f %8.1f %8.1f  brute force %.4f  error: SH alone %.4f, SH + cache %.4f%s\n", p.x, p.y, p.z,
                        e.truthScale, e.shAlone, e.withCache, map.open(p) ? "" : "  (in solid)");
        }
        std::printf("mean error over %d positions: SH alone %.4f, SH + cache %.4f\n", count, alone / count,
                    cached / count);
        writeFileAtomic(argv[3], encodePng(renderPathPicture(map, positions, 32, 2.0f), false));
        std::printf("wrote %s (rows: brute force, SH alone, SH + light cache)\n", argv[3]);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "lightcachepath: %s\n", e.what());
        return 1;
    }
    return 0;
}
