#include <tessera/base/huge_pages.h>

#include <cstdint>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace tessera {

#if defined(__linux__)
void* mapHugePages(size_t bytes) {
  // Mapped a huge page longer than asked, then trimmed to the aligned part.
  const size_t span = bytes + kHugePage;
  void* raw = mmap(nullptr, span, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (raw == MAP_FAILED) throw std::bad_alloc();
  const uintptr_t begin = reinterpret_cast<uintptr_t>(raw);
  const uintptr_t aligned = (begin + kHugePage - 1) / kHugePage * kHugePage;
  if (aligned > begin) munmap(raw, aligned - begin);
  if (begin + span > aligned + bytes)
    munmap(reinterpret_cast<void*>(aligned + bytes), begin + span - (aligned + bytes));
  // Advice only: where transparent huge pages are off the memory is ordinary pages.
  madvise(reinterpret_cast<void*>(aligned), bytes, MADV_HUGEPAGE);
  return reinterpret_cast<void*>(aligned);
}

void unmapHugePages(void* memory, size_t bytes) noexcept {
  munmap(memory, bytes);
}
#else
constexpr std::align_val_t kLine{64};

void* mapHugePages(size_t bytes) {
  return ::operator new(bytes, kLine);
}

void unmapHugePages(void* memory, size_t) noexcept {
  ::operator delete(memory, kLine);
}
#endif

}  // namespace tessera
