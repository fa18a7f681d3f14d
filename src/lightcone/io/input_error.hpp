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

// Throws the refusal of one of the library's rules (frame/request_rules.hpp), if any, as the
// error every door shows.
inline void throw_if_refused(const std::optional<std::string>& refusal) {
  if (refusal) throw InputError(*refusal);
}

}  // namespace lightcone
