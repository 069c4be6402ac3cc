// Tests that the Vulkan backends fail clearly and that users reach them: errors with a message
// and never a hang, the device list, and the CLI's `--backend vulkan|vulkan-raster`. A test that
// needs a Vulkan device skips only when the machine has none, and says so.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "run_process.h"
#include "temp_folder.h"
#include "vulkan_fixtures.h"

using namespace tessera;
using namespace tessera::vulkan_test;

// ---- errors: clear messages, never a hang ----

TEST(VulkanErrors, FenceTimeoutIsAnErrorAndTheBackendRecovers) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  ComputePtr gpu = makeCompute();
  ASSERT_TRUE(gpu);
  const Scene scene = denseScene();
  Frame frame;
  // A zero timeout: the wait returns before the GPU can have finished.
  gpu->setFenceTimeout(0);
  bool timed_out = false;
  for (int attempt = 0; attempt < 5 && !timed_out; ++attempt) {
    gpu->render(scene, options(1024, 768), frame);
    if (Expected<void> r = gpu->lastResult(); !r) {
      EXPECT_NE(r.error().message.find("did not finish"), std::string::npos) << r.error().message;
      timed_out = true;
    }
  }
  EXPECT_TRUE(timed_out);
  EXPECT_EQ(std::count(frame.triangle_id.begin(), frame.triangle_id.end(), kNoTriangle),
            static_cast<long>(frame.pixelCount()))
      << "a failed frame is left empty";
  // With a real timeout the same backend renders again (after the abandoned frame finishes).
  gpu->setFenceTimeout(20000);
  expectComputeMatchesCpu("after a timeout", scene, {}, gpu.get());
}

TEST(VulkanErrors, MissingLoaderIsAnError) {
  ASSERT_EQ(setenv("TESSERA_VULKAN_LOADER", "/nonexistent/libvulkan.so.1", 1), 0);
  Expected<std::unique_ptr<ComputeBackend>> gpu = ComputeBackend::create();
  Expected<std::vector<vulkan::DeviceInfo>> devices = vulkan::listDevices();
  unsetenv("TESSERA_VULKAN_LOADER");
  ASSERT_FALSE(gpu.ok());
  EXPECT_NE(gpu.error().message.find("Vulkan loader"), std::string::npos) << gpu.error().message;
  ASSERT_FALSE(devices.ok());
  EXPECT_NE(devices.error().message.find("/nonexistent/libvulkan.so.1"), std::string::npos);
}

TEST(VulkanErrors, NoDriverIsAnError) {
  TESSERA_SKIP_WITHOUT_VULKAN();  // needs a loader
  // A loader that finds no driver at all.
  ASSERT_EQ(setenv("VK_ICD_FILENAMES", "/nonexistent/icd.json", 1), 0);
  ASSERT_EQ(setenv("VK_DRIVER_FILES", "/nonexistent/icd.json", 1), 0);
  Expected<std::unique_ptr<ComputeBackend>> gpu = ComputeBackend::create();
  unsetenv("VK_ICD_FILENAMES");
  unsetenv("VK_DRIVER_FILES");
  ASSERT_FALSE(gpu.ok());
  EXPECT_NE(gpu.error().message.find("no Vulkan"), std::string::npos) << gpu.error().message;
}

TEST(VulkanErrors, DeviceIndexOutOfRangeIsAnError) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  VulkanOptions vk;
  vk.device = 63;
  Expected<std::unique_ptr<RasterBackend>> raster = RasterBackend::create(vk);
  ASSERT_FALSE(raster.ok());
  EXPECT_NE(raster.error().message.find("device 63 does not exist"), std::string::npos)
      << raster.error().message;
}

TEST(VulkanErrors, MissingFeatureIsNamed) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  VulkanOptions vk;
  vk.pretend_missing_features = {"shaderInt64"};
  Expected<std::unique_ptr<ComputeBackend>> gpu = ComputeBackend::create(vk);
  ASSERT_FALSE(gpu.ok());
  EXPECT_NE(gpu.error().message.find("shaderInt64"), std::string::npos) << gpu.error().message;
  vk.pretend_missing_features = {"geometryShader"};
  Expected<std::unique_ptr<RasterBackend>> raster = RasterBackend::create(vk);
  ASSERT_FALSE(raster.ok());
  EXPECT_NE(raster.error().message.find("geometryShader"), std::string::npos)
      << raster.error().message;
}

TEST(VulkanErrors, SceneTooLargeForTheDeviceIsAnError) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  VulkanOptions vk;
  vk.pretend_max_buffer_bytes = 300 * 1024;  // the visibility buffer alone needs 384 KiB
  ComputePtr gpu = makeCompute(vk);
  ASSERT_TRUE(gpu);
  Frame frame;
  gpu->render(cubeScene(), options(), frame);
  Expected<void> result = gpu->lastResult();
  ASSERT_FALSE(result.ok());
  EXPECT_NE(result.error().message.find("maxStorageBufferRange"), std::string::npos)
      << result.error().message;
  // A smaller image fits, and renders.
  gpu->render(cubeScene(), options(64, 48), frame);
  EXPECT_TRUE(gpu->lastResult().ok());
}

// ---- the device list ----

TEST(VulkanDevices, ListsUsableDevices) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  Expected<std::vector<vulkan::DeviceInfo>> devices = vulkan::listDevices();
  ASSERT_TRUE(devices.ok());
  ASSERT_FALSE(devices->empty());
  for (const vulkan::DeviceInfo& d : *devices) {
    EXPECT_FALSE(d.name.empty());
    EXPECT_FALSE(d.compute_note.empty());
    std::printf("[ device   ] %d: %s (%s, Vulkan %s): vulkan %s (%s); vulkan-raster %s (%s)\n",
                d.index, d.name.c_str(), d.type.c_str(), d.api_version.c_str(),
                d.compute_usable ? "yes" : "no", d.compute_note.c_str(),
                d.raster_usable ? "yes" : "no", d.raster_note.c_str());
  }
}

// ---- the CLI ----
#ifdef TESSERA_EXE

namespace {

// Runs tessera with `args` (shell-quoted) and `environment` (NAME=value ... or empty) in a fresh
// folder, which `folder` receives (the caller removes it); without `folder` the folder is removed
// here.
test::RunResult runCli(const std::string& environment, const std::string& args,
                       std::filesystem::path* folder = nullptr) {
  const std::filesystem::path dir = test::makeTestFolder("tessera_vulkan_cli");
  test::RunResult r = test::runInFolder(dir, TESSERA_EXE, args, environment);
  if (folder)
    *folder = dir;
  else
    std::filesystem::remove_all(dir);
  return r;
}

}  // namespace

TEST(VulkanCli, DevicesListsEachDeviceAndBackend) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  const test::RunResult r = runCli("", "devices");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("0: "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("vulkan:"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("vulkan-raster:"), std::string::npos) << r.out;
}

TEST(VulkanCli, CubeRendersWithBothVulkanBackends) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  for (const char* backend : {"vulkan", "vulkan-raster"}) {
    std::filesystem::path dir;
    const test::RunResult r = runCli(
        "", std::string("cube -w 64 -h 48 -fps 4 -dur 0.5s -out c.gif --backend ") + backend, &dir);
    EXPECT_EQ(r.exit_code, 0) << backend << ": " << r.err;
    EXPECT_TRUE(std::filesystem::exists(dir / "c.gif")) << backend;
    std::filesystem::remove_all(dir);
  }
}

TEST(VulkanCli, MissingLoaderFailsWithAMessageAndNoOutput) {
  std::filesystem::path dir;
  const test::RunResult r = runCli("TESSERA_VULKAN_LOADER=/nonexistent/libvulkan.so.1",
                                   "cube -w 64 -h 48 -dur 0.25s -out c.gif --backend vulkan", &dir);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("cannot open the Vulkan loader"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "c.gif"));
  std::filesystem::remove_all(dir);
  const test::RunResult devices =
      runCli("TESSERA_VULKAN_LOADER=/nonexistent/libvulkan.so.1", "devices");
  EXPECT_EQ(devices.exit_code, 1);
  EXPECT_NE(devices.err.find("Vulkan loader"), std::string::npos) << devices.err;
}

TEST(VulkanCli, DeviceOutOfRangeFails) {
  TESSERA_SKIP_WITHOUT_VULKAN();
  const test::RunResult r = runCli("",
                                   "cube -w 64 -h 48 -dur 0.25s -out c.gif --backend vulkan-raster "
                                   "--device 40");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("device 40 does not exist"), std::string::npos) << r.err;
}

#endif  // TESSERA_EXE
