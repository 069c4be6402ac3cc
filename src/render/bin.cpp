#include "render/bin.h"

namespace tessera::render {

void ChunkBins::reset(int tile_count) {
  if (tiles_.size() != static_cast<size_t>(tile_count))
    tiles_.resize(static_cast<size_t>(tile_count));
  for (PoolVector<uint32_t>& list : tiles_) list.clear();
}

void ChunkBins::addToTiles(const TileGrid& grid, int tx0, int ty0, int tx1, int ty1,
                           uint32_t local_index) {
  for (int ty = ty0; ty <= ty1; ++ty)
    for (int tx = tx0; tx <= tx1; ++tx)
      tiles_[static_cast<size_t>(ty * grid.columns + tx)].push_back(local_index);
}

}  // namespace tessera::render
