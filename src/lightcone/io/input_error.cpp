#include "lightcone/io/input_error.hpp"

#include <fmt/format.h>

#include <string_view>

namespace lightcone {

std::string printable(const std::string& message) {
  std::string out;
  std::size_t start = 0;
  while (start <= message.size()) {
    std::size_t end = message.find(' ', start);
    if (end == std::string::npos) end = message.size();
    std::string_view word(message.data() + start, end - start);
    const bool cut = word.size() > 160;
    if (cut) word = word.substr(0, 80);
    for (const char ch : word) {
      const auto c = static_cast<unsigned char>(ch);
      if (c < 0x20 || c == 0x7f)
        out += fmt::format("\\x{:02x}", c);
      else
        out += ch;
    }
    if (cut) out += "...";
    if (end == message.size()) break;
    out += ' ';
    start = end + 1;
  }
  return out;
}

}  // namespace lightcone
