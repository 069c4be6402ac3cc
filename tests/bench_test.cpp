// Tests of the benchmark: the built-in scenes and `tessera bench` run as a real process (the
// llvmpipe reference's own tests: bench_reference_test.cpp). Nothing here times anything.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include <tessera/render/cpu_renderer.h>

#include "bench/llvmpipe_reference.h"
#include "bench/scenes.h"
#include "bench_test_scenes.h"
#include "run_process.h"
#include "temp_folder.h"

namespace fs = std::filesystem;
using namespace tessera;

using test::colorAndIds;
using test::scene;

TEST(BenchScenes, BuiltinScenesHaveTheAdvertisedTriangleCounts) {
  const std::pair<const char*, size_t> expected[] = {{"cube", bench::kCubeTriangles},
                                                     {"dense", bench::kDenseTriangles},
                                                     {"fill", bench::kFillTriangles},
                                                     {"textured", bench::kTexturedTriangles}};
  for (const auto& [name, triangles] : expected) {
    Expected<bench::BenchScene> s = scene(name);
    ASSERT_TRUE(s.ok()) << name << ": " << s.error().message;
    EXPECT_EQ(s->name, name);
    EXPECT_EQ(s->scene.triangleCount(), triangles) << name;
  }
  EXPECT_EQ(bench::kCubeTriangles, 12u);
  EXPECT_EQ(bench::kDenseTriangles, 1'000'000u);
  EXPECT_EQ(bench::kFillTriangles, 20u);
}

TEST(BenchScenes, BunnyIsTheStanfordBunny) {
  if (!fs::exists(bench::kBunnyPath)) GTEST_SKIP() << bench::kBunnyPath << " is not installed";
  Expected<bench::BenchScene> s = scene("bunny");
  ASSERT_TRUE(s.ok()) << s.error().message;
  EXPECT_EQ(s->scene.triangleCount(), 69'666u);
  EXPECT_EQ(bench::kBunnyTriangles, 69'666u);
}

TEST(BenchScenes, EveryBuiltinNameMakesAScene) {
  for (const std::string& name : bench::builtinSceneNames()) {
    EXPECT_TRUE(bench::isBuiltinScene(name));
    if (name == "bunny" && !fs::exists(bench::kBunnyPath)) continue;
    EXPECT_TRUE(scene(name).ok()) << name;
  }
  EXPECT_EQ(bench::builtinSceneNames().size(), 6u);
}

// 10,000 instances of one 1,000-triangle sphere, 99% of them outside the bench's view in every
// frame; the flattened form (for docs/perf.md's comparison) holds the same triangles in one mesh.
TEST(BenchScenes, InstancesSceneSharesOneMeshAndShowsAboutOnePercent) {
  Expected<bench::BenchScene> s = scene("instances");
  ASSERT_TRUE(s.ok()) << s.error().message;
  ASSERT_EQ(s->scene.objects.size(), 10'000u);
  for (const Object& o : s->scene.objects) ASSERT_EQ(o.mesh, s->scene.objects[0].mesh);
  const size_t mesh_triangles = s->scene.objects[0].mesh->triangleCount();
  EXPECT_GE(mesh_triangles, 1'000u);
  EXPECT_LE(mesh_triangles, 1'100u);
  CpuRenderer renderer(1);
  Frame frame;
  // In every frame of a run: the scene holds still (turned about the origin as the other scenes
  // turn, its grid left the view by frame 40).
  for (int pose : {0, 20, 40, 90}) {
    bench::poseForFrame(*s, pose);
    renderer.render(s->scene, colorAndIds(96, 54), frame);
    const PipelineStats& stats = renderer.lastStats();
    EXPECT_GE(stats.instances_culled, 9'850u) << "pose " << pose;  // at most 1.5% in view
    EXPECT_LE(stats.instances_culled, 9'950u) << "pose " << pose;  // and some of them
  }
  Expected<bench::BenchScene> flat = scene("instances-flat");
  ASSERT_TRUE(flat.ok()) << flat.error().message;
  ASSERT_EQ(flat->scene.objects.size(), 1u);
  EXPECT_EQ(flat->scene.triangleCount(), s->scene.triangleCount());
  EXPECT_FALSE(bench::isBuiltinScene("instances-flat"));  // not in a full bench run
}

TEST(BenchScenes, UnknownSceneIsAnErrorNamingIt) {
  Expected<bench::BenchScene> s = scene("teapot");
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().message.find("teapot"), std::string::npos);
  EXPECT_FALSE(bench::isBuiltinScene("teapot"));
}

TEST(BenchScenes, TexturedSceneSamplesAChecker) {
  Expected<bench::BenchScene> s = scene("textured");
  ASSERT_TRUE(s.ok());
  const Object& object = s->scene.objects.at(0);
  ASSERT_TRUE(object.materials.at(0).albedo);
  EXPECT_FALSE(object.mesh->uvs.empty());
  const Texture& t = *object.materials[0].albedo;
  EXPECT_NE(t.texels.front(), t.texels[t.width / 16]);  // the next cell has the other colour
}

// Ten layers, each of which alone covers every pixel at any angle of the spin: overdraw 10.
TEST(BenchScenes, FillLayersEachCoverTheWholeScreen) {
  Expected<bench::BenchScene> s = scene("fill");
  ASSERT_TRUE(s.ok());
  ASSERT_TRUE(s->fixed_view);
  ASSERT_EQ(s->scene.objects.size(), bench::kFillLayers);
  CpuRenderer renderer(1);
  Frame frame;
  for (int pose : {0, 7, 22}) {  // 0, 14 and 44 degrees about the view axis
    bench::poseForFrame(*s, pose);
    for (size_t layer = 0; layer < bench::kFillLayers; ++layer) {
      Scene one = s->scene;
      one.objects = {s->scene.objects[layer]};
      for (auto [w, h] : {std::pair{32, 24}, std::pair{48, 27}}) {
        renderer.render(one, colorAndIds(w, h), frame);
        size_t covered = 0;
        for (uint32_t id : frame.triangle_id) covered += id != kNoTriangle;
        EXPECT_EQ(covered, frame.pixelCount()) << "layer " << layer << " pose " << pose;
      }
    }
    // Together, the nearest layer (the last drawn) wins everywhere.
    renderer.render(s->scene, colorAndIds(32, 24), frame);
    for (uint32_t id : frame.triangle_id) EXPECT_GT(id, bench::kFillTriangles - 2);
  }
}

TEST(BenchScenes, PoseTurnsAboutThePivot) {
  Expected<bench::BenchScene> s = scene("cube");
  ASSERT_TRUE(s.ok());
  s->pivot = {0.5f, 0.0f, 0.0f};
  bench::poseForFrame(*s, 45);  // 90 degrees about +Y
  const float4x4 m = s->scene.objects[0].transform.matrix();
  const float3 pivot = (m * float4{0.5f, 0.0f, 0.0f, 1.0f}).xyz();
  EXPECT_NEAR(pivot.x, 0.5f, 1e-5f);
  EXPECT_NEAR(pivot.z, 0.0f, 1e-5f);
  const float3 x_axis = (m * float4{1, 0, 0, 0}).xyz();
  EXPECT_NEAR(x_axis.z, -1.0f, 1e-5f);  // +X turns to -Z
  bench::poseForFrame(*s, 0);
  EXPECT_NEAR(s->scene.objects[0].transform.rotation.w, 1.0f, 1e-6f);
}

// ---- tessera bench, the executable ----

namespace {

using test::RunResult;

class BenchCli : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test::makeTestFolder("tessera_bench"); }
  void TearDown() override { fs::remove_all(dir_); }

  // Runs `tessera bench` with `args` (a shell-quoted string) in the test's folder.
  RunResult run(const std::string& args) {
    return test::runInFolder(dir_, TESSERA_EXE, "bench " + args);
  }

  // Runs `tessera bench` with `args` and parses its one JSON line; an empty object (with the
  // test failed) when the run fails or prints no JSON object.
  nlohmann::json runJson(const std::string& args) {
    RunResult r = run(args);
    EXPECT_EQ(r.exit_code, 0) << args << "\n" << r.err;
    nlohmann::json j = nlohmann::json::parse(r.out, nullptr, /*allow_exceptions=*/false);
    EXPECT_TRUE(j.is_object()) << args << "\n" << r.out;
    return j.is_object() ? j : nlohmann::json::object();
  }

  static std::vector<std::string> lines(const std::string& text) {
    std::vector<std::string> out;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);)
      if (!line.empty()) out.push_back(line);
    return out;
  }

  fs::path dir_;
};

}  // namespace

TEST_F(BenchCli, JsonHasTheAdvertisedFields) {
  RunResult r = run("--json --frames 2 --resolution 64,48 cube");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::vector<std::string> objects = lines(r.out);
  ASSERT_EQ(objects.size(), 1u) << r.out;
  nlohmann::json j = nlohmann::json::parse(objects[0], nullptr, /*allow_exceptions=*/false);
  ASSERT_FALSE(j.is_discarded()) << objects[0];
  ASSERT_TRUE(j.is_object());
  EXPECT_EQ(j.value("scene", ""), "cube");
  EXPECT_EQ(j.value("resolution", ""), "64x48");
  EXPECT_EQ(j.value("width", 0), 64);
  EXPECT_EQ(j.value("height", 0), 48);
  EXPECT_EQ(j.value("triangles", 0), 12);
  EXPECT_EQ(j.value("frames", 0), 2);
  ASSERT_TRUE(j.contains("median_ms") && j["median_ms"].is_number());
  EXPECT_GE(j["median_ms"].get<double>(), 0.0);
  EXPECT_FALSE(j.contains("llvmpipe_median_ms"));  // not asked for
}

TEST_F(BenchCli, JsonLinesForEverySceneAndResolution) {
  RunResult r =
      run("--json --frames 1 --warmup 0 --resolution 32x24,40x30 --resolution 16,16 "
          "cube fill");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::vector<std::string> objects = lines(r.out);
  ASSERT_EQ(objects.size(), 6u) << r.out;
  const char* expected[6][2] = {{"cube", "32x24"}, {"cube", "40x30"}, {"cube", "16x16"},
                                {"fill", "32x24"}, {"fill", "40x30"}, {"fill", "16x16"}};
  for (size_t i = 0; i < objects.size(); ++i) {
    nlohmann::json j = nlohmann::json::parse(objects[i], nullptr, false);
    ASSERT_TRUE(j.is_object()) << objects[i];
    EXPECT_EQ(j.value("scene", ""), expected[i][0]);
    EXPECT_EQ(j.value("resolution", ""), expected[i][1]);
    EXPECT_EQ(j.value("frames", 0), 1);
  }
}

TEST_F(BenchCli, TextModePrintsOneLinePerScene) {
  RunResult r = run("--frames 1 --warmup 0 --resolution 32,24 cube fill --shading flat");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::vector<std::string> scene_lines;
  for (const std::string& line : lines(r.out))
    if (line[0] != '#') scene_lines.push_back(line);
  ASSERT_EQ(scene_lines.size(), 2u) << r.out;
  EXPECT_EQ(scene_lines[0].rfind("cube", 0), 0u);
  EXPECT_NE(scene_lines[0].find("32x24"), std::string::npos);
  EXPECT_NE(scene_lines[0].find(" 12 triangles"), std::string::npos);
  EXPECT_EQ(scene_lines[1].rfind("fill", 0), 0u);
  EXPECT_NE(r.out.find("flat shading"), std::string::npos);
}

TEST_F(BenchCli, AModelFileIsAScene) {
  std::ofstream(dir_ / "quad.obj") << "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3 4\n";
  RunResult r = run("--json --frames 1 --warmup 0 --resolution 32,24 quad.obj");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  nlohmann::json j = nlohmann::json::parse(r.out, nullptr, false);
  ASSERT_TRUE(j.is_object()) << r.out;
  EXPECT_EQ(j.value("scene", ""), "quad.obj");
  EXPECT_EQ(j.value("triangles", 0), 2);
}

TEST_F(BenchCli, BadFlagsExitTwoWithUsage) {
  for (const char* args :
       {"--frames 0 cube", "--frames x cube", "--resolution 64 cube", "--resolution 64,48,32 cube",
        "--resolution 0,48 cube", "--bogus cube", "--shading shiny cube", "--vs swiftshader cube",
        "--all cube", "--all --resolution 64,48",
        "--camera-position 0,0,0 "
        "--camera-focal-point 0,0,0 cube"}) {
    RunResult r = run(args);
    EXPECT_EQ(r.exit_code, 2) << args;
    EXPECT_NE(r.err.find("tessera bench --help"), std::string::npos) << args << "\n" << r.err;
    EXPECT_TRUE(r.out.empty()) << args;
  }
}

TEST_F(BenchCli, MsaaOtherThanOneTwoFourOrEightIsAUsageError) {
  for (const char* value : {"3", "0", "16", "-4", "4x", "4294967300"}) {
    RunResult r = run(std::string("--frames 1 --resolution 16,16 --msaa ") + value + " cube");
    EXPECT_EQ(r.exit_code, 2) << value;
    EXPECT_NE(r.err.find("1, 2, 4 or 8"), std::string::npos) << value << "\n" << r.err;
    EXPECT_NE(r.err.find("tessera bench --help"), std::string::npos) << value;
    EXPECT_TRUE(r.out.empty()) << value;
  }
}

TEST_F(BenchCli, OutputSaysTheSampleCount) {
  for (int msaa : {1, 2, 4, 8}) {
    const std::string flag = msaa == 1 ? "" : " --msaa " + std::to_string(msaa);
    RunResult r = run("--json --frames 1 --warmup 0 --resolution 32,24 cube" + flag);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    nlohmann::json j = nlohmann::json::parse(r.out, nullptr, false);
    ASSERT_TRUE(j.is_object()) << r.out;
    ASSERT_TRUE(j.contains("msaa") && j["msaa"].is_number_integer()) << r.out;
    EXPECT_EQ(j["msaa"].get<int>(), msaa);  // 1 without the flag: old numbers stay comparable
  }
  RunResult text = run("--frames 1 --warmup 0 --resolution 32,24 --msaa 4 cube");
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("4 samples per pixel"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("4x MSAA"), std::string::npos) << text.out;
}

// llvmpipe draws the sample count asked for, or the run fails before anything is timed: a count
// that GL rounds to another (llvmpipe makes 4 of 2) would not be the same work.
TEST_F(BenchCli, VersusLlvmpipeDrawsTheSameSampleCountOrFails) {
  if (!bench::llvmpipeReferenceBuilt()) GTEST_SKIP() << "built without OSMesa";
  for (int msaa : {2, 4, 8}) {
    RunResult r =
        run("--json --frames 1 --warmup 0 --resolution 32,24 --workers 1 --vs llvmpipe "
            "--msaa " +
            std::to_string(msaa) + " cube");
    if (r.exit_code == 0) {
      nlohmann::json j = nlohmann::json::parse(r.out, nullptr, false);
      ASSERT_TRUE(j.is_object()) << r.out;
      EXPECT_EQ(j.value("msaa", 0), msaa);
      EXPECT_TRUE(j.contains("llvmpipe_median_ms")) << r.out;
    } else {
      EXPECT_EQ(r.exit_code, 1) << msaa;
      EXPECT_NE(r.err.find("cannot draw " + std::to_string(msaa) + " samples per pixel"),
                std::string::npos)
          << r.err;
      EXPECT_TRUE(r.out.empty()) << "nothing is timed with another sample count";
    }
    // Multisampling at 4x has been in llvmpipe since Mesa 20.
    if (msaa == 4) {
      EXPECT_EQ(r.exit_code, 0) << r.err;
    }
  }
}

TEST_F(BenchCli, HelpExitsZero) {
  RunResult r = run("--help");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("--vs"), std::string::npos);
  EXPECT_NE(r.out.find("--resolution"), std::string::npos);
}

TEST_F(BenchCli, UnknownSceneExitsOneNamingIt) {
  RunResult r = run("--frames 1 cube teapot");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("'teapot'"), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty()) << "nothing is timed before every scene is known";
}

TEST_F(BenchCli, BrokenModelFileExitsOneNamingIt) {
  std::ofstream(dir_ / "broken.obj") << "v 0 0 0\nf 1 2 7\n";
  RunResult r = run("--frames 1 broken.obj");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("broken.obj"), std::string::npos) << r.err;
}

TEST_F(BenchCli, VersusLlvmpipeAddsTheReference) {
  RunResult r = run("--json --frames 2 --resolution 64,48 --workers 1 --vs llvmpipe cube");
  if (!bench::llvmpipeReferenceBuilt()) {
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_NE(r.err.find("OSMesa"), std::string::npos) << r.err;
    return;
  }
  ASSERT_EQ(r.exit_code, 0) << r.err;
  nlohmann::json j = nlohmann::json::parse(r.out, nullptr, false);
  ASSERT_TRUE(j.is_object()) << r.out;
  ASSERT_TRUE(j.contains("llvmpipe_median_ms") && j["llvmpipe_median_ms"].is_number());
  ASSERT_TRUE(j.contains("ratio") && j["ratio"].is_number());
  EXPECT_NE(j.value("reference", "").find("llvmpipe"), std::string::npos);
  EXPECT_EQ(j.value("workers", 0), 1);
}

TEST_F(BenchCli, ToneMappingChangesTheFrameAndIsReported) {
  RunResult plain = run("--json --crc --frames 1 --warmup 0 --resolution 64,48 --shading pbr cube");
  RunResult toned =
      run("--json --crc --frames 1 --warmup 0 --resolution 64,48 --shading pbr --tone-mapping aces "
          "--exposure 1 cube");
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  ASSERT_EQ(toned.exit_code, 0) << toned.err;
  nlohmann::json a = nlohmann::json::parse(plain.out, nullptr, false);
  nlohmann::json b = nlohmann::json::parse(toned.out, nullptr, false);
  ASSERT_TRUE(a.is_object() && b.is_object()) << plain.out << toned.out;
  EXPECT_EQ(a.value("tone_mapping", ""), "none");
  EXPECT_EQ(b.value("tone_mapping", ""), "aces");
  EXPECT_EQ(b.value("exposure", 0.0), 1.0);
  EXPECT_EQ(b.value("shading", ""), "pbr");
  EXPECT_GE(b.value("lights", 0), 1);
  EXPECT_NE(a.value("crc32", ""), b.value("crc32", ""));  // the curve reached tessera's frame
  EXPECT_EQ(run("--frames 1 --tone-mapping filmic cube").exit_code, 2);
}

// The camera flags are recorded in the JSON row (the matrix's "bunny filling the frame" rows are
// told apart from the bench's own view by them) and move tessera's camera.
TEST_F(BenchCli, CameraFlagsAreReported) {
  const std::string common = "--json --crc --frames 1 --warmup 0 --resolution 64,48 ";
  const nlohmann::json a = runJson(common + "cube");
  const nlohmann::json b =
      runJson(common + "--camera-position 0,0.5,4 --camera-view-up 0,1,0 cube");
  EXPECT_EQ(a.value("camera", "?"), "");
  EXPECT_EQ(b.value("camera", ""), "--camera-position 0,0.5,4 --camera-view-up 0,1,0");
  EXPECT_NE(a.value("crc32", ""), b.value("crc32", ""));
}

// --hdri lights tessera's PBR frames with the image (a 4x2 sky, flat RGBE: bright orange above,
// black below) and is reported; llvmpipe draws no environment light, and an unreadable image stops
// the bench before anything is timed.
TEST_F(BenchCli, HdriLightsTheFrameAndIsReported) {
  {
    std::ofstream sky(dir_ / "sky.hdr", std::ios::binary);
    sky << "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 2 +X 4\n";
    for (int i = 0; i < 8; ++i) sky.write(i < 4 ? "\x80\x40\x10\x82" : "\0\0\0\0", 4);
  }
  const std::string common = "--json --crc --frames 1 --warmup 0 --resolution 64,48 --shading pbr ";
  const nlohmann::json a = runJson(common + "cube");
  const nlohmann::json b = runJson(common + "--hdri sky.hdr cube");
  EXPECT_EQ(a.value("hdri", "?"), "");
  EXPECT_EQ(b.value("hdri", ""), "sky.hdr");
  EXPECT_NE(a.value("crc32", ""), b.value("crc32", ""));  // the image reached tessera's frame
  RunResult versus = run("--frames 1 --hdri sky.hdr --vs llvmpipe cube");
  EXPECT_EQ(versus.exit_code, 2);
  EXPECT_NE(versus.err.find("leave out --hdri"), std::string::npos) << versus.err;
  RunResult missing = run("--frames 1 --hdri missing.hdr cube");
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_NE(missing.err.find("missing.hdr"), std::string::npos) << missing.err;
}

TEST_F(BenchCli, VersusLlvmpipeDrawsPbrWithTheToneCurve) {
  if (!bench::llvmpipeReferenceBuilt()) GTEST_SKIP() << "built without OSMesa";
  RunResult r =
      run("--json --frames 1 --warmup 0 --resolution 64,48 --workers 1 --vs llvmpipe --shading pbr "
          "--tone-mapping pbr-neutral cube");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  nlohmann::json j = nlohmann::json::parse(r.out, nullptr, false);
  ASSERT_TRUE(j.is_object()) << r.out;
  EXPECT_EQ(j.value("tone_mapping", ""), "pbr-neutral");
  ASSERT_TRUE(j.contains("ratio") && j["ratio"].is_number());
}
