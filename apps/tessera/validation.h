// --crc and --reference: checking a render against a known CRC or a reference image, for CI.
#pragma once

#include <filesystem>
#include <string>

#include <tessera/render/frame.h>

#include "flags.h"

namespace tessera::cli {

struct ReferenceSettings {
  std::string path;  // empty: no comparison
  float threshold_percent = 0;
  bool update = false;
};

// --reference/--ref, --reference-threshold/--ref-threshold and --reference-update.
void addReferenceFlags(FlagSet& flags, ReferenceSettings& settings);

// "crc32 frame INDEX HEX" on stdout: the CRC-32 of the frame's RGBA8 colour pixels.
void printFrameCrc(int index, const Frame& frame);

// OUTPUT.png -> OUTPUT.diff.png, beside it.
std::filesystem::path differencePath(const std::filesystem::path& output);

// Compares the frame's colour with the reference (or, with update, writes it as the reference)
// and writes the difference image beside `output`; prints the result. Returns the exit status:
// 0 within the threshold (or updated), 1 beyond it, on a size mismatch or an unreadable reference.
int checkReference(const ReferenceSettings& settings, const std::filesystem::path& output,
                   const Frame& frame);

}  // namespace tessera::cli
