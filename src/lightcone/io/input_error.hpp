// The one error type for bad user input: its message already names the file, the line and the
// field (JSON path), so the CLI prints it as it is and exits with status 2.
#pragma once

#include <stdexcept>
#include <string>

namespace lightcone {

struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace lightcone
