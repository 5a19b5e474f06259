// Reading text and JSON files with errors that name the file and line, and
// writing output files whole or not at all.
#pragma once

#include <nlohmann/json.hpp>

#include <cstdio>
#include <string>
#include <string_view>

namespace rtc {

[[nodiscard]] std::string read_text_file(const std::string& path);
// Refuses (InputError naming the file and line) JSON nested deeper than
// kMaxJsonDepth, before nlohmann builds it: copying or destroying a deep
// value recurses once per level and would overflow the stack.
[[nodiscard]] nlohmann::json parse_json_text(const std::string& text, const std::string& file);

// Configs and presets nest fewer than 10 levels.
inline constexpr int kMaxJsonDepth = 128;
void check_json_depth(std::string_view text, const std::string& file);
// How deep `text`'s brackets nest, strings skipped (0 for a scalar); counts
// up to `stop` and no further, so a hostile text costs one pass.
[[nodiscard]] int json_nesting(std::string_view text, int stop = kMaxJsonDepth + 1);

// A file written under a temporary name (`path` + ".partial") and renamed to
// `path` by commit(): a reader never finds a cut file under the real name.
// Every write, the close and the rename are checked: an InputError names
// `path` and the system's reason (a full disk, a file-size limit). Destroyed
// without commit() (an error, an exception), it removes the partial file.
class OutputFile {
public:
    explicit OutputFile(std::string path);
    ~OutputFile();
    OutputFile(const OutputFile&) = delete;
    OutputFile& operator=(const OutputFile&) = delete;

    void write(const void* data, std::size_t bytes);
    void write(std::string_view text) { write(text.data(), text.size()); }
    // For writers that cannot throw (C callbacks): the first error is kept
    // and commit() throws it.
    void write_noexcept(const void* data, std::size_t bytes) noexcept;
    void commit();
    [[nodiscard]] const std::string& path() const { return path_; }

private:
    [[noreturn]] void fail(const char* what, int error);
    std::string path_, partial_;
    std::FILE* f_ = nullptr;
    int error_ = 0;  // the first write's errno, kept by write_noexcept
};

// `content` into `path` through an OutputFile.
void write_file_atomically(const std::string& path, std::string_view content);

}  // namespace rtc
