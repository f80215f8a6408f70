#include "feedback_log.h"

#include <thread>

namespace q3 {

std::shared_ptr<FeedbackStream> connectNetRadiant(std::string_view address, Log& log,
                                                  FeedbackStreamOptions options) {
    std::string shown(address);
    auto parsed = parseFeedbackAddress(address);
    if (!parsed) {
        log.warning("-connect " + shown + ": not a host:port address; continuing without NetRadiant feedback");
        return nullptr;
    }
    std::string error;
    std::shared_ptr<FeedbackStream> stream = FeedbackStream::open(*parsed, std::move(options), &error);
    if (!stream) {
        log.warning("could not connect to NetRadiant at " + shown + " (" + error +
                    "); continuing without feedback");
        return nullptr;
    }
    attachToLog(log, stream);
    return stream;
}

void attachToLog(Log& log, std::shared_ptr<FeedbackStream> stream) {
    log.addSink([stream = std::move(stream)](LogLevel level, std::string_view line) {
        stream->messageFromLog(level, line);
    });
}

FeedbackEchoMute::FeedbackEchoMute(FeedbackStream* stream) : stream_(stream) {
    if (stream_) stream_->setEchoMutedThread(std::this_thread::get_id());
}

FeedbackEchoMute::~FeedbackEchoMute() {
    if (stream_) stream_->clearEchoMutedThread();
}

void reportLeak(Log& log, FeedbackStream* stream, std::span<const Vec3> path) {
    {
        // q3map2 keeps the banner off the XML stream; the editor gets the polyline message.
        FeedbackEchoMute mute(stream);
        log.info("**********************");
        log.info("******* leaked *******");
        log.info("**********************");
    }
    if (stream) stream->leak(path);
}

std::string reportBrushProblem(Log& log, FeedbackStream* stream, int entity, int brush,
                               std::string_view message, bool isError) {
    std::string line = "Entity " + std::to_string(entity) + ", Brush " + std::to_string(brush) + ": ";
    line += message;
    if (stream) stream->brushSelect(entity, brush, message, isError);
    if (!isError) {
        FeedbackEchoMute mute(stream);
        log.warning(line);
    }
    return line;
}

}  // namespace q3
