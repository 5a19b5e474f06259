// .npy writer and reader (see npy.h).
#include "sim/report/npy.h"

#include "core/input_error.h"
#include "sim/util/json_file.h"

#include <algorithm>
#include <bit>
#include <cstring>
#include <fstream>
#include <iterator>

namespace rtc {

static_assert(std::endian::native == std::endian::little, "the .npy writer assumes a little-endian host");

const char* npy_descr(NpyType type) {
    switch (type) {
        case NpyType::U32: return "<u4";
        case NpyType::U64: return "<u8";
        case NpyType::F32: return "<f4";
        case NpyType::F64: return "<f8";
    }
    return "<u4";
}

std::size_t npy_item_size(NpyType type) {
    return type == NpyType::U64 || type == NpyType::F64 ? 8 : 4;
}

std::string npy_header(NpyType type, const std::vector<std::size_t>& shape) {
    std::string dict = std::string("{'descr': '") + npy_descr(type) + "', 'fortran_order': False, 'shape': (";
    for (std::size_t i = 0; i < shape.size(); ++i) dict += (i ? ", " : "") + std::to_string(shape[i]);
    dict += shape.size() == 1 ? ",), }" : "), }";
    // Preamble (10 bytes) + dict + padding + '\n' is a multiple of 64.
    const std::size_t total = (10 + dict.size() + 1 + 63) / 64 * 64;
    dict.append(total - 10 - dict.size() - 1, ' ');
    dict += '\n';
    const auto len = static_cast<std::uint16_t>(dict.size());
    std::string out("\x93NUMPY\x01\x00", 8);
    out += static_cast<char>(len & 0xff);
    out += static_cast<char>(len >> 8);
    return out + dict;
}

void write_npy(const std::string& path, NpyType type, const std::vector<std::size_t>& shape, const void* data) {
    std::size_t items = 1;
    for (std::size_t n : shape) items *= n;
    OutputFile out(path);
    out.write(npy_header(type, shape));
    if (items > 0) out.write(data, items * npy_item_size(type));
    out.commit();
}

void write_npy(const std::string& path, const std::vector<std::size_t>& shape, const std::vector<double>& data) {
    write_npy(path, NpyType::F64, shape, data.data());
}

std::size_t NpyArray::size() const {
    std::size_t n = 1;
    for (std::size_t s : shape) n *= s;
    return n;
}

double NpyArray::as_double(std::size_t i) const {
    const unsigned char* p = bytes.data() + i * npy_item_size(type);
    switch (type) {
        case NpyType::F32: { float v; std::memcpy(&v, p, 4); return v; }
        case NpyType::F64: { double v; std::memcpy(&v, p, 8); return v; }
        default: return static_cast<double>(as_u64(i));
    }
}

std::uint64_t NpyArray::as_u64(std::size_t i) const {
    const unsigned char* p = bytes.data() + i * npy_item_size(type);
    switch (type) {
        case NpyType::U32: { std::uint32_t v; std::memcpy(&v, p, 4); return v; }
        case NpyType::U64: { std::uint64_t v; std::memcpy(&v, p, 8); return v; }
        default: return static_cast<std::uint64_t>(as_double(i));
    }
}

NpyArray read_npy(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path + ": cannot open file");
    const std::string file((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (file.size() < 10 || file.compare(0, 6, "\x93NUMPY") != 0) throw InputError(path + ": not a .npy file (magic)");
    if (file[6] != 1) throw InputError(path + ": .npy version " + std::to_string(file[6]) + " (only 1.x is read)");
    const std::size_t len = static_cast<unsigned char>(file[8]) | (static_cast<std::size_t>(static_cast<unsigned char>(file[9])) << 8);
    if (file.size() < 10 + len) throw InputError(path + ": header longer than the file");
    const std::string header = file.substr(10, len);
    NpyArray a;
    const auto value_of = [&](const std::string& key) {
        const std::size_t k = header.find("'" + key + "':");
        if (k == std::string::npos) throw InputError(path + ": header has no '" + key + "'");
        return header.substr(k + key.size() + 3);
    };
    const std::string descr = value_of("descr");
    const NpyType types[] = {NpyType::U32, NpyType::U64, NpyType::F32, NpyType::F64};
    bool known = false;
    for (NpyType t : types)
        if (descr.find(std::string("'") + npy_descr(t) + "'") == descr.find_first_not_of(' ')) a.type = t, known = true;
    if (!known) throw InputError(path + ": 'descr': unsupported type " + descr.substr(0, descr.find(',')));
    if (value_of("fortran_order").find("False") != value_of("fortran_order").find_first_not_of(' '))
        throw InputError(path + ": 'fortran_order': only C order is read");
    const std::string shape = value_of("shape");
    const std::size_t open = shape.find('('), close = shape.find(')');
    if (open == std::string::npos || close == std::string::npos) throw InputError(path + ": 'shape': expected a tuple");
    std::size_t pos = open + 1;
    while (pos < close) {
        const std::size_t end = std::min(shape.find(',', pos), close);
        const std::string item = shape.substr(pos, end - pos);
        if (item.find_first_not_of(' ') != std::string::npos) a.shape.push_back(std::stoull(item));
        pos = end + 1;
    }
    const std::size_t bytes = a.size() * npy_item_size(a.type);
    if (file.size() != 10 + len + bytes)
        throw InputError(path + ": " + std::to_string(file.size() - 10 - len) + " data bytes, shape needs " +
                         std::to_string(bytes));
    a.bytes.assign(file.begin() + static_cast<std::ptrdiff_t>(10 + len), file.end());
    return a;
}

}  // namespace rtc
