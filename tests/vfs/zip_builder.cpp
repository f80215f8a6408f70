#include "zip_builder.h"

#include <fstream>
#include <stdexcept>

#include <zip.h>

namespace q3::test {

void writeZip(const std::filesystem::path& path, const ZipFiles& files) {
    std::filesystem::create_directories(path.parent_path());
    zipFile zip = zipOpen64(path.string().c_str(), APPEND_STATUS_CREATE);
    if (!zip) throw std::runtime_error("cannot create " + path.string());
    for (const auto& [name, contents] : files) {
        zip_fileinfo info{};
        if (zipOpenNewFileInZip64(zip, name.c_str(), &info, nullptr, 0, nullptr, 0, nullptr, Z_DEFLATED,
                                  Z_DEFAULT_COMPRESSION, 0) != ZIP_OK ||
            zipWriteInFileInZip(zip, contents.data(), unsigned(contents.size())) != ZIP_OK ||
            zipCloseFileInZip(zip) != ZIP_OK)
            throw std::runtime_error("cannot add " + name + " to " + path.string());
    }
    if (zipClose(zip, nullptr) != ZIP_OK) throw std::runtime_error("cannot finish " + path.string());
}

void writeLoose(const std::filesystem::path& path, const std::string& contents) {
    std::filesystem::create_directories(path.parent_path());
    std::ofstream out(path, std::ios::binary);
    out << contents;
    if (!out) throw std::runtime_error("cannot write " + path.string());
}

}  // namespace q3::test
