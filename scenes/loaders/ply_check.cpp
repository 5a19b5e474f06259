// PLY pre-check (see ply_check.h); the format as in Paul Bourke's PLY spec.
#include "scenes/loaders/ply_check.h"

#include "scenes/loaders/text_lines.h"

#include <cmath>
#include <string_view>

namespace rtc {

namespace {

struct Property {
    std::string name;
    int bytes = 0;        // scalar size, or the list's item size
    int count_bytes = 0;  // > 0 for a list: the size of its count
    bool count_signed = false, item_signed = false, item_float = false;
};
struct Element {
    std::string name;
    unsigned long long count = 0;
    std::size_t line = 0;
    std::vector<Property> properties;
};

bool type_signed(std::string_view t) { return t == "char" || t == "short" || t == "int" || t.substr(0, 3) == "int"; }
bool type_float(std::string_view t) { return t == "float" || t == "double" || t == "float32" || t == "float64"; }

// An integer of `bytes` bytes at `at`, in the file's byte order.
long long read_int(const std::string_view all, std::size_t at, int bytes, bool is_signed, bool big_endian) {
    unsigned long long u = 0;
    for (int i = 0; i < bytes; ++i) {
        const auto b = static_cast<unsigned char>(all[at + static_cast<std::size_t>(big_endian ? i : bytes - 1 - i)]);
        u = (u << 8) | b;
    }
    if (is_signed && bytes < 8 && (u >> (8 * bytes - 1)) != 0) return static_cast<long long>(u) - (1LL << (8 * bytes));
    return static_cast<long long>(u);
}

// Walks a binary body item by item: every list's length is read, so a file
// cut anywhere (or a negative length) is found before assimp reads past the
// end; face indices must name existing vertices.
void check_binary_body(const std::string_view all, std::size_t pos, const std::vector<Element>& elements,
                       bool big_endian, const std::string& file) {
    auto fail = [&](std::size_t at, const std::string& problem) {
        throw InputError(file + ": byte " + std::to_string(at) + ": " + problem);
    };
    unsigned long long vertices = 0;
    for (const Element& e : elements) {
        if (e.name == "vertex") vertices = e.count;
        const bool face = e.name == "face";
        for (unsigned long long i = 0; i < e.count; ++i) {
            for (const Property& p : e.properties) {
                const auto need = static_cast<std::size_t>(p.count_bytes ? p.count_bytes : p.bytes);
                if (need > all.size() - pos)
                    fail(pos, "file truncated in element " + e.name + " item " + std::to_string(i) + " (" + p.name + ")");
                if (!p.count_bytes) {
                    pos += need;
                    continue;
                }
                const long long n = read_int(all, pos, p.count_bytes, p.count_signed, big_endian);
                if (n < 0) fail(pos, "negative list length in element " + e.name + " item " + std::to_string(i));
                pos += need;
                if (static_cast<unsigned long long>(n) > (all.size() - pos) / static_cast<std::size_t>(p.bytes))
                    fail(pos, "file truncated in element " + e.name + " item " + std::to_string(i) + " (" + p.name +
                                  ": " + std::to_string(n) + " values)");
                const bool index = face && !p.item_float && (p.name == "vertex_indices" || p.name == "vertex_index");
                for (long long j = 0; j < n; ++j, pos += static_cast<std::size_t>(p.bytes)) {
                    if (!index) continue;
                    const long long v = read_int(all, pos, p.bytes, p.item_signed, big_endian);
                    if (v < 0 || static_cast<unsigned long long>(v) >= vertices)
                        fail(pos, "face " + std::to_string(i) + " refers to vertex " + std::to_string(v) +
                                      ", the file has " + std::to_string(vertices));
                }
            }
        }
    }
}

int type_bytes(std::string_view t) {
    if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
    if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
    if (t == "int" || t == "uint" || t == "int32" || t == "uint32" || t == "float" || t == "float32") return 4;
    if (t == "double" || t == "float64") return 8;
    return 0;
}

}  // namespace

void check_ply(const std::vector<std::uint8_t>& bytes, const std::string& file) {
    const std::string_view all(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    const std::size_t end = all.find("\nend_header");
    if (all.substr(0, 3) != "ply") throw InputError(file + ": line 1: not a PLY file (no \"ply\" magic)");
    if (end == std::string_view::npos) throw InputError(file + ": no \"end_header\" line");
    std::size_t body = all.find('\n', end + 1);
    body = body == std::string_view::npos ? all.size() : body + 1;
    // The header is plain text as assimp expects it: no '#' (TextLines would
    // take it for a comment) and no control characters but tab and CR.
    std::size_t line = 1;
    for (std::size_t i = 0; i < body; ++i) {
        const auto c = static_cast<unsigned char>(all[i]);
        if (c == '\n') ++line;
        else if (c == '#' || (c < 32 && c != '\t' && c != '\r') || c >= 127)
            throw InputError(file + ": line " + std::to_string(line) + ": unexpected character " + std::to_string(c) +
                             " in the PLY header");
    }
    TextLines header(std::string(all.substr(0, body)), file);
    std::string format;
    std::vector<Element> elements;
    while (header.next()) {
        const auto& t = header.tokens();
        if (header.line_number() == 1) {
            if (t.size() != 1 || t[0] != "ply") header.fail("expected \"ply\"");
            continue;
        }
        if (header.blank()) continue;
        if (t[0] == "comment" || t[0] == "obj_info") continue;
        if (t[0] == "format") {
            if (t.size() != 3 || (t[1] != "ascii" && t[1] != "binary_little_endian" && t[1] != "binary_big_endian") ||
                t[2] != "1.0")
                header.fail("expected \"format ascii|binary_little_endian|binary_big_endian 1.0\"");
            if (!format.empty()) header.fail("a second \"format\" line");
            format = t[1];
        } else if (t[0] == "element") {
            if (t.size() != 3) header.fail("expected \"element <name> <count>\"");
            const auto n = header.number<long long>(2, "element count");
            if (n < 0) header.fail("negative element count");
            for (const Element& e : elements)
                if (e.name == t[1]) header.fail("a second element \"" + e.name + "\"");
            elements.push_back({std::string(t[1]), static_cast<unsigned long long>(n), header.line_number(), {}});
        } else if (t[0] == "property") {
            if (elements.empty()) header.fail("property before any element");
            Property p;
            if (t.size() == 5 && t[1] == "list") {
                p.count_bytes = type_bytes(t[2]);
                p.bytes = type_bytes(t[3]);
                p.count_signed = type_signed(t[2]);
                p.item_signed = type_signed(t[3]);
                p.item_float = type_float(t[3]);
                if (p.count_bytes == 0 || p.bytes == 0 || t[2] == "float" || t[2] == "double" ||
                    t[2] == "float32" || t[2] == "float64")
                    header.fail("bad list property types \"" + std::string(t[2]) + " " + std::string(t[3]) + "\"");
            } else if (t.size() == 3) {
                p.bytes = type_bytes(t[1]);
                if (p.bytes == 0) header.fail("unknown property type \"" + std::string(t[1]) + "\"");
            } else {
                header.fail("expected \"property <type> <name>\" or \"property list <type> <type> <name>\"");
            }
            p.name = std::string(t.back());
            elements.back().properties.push_back(std::move(p));
        } else if (t[0] == "end_header") {
            if (t.size() != 1) header.fail("expected \"end_header\" alone");
            break;
        } else {
            header.fail("unknown header line \"" + std::string(t[0]) + "\"");
        }
    }
    if (format.empty()) throw InputError(file + ": line 2: no \"format\" line in the header");
    // The geometry assimp reads: vertex x y z (scalars), faces as a list.
    const Element* vertex = nullptr;
    for (const Element& e : elements) {
        if (e.name == "vertex" && vertex) throw InputError(file + ": line " + std::to_string(e.line) + ": a second vertex element");
        if (e.name == "vertex") vertex = &e;
        for (const char* axis : {"x", "y", "z"}) {
            if (e.name != "vertex") break;
            std::size_t found = 0;
            for (const Property& p : e.properties) found += p.name == axis && !p.count_bytes ? 1 : 0;
            if (found != 1)
                throw InputError(file + ": line " + std::to_string(e.line) + ": element vertex needs one scalar property " +
                                 axis);
        }
        for (const Property& p : e.properties)
            if (e.name == "face" && (p.name == "vertex_indices" || p.name == "vertex_index") && (!p.count_bytes || p.item_float))
                throw InputError(file + ": line " + std::to_string(e.line) + ": face " + p.name + " must be a list of integers");
    }
    if (!vertex) throw InputError(file + ": no \"element vertex\" in the header");
    const unsigned long long left = all.size() - body;
    unsigned long long need = 0;
    for (const Element& e : elements) {
        // The least an instance can take: binary sizes, or two bytes per ASCII field.
        unsigned long long least = 0;
        for (const Property& p : e.properties)
            least += format == "ascii" ? 2 : static_cast<unsigned long long>(p.count_bytes ? p.count_bytes : p.bytes);
        if (least > 0 && e.count > (left + (format == "ascii" ? 1 : 0)) / least)
            throw InputError(file + ": line " + std::to_string(e.line) + ": element " + e.name + " declares " +
                             std::to_string(e.count) + " items, more than the " + std::to_string(left) +
                             " bytes after the header can hold");
        need += e.count * least;
        if (need > left + (format == "ascii" ? 1 : 0))
            throw InputError(file + ": line " + std::to_string(e.line) + ": the elements up to " + e.name +
                             " need at least " + std::to_string(need) + " bytes, the body has " + std::to_string(left));
    }
    // Faces are what the simulator needs (and assimp 5.2 leaks its mesh on
    // files without a face index list, found by fuzz_ply).
    bool faces = false;
    for (const Element& e : elements)
        for (const Property& p : e.properties)
            faces = faces || (e.name == "face" && (p.name == "vertex_indices" || p.name == "vertex_index"));
    if (!faces) throw InputError(file + ": no \"element face\" with a \"vertex_indices\" list in the header");
    if (format != "ascii") return check_binary_body(all, body, elements, format == "binary_big_endian", file);

    // ASCII body: one item per line, each field a number, list lengths as
    // given, fields separated by spaces or tabs only, nothing after the last
    // item (assimp 5.2 leaks on some such files; found by fuzz_ply).
    for (std::size_t i = body, line = header.line_number() + 1; i < all.size(); ++i) {
        const auto c = static_cast<unsigned char>(all[i]);
        if (c == '\n') ++line;
        else if ((c < 32 && c != '\t' && c != '\r') || c >= 127 || c == '#')
            throw InputError(file + ": line " + std::to_string(line) + ": unexpected character " + std::to_string(c));
    }
    TextLines text(std::string(all), file);
    while (text.line_number() < header.line_number() && text.next()) {
    }
    unsigned long long vertices = 0;
    for (const Element& e : elements) {
        if (e.name == "vertex") vertices = e.count;
        for (unsigned long long i = 0; i < e.count; ++i) {
            do {
                if (!text.next()) throw InputError(file + ": end of file in element " + e.name + " item " + std::to_string(i));
            } while (text.blank());
            std::size_t k = 0;
            for (const Property& p : e.properties) {
                const double first = text.number<double>(k++, p.name.c_str());
                if (!std::isfinite(first)) text.fail("non-finite value for " + p.name);
                if (!p.count_bytes) continue;
                if (first < 0 || first != std::floor(first) || first > 1e6)
                    text.fail("bad list length for " + p.name);
                for (long long j = 0; j < static_cast<long long>(first); ++j) {
                    const double v = text.number<double>(k++, p.name.c_str());
                    const bool index = e.name == "face" && (p.name == "vertex_indices" || p.name == "vertex_index");
                    if (index && (v < 0 || v != std::floor(v) || v >= static_cast<double>(vertices)))
                        text.fail("face refers to vertex " + std::string(text.tokens()[k - 1]) + ", the file has " +
                                  std::to_string(vertices));
                }
            }
            if (k != text.tokens().size())
                text.fail("expected " + std::to_string(k) + " fields for element " + e.name + ", got " +
                          std::to_string(text.tokens().size()));
        }
    }
    while (text.next())
        if (!text.blank()) text.fail("text after the last element");
}

}  // namespace rtc
