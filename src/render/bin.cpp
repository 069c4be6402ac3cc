#include "render/bin.h"

namespace tessera::render {

void ChunkBins::reset(int tile_count) {
  if (tiles_.size() != static_cast<size_t>(tile_count)) {
    tiles_.resize(static_cast<size_t>(tile_count));
    for (PoolVector<uint32_t>& list : tiles_) list.clear();
  } else {
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
