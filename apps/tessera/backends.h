// Picks a rendering backend by name for the subcommands.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <tessera/base/expected.h>
#include <tessera/render/backend.h>

namespace tessera::cli {

// The names --backend accepts, in the order shown to users.
std::vector<std::string> backendNames();

// workers: CPU threads (0 = all cores); device: the Vulkan device index (-1 = the first suitable).
Expected<std::unique_ptr<Backend>> makeBackend(const std::string& name, int workers, int device);

// The viewer's Shift+F2 (ViewerHooks::commit_path): on the `vulkan` backend, switches its
// visibility commit path first when `toggle`, and returns the line saying which path is active;
// "" on any other backend.
std::string vulkanCommitPath(Backend& backend, bool toggle);

}  // namespace tessera::cli
