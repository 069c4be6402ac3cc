#include "render/painter.h"

#include <algorithm>
#include <bit>

#include "render/blend.h"
#include "render/clip.h"
#include "render/raster.h"

namespace tessera::render {

namespace {

float windowDepth(const VertexBuffer& vertices, size_t v) {
  const uint16_t code = vertices.outcode[v];
  if (code & kClipNear) return 0.0f;
  if (code & kClipFar) return 1.0f;
  // Inside the depth range, w > 0: the window z of projectToScreen (setup.h).
  const float z = vertices.clip_z[v] * (1.0f / vertices.clip_w[v]) * 0.5f + 0.5f;
  return std::clamp(z, 0.0f, 1.0f);
}

}  // namespace

float painterDepth(const VertexBuffer& vertices, size_t v0, size_t v1, size_t v2) {
  return windowDepth(vertices, v0) + windowDepth(vertices, v1) + windowDepth(vertices, v2);
}

void PainterOrder::build(WorkerPool& pool, const std::vector<TriangleChunk>& chunks,
                         size_t chunk_count, const Scene& scene,
                         const std::vector<ObjectTransforms>& objects, const VertexBuffer& vertices,
                         const TileGrid& grid) {
  first_.resize(chunk_count);
  size_t total = 0, blended = 0;
  for (size_t c = 0; c < chunk_count; ++c) {
    first_[c] = total;
    total += chunks[c].size;
    blended += chunks[c].blended.size();
  }
  order_.resize(total);

  // Keys: records in submission order, so that the low half orders ties.
  pool.parallelFor(chunk_count, [&](size_t c, int) {
    const TriangleChunk& chunk = chunks[c];
    size_t object = chunk.size > 0 ? objectHolding(objects, chunk.shade[0].triangle_id) : 0;
    for (size_t local = 0; local < chunk.size; ++local) {
      const uint32_t id = chunk.shade[local].triangle_id;
      // alphaMode BLEND records are the transparent pass's (blend.h): sorted past every key,
      // then dropped.
      if (!chunk.blended.empty() && isBlended(*chunk.shade[local].material)) {
        order_[first_[c] + local] = ~uint64_t{0};
        continue;
      }
      while (object + 1 < objects.size() && objects[object + 1].triangle_base <= id) ++object;
      const ObjectTransforms& xf = objects[object];
      const uint32_t* idx = &scene.objects[object].mesh->indices[(id - xf.triangle_base) * 3];
      // Depths are not negative: their bits order as they do, and ~bits puts the largest first.
      const float depth = painterDepth(vertices, xf.vertex_base + idx[0], xf.vertex_base + idx[1],
                                       xf.vertex_base + idx[2]);
      const uint32_t bits = std::bit_cast<uint32_t>(depth + 0.0f);
      order_[first_[c] + local] =
          uint64_t{~bits} << 32 | makeKey(static_cast<uint32_t>(c), static_cast<uint32_t>(local));
    }
  });
  sort(pool);
  order_.resize(total - blended);
  total = order_.size();

  // Bins, in the sorted order: slice after slice.
  const size_t slice_count = static_cast<size_t>(pool.size());
  if (slices_.size() != slice_count) slices_.resize(slice_count);
  pool.parallelFor(slice_count, [&](size_t s, int) {
    ChunkBins& bins = slices_[s].bins;
    bins.reset(grid.tileCount(), slice_count > 1);
    const size_t begin = total * s / slice_count, end = total * (s + 1) / slice_count;
    for (size_t i = begin; i < end; ++i) {
      const uint32_t key = static_cast<uint32_t>(order_[i]);
      bins.add(grid, chunks[keyChunk(key)].raster[keyLocal(key)], key);
    }
  });
}

void PainterOrder::sort(WorkerPool& pool) {
  const size_t total = order_.size();
  const size_t parts =
      std::min<size_t>(static_cast<size_t>(pool.size()), std::max<size_t>(total, 1));
  bounds_.resize(parts + 1);
  for (size_t i = 0; i <= parts; ++i) bounds_[i] = total * i / parts;
  pool.parallelFor(parts, [&](size_t i, int) {
    std::sort(order_.begin() + static_cast<ptrdiff_t>(bounds_[i]),
              order_.begin() + static_cast<ptrdiff_t>(bounds_[i + 1]));
  });
  // Pairwise merges: runs [i, i + width) and [i + width, i + 2 width) of the part bounds.
  merged_.resize(total);
  for (size_t width = 1; width < parts; width *= 2) {
    const size_t pairs = (parts + 2 * width - 1) / (2 * width);
    pool.parallelFor(pairs, [&](size_t p, int) {
      const size_t lo = p * 2 * width;
      const size_t mid = std::min(lo + width, parts), hi = std::min(lo + 2 * width, parts);
      const auto at = [&](size_t part) { return static_cast<ptrdiff_t>(bounds_[part]); };
      std::merge(order_.begin() + at(lo), order_.begin() + at(mid), order_.begin() + at(mid),
                 order_.begin() + at(hi), merged_.begin() + at(lo));
    });
    order_.swap(merged_);
  }
}

}  // namespace tessera::render
