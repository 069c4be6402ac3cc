#include "validation.h"

#include <cstdio>
#include <iostream>
#include <system_error>

#include <tessera/io/image_writer.h>
#include <tessera/io/validation.h>

#include "commands.h"

namespace tessera::cli {

namespace fs = std::filesystem;

void addReferenceFlags(FlagSet& flags, ReferenceSettings& settings) {
  flags.addString("reference|ref", &settings.path,
                  "compare the colour image with this PNG: exit 1 when more than the threshold "
                  "of pixels differ, and write OUTPUT.diff.png");
  flags.addFloat("reference-threshold|ref-threshold", &settings.threshold_percent,
                 "percent of pixels allowed to differ by more than 2/255 in a channel "
                 "(default 0)",
                 0.0f, 100.0f);
  flags.addSwitch("reference-update", &settings.update,
                  "write this render as the --reference PNG (creating or "
                  "replacing it) instead of comparing");
}

void printFrameCrc(int index, const Frame& frame) {
  std::cout << "crc32 frame " << index << " "
            << io::crc32Hex(io::crc32Rgba8(frame.color.data(), frame.width, frame.height)) << "\n";
}

fs::path differencePath(const fs::path& output) {
  fs::path path = output;
  return path.replace_extension(".diff.png");
}

namespace {

int failure(const std::string& message) {
  printError("render", message);
  return kExitFailure;
}

}  // namespace

int checkReference(const ReferenceSettings& settings, const fs::path& output, const Frame& frame) {
  const io::Rgba8Image image{frame.width, frame.height, frame.color};
  if (settings.update) {
    if (Expected<void> written =
            io::writePngRgba8(settings.path, image.width, image.height, image.pixels.data());
        !written)
      return failure(written.error().message);
    std::cout << "wrote reference " << settings.path << "\n";
    return kExitOk;
  }
  std::error_code error;
  if (!fs::exists(settings.path, error))
    return failure("the reference '" + settings.path +
                   "' does not exist; create it from this render by adding --reference-update");
  Expected<io::Rgba8Image> reference = io::readPngRgba8(settings.path);
  if (!reference) return failure("cannot read the reference: " + reference.error().message);
  if (reference->width != image.width || reference->height != image.height) {
    std::cout << "reference size-mismatch " << reference->width << "x" << reference->height << " "
              << image.width << "x" << image.height << " fail\n";
    return failure("the comparison fails: the reference '" + settings.path + "' is " +
                   std::to_string(reference->width) + "x" + std::to_string(reference->height) +
                   ", the render " + std::to_string(image.width) + "x" +
                   std::to_string(image.height));
  }
  const io::ImageComparison compared = io::compareRgba8(image, *reference);
  const fs::path diff = differencePath(output);
  if (Expected<void> written =
          io::writePngRgba8(diff, image.width, image.height, compared.difference.pixels.data());
      !written)
    return failure(written.error().message);
  const bool pass = compared.differing_percent <= settings.threshold_percent;
  char line[160];
  std::snprintf(line, sizeof line, "reference %.6g threshold %.6g pixels %lld max %d %s\n",
                compared.differing_percent, static_cast<double>(settings.threshold_percent),
                static_cast<long long>(compared.differing_pixels), compared.max_channel_difference,
                pass ? "pass" : "fail");
  std::cout << line << "wrote " << diff.string() << "\n";
  if (pass) return kExitOk;
  std::snprintf(line, sizeof line, "%.6g%% of pixels (%lld) differ", compared.differing_percent,
                static_cast<long long>(compared.differing_pixels));
  return failure("the render differs from the reference '" + settings.path + "': " + line +
                 " by more than 2/255, above the threshold; see " + diff.string());
}

}  // namespace tessera::cli
