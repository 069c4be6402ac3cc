// Memory in whole 2 MiB pages that the kernel is asked to back with huge pages (MADV_HUGEPAGE,
// where transparent huge pages are on "madvise", Debian's default): for the large buffers that a
// frame reads all over, whose 4 KiB pages would take more translations than the TLB holds (the
// renderer's page pool, render/page_pool.h; a texture's linear copy, Texture::linearTexels).
#pragma once

#include <cstddef>
#include <new>

namespace tessera {

constexpr size_t kHugePage = size_t{2} << 20;

// `bytes` (a multiple of kHugePage) of fresh, zeroed memory starting on a kHugePage boundary and
// marked for huge pages before anything touches it, so that the first touch of each 2 MiB maps
// a huge page (ordinary pages where the system has none). Throws std::bad_alloc.
void* mapHugePages(size_t bytes);
// Gives back what mapHugePages returned, with the same `bytes`.
void unmapHugePages(void* memory, size_t bytes) noexcept;

// A standard allocator that takes blocks of kHugePage / 2 and more from mapHugePages (rounded up
// to whole huge pages: less than half of such a block's memory unused) and smaller ones from
// operator new (a huge page for each would waste most of its memory).
template <class T>
struct HugePageAllocator {
  using value_type = T;
  HugePageAllocator() = default;
  template <class U>
  HugePageAllocator(const HugePageAllocator<U>&) noexcept {}
  static size_t mapped(size_t n) {
    const size_t bytes = n * sizeof(T);
    return bytes >= kHugePage / 2 ? (bytes + kHugePage - 1) / kHugePage * kHugePage : 0;
  }
  T* allocate(size_t n) {
    if (const size_t bytes = mapped(n)) return static_cast<T*>(mapHugePages(bytes));
    return static_cast<T*>(::operator new (n * sizeof(T), std::align_val_t{alignof(T)}));
  }
  void deallocate(T* p, size_t n) noexcept {
    if (const size_t bytes = mapped(n))
      unmapHugePages(p, bytes);
    else
      ::operator delete (p, std::align_val_t{alignof(T)});
  }
  friend bool operator==(HugePageAllocator, HugePageAllocator) { return true; }
};

}  // namespace tessera
