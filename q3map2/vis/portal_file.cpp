#include "portal_file.h"

#include "file_io.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>

namespace q3::vis {

namespace {

// Reads the text the way the scanf formats of LoadPortals do: a blank in the format skips any
// run of white space, numbers skip leading white space themselves.
class PortalScanner {
public:
    PortalScanner(std::string_view text, const std::string& name) : text_(text), name_(name) {}

    [[noreturn]] void fail(const std::string& what) const {
        throw PortalFileError(name_ + ": line " + std::to_string(lineAt(pos_)) + ": " + what);
    }

    void skipSpace() {
        while (pos_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[pos_]))) ++pos_;
    }
    bool atEnd() {
        skipSpace();
        return pos_ >= text_.size();
    }

    // A white-space delimited word (the magic).
    std::string word(size_t maxLength) {
        skipSpace();
        size_t start = pos_;
        while (pos_ < text_.size() && pos_ - start < maxLength && !std::isspace(static_cast<unsigned char>(text_[pos_])))
            ++pos_;
        return std::string(text_.substr(start, pos_ - start));
    }

    // scanf's %i: optional sign, then hexadecimal after 0x, octal after a leading 0, else decimal.
    bool integer(long long& value) {
        skipSpace();
        std::string token = token_([](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '+' || c == '-'; });
        if (token.empty()) return false;
        errno = 0;
        char* end = nullptr;
        value = std::strtoll(token.c_str(), &end, 0);
        if (end == token.c_str()) return false;
        if (errno == ERANGE) fail("number '" + token + "' is out of range");
        pos_ -= token.size() - static_cast<size_t>(end - token.c_str());  // leave what strtoll did not take
        return true;
    }

    // scanf's %f (accepts what strtof accepts).
    bool real(float& value) {
        skipSpace();
        std::string token = token_([](char c) {
            return std::isalnum(static_cast<unsigned char>(c)) || c == '+' || c == '-' || c == '.';
        });
        if (token.empty()) return false;
        char* end = nullptr;
        value = std::strtof(token.c_str(), &end);
        if (end == token.c_str()) return false;
        pos_ -= token.size() - static_cast<size_t>(end - token.c_str());
        return true;
    }

    bool literal(char c) {
        if (pos_ < text_.size() && text_[pos_] == c) {
            ++pos_;
            return true;
        }
        return false;
    }

private:
    template <class Accept>
    std::string token_(Accept accept) {
        size_t start = pos_;
        while (pos_ < text_.size() && accept(text_[pos_])) ++pos_;
        return std::string(text_.substr(start, pos_ - start));
    }

    size_t lineAt(size_t pos) const {
        pos = std::min(pos, text_.size());
        return 1 + static_cast<size_t>(std::count(text_.begin(), text_.begin() + static_cast<std::ptrdiff_t>(pos), '\n'));
    }

    std::string_view text_;
    const std::string& name_;
    size_t pos_ = 0;
};

int readCount(PortalScanner& in, const char* what, long long limit) {
    long long value = 0;
    if (!in.integer(value)) in.fail(std::string("header: missing ") + what);
    if (value < 0) in.fail(std::string("header: negative ") + what + " " + std::to_string(value));
    if (value > limit)
        in.fail(std::string("header: ") + std::to_string(value) + " " + what + " (at most " + std::to_string(limit) + ")");
    return static_cast<int>(value);
}

// "<points> <cluster>..." then the points as "(x y z )". `what` names the record in errors.
std::vector<Vec3> readWinding(PortalScanner& in, long long pointCount, const std::string& what) {
    if (pointCount < 3) in.fail(what + ": " + std::to_string(pointCount) + " points (a winding needs at least 3)");
    if (pointCount > kMaxPortalPoints)
        in.fail(what + ": " + std::to_string(pointCount) + " points (at most " + std::to_string(kMaxPortalPoints) + ")");
    std::vector<Vec3> points(static_cast<size_t>(pointCount));
    for (size_t i = 0; i < points.size(); ++i) {
        in.skipSpace();
        Vec3& p = points[i];
        if (!in.literal('(') || !in.real(p.x) || !in.real(p.y) || !in.real(p.z)) {
            if (in.atEnd()) in.fail(what + ": file ends after " + std::to_string(i) + " of its points");
            in.fail(what + ": point " + std::to_string(i) + " is not \"(x y z )\"");
        }
        in.skipSpace();
        if (!in.literal(')')) in.fail(what + ": point " + std::to_string(i) + " lacks its closing ')'");
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            in.fail(what + ": point " + std::to_string(i) + " is not a finite coordinate");
    }
    return points;
}

int readCluster(PortalScanner& in, int clusterCount, const std::string& what) {
    long long cluster = 0;
    if (!in.integer(cluster)) {
        if (in.atEnd()) in.fail(what + ": file ends before its cluster numbers");
        in.fail(what + ": cluster number expected");
    }
    if (cluster < 0 || cluster >= clusterCount)
        in.fail(what + ": cluster " + std::to_string(cluster) + " out of range (the header says " +
                std::to_string(clusterCount) + " clusters)");
    return static_cast<int>(cluster);
}

long long readPointCount(PortalScanner& in, const std::string& what, size_t declared) {
    long long count = 0;
    if (!in.integer(count)) {
        if (in.atEnd()) in.fail("file ends before " + what + " (the header declares " + std::to_string(declared) + ")");
        in.fail(what + ": point count expected");
    }
    return count;
}

}  // namespace

PortalFile parsePortalFile(std::string_view text, const std::string& name) {
    PortalScanner in(text, name);
    PortalFile file;
    if (in.atEnd()) in.fail("empty file, not a portal file");
    std::string magic = in.word(79);
    if (magic != "PRT1") in.fail("not a portal file (starts with '" + magic + "', expected PRT1)");
    file.clusterCount = readCount(in, "clusters", 0x7fffffff);
    const int portalCount = readCount(in, "portals", kMaxFilePortals);
    const int faceCount = readCount(in, "solid faces", 0x7fffffff);

    file.portals.reserve(static_cast<size_t>(portalCount));
    for (int i = 0; i < portalCount; ++i) {
        const std::string what = "portal " + std::to_string(i);
        FilePortal portal;
        long long pointCount = readPointCount(in, what, static_cast<size_t>(portalCount));
        portal.clusters[0] = readCluster(in, file.clusterCount, what);
        portal.clusters[1] = readCluster(in, file.clusterCount, what);
        long long flags = 0;
        if (!in.integer(flags)) in.fail(what + ": flags expected after the cluster numbers");
        portal.flags = static_cast<uint32_t>(flags);
        portal.points = readWinding(in, pointCount, what);
        file.portals.push_back(std::move(portal));
    }
    // Faces are only read back when they fit in memory one by one: a header claiming billions
    // of faces fails at the first missing one instead of reserving space for them.
    for (int i = 0; i < faceCount; ++i) {
        const std::string what = "solid face " + std::to_string(i);
        FileFace face;
        long long pointCount = readPointCount(in, what, static_cast<size_t>(faceCount));
        face.cluster = readCluster(in, file.clusterCount, what);
        face.points = readWinding(in, pointCount, what);
        file.faces.push_back(std::move(face));
    }
    if (!in.atEnd())
        in.fail("text after the " + std::to_string(portalCount) + " portals and " + std::to_string(faceCount) +
                " solid faces the header declares");
    return file;
}

PortalFile readPortalFile(const std::filesystem::path& path) {
    return parsePortalFile(readFileText(path), path.string());
}

}  // namespace q3::vis
