// `q3map2 -bsp MAP.map`: compiles a .map into MAP.bsp with MAP.srf beside it, and MAP.prt when the
// map is sealed or MAP.lin when it leaks (old .prt/.lin are deleted first). Every file is written
// atomically; the .map is never changed (except the -tempname file, which q3map2 deletes).
#pragma once

#include "bsp_options.h"
#include "common_options.h"

namespace q3 {
class FeedbackStream;
class Log;
}

namespace q3::bspstage {

// Returns the exit code; throws ScriptError, FileError, CompileError or bsp::BspError. With a
// feedback stream (-connect) the leak line and problem brushes also go to the editor as geometry.
int runBspStage(const BspOptions& options, const CommonOptions& common, Log& log, FeedbackStream* feedback = nullptr);

}  // namespace q3::bspstage
