// Whole-file reading shared by every loader (see file_bytes.h).
#include "scenes/loaders/file_bytes.h"

#include <fstream>

namespace rtc {

void require_regular_file(const std::filesystem::path& file) {
    std::error_code ec;
    const std::filesystem::file_status st = std::filesystem::status(file, ec);
    if (ec || !std::filesystem::exists(st)) return;  // opening it names the problem
    if (std::filesystem::is_directory(st))
        throw InputError(file.string() + ": is a directory, expected a file");
    if (!std::filesystem::is_regular_file(st))
        throw InputError(file.string() + ": not a regular file (devices and pipes are not read)");
}

std::vector<std::uint8_t> read_file_bytes(const std::filesystem::path& file) {
    require_regular_file(file);
    std::ifstream in(file, std::ios::binary | std::ios::ate);
    if (!in) throw InputError(file.string() + ": cannot open file");
    const std::streamoff size = in.tellg();
    if (size < 0) throw InputError(file.string() + ": cannot read file size");
    std::vector<std::uint8_t> bytes(static_cast<std::size_t>(size));
    in.seekg(0);
    if (size > 0 && !in.read(reinterpret_cast<char*>(bytes.data()), size))
        throw InputError(file.string() + ": read failed");
    return bytes;
}

}  // namespace rtc
