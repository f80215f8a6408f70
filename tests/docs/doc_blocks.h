// Shell blocks the documentation promises to work. A block is marked by the line
//
//   <!-- quick-start creates: relit/maps/oacmpdm1.bsp relit/oacmpdm1_sh.png -->
//
// right before its ```sh fence; the files listed are what running the block must leave behind
// (relative to the folder it ran in).
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace q3::test {

struct QuickStartBlock {
    int line = 0;                      // of the marker, 1-based
    std::vector<std::string> creates;  // promised outputs
    std::string script;                // the block's lines, each ending in '\n'
};

// Every marked block of a Markdown text. Throws std::runtime_error naming `name` and the line when
// a marker is not followed by a ```sh fence, lists no outputs, or its block is never closed.
std::vector<QuickStartBlock> quickStartBlocks(std::string_view markdown, const std::string& name);

// The script's command lines: comment-only and blank lines dropped, trailing "# ..." comments kept.
std::vector<std::string> commandLines(const std::string& script);

}  // namespace q3::test
