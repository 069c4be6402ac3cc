// The anti-aliasing flags that render and cube share (--msaa, --samples), and the one call that
// renders a frame with them.
#pragma once

#include <tessera/render/accumulate.h>

#include "flags.h"

namespace tessera::cli {

struct SamplingSettings {
  int msaa = 1;     // samples per pixel: 1, 2, 4 or 8
  int samples = 1;  // jittered frames averaged per image
};

// Adds `msaa` and `samples` (each with one or two dashes, as every flag) with the given default
// sample count in the help.
void addSamplingFlags(FlagSet& flags, SamplingSettings& settings);

// Renders one image: `settings.samples` jittered frames averaged (Accumulator), each with
// `settings.msaa` samples per pixel. The backend's error, if any.
Expected<void> renderSampled(Backend& backend, Accumulator& accumulator, const Scene& scene,
                             RenderOptions options, const SamplingSettings& settings, Frame& frame);

}  // namespace tessera::cli
