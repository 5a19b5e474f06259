// `simulate`: the command-line front end. Everything it does lives in the sim
// library; this file only sequences it and turns errors into one clear line.
#include "sim/app/cli.h"
#include "sim/util/json_file.h"
#include "sim/report/report.h"
#include "sim/app/run_all.h"
#include "sim/util/version.h"

#include <cstdio>
#include <exception>
#include <iostream>

int main(int argc, char** argv) {
    try {
        const rtc::CliOptions cli = rtc::parse_cli(std::vector<std::string>(argv + 1, argv + argc));
        if (cli.help) {
            std::cout << rtc::cli_help();
            return 0;
        }
        if (cli.version) {
            std::cout << "simulate (rtcsim) " << rtc::kVersion << "\n";
            return 0;
        }
        return rtc::run_all(cli);
    } catch (const rtc::InputError& e) {
        std::fprintf(stderr, "%s\n", e.what());
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "simulate: error: %s\n", e.what());
        return 3;
    }
}
