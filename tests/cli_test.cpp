// End-to-end tests of the tessera executable: real processes, real files, decoded back. This
// file: the cube demo, the flags and help, errors, MSAA and projections; render's outputs are
// cli_render_test.cpp's.
#include "cli_test_fixture.h"

TEST_F(Cli, CubeWithNoFlagsWritesTheDefaultGif) {
  RunResult r = run("cube");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  DecodedGif gif;
  ASSERT_TRUE(tessera::test::decodeGif((dir_ / "cube.gif").string(), gif));
  EXPECT_EQ(gif.width, 480);
  EXPECT_EQ(gif.height, 480);
  ASSERT_EQ(gif.frames_rgb.size(), 120u);  // 4 s at 30 fps
  EXPECT_TRUE(gif.loops);
  int total = 0;
  for (size_t i = 0; i < gif.delays_cs.size(); ++i) {
    EXPECT_EQ(gif.delays_cs[i], i % 3 == 2 ? 4 : 3) << "frame " << i;
    total += gif.delays_cs[i];
  }
  EXPECT_EQ(total, 400);  // exactly the duration
  // The cube covers a sensible share of every frame: not empty, not the whole frame.
  const uint32_t background = gif.frames_rgb[0][0];
  std::vector<uint32_t> previous;
  for (const auto& frame : gif.frames_rgb) {
    int cube = 0;
    for (uint32_t c : frame) {
      int dr = std::abs(static_cast<int>(c >> 16) - static_cast<int>(background >> 16));
      int dg =
          std::abs(static_cast<int>((c >> 8) & 255) - static_cast<int>((background >> 8) & 255));
      int db = std::abs(static_cast<int>(c & 255) - static_cast<int>(background & 255));
      cube += dr + dg + db > 24;
    }
    double share = static_cast<double>(cube) / (480.0 * 480.0);
    EXPECT_GT(share, 0.08);
    EXPECT_LT(share, 0.6);
    EXPECT_NE(frame, previous);  // it turns
    previous = frame;
  }
}

TEST_F(Cli, CubeFlagsSetSizeFramesAndOutput) {
  RunResult r = run("cube -w 64 -h 48 -fps 10 -dur 1.5s -fov 60 -out small.gif -workers 2 -axes");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  DecodedGif gif;
  ASSERT_TRUE(tessera::test::decodeGif((dir_ / "small.gif").string(), gif));
  EXPECT_EQ(gif.width, 64);
  EXPECT_EQ(gif.height, 48);
  EXPECT_EQ(gif.frames_rgb.size(), 15u);
  int total = 0;
  for (int d : gif.delays_cs) total += d;
  EXPECT_EQ(total, 150);
  EXPECT_FALSE(fs::exists(dir_ / "cube.gif"));
}

TEST_F(Cli, CubeFramesAreIdenticalForAnyWorkerCount) {
  for (int workers : {1, 2, 7}) {
    std::string args = "cube -w 96 -h 80 -fps 4 -dur 1s -axes -workers " + std::to_string(workers) +
                       " -out w" + std::to_string(workers) + "_{frame}.png";
    RunResult r = run(args);
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  for (int frame = 0; frame < 4; ++frame) {
    char name[32];
    std::snprintf(name, sizeof name, "_%04d.png", frame);
    std::string one = slurp(dir_ / ("w1" + std::string(name)));
    ASSERT_FALSE(one.empty());
    EXPECT_EQ(one, slurp(dir_ / ("w2" + std::string(name))));
    EXPECT_EQ(one, slurp(dir_ / ("w7" + std::string(name))));
  }
}

TEST_F(Cli, BadFlagsPointToHelpAndExitTwo) {
  for (const char* args :
       {"cube -w abc", "cube --bogus", "cube -w", "cube -fps 0", "cube -dur -3s", "cube extra",
        "render", "render a.obj b.obj", "render m.obj --resolution 10", "render m.obj --aov rgb",
        "render m.obj --camera-position 1,2", "render m.obj -o out.bmp", "frobnicate"}) {
    RunResult r = run(args);
    EXPECT_EQ(r.exit_code, 2) << args;
    // The error and one line pointing to --help, not a screenful of usage.
    EXPECT_NE(r.err.find("--help"), std::string::npos) << args << ": " << r.err;
    EXPECT_EQ(r.err.find("usage"), std::string::npos) << args << ": " << r.err;
    EXPECT_LE(std::count(r.err.begin(), r.err.end(), '\n'), 2) << args << ": " << r.err;
  }
  EXPECT_TRUE(filesInDir().empty());
}

// The traps of issue 20: -h is help (a number after it is the seed demo's height), --version
// everywhere, WxH sizes, a typo gets a suggestion, missing output folders are made.
TEST_F(Cli, OneGrammarForEveryCommand) {
  for (const char* args :
       {"cube -h", "view -h", "render -h", "bench -h", "info -h", "cube --help"}) {
    RunResult r = run(args);
    EXPECT_EQ(r.exit_code, 0) << args << ": " << r.err;
    EXPECT_NE(r.out.find("usage: tessera"), std::string::npos) << args;
  }
  for (const char* args : {"--version", "render --version", "cube --version", "view --version"}) {
    RunResult r = run(args);
    EXPECT_EQ(r.exit_code, 0) << args;
    EXPECT_EQ(r.out.rfind("tessera ", 0), 0u) << args << ": " << r.out;
  }
  RunResult r = run("render quad.obj --resoltion 640x480");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("did you mean '--resolution'?"), std::string::npos) << r.err;
  r = run("rendr quad.obj");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("did you mean 'render'?"), std::string::npos) << r.err;

  writeQuadObj("quad.obj");
  r = run("render quad.obj --resolution 24x16 -o sizes/wxh.png");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  DecodedPng png;
  ASSERT_TRUE(tessera::test::decodePng((dir_ / "sizes" / "wxh.png").string(), png));
  EXPECT_EQ(png.width, 24);
  EXPECT_EQ(png.height, 16);
  // -h followed by a number is the cube's height; --name=value works as well.
  r = run("cube -w 20 -h 12 --duration=0.1s --output=deep/er/one_{frame}.png");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ASSERT_TRUE(tessera::test::decodePng((dir_ / "deep/er/one_0000.png").string(), png));
  EXPECT_EQ(png.height, 12);
  // A single .png is the turn's first frame.
  r = run("cube -w 20 -h 12 -out still.png");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ASSERT_TRUE(tessera::test::decodePng((dir_ / "still.png").string(), png));
  EXPECT_EQ(png.width, 20);
}

// README's own commands, exactly as written there.
TEST_F(Cli, ReadmeCubeCommandsRun) {
  RunResult r = run("cube -out frames/cube_{frame}.png");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir_ / "frames" / "cube_0000.png"));
  EXPECT_TRUE(fs::exists(dir_ / "frames" / "cube_0119.png"));
  r = run("cube -w 320 -h 240 -fps 25 -dur 2s -axes -out small.gif");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir_ / "small.gif"));
}

TEST_F(Cli, HelpExitsZeroAndListsTheFlags) {
  RunResult r = run("cube --help");
  EXPECT_EQ(r.exit_code, 0);
  for (const char* flag : {"-w", "-h", "-fps", "-dur", "-fov", "-out", "-workers", "-axes"})
    EXPECT_NE(r.out.find(flag), std::string::npos) << flag;
  r = run("render --help");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("--camera-position"), std::string::npos);
}

TEST_F(Cli, UnwritableOutputFailsCleanly) {
  // A missing folder is made; one that cannot be (a file in the way) is named.
  writeFile("blocker", "a file, not a folder");
  RunResult r = run("cube -w 32 -h 32 -dur 0.2s -out blocker/x/cube.gif");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("cannot create the folder 'blocker/x'"), std::string::npos) << r.err;
  EXPECT_EQ(filesInDir(), std::set<std::string>{"blocker"});
  writeQuadObj("quad.obj");
  fs::create_directories(dir_ / "locked");
  fs::permissions(dir_ / "locked", fs::perms::owner_read | fs::perms::owner_exec);
  r = run("render quad.obj --resolution 16,16 -o locked/out.png");
  // Root may write anywhere: then the file must simply be complete.
  if (::geteuid() != 0) {
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_TRUE(fs::is_empty(dir_ / "locked"));
  }
  fs::permissions(dir_ / "locked", fs::perms::owner_all);
}

TEST_F(Cli, MissingOrBrokenModelNamesTheFileAndExitsOne) {
  RunResult r = run("render missing.obj");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("missing.obj"), std::string::npos) << r.err;
  writeFile("broken.obj", "v 0 0 0\nv 1 0 0\nf 1 2 7\n");
  r = run("render broken.obj -o broken.png");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("broken.obj"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "broken.png"));
}

TEST_F(Cli, SampleCountsOutsideTheAllowedOnesAreUsageErrors) {
  writeQuadObj("quad.obj");
  for (const std::string& args :
       {std::string("render quad.obj -o out.png --msaa 3"),
        std::string("render quad.obj -o out.png --msaa 16"),
        std::string("render quad.obj -o out.png --samples 0"),
        std::string("cube -out out.gif -msaa 3"), std::string("cube -out out.gif -samples 0")}) {
    SCOPED_TRACE(args);
    RunResult r = run(args);
    EXPECT_EQ(r.exit_code, 2);
    const bool names_values = r.err.find("1, 2, 4 or 8") != std::string::npos ||
                              r.err.find("1 to 4096") != std::string::npos;
    EXPECT_TRUE(names_values) << r.err;
    EXPECT_EQ(filesInDir(), (std::set<std::string>{"quad.obj"}));
  }
}

TEST_F(Cli, MsaaSmoothsEdgesAndLeavesTheIdAovAlone) {
  // A quad seen at an angle: its slanted edges get in-between colours with --msaa 4 (the default)
  // and none with --msaa 1; the id AOV is the same at any sample count; the coverage AOV is grey
  // in [0, 255] with in-between values at the edges only.
  writeQuadObj("quad.obj");
  const std::string view =
      " --resolution 64,48 --background-color 0,0,0 --shading unlit "
      "--camera-position 1.3,0.4,3 --camera-focal-point 0,0,0";
  auto distinct = [](const DecodedPng& png) {
    std::set<int> values;
    for (int y = 0; y < png.height; ++y)
      for (int x = 0; x < png.width; ++x) values.insert(png.at(x, y, 0));
    return values.size();
  };
  DecodedPng one, four, id1, id8, coverage;
  ASSERT_EQ(run("render quad.obj -o one.png --msaa 1" + view).exit_code, 0);
  ASSERT_EQ(run("render quad.obj -o four.png" + view).exit_code, 0);
  ASSERT_EQ(run("render quad.obj -o id1.png --aov id --msaa 1" + view).exit_code, 0);
  ASSERT_EQ(run("render quad.obj -o id8.png --aov id --msaa 8 --samples 4" + view).exit_code, 0);
  ASSERT_EQ(run("render quad.obj -o cov.png --aov coverage --msaa 4" + view).exit_code, 0);
  ASSERT_TRUE(tessera::test::decodePng((dir_ / "one.png").string(), one));
  ASSERT_TRUE(tessera::test::decodePng((dir_ / "four.png").string(), four));
  ASSERT_TRUE(tessera::test::decodePng((dir_ / "id1.png").string(), id1));
  ASSERT_TRUE(tessera::test::decodePng((dir_ / "id8.png").string(), id8));
  ASSERT_TRUE(tessera::test::decodePng((dir_ / "cov.png").string(), coverage));
  EXPECT_EQ(distinct(one), 2u);  // the quad's colour and the background
  EXPECT_GT(distinct(four), 3u);
  EXPECT_EQ(id1.samples, id8.samples);
  ASSERT_EQ(coverage.channels, 1);
  EXPECT_EQ(coverage.bit_depth, 8);
  int partial = 0, full = 0;
  for (int y = 0; y < coverage.height; ++y)
    for (int x = 0; x < coverage.width; ++x) {
      const int c = coverage.at(x, y, 0);
      partial += c != 0 && c != 255;
      full += c == 255;
      // At the same sample count, fully covered pixels are the quad's colour, uncovered ones the
      // background.
      if (c == 255 || c == 0) {
        EXPECT_EQ(four.at(x, y, 0), c == 0 ? 0 : one.at(x, y, 0)) << x << "," << y;
      }
    }
  EXPECT_GT(partial, 20);
  EXPECT_GT(full, 200);
}

TEST_F(Cli, ProjectionsRenderAndRefuseViewAnglesOutOfTheirRange) {
  writeQuadObj("quad.obj");
  // A panorama of the quad from the default framing: the quad in the middle, background at the
  // seam; the id and depth AOVs come out too.
  for (const std::string mode : {"cylindrical", "spherical", "stereographic", "fisheye"}) {
    SCOPED_TRACE(mode);
    RunResult r = run("render quad.obj --resolution 64,32 --background-color 1,0,0 --projection " +
                      mode + " -o " + mode + ".png");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    DecodedPng png;
    ASSERT_TRUE(tessera::test::decodePng((dir_ / (mode + ".png")).string(), png));
    EXPECT_FALSE(png.at(32, 16, 0) == 255 && png.at(32, 16, 1) == 0);  // the quad
    EXPECT_TRUE(png.at(1, 16, 0) == 255 && png.at(1, 16, 1) == 0);     // the background
    ASSERT_EQ(run("render quad.obj --resolution 64,32 --aov id -o id_" + mode + ".png" +
                  " --projection " + mode)
                  .exit_code,
              0);
  }
  for (const std::string& args :
       {std::string("render quad.obj -o out.png --projection fisheye --camera-view-angle 400"),
        std::string("render quad.obj -o out.png --projection perspective --camera-view-angle 180"),
        std::string("render quad.obj -o out.png --projection spherical --camera-view-angle 180 "
                    "--resolution 400,150"),
        std::string("render quad.obj -o out.png --projection hyperbolic"),
        std::string("cube -out out.gif -projection fisheye -fov 361"),
        std::string("bench cube --projection spherical --vs llvmpipe --frames 1"),
        std::string("bench bunny --projection fisheye --camera-view-angle 400 --frames 1")}) {
    SCOPED_TRACE(args);
    RunResult r = run(args);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    const bool names_range = r.err.find("360") != std::string::npos ||
                             r.err.find("180") != std::string::npos ||
                             r.err.find("fisheye") != std::string::npos ||
                             r.err.find("perspective projection only") != std::string::npos;
    EXPECT_TRUE(names_range) << r.err;
  }
  EXPECT_FALSE(fs::exists(dir_ / "out.png"));
  EXPECT_FALSE(fs::exists(dir_ / "out.gif"));
}

TEST_F(Cli, EverySimdLevelDrawsTheSameImageAndTheBenchSaysWhichRan) {
  // A bumpy grid of small triangles, drawn with 4x MSAA (render's default) on every kernel this
  // CPU runs: the PNGs must be the same bytes. A level the CPU cannot run is an error (exit 1,
  // nothing written), never a quiet fallback.
  std::ostringstream obj;
  const int n = 12;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i)
      obj << "v " << i - n / 2 << " " << j - n / 2 << " " << ((i * 7 + j * 3) % 5) * 0.3 << "\n";
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i + 1, b = a + 1, c = a + n + 1, d = c + 1;
      obj << "f " << a << " " << b << " " << d << "\nf " << a << " " << d << " " << c << "\n";
    }
  writeFile("grid.obj", obj.str());
  std::string scalar;
  int drawn = 0;
  for (const std::string level : {"scalar", "sse2", "avx2", "avx512", "auto"}) {
    SCOPED_TRACE(level);
    const std::string out = level + ".png";
    RunResult r = run("render grid.obj --resolution 96,80 --simd " + level + " -o " + out);
    if (r.exit_code == 1) {
      EXPECT_NE(r.err.find("cannot run those kernels"), std::string::npos) << r.err;
      EXPECT_FALSE(fs::exists(dir_ / out));
      continue;
    }
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::string image = slurp(dir_ / out);
    ASSERT_FALSE(image.empty());
    if (scalar.empty()) scalar = image;
    EXPECT_EQ(image, scalar);
    ++drawn;
  }
  EXPECT_GE(drawn, 3);  // scalar, sse2 and auto run on any x86-64
  RunResult bench = run("bench cube --simd scalar --json --frames 1 --warmup 0 --resolution 32,32");
  ASSERT_EQ(bench.exit_code, 0) << bench.err;
  EXPECT_NE(bench.out.find("\"simd\": \"scalar\""), std::string::npos) << bench.out;
  for (const std::string& args : {std::string("render grid.obj -o bad.png --simd avx3"),
                                  std::string("render grid.obj -o bad.png --simd sse2 "
                                              "--backend vulkan"),
                                  std::string("bench cube --simd sse2 --backend vulkan")}) {
    SCOPED_TRACE(args);
    EXPECT_EQ(run(args).exit_code, 2);
    EXPECT_FALSE(fs::exists(dir_ / "bad.png"));
  }
}
