#include "sim/app/simulate_main.h"

#include "sim/app/cli.h"
#include "sim/app/run_all.h"
#include "sim/app/shard_runs.h"
#include "core/input_error.h"
#include "sim/execution/interrupt.h"
#include "sim/util/json_file.h"
#include "sim/util/version.h"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <exception>
#include <iostream>

namespace rtc {

namespace {

// --data DIR is RTCSIM_DATA=DIR for this process, so the data root stays
// decided in one place (data_root()). Absolute, as the option's value meant
// the working directory's DIR.
void use_data_root(const std::string& dir) {
    std::error_code ec;
    if (!std::filesystem::is_directory(dir, ec))
        throw InputError("simulate: --data " + dir + ": no such directory (scripts/fetch-data fills the repository's data/)");
    const std::filesystem::path abs = std::filesystem::absolute(dir, ec).lexically_normal();
    ::setenv("RTCSIM_DATA", (ec ? std::filesystem::path(dir) : abs).c_str(), 1);
}

}  // namespace

int simulate_main(const std::vector<std::string>& args) {
    try {
        const CliOptions cli = parse_cli(args);
        if (cli.help) {
            std::cout << cli_help();
            return 0;
        }
        if (cli.version) {
            std::cout << "simulate (rtcsim) " << kVersion << " (commit " << git_commit()
                      << (git_dirty() ? ", uncommitted changes" : "") << ")\n";
            return 0;
        }
        if (cli.data) use_data_root(*cli.data);
        if (cli.merge) return run_merge(cli);
        if (cli.estimate && cli.target_error) return print_sampling_estimate(cli);
        if (cli.estimate) return print_shard_estimates(cli);
        if (cli.shard) return run_shard(cli);
        return run_all(cli);
    } catch (const InputError& e) {
        std::fprintf(stderr, "%s\n", e.what());
        return 2;
    } catch (const Interrupted&) {
        // Unwound: temporaries removed, the output directory's mark still
        // says running, so merge and the readers refuse it.
        const int code = interrupted_exit_code();
        std::fprintf(stderr, "simulate: %s; the output directory is left marked unfinished\n",
                     code == 128 + kSigTerm ? "terminated (SIGTERM)" : "interrupted");
        return code;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "simulate: error: %s\n", e.what());
        return 3;
    }
}

}  // namespace rtc
