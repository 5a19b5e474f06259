#include "sim/app/output_dir.h"

#include "core/input_error.h"
#include "sim/execution/interrupt.h"
#include "sim/util/json_file.h"

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

namespace rtc {

namespace fs = std::filesystem;

namespace {

constexpr const char* kMarkText = "This directory was written by rtcsim's simulate; simulate --force may empty it.\n";

bool is_mark(const fs::path& name) { return name.string().rfind(kOutputMark, 0) == 0; }

std::string mark_of(const std::string& dir) { return (fs::path(dir) / kOutputMark).string(); }

// Whether `dir` holds anything besides simulate's mark.
bool has_outputs(const std::string& dir) {
    std::error_code ec;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
        if (!is_mark(it->path().filename())) return true;
    return false;
}

void write_mark(const std::string& dir, const char* state) {
    write_file_atomically(mark_of(dir), std::string(kMarkText) + "state: " + state + "\n");
}

}  // namespace

std::string default_output_dir(const std::string& name, const std::string& suffix, const std::string& file) {
    bool bad = name.empty() || name == "." || name == ".." || name.size() > 200;
    for (const char c : name)
        bad = bad || c == '/' || c == '\\' || static_cast<unsigned char>(c) < 0x20 || c == 0x7f;
    if (bad)
        throw InputError(file + ": /name: " + nlohmann::json(name).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) +
                         " cannot name the output directory out/<name> (it must be a file name: not empty, . or "
                         ".., without / or \\ or control characters, at most 200 bytes): rename the run or pass --out");
    return "out/" + name + suffix;
}

void make_dir(const std::string& dir) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec || !fs::is_directory(dir, ec))
        throw InputError(dir + ": cannot create output directory" + (ec ? " (" + ec.message() + ")" : ""));
}

OutputDir::OutputDir(std::string dir, bool force, const std::vector<std::string>& inputs) : dir_(std::move(dir)) {
    std::error_code ec;
    if (fs::exists(dir_, ec) && !fs::is_directory(dir_, ec))
        throw InputError(dir_ + ": output path exists and is not a directory");
    const std::string mark = mark_of(dir_);
    if (fs::is_symlink(fs::symlink_status(mark, ec)))
        throw InputError(mark + ": is a symbolic link (a copy made with cp -rs?): simulate does not write through "
                                "one; remove it or choose another --out");
    // A directory simulate did not write is refused before anything is
    // created in it.
    if (fs::is_directory(dir_, ec) && !fs::exists(mark, ec) && has_outputs(dir_))
        throw InputError(dir_ + (force ? ": output directory is not empty and was not written by simulate (no " +
                                             std::string(kOutputMark) +
                                             "): --force only clears simulate's own output directories; "
                                             "remove it yourself or choose another --out"
                                       : ": output directory exists and is not empty (--force clears it; it must be "
                                         "one simulate wrote, or choose another --out)"));
    make_dir(dir_);
    // Lock the mark. A run that finishes renames a new mark into place, so
    // the lock is retried until it is on the file the path names.
    const char* no_lock = std::getenv("RTCSIM_NO_LOCK");
    const bool lock = !(no_lock && std::string(no_lock) == "1");
    for (int attempt = 0;; ++attempt) {
        lock_fd_ = ::open(mark.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0644);
        if (lock_fd_ < 0 && errno == ELOOP)
            throw InputError(mark + ": is a symbolic link: simulate does not write through one");
        if (lock_fd_ < 0) throw InputError(dir_ + ": output directory is not writable (" + std::strerror(errno) + ")");
        if (!lock) break;
        if (::flock(lock_fd_, LOCK_EX | LOCK_NB) != 0) {
            const int error = errno;
            ::close(lock_fd_);
            lock_fd_ = -1;
            if (error == EWOULDBLOCK || error == EINTR)
                throw InputError(dir_ + ": output directory is in use by another simulate run (choose another --out, "
                                        "or wait for it to finish)");
            throw InputError(mark + ": cannot lock (" + std::strerror(error) +
                             "; the file system may not support locks): choose --out on another file system, or set "
                             "RTCSIM_NO_LOCK=1 to run without the lock (nothing then stops a second run on it)");
        }
        struct stat held {}, named {};
        if (::fstat(lock_fd_, &held) == 0 && ::stat(mark.c_str(), &named) == 0 && held.st_ino == named.st_ino &&
            held.st_dev == named.st_dev)
            break;
        ::close(lock_fd_);
        lock_fd_ = -1;
        if (attempt == 10) throw InputError(dir_ + ": output directory is in use by another simulate run");
    }
    // From here the lock is held: an error releases it before it is thrown.
    const auto fail = [this](const std::string& message) {
        ::close(lock_fd_);
        lock_fd_ = -1;
        throw InputError(message);
    };
    if (has_outputs(dir_)) {
        if (!force) fail(dir_ + ": output directory exists and is not empty (--force clears it, or choose another --out)");
        // The run's inputs are read after this: emptying must not delete them.
        const fs::path inside = fs::weakly_canonical(fs::absolute(dir_, ec), ec);
        for (const std::string& input : inputs) {
            std::error_code ic;
            const fs::path file = fs::weakly_canonical(fs::absolute(input, ic), ic);
            if (ic || ec) continue;
            const auto [d, f] = std::mismatch(inside.begin(), inside.end(), file.begin(), file.end());
            if (d == inside.end() && f != file.end())
                fail(dir_ + ": --force would empty it, and it holds " + input +
                     ", an input of this run: move the input out, or choose another --out");
        }
        for (fs::directory_iterator it(dir_, ec), end; !ec && it != end; it.increment(ec)) {
            if (it->path().filename() == kOutputMark) continue;
            std::error_code rm;
            fs::remove_all(it->path(), rm);
            if (rm) fail(it->path().string() + ": cannot remove (" + rm.message() + ")");
        }
    }
    // Written in place (the lock is on this file): `state: running`.
    const std::string text = std::string(kMarkText) + "state: running\n";
    if (::ftruncate(lock_fd_, 0) != 0 ||
        ::pwrite(lock_fd_, text.data(), text.size(), 0) != static_cast<ssize_t>(text.size()))
        fail(dir_ + ": output directory is not writable (" + std::strerror(errno) + ")");
}

OutputDir::~OutputDir() {
    if (lock_fd_ >= 0) ::close(lock_fd_);
}

void OutputDir::finish() {
    // A stop requested after the run's last check (while its files were
    // written): not marked complete, and the run exits 128 + the signal.
    throw_if_interrupted();
    write_mark(dir_, "complete");
}

void require_finished_output(const std::string& dir) {
    std::ifstream in(mark_of(dir), std::ios::binary);
    if (!in) return;  // not simulate's directory (a copied report): nothing to check
    std::ostringstream text;
    text << in.rdbuf();
    const std::string s = text.str();
    if (s.find("state: complete\n") != std::string::npos) return;
    // A mark of an older simulate (no state line) is accepted.
    if (!s.empty() && s.find("state: ") == std::string::npos) return;
    throw InputError(dir + ": an unfinished simulate run (" + kOutputMark +
                     " does not say complete: it failed, was killed, or is still running)");
}

}  // namespace rtc
