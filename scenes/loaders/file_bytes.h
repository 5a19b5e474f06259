// Whole-file reading for the loaders, and a little-endian view of binary
// files whose every failed read names the file and byte offset. Loaders read
// the whole file up front (the largest real model is ~3 MB) so that counts
// can be checked against the file size before anything is allocated.
#pragma once

#include "core/input_error.h"

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

namespace rtc {

// Throws InputError "<file>: ..." when `file` exists but is not a regular
// file (a directory, device or pipe has no size to check a header against
// and may never end); a missing file is left to the caller's open, which
// names it. Every reader of input files calls it before opening.
void require_regular_file(const std::filesystem::path& file);

// The bytes of a regular file; throws InputError "<file>: cannot open/read"
// on failure.
[[nodiscard]] std::vector<std::uint8_t> read_file_bytes(const std::filesystem::path& file);

// A read-only little-endian view; out-of-range reads throw rather than crash.
class ByteReader {
public:
    ByteReader(std::vector<std::uint8_t> bytes, std::string file)
        : bytes_(std::move(bytes)), file_(std::move(file)) {}

    [[nodiscard]] std::size_t size() const { return bytes_.size(); }
    [[nodiscard]] const std::string& file() const { return file_; }

    [[noreturn]] void fail(std::size_t offset, const std::string& problem) const {
        throw InputError(file_ + ": byte " + std::to_string(offset) + ": " + problem);
    }
    // Throws unless [offset, offset + n) lies inside the file; `what` names
    // the thing being read ("header", "strand 12 points").
    void require(std::size_t offset, std::size_t n, const std::string& what) const {
        if (offset > bytes_.size() || n > bytes_.size() - offset)
            fail(offset, "file truncated: " + what + " needs " + std::to_string(n) +
                             " bytes, " + std::to_string(offset > bytes_.size() ? 0 : bytes_.size() - offset) +
                             " left (file is " + std::to_string(bytes_.size()) + " bytes)");
    }

    // Throws unless `count` records of `record_bytes` each fit in the file from
    // `offset` on; overflow-safe for any count (no multiplication that wraps).
    void require_records(std::size_t offset, std::uint64_t count, std::size_t record_bytes,
                         const std::string& what, std::size_t report_at) const {
        const std::size_t left = offset > bytes_.size() ? 0 : bytes_.size() - offset;
        if (record_bytes != 0 && count > left / record_bytes)
            fail(report_at, what + " need " + std::to_string(count) + " x " +
                                std::to_string(record_bytes) + " bytes from byte " + std::to_string(offset) +
                                ", file has " + std::to_string(bytes_.size()));
    }

    template <class T>
    [[nodiscard]] T get(std::size_t offset, const char* what = "value") const {
        require(offset, sizeof(T), what);
        T v;
        std::memcpy(&v, bytes_.data() + offset, sizeof(T));  // host is little endian (x86/ARM)
        return v;
    }
    [[nodiscard]] const std::uint8_t* data(std::size_t offset) const { return bytes_.data() + offset; }

private:
    std::vector<std::uint8_t> bytes_;
    std::string file_;
};

}  // namespace rtc
