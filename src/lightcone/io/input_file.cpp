#include "lightcone/io/input_file.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <cstring>
#include <fstream>

#include "lightcone/io/input_error.hpp"

namespace lightcone {

std::string read_input_file(const std::filesystem::path& file, const std::string& what,
                            std::uintmax_t max_bytes) {
  namespace fs = std::filesystem;
  const auto fail = [&](const std::string& reason) {
    throw InputError(fmt::format("{}: cannot read {}: {}", file.string(), what, reason));
  };
  std::error_code ec;
  const fs::file_status status = fs::status(file, ec);
  if (!fs::exists(status)) fail(std::strerror(ENOENT));
  if (fs::is_directory(status)) fail("it is a directory");
  if (!fs::is_regular_file(status)) fail("it is not a regular file (a device, a FIFO or a socket)");
  const std::uintmax_t size = fs::file_size(file, ec);
  if (ec) fail(ec.message());
  if (size > max_bytes)
    fail(fmt::format("{} bytes, more than the limit of {} bytes", size, max_bytes));
  std::ifstream in(file, std::ios::binary);
  if (!in) fail(std::strerror(errno));
  std::string bytes(static_cast<std::size_t>(size), '\0');
  in.read(bytes.data(), static_cast<std::streamsize>(size));
  if (in.bad() || static_cast<std::uintmax_t>(in.gcount()) != size) fail("read error");
  return bytes;
}

}  // namespace lightcone
