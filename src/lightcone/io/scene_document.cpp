#include "lightcone/io/scene_document.hpp"

#include <new>

#if defined(__linux__)
#include <sys/mman.h>
#endif

#if LIGHTCONE_HAVE_MEMORY_RESOURCE
namespace lightcone {
namespace {

// The blocks of the document arenas grow with the document, which for a large scene is hundreds
// of MB. Where the kernel has huge pages on request (Linux's transparent huge pages), the large
// blocks ask for them, so that first touching the document takes a page fault per 2 MiB, not per
// 4 KiB (10^5 bodies: 22,000 of their 75,000 page faults, some 4% of the time to render them).
class BlockResource final : public std::pmr::memory_resource {
 private:
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  static constexpr std::size_t kHugePage = std::size_t{2} << 20;
  static bool mapped(std::size_t bytes, std::size_t alignment) {
    return bytes >= kHugePage && alignment <= alignof(std::max_align_t);
  }
#else
  static bool mapped(std::size_t /*bytes*/, std::size_t /*alignment*/) {
    return false;
  }
#endif

  void* do_allocate(std::size_t bytes, std::size_t alignment) override {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    if (mapped(bytes, alignment)) {
      void* p = mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
      if (p == MAP_FAILED) throw std::bad_alloc();
      madvise(p, bytes, MADV_HUGEPAGE);  // advice only: refused, the pages are the usual ones
      return p;
    }
#endif
    return ::operator new(bytes, std::align_val_t(alignment));
  }

  void do_deallocate(void* p, std::size_t bytes, std::size_t alignment) override {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    if (mapped(bytes, alignment)) {
      munmap(p, bytes);
      return;
    }
#endif
    ::operator delete(p, std::align_val_t(alignment));
  }

  bool do_is_equal(const std::pmr::memory_resource& other) const noexcept override {
    return this == &other;
  }
};

}  // namespace

std::pmr::memory_resource& DocumentArena::blocks() {
  static BlockResource resource;
  return resource;
}

}  // namespace lightcone
#endif
