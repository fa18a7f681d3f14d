#include "lightcone/io/input_file.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <utility>

#include "lightcone/io/input_error.hpp"

namespace lightcone {

std::optional<std::string> try_read_input_file(const std::filesystem::path& file,
                                               std::uintmax_t max_bytes, std::string& reason) {
  namespace fs = std::filesystem;
  const auto fail = [&](std::string why) -> std::optional<std::string> {
    reason = std::move(why);
    return std::nullopt;
  };
  // Nothing is opened before the status says a regular file: opening a FIFO would block.
  std::error_code ec;
  const fs::file_status status = fs::status(file, ec);
  if (!fs::exists(status)) return fail(std::strerror(ENOENT));
  if (fs::is_directory(status)) return fail("it is a directory");
  if (!fs::is_regular_file(status))
    return fail("it is not a regular file (a device, a FIFO or a socket)");
  const std::uintmax_t size = fs::file_size(file, ec);
  if (ec) return fail(ec.message());
  if (size > max_bytes)
    return fail(fmt::format("{} bytes, more than the limit of {} bytes", size, max_bytes));
  std::ifstream in(file, std::ios::binary);
  if (!in) return fail(std::strerror(errno));
  std::string bytes(static_cast<std::size_t>(size), '\0');
  in.read(bytes.data(), static_cast<std::streamsize>(size));
  if (in.bad() || static_cast<std::uintmax_t>(in.gcount()) != size) return fail("read error");
  return bytes;
}

std::string read_input_file(const std::filesystem::path& file, const std::string& what,
                            std::uintmax_t max_bytes) {
  std::string reason;
  std::optional<std::string> bytes = try_read_input_file(file, max_bytes, reason);
  if (!bytes) throw InputError(fmt::format("{}: cannot read {}: {}", file.string(), what, reason));
  return std::move(*bytes);
}

}  // namespace lightcone
