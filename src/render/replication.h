// Which way the CPU renderer runs its vertex stage for a small scene with more than one worker:
// once, shared by every worker's setup, or once per worker, each into its own copy (see
// mayReplicate in cpu_renderer.cpp). Kept apart so that tests can hold it to its rules.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <iterator>

namespace tessera::render {

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
