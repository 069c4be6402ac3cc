// Jittered accumulation: supersampling for stills and turntables on any backend.
#pragma once

#include <vector>

#include <tessera/render/backend.h>

namespace tessera {

// Renders `samples` frames, frame i with its sample pattern moved by jitterOffset(i), and
// averages their colours in linear light: samples x options.msaa samples per pixel in all. The
// AOVs (depth, ids, normals, coverage) are frame 0's, which is not jittered. Deterministic for a
// given sample count (the same offsets, summed in the same order). A frame that a backend fails
// ends the accumulation: the result is that backend's lastResult().
class Accumulator {
 public:
  Expected<void> render(Backend& backend, const Scene& scene, const RenderOptions& options,
                        int samples, Frame& out);

 private:
  Frame scratch_;
  std::vector<float> sum_;  // linear RGB and alpha (0..255) per pixel
};

}  // namespace tessera
