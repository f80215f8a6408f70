#include "info_stage.h"

#include "file_io.h"

#include <filesystem>

namespace q3::info {

namespace fs = std::filesystem;

const cli::OptionTable<InfoOptions>& infoOptionTable() {
    static const cli::OptionTable<InfoOptions> table;
    return table;
}

int runInfoStage(const InfoOptions&, const CommonOptions& common, Log& log) {
    const fs::path& path = common.mapPath;
    std::error_code ec;
    fs::file_status status = fs::status(path, ec);
    if (!fs::exists(status)) throw FileError(path.string() + ": no such file");
    if (fs::is_directory(status)) throw FileError(path.string() + ": is a directory, not a BSP file");
    if (!fs::is_regular_file(status)) throw FileError(path.string() + ": not a regular file");

    bsp::ReadOptions readOptions;
    readOptions.force = common.force;
    bsp::Bsp bsp = bsp::readBsp(path, readOptions);
    uintmax_t size = fs::file_size(path, ec);
    if (ec) throw FileError(path.string() + ": cannot read file size: " + ec.message());

    std::string report = formatBspInfo(bsp, path.string(), size);
    log.raw(report);
    return 0;
}

}  // namespace q3::info
