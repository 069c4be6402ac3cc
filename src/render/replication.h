// Which way the CPU renderer runs its vertex stage for a small scene with more than one worker:
// once, shared by every worker's setup, or once per worker, each into its own copy (see
// mayReplicate below). Kept apart so that tests can hold it to its rules.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <iterator>

namespace tessera::render {

// Small scenes may be transformed once per worker, each worker into its own VertexBuffer, which
// its setup chunks then read: a mesh's triangles reach for vertices all over its vertex order
// (the bunny's last chunk uses vertices 0 to 34,833), so with one shared buffer part of setup's
// vertex reads go to lines the other core wrote. Whether that pays depends on the host: on this
// project's 2-core VM it took 4-7% off the bunny's frame where a line took 450-550 ns between the
// cores and added 3% where it took 120-140 ns (the same VM, an hour apart), so the renderer times
// both ways (ReplicationChoice, render/replication.h). It is tried while all the copies together
// hold at most this many vertices (15 MB; two workers: 128k vertices, 0.4 ms each to transform),
// so that many workers neither hold many copies nor each transform a large mesh.
constexpr size_t kMaxReplicatedVertexCopies = size_t{1} << 18;

inline bool mayReplicate(size_t vertex_total, int workers) {
  return workers > 1 && vertex_total * static_cast<size_t>(workers) <= kMaxReplicatedVertexCopies;
}

// Keeps the faster of the two ways to run the vertex stage for a scene, by the median of each
// way's last kSamples frame times (to the end of the tile stage; a median: one frame in a slow
// spell must not decide). The first 2 * kSamples frames alternate; after them every kProbeEvery-th
// frame takes the other way, so that a change in the host is noticed. Only speed depends on the
// choice: both ways give the same bits.
struct ReplicationChoice {
  static constexpr uint32_t kSamples = 5, kProbeEvery = 16;
  static constexpr double kMargin = 0.98;
  double recent[2][kSamples] = {};  // [replicated], a ring
  uint32_t count[2] = {0, 0};
  bool preferred = true;
  uint32_t frame = 0;
  size_t vertices = 0, triangles = 0;  // the scene the times belong to

  // The way for the next frame of a scene of these sizes (true: once per worker); a scene of
  // other sizes starts over.
  bool next(size_t vertex_total, size_t triangle_total) {
    if (vertex_total != vertices || triangle_total != triangles) *this = ReplicationChoice{};
    vertices = vertex_total;
    triangles = triangle_total;
    const uint32_t f = frame++;
    if (f < 2 * kSamples) return f % 2 == 0;
    return f % kProbeEvery == kProbeEvery - 1 ? !preferred : preferred;
  }
  // That frame's time, taken the way next() said.
  void record(bool replicated, double ms) {
    recent[replicated][count[replicated]++ % kSamples] = ms;
    // Replicating does more work in all, so it must win by a margin: where the two are within
    // the noise of a shared machine the single transform is kept.
    if (count[0] >= kSamples && count[1] >= kSamples)
      preferred = median(recent[1]) < kMargin * median(recent[0]);
  }
  static double median(const double (&times)[kSamples]) {
    double sorted[kSamples];
    std::copy(std::begin(times), std::end(times), sorted);
    std::nth_element(sorted, sorted + kSamples / 2, sorted + kSamples);
    return sorted[kSamples / 2];
  }
};

}  // namespace tessera::render
