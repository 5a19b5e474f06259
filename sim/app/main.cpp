// `simulate`: the command-line front end; everything lives in the sim
// libraries (sim/app/simulate_main.cpp sequences it).
#include "sim/app/simulate_main.h"
#include "sim/util/process_memory.h"

#include <cstdio>
#include <cstdlib>

int main(int argc, char** argv) {
    rtc::keep_freed_memory();
    if (!rtc::set_huge_pages_from_environment("simulate")) return 2;
    return rtc::simulate_main(std::vector<std::string>(argv + 1, argv + argc));
}
