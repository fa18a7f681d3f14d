// The JSON document of a scene file: nlohmann::json with its arrays, objects and string values
// made in an arena (the characters of a long string still come from the heap). A large scene is
// millions of small values (some 25 of them a body), made one by one and freed all together once
// it is read: an arena makes them for a bump of a pointer and frees them in a few large blocks,
// where malloc and free cost more than the parse itself.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "lightcone/portable.hpp"
#if LIGHTCONE_HAVE_MEMORY_RESOURCE
#include <memory_resource>
#endif

namespace lightcone {

#if LIGHTCONE_HAVE_MEMORY_RESOURCE

// Memory for the documents made on this thread while it lives, freed all at once when it ends.
// Every value made under it must be destroyed before it ends.
class DocumentArena {
 public:
  DocumentArena() : memory_(kFirstBlock, &blocks()), outer_(current_) { current_ = &memory_; }
  ~DocumentArena() { current_ = outer_; }
  DocumentArena(const DocumentArena&) = delete;
  DocumentArena& operator=(const DocumentArena&) = delete;

  // The innermost arena of this thread, or null. nlohmann makes an allocator wherever it needs
  // one, so an allocator cannot carry its arena: it finds it here.
  static std::pmr::memory_resource* current() { return current_; }

 private:
  static constexpr std::size_t kFirstBlock = std::size_t{64} << 10;  // each next one is larger
  // Where the arenas' blocks come from.
  static std::pmr::memory_resource& blocks();

  std::pmr::monotonic_buffer_resource memory_;
  std::pmr::memory_resource* outer_;
  static inline thread_local std::pmr::memory_resource* current_ = nullptr;
};

// Allocates from this thread's DocumentArena, whose memory is freed when it ends; outside of any,
// from the heap.
template <class T>
struct DocumentAllocator {
  using value_type = T;

  DocumentAllocator() = default;
  template <class U>
  DocumentAllocator(const DocumentAllocator<U>& /*other*/) noexcept {}

  T* allocate(std::size_t n) {
    if (std::pmr::memory_resource* arena = DocumentArena::current())
      return static_cast<T*>(arena->allocate(n * sizeof(T), alignof(T)));
    return std::allocator<T>().allocate(n);
  }
  void deallocate(T* p, std::size_t n) noexcept {
    if (!DocumentArena::current()) std::allocator<T>().deallocate(p, n);
  }

  friend bool operator==(const DocumentAllocator&, const DocumentAllocator&) { return true; }
};

#else
// Without <memory_resource> (the browser build), documents are made on the heap.
class DocumentArena {
 public:
  DocumentArena() {}  // user-provided, so that a const one may be made
  DocumentArena(const DocumentArena&) = delete;
  DocumentArena& operator=(const DocumentArena&) = delete;
};
template <class T>
using DocumentAllocator = std::allocator<T>;
#endif

using SceneJson = nlohmann::basic_json<std::map, std::vector, std::string, bool, std::int64_t,
                                       std::uint64_t, double, DocumentAllocator>;

}  // namespace lightcone
