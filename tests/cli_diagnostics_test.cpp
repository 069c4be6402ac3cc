// End-to-end tests of `tessera render`'s diagnostics: the diagnostic AOVs and --stats.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "decode.h"
#include "run_process.h"
#include "temp_folder.h"

namespace fs = std::filesystem;
using tessera::test::DecodedPng;
using tessera::test::RunResult;
using tessera::test::slurp;

namespace {

constexpr int kQuads = 4;
// Stacked quads, each far wider than the view, seen face on: every pixel is behind all of them.
const char* kCamera = " --camera-position 0,0,5 --camera-focal-point 0,0,0 --camera-view-angle 30";

class CliDiagnostics : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = tessera::test::makeTestFolder("tessera_cli_diag");
    std::string obj;
    for (int i = 0; i < kQuads; ++i) {
      const std::string z = std::to_string(-0.1 * i);
      obj += "v -10 -10 " + z + "\nv 10 -10 " + z + "\nv 10 10 " + z + "\nv -10 10 " + z + "\n";
      const int b = 4 * i;
      obj += "f " + std::to_string(b + 1) + " " + std::to_string(b + 2) + " " +
             std::to_string(b + 3) + " " + std::to_string(b + 4) + "\n";
    }
    tessera::test::writeFile(dir_ / "quads.obj", obj);
  }
  void TearDown() override { fs::remove_all(dir_); }
  RunResult run(const std::string& args) {
    return tessera::test::runInFolder(dir_, TESSERA_EXE, args);
  }
  DecodedPng png(const std::string& name) {
    DecodedPng out;
    EXPECT_TRUE(tessera::test::decodePng((dir_ / name).string(), out)) << name;
    return out;
  }
  // Renders the quads with `args` (and the camera) into `name`, decoded; an empty image when the
  // run fails (the failure reported).
  DecodedPng renderPng(const std::string& args, const std::string& name) {
    RunResult r = run("render quads.obj -o " + name + " " + args + kCamera);
    EXPECT_EQ(r.exit_code, 0) << args << ": " << r.err;
    return r.exit_code == 0 ? png(name) : DecodedPng{};
  }
  nlohmann::json json(const std::string& name) {
    return nlohmann::json::parse(slurp(dir_ / name), nullptr, /*allow_exceptions=*/false);
  }
  fs::path dir_;
};

}  // namespace

TEST_F(CliDiagnostics, OverdrawOfStackedQuadsIsTheirCountAtEveryPixel) {
  const DecodedPng o = renderPng("--resolution 100,70 --aov overdraw", "o.png");
  ASSERT_EQ(o.channels, 1);
  ASSERT_EQ(o.bit_depth, 16);
  for (int y = 0; y < o.height; ++y)
    for (int x = 0; x < o.width; ++x) ASSERT_EQ(o.at(x, y, 0), kQuads) << x << "," << y;
}

TEST_F(CliDiagnostics, OccupancyMaterialAndTileAovs) {
  for (const char* aov : {"occupancy", "material", "density", "tile-occlusion", "tile-edges"}) {
    const DecodedPng a = renderPng(std::string("--resolution 100,70 --aov ") + aov, "a.png");
    ASSERT_EQ(a.width, 100);
    const std::string name = aov;
    if (name == "occupancy") {
      EXPECT_EQ(a.at(5, 5, 0), 2 * kQuads);  // every triangle touches every tile
      EXPECT_EQ(a.at(99, 69, 0), 2 * kQuads);
    } else if (name == "material") {
      EXPECT_EQ(a.rgb(50, 35), (std::array<int, 3>{1, 0, 0}));  // material 0, plus one
    } else if (name == "density") {
      EXPECT_EQ(a.at(50, 35, 0), 1000);  // the default density 1.0, in thousandths
    } else if (name == "tile-occlusion") {
      EXPECT_EQ(a.at(50, 35, 0), 255);  // covered fraction 1
      EXPECT_EQ(a.at(50, 35, 1), a.at(50, 35, 2));  // a flat quad: min depth == max depth
    } else {
      EXPECT_EQ(a.at(50, 35, 0), 0);  // no depth discontinuity anywhere
    }
  }
}

TEST_F(CliDiagnostics, HeatmapHasTheRampAndALegend) {
  const DecodedPng h = renderPng("--resolution 200,160 --aov overdraw-heatmap", "h.png");
  ASSERT_EQ(h.channels, 3);
  EXPECT_EQ(h.rgb(100, 10), (std::array<int, 3>{252, 255, 164}));  // the maximum: the ramp's top
  EXPECT_EQ(h.rgb(0, 159), (std::array<int, 3>{0, 0, 0}));         // the legend strip
  EXPECT_NE(h.rgb(50, 155), h.rgb(150, 155));                      // the bar ramps
}

TEST_F(CliDiagnostics, StatsJsonAddsUpAndIsTheSameForAnyWorkerCount) {
  const std::string common =
      "render quads.obj --resolution 150,100 --turntable 2 -o f{frame}.png" + std::string(kCamera);
  ASSERT_EQ(run(common + " --stats one.json --workers 1").exit_code, 0);
  RunResult r = run(common + " --stats three.json --workers 3");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  nlohmann::json one = json("one.json"), three = json("three.json");
  ASSERT_FALSE(one.is_discarded());
  ASSERT_EQ(one["schema"], "tessera-stats-1");
  ASSERT_EQ(one["frames"].size(), 2u);
  for (size_t i = 0; i < 2; ++i) {
    const nlohmann::json& f = one["frames"][i];
    const nlohmann::json& c = f["counters"];
    EXPECT_EQ(f["frame"], i);
    EXPECT_EQ(c["triangles_in"], 2 * kQuads);
    EXPECT_EQ(c["triangles_in"].get<int>(), c["culled"]["total"].get<int>() +
                                                c["triangles_setup"].get<int>() -
                                                c["clip_splits"].get<int>());
    EXPECT_EQ(c["tiles"], 6);
    EXPECT_EQ(f["tiles"]["occupancy"].size(), 6u);
    EXPECT_EQ(f["tiles"]["edges"].size(), 6u);
    EXPECT_GT(c["pixels_tested"].get<int>(), 0);
    EXPECT_TRUE(f["times_ms"]["tiles"].is_number());
    EXPECT_EQ(c, three["frames"][i]["counters"]);
    EXPECT_EQ(f["tiles"], three["frames"][i]["tiles"]);
  }
}

TEST_F(CliDiagnostics, AnUnwritableStatsPathFailsBeforeRendering) {
  // A missing folder would be made (issue 20); a file in the way of one cannot be.
  tessera::test::writeFile(dir_ / "blocker", "a file");
  RunResult r = run("render quads.obj --resolution 40,30 -o out.png --stats blocker/s.json" +
                    std::string(kCamera));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("blocker"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "out.png"));
  size_t files = 0;
  for (const auto& e : fs::directory_iterator(dir_))
    files += e.path().filename() != "quads.obj" && e.path().filename() != "blocker";
  EXPECT_EQ(files, 0u);
}

TEST_F(CliDiagnostics, PixelTestAovsNeedThePerspectiveProjection) {
  RunResult r = run("render quads.obj --resolution 40,30 --aov overdraw -o o.png "
                    "--projection fisheye" + std::string(kCamera));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("perspective"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "o.png"));
}

#ifdef TESSERA_TEST_VULKAN_CLI
// The vulkan backend's overdraw AOV and stats: the same numbers as the CPU's on the quads (its
// depth tests are counted on the GPU, the same definition). The tests skip only without a
// Vulkan device, which `tessera devices` reports.
TEST_F(CliDiagnostics, VulkanOverdrawAndStatsAreTheCpus) {
  if (run("devices").exit_code != 0) GTEST_SKIP() << "no Vulkan device (tessera devices fails)";
  const DecodedPng o = renderPng("--resolution 100,70 --aov overdraw --backend vulkan", "o.png");
  ASSERT_EQ(o.width, 100);
  for (int y = 0; y < o.height; ++y)
    for (int x = 0; x < o.width; ++x) ASSERT_EQ(o.at(x, y, 0), kQuads) << x << "," << y;
  const std::string common =
      "render quads.obj --resolution 150,100 -o c.png" + std::string(kCamera) + " --stats ";
  RunResult r = run(common + "gpu.json --backend vulkan");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ASSERT_EQ(run(common + "cpu.json --backend cpu").exit_code, 0);
  nlohmann::json gpu = json("gpu.json"), cpu = json("cpu.json");
  ASSERT_FALSE(gpu.is_discarded());
  const nlohmann::json& g = gpu["frames"][0];
  EXPECT_EQ(g["backend"], "vulkan");
  EXPECT_EQ(g["counters"], cpu["frames"][0]["counters"]);
  EXPECT_EQ(g["tiles"], cpu["frames"][0]["tiles"]);
  EXPECT_TRUE(g["times_ms"]["tiles"].is_number());
}

// vulkan-raster: the measures it has, the counters it cannot count as null, and no overdraw.
TEST_F(CliDiagnostics, VulkanRasterStatsMarkWhatItCannotMeasure) {
  if (run("devices").exit_code != 0) GTEST_SKIP() << "no Vulkan device (tessera devices fails)";
  RunResult r = run("render quads.obj --resolution 150,100 -o c.png --stats s.json "
                    "--backend vulkan-raster" + std::string(kCamera));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  nlohmann::json s = json("s.json");
  ASSERT_FALSE(s.is_discarded());
  const nlohmann::json& c = s["frames"][0]["counters"];
  EXPECT_EQ(c["triangles_in"], 2 * kQuads);
  EXPECT_TRUE(c["culled"].is_null());
  EXPECT_TRUE(c["triangles_setup"].is_null());
  EXPECT_TRUE(c["pixels_tested"].is_null());
  EXPECT_EQ(c["pixels_shaded"], 150 * 100);
  EXPECT_EQ(c["tiles_full"], 6);
  EXPECT_EQ(s["frames"][0]["tiles"]["covered"].size(), 6u);
  r = run("render quads.obj --aov overdraw -o o.png --backend vulkan-raster");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("not measured on the vulkan-raster"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "o.png"));
}
#endif
