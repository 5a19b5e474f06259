// An error in user input (config, scene or ray file). `what()` is the whole
// one-line message, "<file>: <JSON path, line or byte offset>: <problem>", so
// every layer can report bad input the same way and the CLI just prints it.
#pragma once

#include <stdexcept>

namespace rtc {

class InputError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

}  // namespace rtc
