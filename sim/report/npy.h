// NumPy .npy files (format version 1.0), written and read without NumPy: a
// 10-byte preamble ("\x93NUMPY", version 1.0, header length as uint16 LE), an
// ASCII header dict {'descr': '<u4', 'fortran_order': False, 'shape': (H, W, E), }
// padded with spaces to a multiple of 64 bytes and ended by '\n', then the
// raw little-endian data in C order. numpy.load reads these files as they are.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace rtc {

enum class NpyType { U32, U64, F32, F64 };

// "<u4", "<u8", "<f4", "<f8".
[[nodiscard]] const char* npy_descr(NpyType type);
[[nodiscard]] std::size_t npy_item_size(NpyType type);

// The preamble and header for an array of `shape` (the data follows it).
[[nodiscard]] std::string npy_header(NpyType type, const std::vector<std::size_t>& shape);

// Writes `data` (product(shape) items of `type`, native = little-endian
// layout) to `path`; throws rtc::InputError naming the path on failure.
void write_npy(const std::string& path, NpyType type, const std::vector<std::size_t>& shape, const void* data);
void write_npy(const std::string& path, const std::vector<std::size_t>& shape, const std::vector<double>& data);

// A loaded array (for tests and tools). Throws rtc::InputError naming the
// file and what is wrong (magic, version, header key, size).
struct NpyArray {
    NpyType type = NpyType::U32;
    std::vector<std::size_t> shape;
    std::vector<unsigned char> bytes;  // raw data, C order

    [[nodiscard]] std::size_t size() const;  // number of items
    // Item i widened to double (any type) or to uint64 (integer types).
    [[nodiscard]] double as_double(std::size_t i) const;
    [[nodiscard]] std::uint64_t as_u64(std::size_t i) const;
};
[[nodiscard]] NpyArray read_npy(const std::string& path);

}  // namespace rtc
