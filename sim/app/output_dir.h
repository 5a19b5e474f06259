// simulate's output directories: owned by one run, never mixed with what was
// there before, and marked finished only when everything is written.
//
// The rule: `simulate` writes only into a directory that is missing or empty,
// and marks it with a `.rtcsim-output` file. An existing non-empty directory
// is refused (exit 2) unless --force; --force then empties it, but only when
// it carries the mark, i.e. when everything in it came from an earlier run of
// simulate (sweep points, plots, reports); a non-empty directory without the
// mark (a home directory, a typo for the source tree) is refused even with
// --force. So stale sweep points and plots never survive a re-run, and
// nothing simulate did not write is deleted.
//
// The run holds an exclusive lock (flock) on the mark from before the
// emptiness check until it exits, so a second run on the same directory,
// started at the same time, is refused (exit 2) instead of mixing its files
// with the first's. The mark says `state: running` until the run has written
// everything, then `state: complete` (renamed into place, as every output
// file is: OutputFile). Readers (simulate merge, rtcsim.load_report, python
// -m rtcsim.plot) refuse a directory whose mark does not say complete: a run
// that failed, was killed, or is still running.
//
// Never through a symlink: a mark that is a symbolic link (a `cp -rs` copy
// of a finished directory) is refused, so the original is not marked.
// --force never deletes the run's own inputs: a config, scene, ray file or
// preset inside the directory is refused before anything is emptied. Where
// the file system has no locks (flock fails with ENOSYS, ENOLCK, ...) the
// run is refused saying so; RTCSIM_NO_LOCK=1 runs without the lock.
#pragma once

#include <string>
#include <vector>

namespace rtc {

inline constexpr const char* kOutputMark = ".rtcsim-output";

// The output directory of one run, locked for as long as this object lives.
class OutputDir {
public:
    // Makes `dir` ready for a run (see above) and checks it is writable.
    // `inputs`: the files the run reads (input_paths), which --force must
    // not delete. Throws InputError naming `dir`.
    OutputDir(std::string dir, bool force, const std::vector<std::string>& inputs = {});
    ~OutputDir();
    OutputDir(const OutputDir&) = delete;
    OutputDir& operator=(const OutputDir&) = delete;

    // Marks the run complete (call after its last file is written); throws
    // Interrupted instead when a stop was requested (sim/execution/interrupt.h).
    void finish();
    [[nodiscard]] const std::string& path() const { return dir_; }

private:
    std::string dir_;
    int lock_fd_ = -1;
};

// Throws InputError naming `dir` when it carries simulate's mark and the
// mark does not say the run completed.
void require_finished_output(const std::string& dir);

// `out/<name><suffix>`, the output directory of a run without --out. The
// config's `name` becomes a path component: one with `/`, `\`, a control
// character (NUL included), or that is empty, `.` or `..`, is refused with an
// InputError naming `file` and /name.
[[nodiscard]] std::string default_output_dir(const std::string& name, const std::string& suffix,
                                             const std::string& file);

// Creates `dir` (a sweep point's directory inside a prepared one).
void make_dir(const std::string& dir);

}  // namespace rtc
