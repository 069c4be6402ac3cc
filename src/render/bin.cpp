#include "render/bin.h"

#include <cstdint>

namespace tessera::render {

namespace {

// A hint that this core is about to write the line at `p`: PREFETCHW, which x86 processors
// without it run as a no-op.
inline void prefetchForWrite(const void* p) {
#if defined(__x86_64__) || defined(__i386__)
  asm volatile("prefetchw %0" : : "m"(*static_cast<const char*>(p)));
#else
  __builtin_prefetch(p, 1);
#endif
}

// Every line of [begin, end).
void prefetchForWrite(const void* begin, const void* end) {
  const auto first = reinterpret_cast<uintptr_t>(begin) & ~uintptr_t{63};
  for (uintptr_t line = first; line < reinterpret_cast<uintptr_t>(end); line += 64)
    prefetchForWrite(reinterpret_cast<const void*>(line));
}

}  // namespace

void ChunkBins::reset(int tile_count, bool shared) {
  if (tiles_.size() != static_cast<size_t>(tile_count)) {
    tiles_.resize(static_cast<size_t>(tile_count));
    for (PoolVector<uint32_t>& list : tiles_) list.clear();
  } else {
    if (shared) {
      prefetchForWrite(used_.data(), used_.data() + used_.size());
      for (uint32_t tile : used_) {
        const PoolVector<uint32_t>& list = tiles_[tile];
        prefetchForWrite(&list);
        prefetchForWrite(list.data(), list.data() + list.size());
      }
    }
    for (uint32_t tile : used_) tiles_[tile].clear();
  }
  used_.clear();
}

void ChunkBins::addToTiles(const TileGrid& grid, int tx0, int ty0, int tx1, int ty1,
                           uint32_t local_index) {
  for (int ty = ty0; ty <= ty1; ++ty)
    for (int tx = tx0; tx <= tx1; ++tx) push(ty * grid.columns + tx, local_index);
}

}  // namespace tessera::render
