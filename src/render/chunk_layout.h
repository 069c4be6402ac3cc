// How the setup stage splits the scene's triangles into chunks (TriangleChunk), with the worker
// pool's blocks in mind.
#pragma once

#include <algorithm>
#include <cstddef>
#include <iterator>
#include <vector>

#include "render/bin.h"
#include "render/cull.h"
#include "render/raster.h"

namespace tessera::render {

// The setup stage's chunks: triangle ranges of at most chunk_size, in order. With several
// workers each worker's block of chunks (WorkerPool::parallelFor gives worker w the w-th of
// `workers` equal runs of indices, and hands every block out in increasing order) ends in chunks
// of a half, a quarter and an eighth of that size, so the workers reach the small ones last and
// finish close together: with equal chunks one waited 50-80 us a frame on the bunny for the
// other's last chunk, 17 us with these (docs/perf-notes/frame-stages.md, round 6). Equal chunks
// where that would pass kMaxChunks. Writes first_triangle and triangle_count of chunks[0, count);
// returns count.
inline size_t layOutChunks(size_t triangle_total, size_t chunk_size, int workers,
                           std::vector<TriangleChunk>& chunks) {
  auto place = [&](size_t c, size_t first, size_t count) {
    if (chunks.size() <= c) chunks.resize(c + 1);
    chunks[c].first_triangle = first;
    chunks[c].triangle_count = count;
  };
  const size_t n = static_cast<size_t>(std::max(1, workers));
  const size_t tail[] = {chunk_size / 2, chunk_size / 4, chunk_size / 8};
  const size_t tail_total = tail[0] + tail[1] + tail[2];
  const size_t share = (triangle_total + n - 1) / n;  // triangles per worker, the last fewer
  const size_t head = share > tail_total ? (share - tail_total + chunk_size - 1) / chunk_size : 0;
  const size_t per_worker = head + std::size(tail);
  if (n == 1 || head == 0 || n * per_worker > kMaxChunks) {
    const size_t count = (triangle_total + chunk_size - 1) / chunk_size;
    for (size_t c = 0; c < count; ++c)
      place(c, c * chunk_size, std::min(chunk_size, triangle_total - c * chunk_size));
    return count;
  }
  size_t c = 0;
  for (size_t w = 0; w < n; ++w) {
    size_t first = std::min(triangle_total, w * share);
    const size_t end = std::min(triangle_total, first + share);
    // The head takes what the tail leaves, in chunks of at most chunk_size.
    const size_t head_total = end - first > tail_total ? end - first - tail_total : 0;
    for (size_t h = 0; h < head; ++h) {
      const size_t count = std::min(chunk_size, head_total - std::min(head_total, h * chunk_size));
      place(c++, first, count);
      first += count;
    }
    for (size_t size : tail) {
      const size_t count = std::min(size, end - first);
      place(c++, first, count);
      first += count;
    }
  }
  return c;
}

// Chunks laid out by layOutChunks over the ordinals of the triangles a frame draws (`drawn`:
// sorted, disjoint ranges of scene triangle indices, what culling keeps) moved to scene triangle
// indices: chunk c then runs from the index of its first drawn triangle to that of the next
// chunk's first (the first chunk from 0, the last to triangle_total), so that the chunks tile the
// scene's indices and each holds the drawn triangles layOutChunks gave it. Laid out over the
// scene's indices instead, a scene of 10,000 instances of which 50 were in view had its drawn
// triangles in one or two chunks, set up by one worker.
inline void toSceneIndices(const std::vector<IndexRange>& drawn, size_t triangle_total,
                           std::vector<TriangleChunk>& chunks, size_t chunk_count) {
  size_t range = 0, before = 0;  // the drawn triangles of the ranges before `range`
  // The scene index of drawn triangle d (nondecreasing from call to call); triangle_total past
  // the last.
  const auto scene_index = [&](size_t d) {
    for (; range < drawn.size(); ++range) {
      const size_t size = drawn[range].end - drawn[range].first;
      if (before + size > d) break;
      before += size;
    }
    return range < drawn.size() ? drawn[range].first + (d - before) : triangle_total;
  };
  size_t begin = 0;
  for (size_t c = 0; c < chunk_count; ++c) {
    const size_t end = c + 1 == chunk_count
                           ? triangle_total
                           : scene_index(chunks[c].first_triangle + chunks[c].triangle_count);
    chunks[c].first_triangle = begin;
    chunks[c].triangle_count = end - begin;
    begin = end;
  }
}

}  // namespace tessera::render
