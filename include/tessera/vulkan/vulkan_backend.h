// The two Vulkan backends.
//
//   "vulkan"         ComputeBackend: a tiled rasterizer written entirely in compute shaders
//                    (clear, transform, setup and cull, bin into 16x16 tiles, fine raster with a
//                    64-bit atomic min of depth << 32 | triangle key per sample, shade and
//                    resolve). Coverage uses the CPU's fixed-point arithmetic at the standard
//                    sample positions, so its triangle ids and coverage match the CPU's.
//   "vulkan-raster"  RasterBackend: the same scene through Vulkan's graphics pipeline (vertex and
//                    fragment shaders, a depth attachment, a R32_UINT triangle-id attachment;
//                    with MSAA, a multisampled pass resolved by the render pass).
//
// Nothing here exposes a Vulkan type: only tessera_vulkan sees Vulkan. The Vulkan loader is
// opened at run time, so every way of not having Vulkan (no loader, no device, a device without
// a needed feature) is an Error from create(), never a crash or an executable that won't start.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <tessera/base/expected.h>
#include <tessera/render/backend.h>

namespace tessera::vulkan {

// A physical device as the Vulkan loader reports it, and whether each backend can run on it.
struct DeviceInfo {
  int index = 0;                // the number --device takes
  std::string name;             // e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
  std::string type;             // "discrete GPU", "integrated GPU", "virtual GPU", "CPU", "other"
  std::string driver;           // driver name and version string
  std::string api_version;      // e.g. "1.3.230"
  bool compute_usable = false;  // the "vulkan" backend runs on it
  std::string compute_note;     // what is missing, or which paths the backend takes
  bool raster_usable = false;   // the "vulkan-raster" backend runs on it
  std::string raster_note;
  std::vector<int> raster_sample_counts;  // the RenderOptions::msaa values vulkan-raster takes
  bool int64_atomics = false;             // shaderBufferInt64Atomics
  bool float64 = false;                   // shaderFloat64
};

// Every Vulkan device, in the loader's order. An Error when there is no loader or no instance.
Expected<std::vector<DeviceInfo>> listDevices();

// True when the environment variable TESSERA_VULKAN_VALIDATION is set to 1.
bool validationRequestedByEnvironment();

struct VulkanOptions {
  // A listDevices() index; -1 picks the first usable device, discrete GPUs first.
  int device = -1;
  // Enable VK_LAYER_KHRONOS_validation and record its error messages (validationErrors()).
  // Defaults to TESSERA_VULKAN_VALIDATION=1; asking for it without the layer installed is an Error.
  bool validation = validationRequestedByEnvironment();
  // Every wait for the GPU is bounded by this; a timeout makes render() fail with an Error.
  uint32_t fence_timeout_ms = 20000;
  // Compute backend: take the two-pass 32-bit visibility commit even where 64-bit atomics exist.
  bool force_32bit_atomics = false;
  // Compute backend: set up depth planes in float even where shaderFloat64 exists.
  bool force_fp32_setup = false;
  // Compute backend: bin entries to allocate at first (0 = automatic). Small values exercise the
  // overflow path: the frame is rendered again with bins as large as the count asked for.
  uint32_t initial_bin_capacity = 0;
  // Treat these device features as absent (for tests of the fallbacks and of the errors):
  // "shaderInt64", "shaderFloat64", "shaderBufferInt64Atomics", "geometryShader",
  // "standardSampleLocations".
  std::vector<std::string> pretend_missing_features;
  // Raster backend: treat sample counts above this as unsupported by the device (0 = the
  // device's own): tests of the "sample count not supported" error.
  int pretend_max_samples = 0;
  // Treat the device's largest storage buffer (maxStorageBufferRange) as this many bytes when
  // smaller (0 = the device's own): tests of the "scene too large for the device" error.
  uint64_t pretend_max_buffer_bytes = 0;
};

// GPU time per pass, from timestamp queries, in milliseconds. valid is false (and every time 0)
// when the device's queue has no timestamps.
struct PassTimings {
  double clear = 0, transform = 0, setup = 0, bin = 0, raster = 0, shade = 0;
  double diagnostics = 0;  // the diagnostics passes (compute backend, RenderOptions::diagnostics)
  double total = 0;  // first timestamp to last, on the GPU
  bool valid = false;
};

// What the compute backend did in its last frame.
struct ComputeStats {
  size_t triangles_in = 0;       // triangles in the scene
  size_t triangles_culled = 0;   // back/front-facing, degenerate, off-screen, non-finite (as CPU)
  size_t triangles_clipped = 0;  // crossed the near or far plane or left the guard band
  size_t triangles_setup = 0;    // setup records (clipped triangles give one per fan piece)
  size_t triangles_binned = 0;   // setup records that landed in at least one tile
  size_t bin_entries = 0;        // (record, tile) pairs
  size_t bin_capacity = 0;       // entries the bin buffer held when the frame finished
  size_t bin_overflows = 0;      // rounds rendered again because the bins (or the clip records)
                                 // were too small; the frame is never drawn with dropped triangles
  size_t tiles = 0;              // 16x16 tiles in the viewport
  size_t tiles_occupied = 0;     // tiles with at least one entry
  size_t max_tile_entries = 0;   // the fullest tile
  size_t raster_workgroups = 0;  // fine-raster workgroups (a full tile is split into several)
  bool int64_atomics = false;    // the 64-bit atomic commit (else the two-pass 32-bit one)
  bool fp64_setup = false;       // depth planes in double, exactly as the CPU
  PassTimings timings;
};

// Entries per 16x16 tile in the last frame, row-major.
struct TileOccupancy {
  int columns = 0, rows = 0;
  int tile_size = 16;
  std::vector<uint32_t> entries;
};

// An RGBA8 image (R in the low byte, row 0 at the top) of width x height pixels that colours each
// tile by its entry count, in proportion to the fullest tile's: black for an empty tile, then
// dark blue, blue, green and yellow to white for the fullest; a darker one-pixel border shows the
// tile grid.
std::vector<uint32_t> makeOccupancyHeatmap(const TileOccupancy& occupancy, int width, int height);

class ComputeBackend final : public Backend {
 public:
  static Expected<std::unique_ptr<ComputeBackend>> create(const VulkanOptions& options = {});
  ~ComputeBackend() override;
  ComputeBackend(const ComputeBackend&) = delete;
  ComputeBackend& operator=(const ComputeBackend&) = delete;

  const char* name() const override { return "vulkan"; }
  void render(const Scene& scene, const RenderOptions& options, Frame& frame) override;
  Expected<void> lastResult() const override;

  const ComputeStats& lastStats() const;
  const TileOccupancy& lastTileOccupancy() const;
  const DeviceInfo& device() const;
  // Validation-layer errors since creation (empty without validation).
  std::vector<std::string> validationErrors() const;
  void setFenceTimeout(uint32_t milliseconds);
  // The visibility commit the next frame takes: true for the 64-bit atomic one, false for the
  // two-pass 32-bit one (a device without shaderBufferInt64Atomics, or force_32bit_atomics).
  bool uses64BitCommits() const;
  // VulkanOptions::force_32bit_atomics at run time (the viewer's Shift+F2): the backend is set up
  // again on the same device with the option changed. Both paths draw the same image. On an
  // Error the backend is unchanged.
  Expected<void> setForce32BitAtomics(bool force);

  struct State;

 private:
  explicit ComputeBackend(std::unique_ptr<State> state);
  std::unique_ptr<State> state_;
};

// What the raster backend did in its last frame.
struct RasterStats {
  size_t triangles_in = 0;
  size_t draws = 0;   // one indexed draw per object (in each pass)
  int samples = 1;    // RenderOptions::msaa: above 1, the multisample pass ran
  double gpu_ms = 0;  // render pass and copies, from timestamps (0 without timestamps)
  bool timings_valid = false;
};

class RasterBackend final : public Backend {
 public:
  static Expected<std::unique_ptr<RasterBackend>> create(const VulkanOptions& options = {});
  ~RasterBackend() override;
  RasterBackend(const RasterBackend&) = delete;
  RasterBackend& operator=(const RasterBackend&) = delete;

  const char* name() const override { return "vulkan-raster"; }
  void render(const Scene& scene, const RenderOptions& options, Frame& frame) override;
  Expected<void> lastResult() const override;

  const RasterStats& lastStats() const;
  const DeviceInfo& device() const;
  std::vector<std::string> validationErrors() const;
  void setFenceTimeout(uint32_t milliseconds);

  struct State;

 private:
  explicit RasterBackend(std::unique_ptr<State> state);
  std::unique_ptr<State> state_;
};

// The factories the CLI's backend table uses.
Expected<std::unique_ptr<Backend>> makeComputeBackend(const VulkanOptions& options = {});
Expected<std::unique_ptr<Backend>> makeRasterBackend(const VulkanOptions& options = {});

}  // namespace tessera::vulkan
