// Paths named in configs, the data root, and where hardware presets are found.
//
// A relative path in a config resolves against the directory of the config
// file that names it (never the working directory), so a config runs from
// anywhere. A path starting "data:" names a file under the data root instead
// (the public models scripts/fetch-data installs, docs/data.md), so the
// shipped configs do not depend on where the data lies. A preset value without a '/' and without ".json" is a preset
// *name*: `"cost": ["turing-calibrated"]` is <preset dir>/turing-calibrated.json,
// with the preset directories searched in order (preset_dirs()).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace rtc {

// `path` as given when absolute, else relative to the directory of
// `config_file` (the working directory when it has none), lexically normal.
[[nodiscard]] std::string config_relative_path(const std::string& path, const std::string& config_file);

// The prefix of a path under the data root: "data:hair/sintel_hair_16pts.tfx".
inline constexpr const char* kDataPrefix = "data:";
[[nodiscard]] bool is_data_path(const std::string& path);

// The one place the data root is decided, the first given of
//   1. $RTCSIM_DATA, if set and not empty (`simulate --data DIR` sets it for
//      its own run and the processes it starts);
//   2. the source tree's data/, compiled in (where scripts/fetch-data puts it).
[[nodiscard]] std::filesystem::path data_root();

// A data file's path from a config: "data:REL" is data_root()/REL, anything
// else config_relative_path(). Lexically normal.
[[nodiscard]] std::string config_data_path(const std::string& path, const std::string& config_file);

// Where presets named by name are looked for, in order, existing or not:
//   1. $RTCSIM_PRESET_DIR, if set and not empty;
//   2. <directory of the running program>/../share/rtcsim/hw (a relocated install);
//   3. the install's preset directory compiled in (CMAKE_INSTALL_FULL_DATADIR/rtcsim/hw);
//   4. the source tree's configs/hw compiled in (so a build tree works);
//   5. configs/hw beside the shared object holding this code, when it is one
//      (the Python module installed by pip carries the presets so: rtcsim/).
[[nodiscard]] std::vector<std::filesystem::path> preset_dirs();

// True when `value` names a preset by name rather than by path.
[[nodiscard]] bool is_preset_name(const std::string& value);

// A preset value from a config: a name (searched in preset_dirs()) or a path
// (config_relative_path). Throws InputError "<config_file>: <key>: ..." naming
// the places searched when the preset is not found.
[[nodiscard]] std::string resolve_preset(const std::string& value, const std::string& config_file,
                                         const std::string& key);

// A preset or method name as part of an output file name (cycles_<method>_<preset>.npy):
// letters, digits, '-', '_' and '.' kept, anything else '_'. Configs are
// checked when planned so that no two of a run's names give one file name.
[[nodiscard]] std::string file_name_part(const std::string& name);
// Output names longer than this are refused when planned (file names stay
// well under the file systems' 255 bytes with their prefixes).
inline constexpr std::size_t kMaxFileNamePart = 100;

// True when `file` lies in one of preset_dirs() (a shipped or installed preset).
[[nodiscard]] bool in_preset_dir(const std::filesystem::path& file);

}  // namespace rtc
