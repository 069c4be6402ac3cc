// End-to-end tests of f3d's names on `tessera render`: --up with any signed axis, the camera's
// azimuth and elevation, --color, the aliases (--bg-color, -x/--axis) that go through the
// same flag table as the rest, so help and "did you mean" know them, and the point and line
// flags (--point-size, --point-sprites, --line-width, on view and bench too).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "decode.h"
#include "run_process.h"
#include "stb_image_write.h"
#include "temp_folder.h"

namespace fs = std::filesystem;
using tessera::test::DecodedPng;
using tessera::test::RunResult;

namespace {

class CliF3d : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = tessera::test::makeTestFolder("tessera_cli_f3d"); }
  void TearDown() override { fs::remove_all(dir_); }

  RunResult run(const std::string& args) {
    return tessera::test::runInFolder(dir_, TESSERA_EXE, args);
  }

  DecodedPng decode(const std::string& name) {
    DecodedPng png;
    EXPECT_TRUE(tessera::test::decodePng((dir_ / name).string(), png)) << name;
    return png;
  }

  fs::path dir_;
};

// An axis-aligned box of half size h around c, its faces using material `mtl`; OBJ indices
// continue from `first` (1-based).
std::string box(std::array<float, 3> c, float h, const std::string& mtl, int first) {
  std::ostringstream o;
  o << "usemtl " << mtl << "\n";
  for (int i = 0; i < 8; ++i)
    o << "v " << c[0] + (i & 1 ? h : -h) << " " << c[1] + (i & 2 ? h : -h) << " "
      << c[2] + (i & 4 ? h : -h) << "\n";
  const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& f : faces)
    o << "f " << first + f[0] << " " << first + f[1] << " " << first + f[2] << " " << first + f[3]
      << "\n";
  return o.str();
}

constexpr const char* kMtl = "newmtl red\nKd 1 0 0\nnewmtl blue\nKd 0 0 1\n";

// The mean row of the pixels that are mostly `channel` (0 red, 2 blue); -1 when none is.
double meanRow(const DecodedPng& png, int channel, int* count) {
  double sum = 0;
  *count = 0;
  for (int y = 0; y < png.height; ++y)
    for (int x = 0; x < png.width; ++x)
      if (png.at(x, y, channel) > 128 && png.at(x, y, 2 - channel) < 64 && png.at(x, y, 1) < 64) {
        sum += y;
        ++*count;
      }
  return *count ? sum / *count : -1.0;
}

// For each signed axis, a red box at its + end and a blue one at its - end: with --up set to
// that axis the red box (the model's top) is above the blue one in the image.
TEST_F(CliF3d, UpAcceptsEverySignedAxisAndPutsTheTopAtTheTop) {
  tessera::test::writeFile(dir_ / "m.mtl", kMtl);
  const char* axes[] = {"+X", "-X", "+Y", "-Y", "+Z", "-Z"};
  for (const char* axis : axes) {
    const int a = axis[1] - 'X';
    const float sign = axis[0] == '+' ? 1.0f : -1.0f;
    std::array<float, 3> top{0, 0, 0}, bottom{0, 0, 0};
    top[a] = sign;
    bottom[a] = -sign;
    const std::string name = std::string("up") + (sign > 0 ? "p" : "m") + axis[1];
    tessera::test::writeFile(dir_ / (name + ".obj"), "mtllib m.mtl\n" + box(top, 0.3f, "red", 1) +
                                                         box(bottom, 0.3f, "blue", 9));
    RunResult r =
        run("render " + name + ".obj --up=" + axis +
            " --shading unlit --background-color 0,0,0 --resolution 60,60 -o " + name + ".png");
    ASSERT_EQ(r.exit_code, 0) << axis << ": " << r.err;
    const DecodedPng png = decode(name + ".png");
    int reds = 0, blues = 0;
    const double red_row = meanRow(png, 0, &reds), blue_row = meanRow(png, 2, &blues);
    ASSERT_GT(reds, 20) << axis;
    ASSERT_GT(blues, 20) << axis;
    EXPECT_LT(red_row + 10, blue_row) << axis << ": the top box is not above the bottom one";
  }
  RunResult r = run("render upmX.obj --up Y");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("+X|-X|+Y|-Y|+Z|-Z"), std::string::npos) << r.err;
}

// Two boxes that look different from the front (+Z) and from the right (+X).
void writeLModel(const fs::path& dir) {
  tessera::test::writeFile(dir / "m.mtl", kMtl);
  tessera::test::writeFile(dir / "l.obj", "mtllib m.mtl\n" + box({0.8f, 0, 0}, 0.4f, "red", 1) +
                                              box({0, 0.5f, -0.8f}, 0.3f, "blue", 9));
}

// The share of pixels whose triangle id differs between two id AOV images.
double idDifference(const DecodedPng& a, const DecodedPng& b) {
  EXPECT_EQ(a.width, b.width);
  EXPECT_EQ(a.height, b.height);
  int differ = 0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) differ += a.rgb(x, y) != b.rgb(x, y);
  return static_cast<double>(differ) / (a.width * a.height);
}

// f3d's (VTK's) sense: azimuth turns the camera about view up (positive: to its right), so from
// +Z, 90 degrees is the view from +X; elevation raises it towards view up.
TEST_F(CliF3d, AzimuthAndElevationTurnTheCameraAboutTheFocalPoint) {
  writeLModel(dir_);
  const std::string common = "render l.obj --aov id --resolution 64,48 --camera-focal-point 0,0,0 ";
  ASSERT_EQ(run(common + "--camera-position 0,0,5 -o front.png").exit_code, 0);
  RunResult r = run(common + "--camera-position 0,0,5 --camera-azimuth-angle 90 -o az.png");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ASSERT_EQ(run(common + "--camera-position 5,0,0 -o side.png").exit_code, 0);
  const DecodedPng front = decode("front.png"), az = decode("az.png"), side = decode("side.png");
  EXPECT_LT(idDifference(az, side), 0.01);
  EXPECT_GT(idDifference(az, front), 0.05) << "the side view should differ from the front";

  r = run(common + "--camera-position 0,0,5 --camera-elevation-angle=45 -o el.png");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ASSERT_EQ(run(common + "--camera-position 0,3.5355339,3.5355339 -o above.png").exit_code, 0);
  const DecodedPng el = decode("el.png"), above = decode("above.png");
  EXPECT_LT(idDifference(el, above), 0.01);
  EXPECT_GT(idDifference(el, front), 0.05);

  // On the framing camera too: a full turn is where it started, a quarter turn is not.
  ASSERT_EQ(run("render l.obj --aov id --resolution 64,48 -o framed.png").exit_code, 0);
  ASSERT_EQ(run("render l.obj --aov id --resolution 64,48 --camera-azimuth-angle -360 "
                "-o full.png")
                .exit_code,
            0);
  ASSERT_EQ(run("render l.obj --aov id --resolution 64,48 --camera-azimuth-angle 90 "
                "-o quarter.png")
                .exit_code,
            0);
  const DecodedPng framed = decode("framed.png");
  EXPECT_LT(idDifference(decode("full.png"), framed), 0.01);
  EXPECT_GT(idDifference(decode("quarter.png"), framed), 0.05);
}

TEST_F(CliF3d, ColorPaintsTheDefaultMaterialOnly) {
  tessera::test::writeFile(dir_ / "quad.obj",
                           "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3 4\n");
  RunResult r =
      run("render quad.obj --shading unlit --resolution 20,20 --color 0,1,0 -o green.png");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(decode("green.png").rgb(10, 10), (std::array<int, 3>{0, 255, 0}));
  ASSERT_EQ(run("render quad.obj --shading unlit --resolution 20,20 -o grey.png").exit_code, 0);
  EXPECT_NE(decode("grey.png").rgb(10, 10), (std::array<int, 3>{0, 255, 0}));
  // A file's own material keeps its colour, and the warning says --color did nothing.
  writeLModel(dir_);
  r = run("render l.obj --shading unlit --resolution 20,20 --color 0,1,0 -o own.png");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("--color"), std::string::npos) << r.err;
  const DecodedPng own = decode("own.png");
  for (int y = 0; y < own.height; ++y)
    for (int x = 0; x < own.width; ++x) EXPECT_LT(own.at(x, y, 1), 128) << x << "," << y;
  EXPECT_EQ(run("render quad.obj --color 0,2,0").exit_code, 2);
}

TEST_F(CliF3d, AliasesShareTheFlagTable) {
  tessera::test::writeFile(dir_ / "quad.obj",
                           "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3 4\n");
  RunResult r = run("render quad.obj --resolution 20,20 --bg-color 1,0,0 -o bg.png");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(decode("bg.png").rgb(0, 0), (std::array<int, 3>{255, 0, 0}));
  // -x, --axis and --axes draw the same axes.
  ASSERT_EQ(run("render quad.obj --resolution 40,30 --axes -o axes.png").exit_code, 0);
  ASSERT_EQ(run("render quad.obj --resolution 40,30 -x -o x.png").exit_code, 0);
  ASSERT_EQ(run("render quad.obj --resolution 40,30 --axis -o axis.png").exit_code, 0);
  ASSERT_EQ(run("render quad.obj --resolution 40,30 -o none.png").exit_code, 0);
  EXPECT_EQ(tessera::test::slurp(dir_ / "axes.png"), tessera::test::slurp(dir_ / "x.png"));
  EXPECT_EQ(tessera::test::slurp(dir_ / "axes.png"), tessera::test::slurp(dir_ / "axis.png"));
  EXPECT_NE(tessera::test::slurp(dir_ / "axes.png"), tessera::test::slurp(dir_ / "none.png"));
  // Help lists the aliases and a typo of one is answered with it.
  r = run("render --help");
  for (const char* name : {"--bg-color", "--axis", "-x", "--camera-azimuth-angle",
                           "--camera-elevation-angle", "--color", "--duration", "--quiet",
                           "--progress", "--ref", "--texture-base-color", "--edges, -e"})
    EXPECT_NE(r.out.find(name), std::string::npos) << name;
  r = run("render quad.obj --bg-colr 1,0,0");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("did you mean '--bg-color'"), std::string::npos) << r.err;
  r = run("render quad.obj --camera-azimut-angle 10");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("did you mean '--camera-azimuth-angle'"), std::string::npos) << r.err;
}

// --no-background: an RGBA PNG, transparent where the model is not, opaque where it is, and
// straight (not premultiplied) colour at its anti-aliased edge; refused for GIF and for AOVs.
TEST_F(CliF3d, NoBackgroundWritesAnRgbaPngWithTheModelsCoverage) {
  tessera::test::writeFile(dir_ / "tri.obj", "v -1 -1 0\nv 1 -1 0\nv 0 1 0\nf 1 2 3\n");
  RunResult r =
      run("render tri.obj --shading unlit --color 1,1,1 --resolution 48,48 "
          "--no-background -o clear.png");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const DecodedPng png = decode("clear.png");
  ASSERT_EQ(png.channels, 4);
  EXPECT_EQ(png.rgba(0, 0), (std::array<int, 4>{0, 0, 0, 0}));
  EXPECT_EQ(png.rgba(24, 30), (std::array<int, 4>{255, 255, 255, 255}));
  int partial = 0;
  for (int y = 0; y < png.height; ++y)
    for (int x = 0; x < png.width; ++x) {
      const int a = png.at(x, y, 3);
      if (a == 0 || a == 255) continue;
      ++partial;
      EXPECT_GE(png.at(x, y, 0), 250) << x << "," << y << ": the edge is premultiplied";
    }
  EXPECT_GT(partial, 10) << "no anti-aliased edge";
  // The same without the flag: an opaque RGB PNG.
  ASSERT_EQ(run("render tri.obj --resolution 48,48 -o opaque.png").exit_code, 0);
  EXPECT_EQ(decode("opaque.png").channels, 3);
  r = run("render tri.obj --no-background --turntable 3 -o spin.gif");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("alpha"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "spin.gif"));
  EXPECT_EQ(run("render tri.obj --no-background --aov depth -o d.png").exit_code, 2);
}

TEST_F(CliF3d, OpacityMixesTheModelWithTheBackground) {
  tessera::test::writeFile(dir_ / "quad.obj",
                           "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3 4\n");
  const std::string common =
      "render quad.obj --shading unlit --color 1,1,1 --bg-color 0,0,0 "
      "--resolution 20,20 ";
  ASSERT_EQ(run(common + "--opacity 0.5 -o half.png").exit_code, 0);
  EXPECT_EQ(decode("half.png").rgb(10, 10), (std::array<int, 3>{188, 188, 188}));  // linear 0.5
  ASSERT_EQ(run(common + "--opacity 0 -o none.png").exit_code, 0);
  EXPECT_EQ(decode("none.png").rgb(10, 10), (std::array<int, 3>{0, 0, 0}));
  EXPECT_EQ(run(common + "--opacity 1.5 -o bad.png").exit_code, 2);
}

// --hdri and --hdri-background: a sky (blue above the horizon, green below) behind a small white
// triangle; the flags' refusals leave no file.
TEST_F(CliF3d, HdriBackgroundShowsTheSkyAboveAndTheGroundBelow) {
  tessera::test::writeFile(dir_ / "tri.obj", "v -1 -1 0\nv 1 -1 0\nv 0 1 0\nf 1 2 3\n");
  std::vector<float> rgb;
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 32; ++x)
      for (float v : {0.0f, y < 8 ? 0.0f : 1.0f, y < 8 ? 1.0f : 0.0f}) rgb.push_back(v);
  ASSERT_NE(stbi_write_hdr((dir_ / "sky.hdr").string().c_str(), 32, 16, 3, rgb.data()), 0);
  RunResult r =
      run("render tri.obj --resolution 64,64 --camera-position 0,0,6 --camera-focal-point 0,0,0 "
          "--camera-view-angle 60 --hdri sky.hdr --hdri-background -o sky.png");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const DecodedPng png = decode("sky.png");
  EXPECT_EQ(png.rgb(2, 1), (std::array<int, 3>{0, 0, 255}));   // up: the sky
  EXPECT_EQ(png.rgb(2, 62), (std::array<int, 3>{0, 255, 0}));  // down: the ground
  // The same with +Z up: the sky turns with the model.
  ASSERT_EQ(run("render tri.obj --up +Z --resolution 64,64 --camera-position 0,-6,0 "
                "--camera-focal-point 0,0,0 --camera-view-angle 60 --hdri sky.hdr --hdri-skybox "
                "-o z.png")
                .exit_code,
            0);
  EXPECT_EQ(decode("z.png").rgb(2, 1), (std::array<int, 3>{0, 0, 255}));
  EXPECT_EQ(decode("z.png").rgb(2, 62), (std::array<int, 3>{0, 255, 0}));
  // Without --hdri-background the image lights but is not seen.
  ASSERT_EQ(
      run("render tri.obj --resolution 64,64 --bg-color 1,0,0 --hdri sky.hdr -o lit.png").exit_code,
      0);
  EXPECT_EQ(decode("lit.png").rgb(2, 1), (std::array<int, 3>{255, 0, 0}));
  r = run("render tri.obj --hdri-background -o a.png");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--hdri PATH"), std::string::npos) << r.err;
  EXPECT_EQ(
      run("render tri.obj --hdri sky.hdr --hdri-background --no-background -o b.png").exit_code, 2);
  tessera::test::writeFile(dir_ / "fake.hdr", "not an image");
  r = run("render tri.obj --hdri fake.hdr -o c.png");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("not a Radiance .hdr"), std::string::npos) << r.err;
  EXPECT_EQ(run("render tri.obj --hdri missing.hdr -o d.png").exit_code, 1);
  for (const char* name : {"a.png", "b.png", "c.png", "d.png"})
    EXPECT_FALSE(fs::exists(dir_ / name));
}

// --exposure and --tone-mapping: on the shaded model and on the --hdri sky, not on the plain
// background; bad values are a usage error and leave no file.
TEST_F(CliF3d, ExposureAndToneMappingActOnTheModelAndTheSky) {
  tessera::test::writeFile(dir_ / "tri.obj", "v -1 -1 0\nv 1 -1 0\nv 0 1 0\nf 1 2 3\n");
  std::vector<float> rgb;
  for (int i = 0; i < 32 * 16; ++i)
    for (float v : {0.0f, 0.0f, 1.0f}) rgb.push_back(v);
  ASSERT_NE(stbi_write_hdr((dir_ / "blue.hdr").string().c_str(), 32, 16, 3, rgb.data()), 0);
  const std::string common =
      "render tri.obj --shading unlit --color 1,1,1 --resolution 64,64 --camera-position 0,0,4 "
      "--camera-focal-point 0,0,0 --camera-view-angle 60 ";
  RunResult r = run(common + "--hdri blue.hdr --hdri-background --exposure -1 -o dim.png");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const DecodedPng dim = decode("dim.png");
  EXPECT_EQ(dim.rgb(2, 1), (std::array<int, 3>{0, 0, 188}));  // linear 0.5
  EXPECT_EQ(dim.rgb(32, 36), (std::array<int, 3>{188, 188, 188}));
  // Khronos PBR Neutral takes white (1.0) to 0.869 (sRGB 240) and keeps it grey.
  ASSERT_EQ(run(common + "--bg-color 0,0,1 --tone-mapping pbr-neutral -o neutral.png").exit_code,
            0);
  const DecodedPng neutral = decode("neutral.png");
  EXPECT_EQ(neutral.rgb(32, 36), (std::array<int, 3>{240, 240, 240}));
  EXPECT_EQ(neutral.rgb(2, 1), (std::array<int, 3>{0, 0, 255}));  // the background as given
  for (const char* bad : {"--tone-mapping filmic", "--tone-mapping", "--exposure nan",
                          "--exposure 21", "--exposure bright"}) {
    r = run(common + bad + " -o bad.png");
    EXPECT_EQ(r.exit_code, 2) << bad;
    EXPECT_NE(r.err.find(std::string(bad).substr(0, std::string(bad).find(' '))), std::string::npos)
        << r.err;
  }
  EXPECT_FALSE(fs::exists(dir_ / "bad.png"));
}

// --grid: lines under the model, across the up axis; seen below a model viewed from above.
TEST_F(CliF3d, GridDrawsAGroundUnderTheModel) {
  tessera::test::writeFile(dir_ / "m.mtl", kMtl);
  tessera::test::writeFile(dir_ / "box.obj", "mtllib m.mtl\n" + box({0, 0.3f, 0}, 0.3f, "red", 1));
  const std::string common = "render box.obj --shading unlit --bg-color 0,0,0 --resolution 80,60 ";
  ASSERT_EQ(run(common + "-o plain.png").exit_code, 0);
  RunResult r = run(common + "--grid -o grid.png");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const DecodedPng plain = decode("plain.png"), grid = decode("grid.png");
  int lit = 0, reds = 0, red_changed = 0;
  for (int y = 0; y < grid.height; ++y)
    for (int x = 0; x < grid.width; ++x) {
      const bool red = plain.at(x, y, 0) > 128 && plain.at(x, y, 1) < 64;
      reds += red;
      if (red) red_changed += grid.rgb(x, y) != plain.rgb(x, y);
      lit += !red && plain.rgb(x, y) == (std::array<int, 3>{0, 0, 0}) &&
             grid.rgb(x, y) != plain.rgb(x, y);
    }
  EXPECT_GT(lit, 100) << "no grid drawn on the background";
  // (A pixel at the box's anti-aliased edge whose centre is the background may take a line.)
  ASSERT_GT(reds, 200);
  EXPECT_LT(red_changed * 20, reds) << "the grid shows through the box, which stands on it";
}

TEST_F(CliF3d, PointAndLineFlagsOnRenderViewAndBench) {
  tessera::test::writeFile(dir_ / "quad.obj",
                           "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3 4\n");
  RunResult r =
      run("render quad.obj --resolution 20,20 --point-size 4.5 --point-sprites --line-width=2 "
          "-o p.png");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* command : {"render", "view", "bench"}) {
    r = run(std::string(command) + " --help");
    for (const char* name : {"--point-size PIXELS", "--point-sprites", "--line-width PIXELS"})
      EXPECT_NE(r.out.find(name), std::string::npos) << command << " " << name;
    // 0, below 0, above 64, NaN and words: one line saying what is wrong, exit 2.
    for (const char* flag : {"--point-size", "--line-width"}) {
      for (const char* bad : {"0", "-1", "65", "nan", "wide"}) {
        r = run(std::string(command) + " quad.obj " + flag + " " + bad);
        EXPECT_EQ(r.exit_code, 2) << command << " " << flag << " " << bad;
        const std::string first_line = r.err.substr(0, r.err.find('\n'));
        EXPECT_NE(first_line.find(std::string("flag '") + flag + "'"), std::string::npos) << r.err;
        EXPECT_NE(first_line.find("above 0 and up to 64, not '" + std::string(bad) + "'"),
                  std::string::npos)
            << r.err;
      }
    }
  }
}

}  // namespace
