// "Did you mean": the nearest of some names to a misspelt one, for messages about unknown scene
// keys and command-line options.
#pragma once

#include <optional>
#include <span>
#include <string_view>

namespace lightcone {

// The number of single-character insertions, deletions, substitutions and swaps of neighbours
// that turn a into b (the optimal-string-alignment distance).
std::size_t edit_distance(std::string_view a, std::string_view b);

// The name nearest to `word` within a third of its length (at least one edit, so that "colour"
// finds "color" and "--sample" finds "--samples"), the first of equally near ones; none when
// nothing is that near.
std::optional<std::string_view> nearest_name(std::string_view word,
                                             std::span<const std::string_view> names);

}  // namespace lightcone
