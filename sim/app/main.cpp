// `simulate`: the command-line front end; everything lives in the sim
// libraries (sim/app/simulate_main.cpp sequences it).
#include "sim/app/simulate_main.h"
#include "sim/util/process_memory.h"

int main(int argc, char** argv) {
    rtc::keep_freed_memory();
    return rtc::simulate_main(std::vector<std::string>(argv + 1, argv + argc));
}
