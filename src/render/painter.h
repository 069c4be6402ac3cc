// The painter's algorithm (RenderOptions::visibility = Visibility::kPainter): after setup, the
// frame's triangles are put in back-to-front order and binned in that order; the tile raster
// then draws them with the depth test replaced by "later wins" (painter_kernel.h), so the
// nearest-sorted triangle covers a pixel whatever its depth there.
//
// The order is a total one: the sum of the triangle's three window depths (the Python renderer's
// average, times three: the same order without a rounding of its own), largest first, then
// submission order. Any split of the sort over the workers gives the same sequence, so the image
// is bit-identical for any worker count.
#pragma once

#include <cstdint>
#include <vector>

#include <tessera/scene/scene.h>

#include "render/bin.h"
#include "render/vertex.h"
#include "render/worker_pool.h"

namespace tessera::render {

// One part of the sorted sequence, binned by one worker. Slices are read in order; each has
// lines of its own (two workers fill neighbouring slices at once).
struct alignas(128) PainterSlice {
  ChunkBins bins;  // entries are keys (raster.h's makeKey) into the chunks
};

// A triangle's painter depth: the sum of its window depths, a vertex in front of the near plane
// (or behind the eye) counting as 0 and one past the far plane as 1. From the vertex stage's
// clip coordinates, so the pieces of a clipped triangle all take the whole triangle's.
float painterDepth(const VertexBuffer& vertices, size_t v0, size_t v1, size_t v2);

class PainterOrder {
 public:
  // Orders the setup records of chunks [0, chunk_count) (each chunk's shading record names its
  // triangle) and bins them in that order into slices(). `vertices`: the frame's vertex stage
  // output, whole (not one worker's copy in the making). The buffers only grow: a frame after
  // warm-up allocates nothing.
  void build(WorkerPool& pool, const std::vector<TriangleChunk>& chunks, size_t chunk_count,
             const Scene& scene, const std::vector<ObjectTransforms>& objects,
             const VertexBuffer& vertices, const TileGrid& grid);

  const std::vector<PainterSlice>& slices() const { return slices_; }
  // The keys in drawing order (tests).
  size_t size() const { return order_.size(); }
  uint32_t keyAt(size_t i) const { return static_cast<uint32_t>(order_[i]); }

 private:
  // Sorts order_ in `parts` pieces at once, then merges them pairwise (merged_ is the other
  // buffer of each round).
  void sort(WorkerPool& pool);

  std::vector<size_t> first_;    // per chunk: the place of its first record in order_
  std::vector<uint64_t> order_;  // per record: ~depth bits << 32 | key
  std::vector<uint64_t> merged_;
  std::vector<size_t> bounds_;  // the sorted runs, [bounds_[i], bounds_[i + 1])
  std::vector<PainterSlice> slices_;
};

}  // namespace tessera::render
