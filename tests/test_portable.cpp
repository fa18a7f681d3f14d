// The browser build's shims (src/lightcone/portable.hpp), checked natively against the standard
// library they stand in for.
#include <gtest/gtest.h>

#include <charconv>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "lightcone/portable.hpp"

namespace lightcone {
namespace {

// The same value, the same end and the same error as std::from_chars.
void expect_as_from_chars(const std::string& text) {
  double ours = -7, theirs = -7;
  const auto a = detail::from_chars_by_strtod(text.data(), text.data() + text.size(), ours);
  const auto b = std::from_chars(text.data(), text.data() + text.size(), theirs);
  EXPECT_EQ(a.ec, b.ec) << '"' << text << '"';
  EXPECT_EQ(a.ptr - text.data(), b.ptr - text.data()) << '"' << text << '"';
  if (b.ec == std::errc()) {
    EXPECT_EQ(bit_cast<std::uint64_t>(ours), bit_cast<std::uint64_t>(theirs)) << '"' << text << '"';
  }
}

TEST(Portable, FromCharsByStrtodReadsAsStdFromChars) {
  for (const char* text :
       {"0",
        "-0",
        "1",
        "-2.5",
        "3.25e2",
        "1E-3",
        "6.02214076e23",
        "1.5abc",
        "2.",
        ".5",
        "-.5",
        "1e",
        "1e+",
        "7e-2x",
        "0x1p3",
        "0X10",
        "inf",
        "-infinity",
        "nan",
        "1e400",
        "",
        "+1",
        " 1",
        "-",
        "abc",
        "1,5",
        "0.1000000000000000055511151231257827021181583404541015625",
        "123456789012345678901234567890123456789012345678901234567890123456789e-50"})
    expect_as_from_chars(text);
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> exponent(-300, 300), mantissa(-10, 10);
  char text[64];
  for (int i = 0; i < 20000; ++i) {
    const double value = mantissa(random) * std::pow(10.0, exponent(random));
    std::snprintf(text, sizeof text, i % 2 ? "%.17g" : "%g", value);
    expect_as_from_chars(text);
  }
}

TEST(Portable, ParallelForVisitsEveryIndexOnce) {
  std::vector<int> seen(10007, 0);
  parallel_for(0, static_cast<int>(seen.size()),
               [&](int i) { ++seen[static_cast<std::size_t>(i)]; });
  for (const int count : seen) EXPECT_EQ(count, 1);
  std::vector<int> pieces(10007, 0);
  parallel_for_pieces(0, static_cast<int>(pieces.size()), 64, [&](int begin, int end) {
    for (int i = begin; i < end; ++i) ++pieces[static_cast<std::size_t>(i)];
  });
  for (const int count : pieces) EXPECT_EQ(count, 1);
}

}  // namespace
}  // namespace lightcone
