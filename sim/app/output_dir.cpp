#include "sim/app/output_dir.h"

#include "core/input_error.h"

#include <cstdio>
#include <filesystem>

namespace rtc {

namespace fs = std::filesystem;

void make_dir(const std::string& dir) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec || !fs::is_directory(dir))
        throw InputError(dir + ": cannot create output directory" + (ec ? " (" + ec.message() + ")" : ""));
}

void prepare_output_dir(const std::string& dir, bool force) {
    std::error_code ec;
    if (fs::exists(dir, ec) && !fs::is_directory(dir, ec))
        throw InputError(dir + ": output path exists and is not a directory");
    if (fs::is_directory(dir, ec)) {
        bool empty = true;
        for (const fs::directory_entry& e : fs::directory_iterator(dir, ec))
            if (e.path().filename() != kOutputMark) empty = false;
        if (!empty) {
            const bool marked = fs::exists(fs::path(dir) / kOutputMark, ec);
            if (!force)
                throw InputError(dir + ": output directory exists and is not empty (--force clears it" +
                                 std::string(marked ? "" : "; it must be one simulate wrote") +
                                 ", or choose another --out)");
            if (!marked)
                throw InputError(dir + ": output directory is not empty and was not written by simulate (no " +
                                 kOutputMark + "): --force only clears simulate's own output directories; "
                                 "remove it yourself or choose another --out");
            for (const fs::directory_entry& e : fs::directory_iterator(dir, ec)) {
                fs::remove_all(e.path(), ec);
                if (ec) throw InputError(e.path().string() + ": cannot remove (" + ec.message() + ")");
            }
        }
    }
    make_dir(dir);
    const std::string mark = (fs::path(dir) / kOutputMark).string();
    std::FILE* f = std::fopen(mark.c_str(), "wb");
    if (!f) throw InputError(dir + ": output directory is not writable");
    std::fputs("This directory was written by rtcsim's simulate; simulate --force may empty it.\n", f);
    std::fclose(f);
}

}  // namespace rtc
