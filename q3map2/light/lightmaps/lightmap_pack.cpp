#include "lightmap_pack.h"

#include <oneapi/tbb/parallel_for.h>

#include <algorithm>
#include <optional>
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <map>
#include <system_error>
#include <tuple>

#include "file_io.h"
#include "image.h"
#include "log.h"

namespace q3::light {

namespace {

bool texelUsed(const LightmapBlock& b, size_t i) { return b.used.empty() || b.used[i] != 0; }

// q3map2 stores a solid lightmap with the minimum of its colour range.
Rgb8 solidColor(const LightmapBlock& b) {
    Rgb8 low{255, 255, 255};
    bool any = false;
    for (size_t i = 0; i < b.texels.size(); ++i) {
        if (!texelUsed(b, i)) continue;
        any = true;
        for (int c = 0; c < 3; ++c) low[c] = std::min(low[c], b.texels[i][c]);
    }
    return any ? low : Rgb8{0, 0, 0};
}

int usedTexels(const LightmapBlock& b) {
    int n = 0;
    for (size_t i = 0; i < b.texels.size(); ++i) n += texelUsed(b, i);
    return n;
}

// The used texels of a block as runs of columns, row by row.
struct TexelRun {
    int row = 0, first = 0, length = 0;
};

// A page's used texels as one bit each, row by row: a placement test compares a block row with
// a page row a 64-texel word at a time instead of texel by texel.
struct Page {
    std::vector<uint8_t> rgb;
    std::vector<uint8_t> used;
    std::vector<uint64_t> usedBits;  // pageSize rows of wordsPerRow words
    int wordsPerRow = 0;
    int freeTexels = 0;
    // Per row, the longest run of free texels: a block row whose longest run is longer cannot go
    // there, which rules out most of a full page's rows before their columns are compared.
    std::vector<int> longestFree;
    // Sizes of whole rectangles that found no place here when every position was tried. A page
    // only fills up, so no rectangle at least as wide and as tall fits it later either.
    std::vector<std::pair<int, int>> rectanglesRefused;

    bool refuses(int width, int height) const {
        return std::any_of(rectanglesRefused.begin(), rectanglesRefused.end(),
                           [&](const auto& r) { return r.first <= width && r.second <= height; });
    }
};

// True when the runs cover every texel of a width x height block.
bool runsFillRectangle(std::span<const TexelRun> runs, int width, int height) {
    if (runs.size() != size_t(height)) return false;
    return std::all_of(runs.begin(), runs.end(), [&](const TexelRun& r) { return r.first == 0 && r.length == width; });
}

// q3map2 TestOutLightmapStamp for a solid block: it must lie inside the page at its full size,
// and its one texel must be free.
bool solidStampFits(const Page& page, int pageSize, const LightmapBlock& b, int x, int y) {
    if (x < 0 || y < 0 || x + b.width > pageSize || y + b.height > pageSize) return false;
    return !page.used[size_t(y) * pageSize + x];
}

std::vector<TexelRun> texelRuns(const LightmapBlock& b) {
    std::vector<TexelRun> runs;
    for (int sy = 0; sy < b.height; ++sy)
        for (int sx = 0; sx < b.width;) {
            if (!texelUsed(b, size_t(sy) * b.width + sx)) {
                ++sx;
                continue;
            }
            TexelRun run{sy, sx, 0};
            while (sx < b.width && texelUsed(b, size_t(sy) * b.width + sx)) ++sx, ++run.length;
            runs.push_back(run);
        }
    return runs;
}

// dst |= src shifted down by `shift` bits (bit i + shift of src lands on bit i).
void orShiftedDown(const uint64_t* src, int words, int shift, uint64_t* dst) {
    const int q = shift / 64, r = shift % 64;
    for (int w = 0; w + q < words; ++w) {
        uint64_t v = src[w + q] >> r;
        if (r != 0 && w + q + 1 < words) v |= src[w + q + 1] << (64 - r);
        dst[w] |= v;
    }
}

// The first clear bit of `bits` below `limit`, or -1.
int firstClearBit(const std::vector<uint64_t>& bits, int limit) {
    for (int w = 0; w * 64 < limit; ++w) {
        const uint64_t clear = ~bits[size_t(w)];
        if (clear == 0) continue;
        const int x = w * 64 + std::countr_zero(clear);
        return x < limit ? x : -1;
    }
    return -1;
}

// A page row OR-ed with itself shifted down by 0 .. length - 1 bits: bit x is set when any texel
// x .. x + length - 1 of the row is used.
void smearRow(const uint64_t* row, int words, int length, uint64_t* out, std::vector<uint64_t>& scratch) {
    std::copy(row, row + words, out);
    int covered = 1;  // out holds the OR of the row shifted down by 0 .. covered - 1
    while (covered < length) {
        const int step = std::min(covered, length - covered);
        std::copy(out, out + words, scratch.begin());
        orShiftedDown(scratch.data(), words, step, out);
        covered += step;
    }
}

// The page rows smeared over each run length of one block (smearRow), made when first asked during
// the block's scan of one page: a block of h rows tests every page row up to h times, once for
// each of its own rows, and the smear is the same each time.
class SmearedRows {
public:
    // For a scan of `page` by a block with these runs (the same runs as blockedColumns is given).
    void begin(const Page& page, std::span<const TexelRun> runs, int pageSize) {
        page_ = &page;
        rows_ = pageSize;
        words_ = page.wordsPerRow;
        lengths_.clear();
        runLength_.clear();
        for (const TexelRun& run : runs) {
            auto it = std::find(lengths_.begin(), lengths_.end(), run.length);
            runLength_.push_back(int(it - lengths_.begin()));
            if (it == lengths_.end()) lengths_.push_back(run.length);
        }
        made_.assign(lengths_.size() * size_t(rows_), 0);
        smeared_.resize(made_.size() * size_t(words_));
        scratch_.resize(size_t(words_));
    }
    // Page row `row` smeared over the length of run `run` (its index in the runs given to begin).
    const uint64_t* row(size_t run, int row) {
        const size_t slot = size_t(runLength_[run]) * size_t(rows_) + size_t(row);
        uint64_t* out = &smeared_[slot * size_t(words_)];
        if (!made_[slot]) {
            smearRow(&page_->usedBits[size_t(row) * size_t(words_)], words_, lengths_[size_t(runLength_[run])], out,
                     scratch_);
            made_[slot] = 1;
        }
        return out;
    }
    int words() const { return words_; }  // per row

private:
    const Page* page_ = nullptr;
    int rows_ = 0, words_ = 0;
    std::vector<int> lengths_;    // distinct run lengths
    std::vector<int> runLength_;  // per run: index into lengths_
    std::vector<uint8_t> made_;   // per (length, page row)
    std::vector<uint64_t> smeared_, scratch_;
};

// q3map2 TestOutLightmapStamp for every x of one page row at once: bit x of `blocked` is set when
// the block placed at (x, y) would cover a used texel. A run of `length` columns from `first`
// collides at x when any page texel x + first .. x + first + length - 1 is used: the page row,
// smeared down over the run's length, then shifted down by its start. Stops early once every x
// below `xMax` is blocked.
void blockedColumns(std::span<const TexelRun> runs, int y, int xMax, SmearedRows& smeared,
                    std::vector<uint64_t>& blocked) {
    std::fill(blocked.begin(), blocked.end(), 0);
    for (size_t k = 0; k < runs.size(); ++k) {
        if (firstClearBit(blocked, xMax) < 0) return;
        orShiftedDown(smeared.row(k, y + runs[k].row), smeared.words(), runs[k].first, blocked.data());
    }
}

// Whether a block whose rows need free runs of `longestRun` (per block row) may lie with its top at
// page row y: every page row must have a free run at least as long (needed, not enough).
bool rowsMayHold(const Page& page, std::span<const int> longestRun, int y) {
    for (size_t r = 0; r < longestRun.size(); ++r)
        if (longestRun[r] > page.longestFree[size_t(y) + r]) return false;
    return true;
}

std::vector<int> longestRunPerRow(std::span<const TexelRun> runs, int height) {
    std::vector<int> longest(size_t(height), 0);
    for (const TexelRun& run : runs) longest[size_t(run.row)] = std::max(longest[size_t(run.row)], run.length);
    return longest;
}

void updateLongestFree(Page& page, int pageSize, int firstRow, int rows) {
    for (int py = firstRow; py < firstRow + rows; ++py) {
        const uint8_t* used = &page.used[size_t(py) * pageSize];
        int longest = 0, run = 0;
        for (int px = 0; px < pageSize; ++px) {
            run = used[px] ? 0 : run + 1;
            longest = std::max(longest, run);
        }
        page.longestFree[size_t(py)] = longest;
    }
}

void stamp(Page& page, int pageSize, const LightmapBlock& b, bool solid, Rgb8 solidTexel, int x, int y) {
    auto put = [&](int px, int py, const Rgb8& c) {
        const size_t o = size_t(py) * pageSize + px;
        if (!page.used[o]) --page.freeTexels;
        page.used[o] = 1;
        page.usedBits[size_t(py) * size_t(page.wordsPerRow) + size_t(px / 64)] |= uint64_t(1) << (px % 64);
        for (int k = 0; k < 3; ++k) page.rgb[o * 3 + size_t(k)] = c[k];
    };
    if (solid) {
        put(x, y, solidTexel);
        updateLongestFree(page, pageSize, y, 1);
        return;
    }
    for (int sy = 0; sy < b.height; ++sy)
        for (int sx = 0; sx < b.width; ++sx) {
            const size_t i = size_t(sy) * b.width + sx;
            if (texelUsed(b, i)) put(x + sx, y + sy, b.texels[i]);
        }
    updateLongestFree(page, pageSize, y, b.height);
}

}  // namespace

bool blockIsSolid(const LightmapBlock& b) {
    if (b.width <= 2 && b.height <= 2) return true;  // small lightmaps are forced solid
    bool first = true;
    Rgb8 reference{};
    for (size_t i = 0; i < b.texels.size(); ++i) {
        if (!texelUsed(b, i)) continue;
        if (first) {
            reference = b.texels[i];
            first = false;
        } else if (b.texels[i] != reference) {
            return false;  // q3map2's tolerance (0.0625) is below one byte step
        }
    }
    return true;
}

namespace {

// q3map2 CompareBSPLuxels with the solid state of both blocks already known.
bool blocksMatchKnown(const LightmapBlock& a, bool solidA, const Rgb8& colorA, const LightmapBlock& b, bool solidB,
                      const Rgb8& colorB) {
    if (solidA != solidB) return false;
    if (solidA) return colorA == colorB;
    if (a.width != b.width || a.height != b.height) return false;
    constexpr double kLuxelTolerance = 0.0025;
    constexpr double kColorFraction = 1.0 / 768.0;  // 1 / 3 / 256
    double delta = 0.0, total = 0.0;
    for (size_t i = 0; i < a.texels.size(); ++i) {
        total += 1.0;
        if (!texelUsed(a, i) || !texelUsed(b, i)) continue;
        int sum = 0;
        for (int c = 0; c < 3; ++c) {
            const int d = std::abs(int(a.texels[i][c]) - int(b.texels[i][c]));
            if (d > 3) return false;
            sum += d;
        }
        delta += sum * kColorFraction;
        // Checked as it accumulates, as q3map2 does.
        if (delta / total > kLuxelTolerance) return false;
    }
    return true;
}

// q3map2 MergeBSPLuxels: a lightmap taking a twin keeps the twin's texels where it has none of its
// own and the mean of both where both have one, so the shared texels cover both surfaces and later
// comparisons see the merged lightmap.
void mergeTwinTexels(LightmapBlock& master, const LightmapBlock& twin) {
    if (master.used.empty()) return;  // every texel is used already: nothing to take, means only
    for (size_t i = 0; i < master.texels.size(); ++i) {
        if (!texelUsed(twin, i)) continue;
        if (!master.used[i]) {
            master.texels[i] = twin.texels[i];
            master.used[i] = 1;
            continue;
        }
        for (int c = 0; c < 3; ++c) master.texels[i][c] = uint8_t((int(master.texels[i][c]) + twin.texels[i][c]) / 2);
    }
}

// The solid state and colour of a block, and the blocks it is compared with, on bytes or (when
// every block carries it) on light.
struct CollapseState {
    // The blocks as merging leaves them: masters that took in a twin have their own copy (made at
    // the first merge), every other block is read in place.
    std::span<const LightmapBlock> blocks;
    std::vector<std::optional<LightmapBlock>> own;
    const LightmapBlock& merged(size_t i) const { return own[i] ? *own[i] : blocks[i]; }
    LightmapBlock& mergedForWrite(size_t i) {
        if (!own[i]) own[i] = blocks[i];
        return *own[i];
    }
    std::vector<uint8_t> solid;
    std::vector<Rgb8> solidTexel;       // the stored texel of a solid block
    std::vector<Vec3> solidLight;       // light mode: q3map2's solid colour (the lowest light)
    std::vector<int> twin;              // master of each block, -1 = stored itself
};

Vec3 absolute(Vec3 v) { return {std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)}; }

bool carriesLight(const LightmapBlock& b) { return b.light.size() == b.texels.size() && !b.texels.empty(); }

Rgb8 lightToTexel(Vec3 light, float brightness, const PackOptions& o) {
    return colorToBytes(vmax(light, o.minLight), brightness, o.color);
}

// q3map2's solid test on light: every used texel within 0.0625 of the others in each channel (or a
// lightmap of at most 2 x 2); the solid colour is the lowest light.
constexpr float kSolidEpsilon = 0.0625f;
bool lightIsSolid(const LightmapBlock& b, Vec3& lowest) {
    Vec3 lo = Vec3::splat(std::numeric_limits<float>::max()), hi = Vec3::splat(-std::numeric_limits<float>::max());
    bool any = false;
    for (size_t i = 0; i < b.light.size(); ++i) {
        // q3map2 stores -1 in a luxel nothing reached, neither a sample nor a neighbour, and its
        // solid test takes that value in: a lightmap with such holes is not solid.
        const Vec3 light = texelUsed(b, i) ? b.light[i] : Vec3::splat(-1.0f);
        any = true;
        lo = vmin(lo, light);
        hi = vmax(hi, light);
    }
    lowest = any ? lo : Vec3{};
    if (b.width <= 2 && b.height <= 2) return true;
    return !any || maxComponent(hi - lo) <= kSolidEpsilon;
}

// q3map2 CompareBSPLuxels on light: equal brightness and solid state; solid colours within the solid
// epsilon; otherwise the same size and, over the texels both use, every channel within 3 and the
// mean difference (checked as it accumulates) within the luxel tolerance.
bool lightMatches(const CollapseState& st, size_t a, size_t b) {
    const LightmapBlock& la = st.merged(a);
    const LightmapBlock& lb = st.merged(b);
    if (la.brightness != lb.brightness || st.solid[a] != st.solid[b]) return false;
    if (st.solid[a]) return maxComponent(absolute(st.solidLight[a] - st.solidLight[b])) < kSolidEpsilon;
    if (la.width != lb.width || la.height != lb.height) return false;
    constexpr double kLuxelTolerance = 0.0025;
    constexpr double kColorFraction = 0.001302083;  // 1 / 3 / 256, as q3map2 rounds it
    double delta = 0.0, total = 0.0;
    for (size_t i = 0; i < la.light.size(); ++i) {
        total += 1.0;
        if (!texelUsed(la, i) || !texelUsed(lb, i)) continue;
        const Vec3 d = absolute(la.light[i] - lb.light[i]);
        if (maxComponent(d) >= 3.0f) return false;
        delta += (double(d.x) + double(d.y) + double(d.z)) * kColorFraction;
        if (delta / total > kLuxelTolerance) return false;
    }
    return true;
}

// q3map2 MergeBSPLuxels on light: the master takes the twin's light where it has none and the mean
// where both have some (solid ones: the mean colour); its bytes follow.
void mergeTwinLight(CollapseState& st, size_t master, size_t twin, const PackOptions& o) {
    if (st.solid[master]) {
        st.solidLight[master] = (st.solidLight[master] + st.solidLight[twin]) * 0.5f;
        st.solidTexel[master] = lightToTexel(st.solidLight[master], st.merged(master).brightness, o);
        return;
    }
    LightmapBlock& m = st.mergedForWrite(master);
    const LightmapBlock& t = st.merged(twin);
    if (m.used.empty()) m.used.assign(m.texels.size(), 1);
    for (size_t i = 0; i < m.light.size(); ++i) {
        if (!texelUsed(t, i)) continue;
        m.light[i] = m.used[i] ? (m.light[i] + t.light[i]) * 0.5f : t.light[i];
        m.used[i] = 1;
        m.texels[i] = lightToTexel(m.light[i], m.brightness, o);
    }
}

// Finds the twins of every block, in block order as q3map2 walks its raw lightmaps: each block not
// yet a twin takes every later one that matches it (merged as it goes). Only blocks alike in a key
// can match (solid ones all together, others by size): the search runs within each key.
CollapseState collapseTwins(std::span<const LightmapBlock> blocks, const PackOptions& o) {
    CollapseState st;
    st.blocks = blocks;
    const size_t n = blocks.size();
    st.own.resize(n);
    st.solid.assign(n, 0);
    st.solidTexel.assign(n, Rgb8{});
    st.solidLight.assign(n, Vec3{});
    st.twin.assign(n, -1);
    const bool onLight = n > 0 && std::all_of(blocks.begin(), blocks.end(), carriesLight);
    tbb::parallel_for(size_t(0), n, [&](size_t i) {
        const LightmapBlock& b = blocks[i];
        if (onLight) {
            // -nocollapse also keeps small and uniform lightmaps at full size.
            st.solid[i] = o.collapse && lightIsSolid(b, st.solidLight[i]);
            st.solidTexel[i] = lightToTexel(st.solidLight[i], b.brightness, o);
        } else {
            st.solid[i] = o.collapse && blockIsSolid(b);
            st.solidTexel[i] = solidColor(b);
        }
    });
    if (!o.collapse || !o.twins) return st;
    std::map<std::tuple<bool, int, int, int>, std::vector<size_t>> groups;
    for (size_t i = 0; i < n; ++i) {
        const Rgb8 c = onLight ? Rgb8{} : st.solidTexel[i];  // light: solid colours within epsilon of any byte
        groups[st.solid[i] ? std::make_tuple(true, int(c[0]), int(c[1]), int(c[2]))
                           : std::make_tuple(false, blocks[i].width, blocks[i].height, 0)]
            .push_back(i);
    }
    // Blocks of different keys never match: each key's search and merges touch its own blocks only.
    std::vector<const std::vector<size_t>*> keys;
    for (const auto& [key, members] : groups) keys.push_back(&members);
    tbb::parallel_for(size_t(0), keys.size(), [&](size_t k) {
        const std::vector<size_t>& members = *keys[k];
        for (size_t a = 0; a < members.size(); ++a) {
            const size_t i = members[a];
            if (st.twin[i] >= 0) continue;
            for (size_t c = a + 1; c < members.size(); ++c) {
                const size_t j = members[c];
                if (st.twin[j] >= 0) continue;
                if (onLight) {
                    if (!lightMatches(st, i, j)) continue;
                    st.twin[j] = int(i);
                    mergeTwinLight(st, i, j, o);
                } else {
                    if (!blocksMatchKnown(st.merged(i), st.solid[i], st.solidTexel[i], blocks[j], st.solid[j],
                                          st.solidTexel[j]))
                        continue;
                    st.twin[j] = int(i);
                    if (!st.solid[i]) mergeTwinTexels(st.mergedForWrite(i), blocks[j]);
                }
            }
        }
    });
    return st;
}

// q3map2 CompareRawLightmap: the shader names in turn (as many as both have), then fewer styles,
// then the larger area first.
bool placesBefore(const LightmapBlock& a, const LightmapBlock& b) {
    const std::span<const std::string> namesA = a.shaderNames.empty() ? std::span(&a.sortKey, 1) : std::span(a.shaderNames);
    const std::span<const std::string> namesB = b.shaderNames.empty() ? std::span(&b.sortKey, 1) : std::span(b.shaderNames);
    const size_t common = std::min(namesA.size(), namesB.size());
    for (size_t i = 0; i < common; ++i) {
        const int diff = namesA[i].compare(namesB[i]);
        if (diff != 0) return diff < 0;
    }
    if (a.styleSum != b.styleSum) return b.styleSum - a.styleSum < 0;
    const long areaA = long(a.width) * a.height, areaB = long(b.width) * b.height;
    return areaB - areaA < 0;
}

}  // namespace

bool blocksMatch(const LightmapBlock& a, const LightmapBlock& b) {
    return blocksMatchKnown(a, blockIsSolid(a), solidColor(a), b, blockIsSolid(b), solidColor(b));
}

int PackedLightmaps::lightmapNumForPage(int page) const {
    if (page < 0) return bsp::kLightmapByVertex;
    return customSize ? bsp::kLightmapByVertex : page;
}

std::vector<uint8_t> PackedLightmaps::lump14() const {
    std::vector<uint8_t> out;
    if (external || customSize) return out;
    for (const auto& page : pages) out.insert(out.end(), page.begin(), page.end());
    return out;
}

PackedLightmaps packLightmaps(std::span<const LightmapBlock> blocks, const PackOptions& options) {
    const int pageSize = options.pageSize;
    if (pageSize < 2 || (pageSize & (pageSize - 1)) != 0)
        throw CompileError("lightmap page size " + std::to_string(pageSize) + " is not a power of two >= 2");
    PackedLightmaps packed;
    packed.pageSize = pageSize;
    packed.external = options.external;
    packed.customSize = !options.external && pageSize != options.gamePageSize;
    packed.placements.assign(blocks.size(), BlockPlacement{});

    for (size_t i = 0; i < blocks.size(); ++i) {
        const LightmapBlock& b = blocks[i];
        if (b.width <= 0 || b.height <= 0 || b.texels.size() != size_t(b.width) * b.height ||
            (!b.used.empty() && b.used.size() != b.texels.size()))
            throw CompileError("lightmap block " + std::to_string(i) + " has inconsistent texel data");
        if (b.width > pageSize || b.height > pageSize)
            throw CompileError("lightmap block " + std::to_string(i) + " (" + std::to_string(b.width) + "x" +
                               std::to_string(b.height) + ") does not fit a " + std::to_string(pageSize) + " page");
    }
    // Identical lightmaps share the texels of the first one, which takes theirs in.
    const CollapseState collapsed = collapseTwins(blocks, options);
    const std::vector<uint8_t>& solid = collapsed.solid;
    const std::vector<int>& twin = collapsed.twin;

    // q3map2 sorts every raw lightmap, twins included, then skips the twins while placing.
    std::vector<size_t> sorted(blocks.size());
    for (size_t i = 0; i < blocks.size(); ++i) sorted[i] = i;
    std::sort(sorted.begin(), sorted.end(), [&](size_t a, size_t b) { return placesBefore(blocks[a], blocks[b]); });
    std::vector<size_t> order;
    for (size_t i : sorted)
        if (twin[i] < 0) order.push_back(i);

    std::vector<Page> pages;
    const int pageTexels = pageSize * pageSize;
    std::vector<uint64_t> blocked(size_t((pageSize + 63) / 64));
    SmearedRows smeared;
    for (size_t index : order) {
        const LightmapBlock& b = blocks[index];
        const bool isSolid = solid[index] != 0;
        // q3map2's early page test counts the texels of the lightmap before any twin merged in,
        // solid or not.
        const int needed = usedTexels(b);
        const std::vector<TexelRun> runs = isSolid ? std::vector<TexelRun>{} : texelRuns(collapsed.merged(index));
        const bool rectangle = !isSolid && runsFillRectangle(runs, b.width, b.height);
        const std::vector<int> longestRun = longestRunPerRow(runs, b.height);
        int pageIndex = -1, px = 0, py = 0;
        for (size_t p = 0; p < pages.size() && pageIndex < 0; ++p) {
            Page& page = pages[p];
            if (page.freeTexels < needed) continue;
            // Fast allocation skips pages more than 90% full and steps through positions.
            if (options.fastAllocate && page.freeTexels < pageTexels / 10) continue;
            if (rectangle && page.refuses(b.width, b.height)) continue;
            const int xMax = isSolid ? pageSize : pageSize - b.width + 1;
            const int yMax = isSolid ? pageSize : pageSize - b.height + 1;
            const int xStep = options.fastAllocate ? std::max(1, b.width / 15) : 1;
            const int yStep = options.fastAllocate ? std::max(1, b.height / 15) : 1;
            if (!isSolid) smeared.begin(page, runs, pageSize);
            for (int y = 0; y < yMax && pageIndex < 0; y += yStep) {
                if (isSolid) {
                    for (int x = 0; x < xMax; x += xStep)
                        if (solidStampFits(page, pageSize, b, x, y)) {
                            pageIndex = int(p), px = x, py = y;
                            break;
                        }
                    continue;
                }
                if (!rowsMayHold(page, longestRun, y)) continue;
                blockedColumns(runs, y, xMax, smeared, blocked);
                if (xStep == 1) {
                    const int x = firstClearBit(blocked, xMax);
                    if (x >= 0) pageIndex = int(p), px = x, py = y;
                    continue;
                }
                for (int x = 0; x < xMax; x += xStep)
                    if (!((blocked[size_t(x / 64)] >> (x % 64)) & 1)) {
                        pageIndex = int(p), px = x, py = y;
                        break;
                    }
            }
            if (pageIndex < 0 && rectangle && xStep == 1 && yStep == 1)
                page.rectanglesRefused.emplace_back(b.width, b.height);
        }
        if (pageIndex < 0) {
            Page fresh;
            fresh.rgb.assign(size_t(pageTexels) * 3, 0);
            fresh.used.assign(size_t(pageTexels), 0);
            fresh.wordsPerRow = (pageSize + 63) / 64;
            fresh.usedBits.assign(size_t(pageSize) * size_t(fresh.wordsPerRow), 0);
            fresh.freeTexels = pageTexels;
            fresh.longestFree.assign(size_t(pageSize), pageSize);
            pages.push_back(std::move(fresh));
            pageIndex = int(pages.size()) - 1;
            px = py = 0;
        }
        stamp(pages[size_t(pageIndex)], pageSize, collapsed.merged(index), isSolid, collapsed.solidTexel[index], px, py);
        packed.placements[index] = {pageIndex, px, py, isSolid ? 1 : b.width, isSolid ? 1 : b.height, isSolid, -1};
    }
    for (size_t i = 0; i < blocks.size(); ++i) {
        if (twin[i] < 0) continue;
        packed.placements[i] = packed.placements[size_t(twin[i])];
        packed.placements[i].twinOf = twin[i];
    }
    for (Page& page : pages) {
        packed.pages.push_back(std::move(page.rgb));
        packed.pageUsed.push_back(std::move(page.used));
    }
    return packed;
}

void fillUnusedTexels(PackedLightmaps& packed) {
    const int n = packed.pageSize;
    for (size_t p = 0; p < packed.pages.size(); ++p) {
        std::vector<uint8_t>& rgb = packed.pages[p];
        std::vector<uint8_t>& used = packed.pageUsed[p];
        for (;;) {
            std::vector<uint8_t> nextRgb = rgb, nextUsed = used;
            int filled = 0;
            for (int y = 0; y < n; ++y)
                for (int x = 0; x < n; ++x) {
                    const size_t o = size_t(y) * n + x;
                    if (used[o]) continue;
                    const size_t neighbours[4] = {size_t((y + n - 1) % n) * n + x, size_t((y + 1) % n) * n + x,
                                                  size_t(y) * n + (x + n - 1) % n, size_t(y) * n + (x + 1) % n};
                    int count = 0, sum[3] = {0, 0, 0};
                    for (size_t q : neighbours) {
                        if (!used[q]) continue;
                        ++count;
                        for (int c = 0; c < 3; ++c) sum[c] += rgb[q * 3 + size_t(c)];
                    }
                    if (count == 0) continue;
                    for (int c = 0; c < 3; ++c) nextRgb[o * 3 + size_t(c)] = uint8_t(sum[c] / count);
                    nextUsed[o] = 1;
                    ++filled;
                }
            if (filled == 0) break;
            rgb.swap(nextRgb);
            used.swap(nextUsed);
        }
    }
}

void fillUnusedTexelsPink(PackedLightmaps& packed) {
    for (size_t p = 0; p < packed.pages.size(); ++p)
        for (size_t o = 0; o < packed.pageUsed[p].size(); ++o) {
            if (packed.pageUsed[p][o]) continue;
            packed.pages[p][o * 3] = 255;
            packed.pages[p][o * 3 + 1] = 0;
            packed.pages[p][o * 3 + 2] = 255;
        }
}

void applyPackedLightmaps(bsp::Bsp& bsp, std::span<const LightmapBlock> blocks, const PackedLightmaps& packed) {
    if (packed.placements.size() != blocks.size())
        throw CompileError("lightmap packing does not match its " + std::to_string(blocks.size()) + " blocks");
    const float inv = 1.0f / float(packed.pageSize);
    // Surfaces without a lightmap are lit by vertex, whatever an earlier light run wrote
    // (q3map2 StoreSurfaceLightmaps).
    for (bsp::Surface& surface : bsp.surfaces) surface.lightmapNum = bsp::kLightmapByVertex;
    for (size_t i = 0; i < blocks.size(); ++i) {
        const LightmapBlock& b = blocks[i];
        const BlockPlacement& p = packed.placements[i];
        if (b.vertexCoords.size() != b.surfaces.size())
            throw CompileError("lightmap block " + std::to_string(i) + " lacks vertex coordinates for its surfaces");
        for (size_t k = 0; k < b.surfaces.size(); ++k) {
            const int s = b.surfaces[k];
            if (s < 0 || s >= int(bsp.surfaces.size()))
                throw CompileError("lightmap block " + std::to_string(i) + " names surface " + std::to_string(s) +
                                   " which does not exist");
            bsp::Surface& surface = bsp.surfaces[size_t(s)];
            const auto& coords = b.vertexCoords[k];
            if (int(coords.size()) != surface.numVerts)
                throw CompileError("surface " + std::to_string(s) + " has " + std::to_string(surface.numVerts) +
                                   " vertices but " + std::to_string(coords.size()) + " lightmap coordinates");
            surface.lightmapNum = packed.lightmapNumForPage(p.page);
            surface.lightmapX = p.x;
            surface.lightmapY = p.y;
            surface.lightmapWidth = p.width;
            surface.lightmapHeight = p.height;
            for (int v = 0; v < surface.numVerts; ++v) {
                bsp::DrawVert& dv = bsp.drawVerts.at(size_t(surface.firstVert) + size_t(v));
                if (p.solid) {
                    dv.lightmap[0] = (float(p.x) + 0.5f) * inv;
                    dv.lightmap[1] = (float(p.y) + 0.5f) * inv;
                } else {
                    dv.lightmap[0] = (float(p.x) + coords[size_t(v)][0]) * inv;
                    dv.lightmap[1] = (float(p.y) + coords[size_t(v)][1]) * inv;
                }
            }
        }
    }
    bsp.lightmaps = packed.lump14();
}

std::vector<uint8_t> encodeLightmapTga(std::span<const uint8_t> rgb, int width, int height) {
    Image image;
    image.width = width;
    image.height = height;
    image.rgba.resize(size_t(width) * height * 4);
    for (size_t i = 0; i < size_t(width) * height; ++i) {
        for (int c = 0; c < 3; ++c) image.rgba[i * 4 + size_t(c)] = rgb[i * 3 + size_t(c)];
        image.rgba[i * 4 + 3] = 255;
    }
    return encodeTga(image, false);
}

std::string externalLightmapName(int index) {
    char name[32];
    std::snprintf(name, sizeof(name), "lm_%04d.tga", index);
    return name;
}

std::vector<std::filesystem::path> writeExternalLightmaps(const PackedLightmaps& packed, const std::filesystem::path& dir) {
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec) throw FileError(dir.string() + ": cannot create the lightmap folder: " + ec.message());
    std::vector<std::filesystem::path> written;
    for (size_t i = 0; i < packed.pages.size(); ++i) {
        const auto path = dir / externalLightmapName(int(i));
        writeFileAtomic(path, encodeLightmapTga(packed.pages[i], packed.pageSize, packed.pageSize));
        written.push_back(path);
    }
    // Remove pages left by an earlier compile that produced more of them, as q3map2 does.
    for (int i = int(packed.pages.size());; ++i) {
        const auto stale = dir / externalLightmapName(i);
        if (!std::filesystem::exists(stale, ec)) break;
        std::filesystem::remove(stale, ec);
    }
    return written;
}

}  // namespace q3::light
