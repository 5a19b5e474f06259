#include "sim/app/simulate_main.h"

#include "sim/app/cli.h"
#include "sim/app/run_all.h"
#include "sim/app/shard_runs.h"
#include "core/input_error.h"
#include "sim/execution/interrupt.h"
#include "sim/util/json_file.h"
#include "sim/util/version.h"

#include <cstdio>
#include <exception>
#include <iostream>

namespace rtc {

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
        std::fprintf(stderr, "simulate: interrupted; the output directory is left marked unfinished\n");
        return kInterruptedExitCode;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "simulate: error: %s\n", e.what());
        return 3;
    }
}

}  // namespace rtc
