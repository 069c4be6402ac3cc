// Picks a rendering backend by name for the subcommands.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <tessera/base/expected.h>
#include <tessera/render/backend.h>

#include "flags.h"

namespace tessera::cli {

// The names --backend accepts, in the order shown to users.
std::vector<std::string> backendNames();

// --simd (render and bench): the cpu backend's kernels, one of auto (the default), scalar, sse2,
// avx2 or avx512.
void addSimdFlag(FlagSet& flags, std::string* simd);

// What --simd cannot go with: another backend than cpu. "" or the usage error.
std::string refuseSimd(const std::string& simd, const std::string& backend);

// workers: CPU threads (0 = all cores); device: the Vulkan device index (-1 = the first suitable);
// simd: the cpu backend's kernels (addSimdFlag's names; anything but auto is an error on another
// backend, and on a CPU that cannot run those kernels).
Expected<std::unique_ptr<Backend>> makeBackend(const std::string& name, int workers, int device,
                                               const std::string& simd = "auto");

// The cpu backend's kernels (scalar, sse2, avx2 or avx512); "" for another backend.
std::string simdName(const Backend& backend);

// The viewer's Shift+F2 (ViewerHooks::commit_path): on the `vulkan` backend, switches its
// visibility commit path first when `toggle`, and returns the line saying which path is active;
// "" on any other backend.
std::string vulkanCommitPath(Backend& backend, bool toggle);

}  // namespace tessera::cli
