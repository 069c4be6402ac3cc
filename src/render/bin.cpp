#include "render/bin.h"

#include <algorithm>

namespace tessera::render {

void ChunkBins::reset(int tile_count) {
  entries_.clear();
  counts_.assign(static_cast<size_t>(tile_count), 0);
  offsets_.assign(static_cast<size_t>(tile_count) + 1, 0);
}

void ChunkBins::addToTiles(const TileGrid& grid, int tx0, int ty0, int tx1, int ty1,
                           uint32_t local_index) {
  for (int ty = ty0; ty <= ty1; ++ty) {
    for (int tx = tx0; tx <= tx1; ++tx) {
      const uint32_t tile = static_cast<uint32_t>(ty * grid.columns + tx);
      entries_.push_back({tile, local_index});
      ++counts_[tile];
    }
  }
}

void ChunkBins::finish() {
  // Counting sort by tile: stable, so each tile keeps submission order.
  uint32_t running = 0;
  for (size_t t = 0; t < counts_.size(); ++t) {
    offsets_[t] = running;
    running += counts_[t];
  }
  offsets_[counts_.size()] = running;
  sorted_.resize(running);
  std::fill(counts_.begin(), counts_.end(), 0u);
  for (const Entry& e : entries_) sorted_[offsets_[e.tile] + counts_[e.tile]++] = e.triangle;
}

}  // namespace tessera::render
