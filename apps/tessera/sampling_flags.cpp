#include "sampling_flags.h"

#include <string>

namespace tessera::cli {

void addSamplingFlags(FlagSet& flags, SamplingSettings& settings) {
  flags.addCustom(
      "msaa", "N",
      "samples per pixel: 1, 2, 4 or 8 (default " + std::to_string(settings.msaa) + ")",
      [&settings](const std::string& v) -> std::string {
        long long n;
        if (!parseIntStrict(v, n) || n < 1 || n > 8 || !isSampleCount(static_cast<int>(n)))
          return "samples per pixel must be 1, 2, 4 or 8, not '" + v + "'";
        settings.msaa = static_cast<int>(n);
        return "";
      });
  flags.addCustom("samples", "N",
                  "jittered frames averaged per image, 1..4096 (default 1): N x msaa samples "
                  "per pixel in all",
                  [&settings](const std::string& v) -> std::string {
                    long long n;
                    if (!parseIntStrict(v, n) || n < 1 || n > 4096)
                      return "--samples must be a whole number from 1 to 4096, not '" + v + "'";
                    settings.samples = static_cast<int>(n);
                    return "";
                  });
}

Expected<void> renderSampled(Backend& backend, Accumulator& accumulator, const Scene& scene,
                             RenderOptions options, const SamplingSettings& settings,
                             Frame& frame) {
  options.msaa = settings.msaa;
  return accumulator.render(backend, scene, options, settings.samples, frame);
}

}  // namespace tessera::cli
