#include "lightcone/io/spelling.hpp"

#include <algorithm>
#include <vector>

namespace lightcone {

std::size_t edit_distance(std::string_view a, std::string_view b) {
  // Three rows of the dynamic programme: the one before last is for swaps.
  std::vector<std::size_t> before(b.size() + 1), last(b.size() + 1), row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) last[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t change = a[i - 1] == b[j - 1] ? 0 : 1;
      row[j] = std::min({last[j] + 1, row[j - 1] + 1, last[j - 1] + change});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
        row[j] = std::min(row[j], before[j - 2] + 1);
    }
    std::swap(before, last);
    std::swap(last, row);
  }
  return last[b.size()];
}

std::optional<std::string_view> nearest_name(std::string_view word,
                                             std::span<const std::string_view> names) {
  const std::size_t reach = std::max<std::size_t>(1, word.size() / 3);
  std::optional<std::string_view> best;
  std::size_t best_distance = reach + 1;
  for (const std::string_view name : names) {
    // The distance is at least the difference in length: a 10 MB key is compared with no name.
    const std::size_t length_gap =
        word.size() > name.size() ? word.size() - name.size() : name.size() - word.size();
    if (length_gap >= best_distance) continue;
    if (const std::size_t d = edit_distance(word, name); d < best_distance)
      best = name, best_distance = d;
  }
  return best;
}

}  // namespace lightcone
