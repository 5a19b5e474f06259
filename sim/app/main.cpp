// `simulate`: the command-line front end; everything lives in the sim
// libraries (sim/app/simulate_main.cpp sequences it).
#include "sim/app/simulate_main.h"

int main(int argc, char** argv) {
    return rtc::simulate_main(std::vector<std::string>(argv + 1, argv + argc));
}
