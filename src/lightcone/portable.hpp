// The few things the browser build lacks, in one place. Emscripten's libc++ has no std::bit_cast,
// no floating-point std::from_chars and no <memory_resource> (the scene document is then made on
// the heap), and a page without threads has no TBB: there, parallel loops run in order on the one
// thread. Native builds use the standard library and TBB unchanged.
#pragma once

#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <string>
#include <type_traits>
#include <utility>

#ifdef __EMSCRIPTEN__
#define LIGHTCONE_HAVE_MEMORY_RESOURCE 0
#else
#define LIGHTCONE_HAVE_MEMORY_RESOURCE 1
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <bit>
#endif

namespace lightcone {

// std::bit_cast where the library has it.
template <class To, class From>
To bit_cast(const From& from) noexcept {
  static_assert(sizeof(To) == sizeof(From) && std::is_trivially_copyable_v<From> &&
                std::is_trivially_copyable_v<To>);
#ifdef __EMSCRIPTEN__
  To to;
  std::memcpy(&to, &from, sizeof(To));
  return to;
#else
  return std::bit_cast<To>(from);
#endif
}

namespace detail {
// Floating-point from_chars by strtod, as from_chars reads: no leading space or plus sign, no
// hexadecimal. The browser's; compiled everywhere, so that the native tests check it against
// std::from_chars.
template <class T>
std::from_chars_result from_chars_by_strtod(const char* first, const char* last, T& value) {
  static_assert(std::is_floating_point_v<T>);
  // strtod reads a terminated string: a copy on the stack (on the heap past 63 characters).
  char buffer[64];
  std::string long_text;
  const auto size = static_cast<std::size_t>(last - first);
  const char* text = buffer;
  if (size < sizeof buffer) {
    std::memcpy(buffer, first, size);
    buffer[size] = '\0';
  } else {
    long_text.assign(first, last);
    text = long_text.c_str();
  }
  // from_chars reads "0x1p3" as 0 followed by text: so does strtod, cut before the x.
  if (char* x = std::strpbrk(text == buffer ? buffer : long_text.data(), "xX")) *x = '\0';
  const bool refused =
      size == 0 || text[0] == '+' || std::isspace(static_cast<unsigned char>(text[0]));
  char* end = nullptr;
  errno = 0;
  const double parsed = refused ? 0 : std::strtod(text, &end);
  if (refused || end == text) return {first, std::errc::invalid_argument};
  const char* stop = first + (end - text);
  if (errno == ERANGE && std::abs(parsed) > 1) return {stop, std::errc::result_out_of_range};
  value = static_cast<T>(parsed);
  return {stop, std::errc()};
}
}  // namespace detail

// std::from_chars where the library has it; in the browser, floating-point values are read by
// detail::from_chars_by_strtod.
template <class T>
std::from_chars_result from_chars(const char* first, const char* last, T& value) {
#ifdef __EMSCRIPTEN__
  if constexpr (std::is_floating_point_v<T>) {
    return detail::from_chars_by_strtod(first, last, value);
  } else {
    return std::from_chars(first, last, value);
  }
#else
  return std::from_chars(first, last, value);
#endif
}

// body(i) for every i in [first, last), in any order and on any thread.
template <class Index, class Body>
void parallel_for(Index first, Index last, const Body& body) {
#ifdef __EMSCRIPTEN__
  for (Index i = first; i < last; ++i) body(i);
#else
  tbb::parallel_for(first, last, body);
#endif
}

// The colour tables' nodes (color/doppler_table.hpp's ForEachNode) on the TBB pool: a frame of
// the viewer builds its tables while it waits.
struct ParallelNodes {
  template <class F>
  void operator()(int n, const F& f) const {
    parallel_for(0, n, [&](int k) { f(k); });
  }
};

// body(begin, end) over pieces of [first, last) of about `grain` items each.
template <class Index, class Body>
void parallel_for_pieces(Index first, Index last, Index grain, const Body& body) {
#ifdef __EMSCRIPTEN__
  (void)grain;
  if (first < last) body(first, last);
#else
  tbb::parallel_for(tbb::blocked_range<Index>(first, last, grain),
                    [&](const tbb::blocked_range<Index>& r) { body(r.begin(), r.end()); });
#endif
}

// One T a thread (TBB's enumerable_thread_specific; in the browser, the one thread's), made on
// first use; combined() adds them with T::add.
template <class T>
class PerThread {
 public:
  T& local() {
#ifdef __EMSCRIPTEN__
    return one_;
#else
    return each_.local();
#endif
  }
  T combined() {
#ifdef __EMSCRIPTEN__
    return std::move(one_);
#else
    T sum;
    for (const T& part : each_) sum.add(part);
    return sum;
#endif
  }

 private:
#ifdef __EMSCRIPTEN__
  T one_;
#else
  tbb::enumerable_thread_specific<T> each_;
#endif
};

}  // namespace lightcone
