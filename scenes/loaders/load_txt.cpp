// The plain text curve format, this project's interchange format (also what
// export.h writes): one "x y z r" line per point, one or more blank lines
// between strands, '#' starts a comment. A line holding only a comment does
// not separate strands, so files can be annotated freely.
#include "scenes/loaders/file_bytes.h"
#include "scenes/loaders/loaders.h"
#include "scenes/generators/strand_builder.h"
#include "scenes/loaders/text_lines.h"

namespace rtc {

LoadedCurves load_txt(const std::filesystem::path& file) {
    const std::vector<std::uint8_t> bytes = read_file_bytes(file);
    const std::string text_bytes(bytes.begin(), bytes.end());
    TextLines text(text_bytes, file.string());
    LoadedCurves out;
    out.has_radius = true;
    StrandBuilder build(out.strands, file.string());
    std::size_t strand_line = 0;  // where the open strand started
    // A truly empty line (no comment) separates strands; find it by raw text.
    std::size_t raw_pos = 0;
    while (text.next()) {
        const std::size_t end = text_bytes.find('\n', raw_pos);
        const std::string_view raw(text_bytes.data() + raw_pos,
                                   (end == std::string::npos ? text_bytes.size() : end) - raw_pos);
        raw_pos = end == std::string::npos ? text_bytes.size() : end + 1;
        if (text.blank()) {
            const bool comment_only = raw.find('#') != std::string_view::npos;
            if (!comment_only && build.open_points() > 0) build.end_strand(at_line(strand_line));
            continue;
        }
        if (text.tokens().size() != 4)
            text.fail("expected 4 numbers \"x y z r\", got " + std::to_string(text.tokens().size()) +
                      " fields");
        if (build.open_points() == 0) strand_line = text.line_number();
        build.add_point(Vec3(text.number<float>(0, "x"), text.number<float>(1, "y"),
                             text.number<float>(2, "z")),
                        text.number<float>(3, "r"), at_line(text.line_number()));
    }
    if (build.open_points() > 0) build.end_strand(at_line(strand_line));
    return out;
}

}  // namespace rtc
