// Facts of the q3map2 -> NetRadiant feedback protocol, as pure functions.
//
// The compiler connects to the editor (NetRadiant listens on port 39000) and streams one XML
// document, <q3map_feedback version="1">, whose children are sent as they happen: <message
// level="N"> for every console line, and geometry for problems (<select> with <brush>, a leak's
// <polyline> of <point>s, <pointmsg>, <windingmsg>). On the wire the text travels in the framing
// of id's l_net library: each chunk is a 4-byte little-endian length followed by that many bytes,
// the text and a terminating NUL. The editor copies each chunk into a 1024-byte buffer, so no
// chunk carries more than kMaxChunkText bytes of text.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "log.h"

namespace q3 {

// The version attribute of the root element; NetRadiant refuses a stream without it.
inline constexpr std::string_view kFeedbackStreamVersion = "1";
// NetRadiant's listening port for monitored builds.
inline constexpr uint16_t kNetRadiantPort = 39000;
// l_net's MAX_NETMESSAGE is 1024; q3map2 splits node text at MAX_NETMESSAGE - 10.
inline constexpr std::size_t kMaxChunkText = 1014;

// q3map2's message levels (SYS_VRB, SYS_STD, SYS_WRN, SYS_ERR). NetRadiant stops monitoring the
// build after a level-3 element.
enum class FeedbackLevel : int { Verbose = 0, Standard = 1, Warning = 2, Error = 3 };

FeedbackLevel feedbackLevelFor(LogLevel level);
// The level attribute's text ("0".."3").
std::string feedbackLevelText(FeedbackLevel level);

struct FeedbackAddress {
    std::string host;  // a name, an IPv4 address or an IPv6 address (given in brackets)
    uint16_t port = kNetRadiantPort;
};

// Parses "host:port", "host" (NetRadiant's port) or "[v6addr]:port". Empty host, a port that is
// not a number in 1..65535, or stray brackets give nullopt.
std::optional<FeedbackAddress> parseFeedbackAddress(std::string_view text);

// Text that libxml2 can write and any XML parser accepts: valid UTF-8 sequences are kept, bytes
// that do not form one are read as Latin-1 (what a Windows-era .map usually holds), and control
// characters XML 1.0 forbids are dropped (tab, newline and carriage return stay).
std::string toXmlText(std::string_view text);

// One wire chunk for at most kMaxChunkText bytes of text: length prefix, text, NUL.
std::string frameChunk(std::string_view text);
// Splits text into consecutive framed chunks of at most kMaxChunkText text bytes each.
std::string frameChunks(std::string_view text);

}  // namespace q3
