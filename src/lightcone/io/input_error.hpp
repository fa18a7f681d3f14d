// The one error type for bad user input: its message already names the file, the line and the
// field (JSON path), so the CLI prints it as it is and exits with status 2.
#pragma once

#include <optional>
#include <stdexcept>
#include <string>

namespace lightcone {

struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A message as every door shows it (the program on a terminal, the Python module's exceptions,
// the web page): control characters (a NUL, escape sequences) shown as \xNN, and any run of more
// than 160 characters without a space (a 10 MB key echoed back) cut to its first 80 and "...".
std::string printable(const std::string& message);

// Throws the refusal of one of the library's rules (frame/request_rules.hpp), if any, as the
// error every door shows.
inline void throw_if_refused(const std::optional<std::string>& refusal) {
  if (refusal) throw InputError(*refusal);
}

}  // namespace lightcone
