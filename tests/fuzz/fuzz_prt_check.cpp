// The portal file check of the map_bsp entry, apart because it needs -vis's headers.
#include "fuzz_entries.h"

#include "portal_file.h"

#include <string>

namespace q3::fuzz {

void checkPortalFileReads(std::string_view text) {
    try {
        vis::parsePortalFile(text, "fuzz.prt");
    } catch (const vis::PortalFileError& e) {
        throw PropertyViolation(std::string("-bsp wrote a portal file -vis refuses: ") + e.what());
    }
}

}  // namespace q3::fuzz
