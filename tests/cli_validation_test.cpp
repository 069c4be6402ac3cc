// Frame validation: the CRC-32 of frames (library and `--crc` on render, cube and bench) and
// `render --reference` (pass, fail, threshold, update, bad references).
#include <gtest/gtest.h>

#include <zlib.h>

#include <cmath>
#include <filesystem>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <tessera/io/image_writer.h>
#include <tessera/io/validation.h>
#include <tessera/render/cpu_renderer.h>
#include <tessera/scene/primitives.h>

#include "decode.h"
#include "run_process.h"
#include "temp_folder.h"

namespace fs = std::filesystem;
using tessera::test::DecodedPng;
using tessera::test::RunResult;

namespace {

// zlib's own crc32 of the RGBA bytes of a decoded 8-bit PNG (alpha 255 when it has none).
uint32_t zlibCrcOfPng(const DecodedPng& png) {
  std::vector<Bytef> bytes;
  for (int y = 0; y < png.height; ++y)
    for (int x = 0; x < png.width; ++x)
      for (int c = 0; c < 4; ++c)
        bytes.push_back(static_cast<Bytef>(c < png.channels ? png.at(x, y, c) : 255));
  return static_cast<uint32_t>(::crc32(0L, bytes.data(), static_cast<uInt>(bytes.size())));
}

// The values of every "crc32 frame N HEX" line, in order; fails on a malformed crc32 line.
std::vector<std::string> frameCrcs(const std::string& out) {
  std::vector<std::string> crcs;
  const std::regex line("crc32 frame ([0-9]+) ([0-9a-f]{8})");
  std::istringstream in(out);
  for (std::string text; std::getline(in, text);) {
    if (text.rfind("crc32", 0) != 0) continue;
    std::smatch m;
    EXPECT_TRUE(std::regex_match(text, m, line)) << text;
    if (m.empty()) continue;
    EXPECT_EQ(std::stoi(m[1]), static_cast<int>(crcs.size())) << text;
    crcs.push_back(m[2]);
  }
  return crcs;
}

tessera::Frame renderCube(tessera::Backend& renderer) {
  tessera::Scene scene;
  tessera::Object cube;
  cube.mesh = std::make_shared<tessera::Mesh>(tessera::makeCube());
  cube.transform.rotation = tessera::quat::fromAxisAngle({0.3f, 1, 0.2f}, 0.7f);
  scene.objects.push_back(cube);
  scene.lights.push_back(
      {tessera::normalize(tessera::float3{-0.6f, -1.0f, -0.8f}), tessera::float3(0.9f)});
  scene.camera.position = {0.0f, 1.0f, 3.0f};
  scene.camera.target = {0, 0, 0};
  tessera::RenderOptions options;
  options.width = 97;  // not a multiple of a tile or a SIMD width
  options.height = 61;
  tessera::Frame frame;
  renderer.render(scene, options, frame);
  return frame;
}

}  // namespace

TEST(Crc32, OfAKnownSmallImageEqualsZlibs) {
  // Bytes R, G, B, A per pixel: ff 00 00 ff | 00 80 00 ff | 00 00 40 7f | 01 02 03 04.
  const uint32_t pixels[] = {0xff0000ffu, 0xff008000u, 0x7f400000u, 0x04030201u};
  const Bytef bytes[] = {0xff, 0, 0, 0xff, 0, 0x80, 0, 0xff, 0, 0, 0x40, 0x7f, 1, 2, 3, 4};
  const uint32_t crc = tessera::io::crc32Rgba8(pixels, 2, 2);
  EXPECT_EQ(crc, static_cast<uint32_t>(::crc32(0L, bytes, sizeof bytes)));
  EXPECT_EQ(crc, 0x01289e53u);  // Python: zlib.crc32(bytes)
  EXPECT_EQ(tessera::io::crc32Hex(crc), "01289e53");
  // Rows top to bottom: swapping the rows changes it.
  const uint32_t swapped[] = {pixels[2], pixels[3], pixels[0], pixels[1]};
  EXPECT_NE(tessera::io::crc32Rgba8(swapped, 2, 2), crc);
}

TEST(Crc32, IsTheSameForAnyWorkerCountAndSimdLevel) {
  using tessera::SimdLevel;
  tessera::CpuRenderer reference_renderer(1, SimdLevel::kScalar);
  const tessera::Frame reference = renderCube(reference_renderer);
  const uint32_t expected =
      tessera::io::crc32Rgba8(reference.color.data(), reference.width, reference.height);
  int drawn = 0;
  for (uint32_t c : reference.color) drawn += c != reference.color[0];
  ASSERT_GT(drawn, 200) << "the cube is not in the picture";
  for (SimdLevel simd : {SimdLevel::kScalar, SimdLevel::kSse2, SimdLevel::kAvx2, SimdLevel::kAvx512,
                         SimdLevel::kAuto})
    for (int workers : {1, 2, 5}) {
      tessera::CpuRenderer renderer(workers, simd);
      const tessera::Frame frame = renderCube(renderer);
      EXPECT_EQ(tessera::io::crc32Rgba8(frame.color.data(), frame.width, frame.height), expected)
          << renderer.simdName() << ", " << workers << " workers";
    }
}

TEST(CompareRgba8, CountsPixelsBeyondTwoOf255AndDrawsThemRed) {
  tessera::io::Rgba8Image a{10, 10, std::vector<uint32_t>(100, 0xff404040u)};
  tessera::io::Rgba8Image b = a;
  b.pixels[0] = 0xff404043u;   // blue +3: differs
  b.pixels[1] = 0xff404240u;   // green +2: within the tolerance
  b.pixels[2] = 0xff40403du;   // red -3: differs
  b.pixels[3] = 0x00404040u;   // alpha only: not compared
  b.pixels[99] = 0xffffffffu;  // white: differs by 191
  const tessera::io::ImageComparison c = tessera::io::compareRgba8(a, b);
  EXPECT_EQ(c.differing_pixels, 3);
  EXPECT_DOUBLE_EQ(c.differing_percent, 3.0);
  EXPECT_EQ(c.max_channel_difference, 191);
  ASSERT_EQ(c.difference.pixels.size(), 100u);
  auto red = [&](int i) { return c.difference.pixels[i] & 0xff; };
  auto green = [&](int i) { return (c.difference.pixels[i] >> 8) & 0xff; };
  EXPECT_GE(red(0), 96);
  EXPECT_EQ(green(0), 0);
  EXPECT_EQ(red(99), 255);       // amplified, and clamped
  EXPECT_EQ(green(1), red(1));   // within the tolerance: yellow
  EXPECT_LT(red(50), 0x40 / 2);  // the same: the reference dimmed
  EXPECT_EQ(tessera::io::compareRgba8(a, a).differing_pixels, 0);
}

class CliValidation : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = tessera::test::makeTestFolder("tessera_validation");
    // A triangle well inside the picture, so that moving the camera moves its edges.
    tessera::test::writeFile(dir_ / "tri.obj", "v -0.5 -0.4 0\nv 0.5 -0.3 0\nv 0 0.5 0\nf 1 2 3\n");
  }
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(dir_);
  }
  RunResult run(const std::string& args) {
    return tessera::test::runInFolder(dir_, TESSERA_EXE, args);
  }
  // The triangle from 3 units away with a 30 degree view angle at 64x48: a pixel is
  // 2 * 3 * tan(15 degrees) / 48 = 0.0335 units there. `shift_pixels` moves the camera right.
  RunResult renderTriangle(const std::string& output, double shift_pixels,
                           const std::string& extra) {
    const double x = shift_pixels * 6.0 * std::tan(15.0 * M_PI / 180.0) / 48.0;
    const std::string at = std::to_string(x);
    return run("render tri.obj -o " + output + " --resolution 64,48 --camera-position " + at +
               ",0,3 --camera-focal-point " + at + ",0,0 --camera-view-angle 30 " + extra);
  }
  fs::path dir_;
};

TEST_F(CliValidation, RenderCrcIsZlibsCrcOfTheWrittenPngAndTheSameForAnyWorkerCount) {
  RunResult one = run("render tri.obj -o one.png --resolution 50,30 --crc --workers 1");
  ASSERT_EQ(one.exit_code, 0) << one.err;
  const std::vector<std::string> crcs = frameCrcs(one.out);
  ASSERT_EQ(crcs.size(), 1u) << one.out;
  DecodedPng png;
  ASSERT_TRUE(tessera::test::decodePng((dir_ / "one.png").string(), png));
  ASSERT_EQ(png.bit_depth, 8);
  EXPECT_EQ(crcs[0], tessera::io::crc32Hex(zlibCrcOfPng(png)));
  // And Python's zlib.crc32 through the documented script (standard library only).
  RunResult python = tessera::test::runInFolder(
      dir_, "python3",
      std::string("'") + TESSERA_TEST_DATA_DIR + "/../../scripts/png_crc32.py' one.png");
  ASSERT_EQ(python.exit_code, 0) << python.err;
  EXPECT_EQ(python.out, crcs[0] + "\n");
  RunResult three = run("render tri.obj -o three.png --resolution 50,30 --crc --workers 3");
  ASSERT_EQ(three.exit_code, 0) << three.err;
  EXPECT_EQ(frameCrcs(three.out), crcs);
  // A different picture, a different CRC.
  RunResult other = run("render tri.obj -o other.png --resolution 50,30 --crc --up +Z");
  ASSERT_EQ(other.exit_code, 0) << other.err;
  EXPECT_NE(frameCrcs(other.out), crcs);
}

#ifdef TESSERA_TEST_VULKAN
// vulkan is held to cpu within 2/255, not bit for bit: their CRCs are equal exactly when their
// images are (on lavapipe these scenes come out identical).
TEST_F(CliValidation, CpuAndVulkanCrcsAreEqualWhenTheirImagesAre) {
  for (const std::string msaa : {"1", "4"}) {
    std::vector<std::string> crcs;
    std::vector<DecodedPng> pngs(2);
    for (const std::string backend : {"cpu", "vulkan"}) {
      const std::string out = backend + msaa + ".png";
      RunResult r = run("render tri.obj -o " + out + " --resolution 48,40 --crc --msaa " + msaa +
                        " --backend " + backend);
      ASSERT_EQ(r.exit_code, 0) << backend << ": " << r.err;
      const std::vector<std::string> frame = frameCrcs(r.out);
      ASSERT_EQ(frame.size(), 1u) << r.out;
      crcs.push_back(frame[0]);
      ASSERT_TRUE(tessera::test::decodePng((dir_ / out).string(), pngs[crcs.size() - 1]));
    }
    EXPECT_EQ(crcs[0] == crcs[1], pngs[0].samples == pngs[1].samples) << "msaa " << msaa;
    EXPECT_EQ(crcs[1], tessera::io::crc32Hex(zlibCrcOfPng(pngs[1])));
  }
}
#endif

TEST_F(CliValidation, TurntableAndCubePrintOneCrcPerFrame) {
  RunResult turn = run("render tri.obj -o turn_{frame}.png --resolution 32,24 --turntable 3 --crc");
  ASSERT_EQ(turn.exit_code, 0) << turn.err;
  const std::vector<std::string> crcs = frameCrcs(turn.out);
  ASSERT_EQ(crcs.size(), 3u) << turn.out;
  for (int i = 0; i < 3; ++i) {
    DecodedPng png;
    ASSERT_TRUE(
        tessera::test::decodePng((dir_ / ("turn_000" + std::to_string(i) + ".png")).string(), png));
    EXPECT_EQ(crcs[i], tessera::io::crc32Hex(zlibCrcOfPng(png))) << "frame " << i;
  }
  RunResult cube = run("cube -w 40 -h 30 -fps 4 -dur 1s -out c_{frame}.png -crc");
  ASSERT_EQ(cube.exit_code, 0) << cube.err;
  const std::vector<std::string> cube_crcs = frameCrcs(cube.out);
  ASSERT_EQ(cube_crcs.size(), 4u) << cube.out;
  EXPECT_EQ(std::set<std::string>(cube_crcs.begin(), cube_crcs.end()).size(), 4u);  // it turns
  DecodedPng last;
  ASSERT_TRUE(tessera::test::decodePng((dir_ / "c_0003.png").string(), last));
  EXPECT_EQ(cube_crcs[3], tessera::io::crc32Hex(zlibCrcOfPng(last)));
  RunResult again = run("cube -w 40 -h 30 -fps 4 -dur 1s -out c.gif --crc -workers 1");
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_EQ(frameCrcs(again.out), cube_crcs);
}

TEST_F(CliValidation, BenchPrintsACrcPerSceneAndResolutionAndInJson) {
  const std::string args = "bench cube --resolution 40x30,32x32 --frames 2 --warmup 0 --crc";
  RunResult text = run(args);
  ASSERT_EQ(text.exit_code, 0) << text.err;
  std::smatch m;
  const std::regex first("crc32 cube 40x30 ([0-9a-f]{8})\n");
  ASSERT_TRUE(std::regex_search(text.out, m, first)) << text.out;
  const std::string crc_40x30 = m[1];
  EXPECT_TRUE(std::regex_search(text.out, std::regex("crc32 cube 32x32 [0-9a-f]{8}\n")))
      << text.out;
  RunResult json = run(args + " --json --workers 1");
  ASSERT_EQ(json.exit_code, 0) << json.err;
  EXPECT_NE(json.out.find("\"resolution\": \"40x30\""), std::string::npos) << json.out;
  EXPECT_NE(json.out.find("\"crc32\": \"" + crc_40x30 + "\"}"), std::string::npos) << json.out;
  RunResult plain = run("bench cube --resolution 40x30 --frames 1 --warmup 0 --json");
  EXPECT_EQ(plain.out.find("crc32"), std::string::npos) << "only with --crc";
}

TEST_F(CliValidation, ReferencePassesOnTheSameRenderAndFailsOnACameraMovedByOnePixel) {
  RunResult missing = renderTriangle("out.png", 0, "--reference ref.png");
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_NE(missing.err.find("'ref.png' does not exist; create it from this render by adding "
                             "--reference-update"),
            std::string::npos)
      << missing.err;
  RunResult update = renderTriangle("out.png", 0, "--reference ref.png --reference-update");
  ASSERT_EQ(update.exit_code, 0) << update.err;
  EXPECT_NE(update.out.find("wrote reference ref.png"), std::string::npos) << update.out;
  ASSERT_TRUE(fs::exists(dir_ / "ref.png"));

  RunResult same = renderTriangle("out.png", 0, "--reference ref.png");
  EXPECT_EQ(same.exit_code, 0) << same.err;
  EXPECT_NE(same.out.find("reference 0 threshold 0 pixels 0 max 0 pass"), std::string::npos)
      << same.out;
  EXPECT_TRUE(fs::exists(dir_ / "out.diff.png"));

  RunResult moved = renderTriangle("moved.png", 1, "--ref ref.png");
  EXPECT_EQ(moved.exit_code, 1) << moved.out;
  std::smatch m;
  ASSERT_TRUE(std::regex_search(moved.out, m,
                                std::regex("reference ([0-9.]+) threshold 0 pixels ([0-9]+) "
                                           "max ([0-9]+) fail\nwrote moved.diff.png\n")))
      << moved.out;
  const double percent = std::stod(m[1]);
  // The edges moved: a few percent of the picture, not all of it.
  EXPECT_GT(percent, 0.5);
  EXPECT_LT(percent, 20.0);
  EXPECT_NEAR(percent, std::stod(m[2]) * 100.0 / (64 * 48), 1e-3);
  EXPECT_NE(moved.err.find("differs from the reference 'ref.png'"), std::string::npos) << moved.err;
  // The difference image marks the changed pixels in red over the dimmed reference.
  DecodedPng diff;
  ASSERT_TRUE(tessera::test::decodePng((dir_ / "moved.diff.png").string(), diff));
  ASSERT_EQ(diff.width, 64);
  int red = 0;
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 64; ++x) red += diff.at(x, y, 0) >= 96 && diff.at(x, y, 1) == 0;
  EXPECT_EQ(red, std::stoi(m[2]));

  const std::string loose = "--ref-threshold " + std::to_string(percent + 0.5);
  RunResult passes = renderTriangle("moved.png", 1, "--ref ref.png " + loose);
  EXPECT_EQ(passes.exit_code, 0) << passes.out << passes.err;
  EXPECT_NE(passes.out.find(" pass\n"), std::string::npos) << passes.out;
  RunResult tight = renderTriangle(
      "moved.png", 1, "--reference ref.png --reference-threshold " + std::to_string(percent * 0.5));
  EXPECT_EQ(tight.exit_code, 1) << tight.out;
}

TEST_F(CliValidation, AReferenceOfAnotherSizeOrNotAPngFailsClearly) {
  ASSERT_EQ(renderTriangle("ref.png", 0, "").exit_code, 0);
  RunResult size = run("render tri.obj -o out.png --resolution 60,48 --reference ref.png");
  EXPECT_EQ(size.exit_code, 1);
  EXPECT_NE(size.out.find("reference size-mismatch 64x48 60x48 fail"), std::string::npos)
      << size.out;
  EXPECT_NE(size.err.find("the comparison fails: the reference 'ref.png' is 64x48, the render "
                          "60x48"),
            std::string::npos)
      << size.err;
  EXPECT_FALSE(fs::exists(dir_ / "out.diff.png"));

  tessera::test::writeFile(dir_ / "fake.png", "GIF89a not a png at all");
  RunResult fake = renderTriangle("out.png", 0, "--reference fake.png");
  EXPECT_EQ(fake.exit_code, 1);
  EXPECT_NE(fake.err.find("'fake.png' is not a PNG file"), std::string::npos) << fake.err;
  tessera::test::writeFile(dir_ / "cut.png", tessera::test::slurp(dir_ / "ref.png").substr(0, 60));
  RunResult cut = renderTriangle("out.png", 0, "--reference cut.png");
  EXPECT_EQ(cut.exit_code, 1);
  EXPECT_NE(cut.err.find("'cut.png'"), std::string::npos) << cut.err;

  // Usage errors: status 2 before any work.
  for (const std::string& bad :
       {std::string("--aov depth --crc"), std::string("--aov id --reference ref.png"),
        std::string("--reference-update"), std::string("--reference-threshold 101 --ref ref.png"),
        std::string("-o t.gif --turntable 2 --ref ref.png")}) {
    RunResult r = run("render tri.obj " + bad);
    EXPECT_EQ(r.exit_code, 2) << bad << ": " << r.err;
  }
}
