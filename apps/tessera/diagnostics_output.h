// The diagnostics of `tessera render`: the diagnostic AOVs as PNGs and the --stats JSON
// (docs/rendering.md has the encodings, docs/stats.md the JSON schema).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <tessera/base/expected.h>
#include <tessera/render/frame.h>

namespace tessera::cli {

// The --aov names this file writes, in the order `--help` lists them.
const std::vector<std::string>& diagnosticAovNames();
bool isDiagnosticAov(const std::string& aov);
// Whether the AOV needs the replayed depth tests (overdraw, occupancy): perspective frames only.
bool needsPixelTests(const std::string& aov);

// Writes frame.diagnostics as the AOV `aov` (isDiagnosticAov).
Expected<void> writeDiagnosticAov(const std::filesystem::path& path, const Frame& frame,
                                  const std::string& aov);

// One frame of the --stats file (a JSON object, docs/stats.md).
std::string statsFrameJson(const Frame& frame, int index, const std::string& backend);
// The whole file around the frames' objects.
std::string statsFileJson(const std::vector<std::string>& frames);

}  // namespace tessera::cli
