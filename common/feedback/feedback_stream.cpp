#include "feedback_stream.h"

#include <cstdio>
#include <libxml/xmlwriter.h>

namespace q3 {

namespace {

const xmlChar* xc(const char* s) { return reinterpret_cast<const xmlChar*>(s); }

// q3map2 writes leak points with "%f" and problem points and windings with "%g".
std::string formatPoint(const char* format, Vec3 v) {
    char buffer[160];
    std::snprintf(buffer, sizeof buffer, format, double(v.x), double(v.y), double(v.z));
    return buffer;
}

// libxml2 pushes the serialized bytes here; they are sent after each complete element.
int appendToPending(void* context, const char* bytes, int length) {
    static_cast<std::string*>(context)->append(bytes, static_cast<size_t>(length));
    return length;
}
int closeNothing(void*) { return 0; }

}  // namespace

struct FeedbackStream::Impl {
    mutable std::mutex mutex;
    FeedbackSocket socket;
    std::function<void(std::string_view)> notice;
    std::string pending;
    xmlTextWriterPtr writer = nullptr;
    bool open = true;
    std::thread::id echoMuted;

    explicit Impl(FeedbackSocket s) : socket(std::move(s)) {}
    ~Impl() {
        if (writer) xmlFreeTextWriter(writer);
    }

    // Sends what the writer produced. On failure the stream stops for good and says so once.
    void flush() {
        if (!open) return;
        if (xmlTextWriterFlush(writer) < 0) {
            lose("the XML writer failed");
            return;
        }
        if (pending.empty()) return;
        std::string bytes = frameChunks(pending);
        pending.clear();
        std::string error;
        if (!socket.sendAll(bytes, &error)) lose(error);
    }

    void lose(const std::string& reason) {
        open = false;
        socket.close();
        if (notice) notice(std::string(kLostConnectionNotice) + " (" + reason + ")");
    }

    // One top-level child of the root: name, level attribute, text, then whatever `children`
    // writes, and the end tag; sent at once.
    template <class Children>
    void element(const char* name, FeedbackLevel level, std::string_view text, Children&& children) {
        if (!open) return;
        std::string safeText = toXmlText(text);
        std::string levelText = feedbackLevelText(level);
        bool ok = xmlTextWriterStartElement(writer, xc(name)) >= 0 &&
                  xmlTextWriterWriteAttribute(writer, xc("level"), xc(levelText.c_str())) >= 0 &&
                  xmlTextWriterWriteString(writer, xc(safeText.c_str())) >= 0 && children() &&
                  xmlTextWriterEndElement(writer) >= 0;
        if (!ok) {
            lose("the XML writer failed");
            return;
        }
        flush();
    }

    bool child(const char* name, const std::string& text) {
        return xmlTextWriterWriteElement(writer, xc(name), xc(text.c_str())) >= 0;
    }
};

std::unique_ptr<FeedbackStream> FeedbackStream::open(const FeedbackAddress& address,
                                                     FeedbackStreamOptions options,
                                                     std::string* error) {
    xmlInitParser();  // idempotent; makes libxml2's global setup happen before any thread uses it
    auto socket = FeedbackSocket::connect(address, options.connectTimeout, options.sendTimeout, error);
    if (!socket) return nullptr;
    auto impl = std::make_unique<Impl>(std::move(*socket));
    impl->notice = options.notice ? std::move(options.notice) : [](std::string_view text) {
        std::fprintf(stderr, "%.*s\n", static_cast<int>(text.size()), text.data());
        std::fflush(stderr);
    };
    xmlOutputBufferPtr out = xmlOutputBufferCreateIO(appendToPending, closeNothing, &impl->pending, nullptr);
    if (!out || !(impl->writer = xmlNewTextWriter(out))) {
        if (out && !impl->writer) xmlOutputBufferClose(out);
        *error = "cannot create the XML writer";
        return nullptr;
    }
    // The header as q3map2 sends it: the declaration and the open root element with its version.
    // Writing empty raw text makes the writer finish the start tag ("...version=\"1\">") now.
    std::string version(kFeedbackStreamVersion);
    bool ok = xmlTextWriterStartDocument(impl->writer, "1.0", nullptr, nullptr) >= 0 &&
              xmlTextWriterStartElement(impl->writer, xc("q3map_feedback")) >= 0 &&
              xmlTextWriterWriteAttribute(impl->writer, xc("version"), xc(version.c_str())) >= 0 &&
              xmlTextWriterWriteRaw(impl->writer, xc("")) >= 0 &&
              xmlTextWriterFlush(impl->writer) >= 0;
    if (!ok) {
        *error = "cannot write the feedback header";
        return nullptr;
    }
    std::string header = frameChunks(impl->pending);
    impl->pending.clear();
    if (!impl->socket.sendAll(header, error)) return nullptr;
    return std::unique_ptr<FeedbackStream>(new FeedbackStream(std::move(impl)));
}

FeedbackStream::FeedbackStream(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}

FeedbackStream::~FeedbackStream() { close(); }

void FeedbackStream::message(FeedbackLevel level, std::string_view text) {
    std::lock_guard lock(impl_->mutex);
    impl_->element("message", level, text, [] { return true; });
}

void FeedbackStream::messageFromLog(LogLevel level, std::string_view text) {
    std::lock_guard lock(impl_->mutex);
    if (impl_->echoMuted == std::this_thread::get_id()) return;
    impl_->element("message", feedbackLevelFor(level), text, [] { return true; });
}

void FeedbackStream::leak(std::span<const Vec3> path, std::string_view text) {
    std::lock_guard lock(impl_->mutex);
    Impl& s = *impl_;
    s.element("message", FeedbackLevel::Error, text, [&] {
        if (xmlTextWriterStartElement(s.writer, xc("polyline")) < 0) return false;
        for (Vec3 p : path)
            if (!s.child("point", formatPoint("%f %f %f", p))) return false;
        return xmlTextWriterEndElement(s.writer) >= 0;
    });
}

void FeedbackStream::brushSelect(int entity, int brush, std::string_view text, bool isError) {
    std::lock_guard lock(impl_->mutex);
    Impl& s = *impl_;
    std::string line = "Entity " + std::to_string(entity) + ", Brush " + std::to_string(brush) + ": ";
    line += text;
    FeedbackLevel level = isError ? FeedbackLevel::Error : FeedbackLevel::Warning;
    s.element("select", level, line, [&] {
        return s.child("brush", std::to_string(entity) + " " + std::to_string(brush));
    });
}

void FeedbackStream::point(std::string_view text, Vec3 where, FeedbackLevel level) {
    std::lock_guard lock(impl_->mutex);
    Impl& s = *impl_;
    s.element("pointmsg", level, text, [&] { return s.child("point", formatPoint("%g %g %g", where)); });
}

void FeedbackStream::winding(std::string_view text, std::span<const Vec3> points, FeedbackLevel level) {
    std::lock_guard lock(impl_->mutex);
    Impl& s = *impl_;
    std::string body = std::to_string(points.size()) + " ";
    for (Vec3 p : points) body += formatPoint("(%g %g %g)", p);
    s.element("windingmsg", level, text, [&] { return s.child("winding", body); });
}

void FeedbackStream::close() {
    std::lock_guard lock(impl_->mutex);
    Impl& s = *impl_;
    if (!s.open) return;
    // Ends the root element so that the stream is a complete document, then hangs up.
    if (xmlTextWriterEndDocument(s.writer) >= 0) s.flush();
    s.open = false;
    s.socket.close();
}

bool FeedbackStream::connected() const {
    std::lock_guard lock(impl_->mutex);
    return impl_->open;
}

void FeedbackStream::setEchoMutedThread(std::thread::id thread) {
    std::lock_guard lock(impl_->mutex);
    impl_->echoMuted = thread;
}

void FeedbackStream::clearEchoMutedThread() { setEchoMutedThread(std::thread::id()); }

}  // namespace q3
