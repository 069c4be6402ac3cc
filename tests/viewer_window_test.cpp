// The real `tessera view` window under Xvfb, driven by real X input (xdotool sends XTEST
// pointer and key events); every picture checked is a screenshot the viewer saved on F12 from the
// renderer's own pixels. Also the failures that need no display: no display, a bad SDL driver,
// a missing model.
#include "viewer_window.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <array>
#include <fstream>
#include <map>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include <tessera/io/image_writer.h>

#include "x11_client.h"

namespace {

using namespace tessera::test;

TEST_F(ViewerWindow, ShowsTheCubeReactsToInputResizesAndQuitsOnEscape) {
  std::string why;
  if (!startX(why)) GTEST_SKIP() << why;
  startViewer({"-w", "320", "-h", "240", "-workers", "2"});
  ASSERT_TRUE(viewer_->waitForLine("tessera view: showing cube"))
      << viewer_->output() << slurp(dir_ / "viewer.err");
  const std::string window = findWindow();
  ASSERT_FALSE(window.empty()) << "no visible 'tessera view' window";
  // Keys go to the window under the pointer (there is no window manager to give focus).
  xdotool({"mousemove", "--window", window, "160", "120"});

  // It opens and shows the model: the cube covers a sensible share of the picture.
  const DecodedPng first = screenshot();
  ASSERT_EQ(first.width, 320);
  ASSERT_EQ(first.height, 240);
  const Rgb background = pixel(first, 2, 2);
  EXPECT_TRUE(near(background, {51, 51, 51}, 2)) << background.r << "," << background.g;
  const Coverage framed = coverage(first, background);
  EXPECT_GT(framed.share, 0.15);
  EXPECT_LT(framed.share, 0.85);
  // The cube is orange: more red than blue at the centre.
  const Rgb centre = pixel(first, 160, 120);
  EXPECT_GT(centre.r, centre.b + 60);

  // A left drag orbits: the picture changes.
  xdotool({"mousemove", "--window", window, "120", "120", "mousedown", "1", "mousemove", "--window",
           window, "150", "130", "mousemove", "--window", window, "200", "150", "mouseup", "1"});
  const DecodedPng dragged = screenshot();
  ASSERT_EQ(dragged.width, 320);
  EXPECT_GT(countDifferent(first, dragged, 0, 0, 320, 240), 320 * 240 / 20);

  // Enter puts the camera back where it started: the very same picture.
  xdotool({"key", "Return"});
  const DecodedPng reset = screenshot();
  ASSERT_EQ(reset.width, 320);
  EXPECT_EQ(countDifferent(first, reset, 0, 0, 320, 240), 0);

  // F1 shows the stats overlay in the top-left corner and leaves the rest alone...
  xdotool({"key", "F1"});
  const DecodedPng stats = screenshot();
  ASSERT_EQ(stats.width, 320);
  EXPECT_GT(countDifferent(reset, stats, 0, 0, 120, 40), 120 * 40 / 4);
  EXPECT_EQ(countDifferent(reset, stats, 0, 120, 320, 240), 0);
  // ...and F1 again hides it.
  xdotool({"key", "F1"});
  const DecodedPng hidden = screenshot();
  ASSERT_EQ(hidden.width, 320);
  EXPECT_EQ(countDifferent(reset, hidden, 0, 0, 320, 240), 0);

  // Two wheel steps towards the screen zoom in: the cube covers more.
  xdotool({"click", "4"});
  xdotool({"click", "4"});
  const DecodedPng zoomed = screenshot();
  ASSERT_EQ(zoomed.width, 320);
  const Coverage closer = coverage(zoomed, background);
  EXPECT_GT(closer.share, framed.share * 1.15);

  // A middle drag pans: the cube follows the pointer, 40 points right and 20 down.
  xdotool({"mousemove", "--window", window, "100", "100", "mousedown", "2", "mousemove", "--window",
           window, "120", "110", "mousemove", "--window", window, "140", "120", "mouseup", "2"});
  const DecodedPng panned = screenshot();
  ASSERT_EQ(panned.width, 320);
  const Coverage moved = coverage(panned, background);
  EXPECT_NEAR(moved.centre_x - closer.centre_x, 40.0, 8.0);
  EXPECT_NEAR(moved.centre_y - closer.centre_y, 20.0, 8.0);

  // The framebuffer follows the window's size.
  xdotool({"windowsize", window, "400", "300"});
  const DecodedPng resized = screenshot();
  EXPECT_EQ(resized.width, 400);
  EXPECT_EQ(resized.height, 300);

  // Screenshots take the next free number in the working folder.
  EXPECT_TRUE(fs::exists(dir_ / "screenshot-0001.png"));
  EXPECT_TRUE(fs::exists(dir_ / "screenshot-0008.png"));

  xdotool({"key", "Escape"});
  EXPECT_EQ(viewer_->waitExit(), 0) << viewer_->output() << slurp(dir_ / "viewer.err");
}

TEST_F(ViewerWindow, LoadsAModelInTheBackgroundAndKeysChangeTheView) {
  std::string why;
  if (!startX(why)) GTEST_SKIP() << why;
  // A tetrahedron (4 triangles) away from the origin, so that the world axes show beside it.
  std::ofstream(dir_ / "tetra.obj")
      << "v 0.5 0.5 0.5\nv 1.5 0.5 0.5\nv 0.5 1.5 0.5\nv 0.5 0.5 1.5\n"
         "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
  startViewer({"tetra.obj", "-w", "200", "-h", "200", "-workers", "1"});
  ASSERT_TRUE(viewer_->waitForLine("tessera view: showing tetra.obj (4 triangles"))
      << viewer_->output() << slurp(dir_ / "viewer.err");
  const std::string window = findWindow();
  ASSERT_FALSE(window.empty());
  xdotool({"mousemove", "--window", window, "100", "100"});
  const DecodedPng start = screenshot();
  xdotool({"key", "7"});  // the top view
  const DecodedPng top = screenshot();
  ASSERT_EQ(start.width, 200);
  ASSERT_EQ(top.width, 200);
  EXPECT_GT(countDifferent(start, top, 0, 0, 200, 200), 200 * 200 / 50);
  xdotool({"key", "F2"});  // the world axes add coloured lines
  const DecodedPng axes = screenshot();
  ASSERT_EQ(axes.width, 200);
  EXPECT_GT(countDifferent(top, axes, 0, 0, 200, 200), 20);
  xdotool({"key", "Escape"});
  EXPECT_EQ(viewer_->waitExit(), 0);
}

// A tetrahedron away from the origin, for the tests that compare two views of one model.
constexpr const char* kOffsetTetrahedron =
    "v 0.5 0.5 0.5\nv 1.5 0.5 0.5\nv 0.5 1.5 0.5\nv 0.5 0.5 1.5\n"
    "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";

// --grid (f3d's -g): the same model with a ground grid under it; the grid's lines change the
// background around the model's foot.
TEST_F(ViewerWindow, GridDrawsAGroundUnderTheModel) {
  std::string why;
  if (!startX(why)) GTEST_SKIP() << why;
  std::ofstream(dir_ / "tetra.obj") << kOffsetTetrahedron;
  const std::vector<std::string> args{"-w", "200", "-h", "200", "-workers", "1"};
  std::vector<std::string> with_grid = args;
  with_grid.push_back("--grid");
  const DecodedPng shots[2] = {shotOfModel("tetra.obj", args), shotOfModel("tetra.obj", with_grid)};
  ASSERT_EQ(shots[0].width, 200);
  ASSERT_EQ(shots[1].width, 200);
  EXPECT_GT(countDifferent(shots[0], shots[1], 0, 0, 200, 200), 200) << "no grid drawn";
}

// A 32x16 equirectangular Radiance .hdr, flat RGBE scanlines: blue sky above the horizon, green
// ground below.
void writeSkyHdr(const fs::path& path) {
  std::ofstream out(path, std::ios::binary);
  out << "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 16 +X 32\n";
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 32; ++x) {
      const char blue[4] = {0, 0, static_cast<char>(128), static_cast<char>(129)};
      const char green[4] = {0, static_cast<char>(128), 0, static_cast<char>(129)};
      out.write(y < 8 ? blue : green, 4);
    }
}

// --hdri and --hdri-background on the viewer: the sky is seen behind the model from its
// three-quarter view from above (the horizon near the top of the window: blue above it, green
// below).
TEST_F(ViewerWindow, HdriBackgroundShowsTheSkyBehindTheModel) {
  std::string why;
  if (!startX(why)) GTEST_SKIP() << why;
  std::ofstream(dir_ / "tetra.obj") << kOffsetTetrahedron;
  writeSkyHdr(dir_ / "sky.hdr");
  const std::vector<std::string> args{"-w",       "200", "-h",        "200",
                                      "-workers", "1",   "--shading", "pbr"};
  std::vector<std::string> sky = args;
  sky.insert(sky.end(), {"--hdri", "sky.hdr", "--hdri-background"});
  const DecodedPng shots[2] = {shotOfModel("tetra.obj", args), shotOfModel("tetra.obj", sky)};
  ASSERT_EQ(shots[0].width, 200);
  ASSERT_EQ(shots[1].width, 200);
  const std::array<int, 3> top = shots[1].rgb(100, 2), bottom = shots[1].rgb(100, 197);
  EXPECT_GT(top[2], 200) << "not the sky at the top";
  EXPECT_LT(top[0], 30) << "not the sky at the top";
  EXPECT_GT(top[2], top[1]) << "not the sky at the top";
  EXPECT_GT(bottom[1], 200) << "not the ground at the bottom";
  EXPECT_LT(bottom[0] + bottom[2], 60) << "not the ground at the bottom";
  EXPECT_NE(shots[0].rgb(100, 2), top) << "the background was already the sky's";
}

// --exposure and --tone-mapping on the viewer: two stops down darkens the model, not the
// background (a display colour).
TEST_F(ViewerWindow, ExposureDarkensTheModelNotTheBackground) {
  std::string why;
  if (!startX(why)) GTEST_SKIP() << why;
  std::ofstream(dir_ / "tetra.obj") << kOffsetTetrahedron;
  const std::vector<std::string> args{"-w", "200", "-h", "200", "-workers", "1"};
  std::vector<std::string> dimmed = args;
  dimmed.insert(dimmed.end(), {"--exposure", "-2", "--tone-mapping", "pbr-neutral"});
  const DecodedPng shots[2] = {shotOfModel("tetra.obj", args), shotOfModel("tetra.obj", dimmed)};
  ASSERT_EQ(shots[0].width, 200);
  ASSERT_EQ(shots[1].width, 200);
  const std::array<int, 3> background = shots[0].rgb(2, 2);
  EXPECT_EQ(shots[1].rgb(2, 2), background);
  int model = 0, darker = 0;
  for (int y = 0; y < 200; ++y)
    for (int x = 0; x < 200; ++x) {
      if (shots[0].rgb(x, y) == background) continue;
      ++model;
      const auto a = shots[0].rgb(x, y), b = shots[1].rgb(x, y);
      darker += b[0] + b[1] + b[2] < a[0] + a[1] + a[2];
    }
  ASSERT_GT(model, 500) << "the model is not in view";
  EXPECT_GT(darker * 10, model * 9) << "the exposure left the model as it was";
}

TEST_F(ViewerWindow, TheWindowStaysLiveWhileAModelLoads) {
  std::string why;
  if (!startX(why)) GTEST_SKIP() << why;
  std::ofstream(dir_ / "tetra.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
                                       "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
  // The load waits on this file (a test hook of `tessera view`), as a large model would.
  const fs::path hold = dir_ / "hold";
  std::ofstream(hold) << "";
  std::vector<std::string> argv{TESSERA_EXE, "view", "tetra.obj", "-w", "320", "-h", "240"};
  std::map<std::string, std::string> env = viewerEnv();
  env["TESSERA_VIEW_TEST_HOLD_LOADS"] = hold.string();
  viewer_ = std::make_unique<Process>();
  ASSERT_TRUE(viewer_->start(argv, dir_, env, dir_ / "viewer.err"));
  const std::string window = findWindow();
  ASSERT_FALSE(window.empty());
  xdotool({"mousemove", "--window", window, "160", "120"});
  // The window answers keys during the load: F1 brings up the stats, F12 saves what is shown.
  xdotool({"key", "F1"});
  const DecodedPng loading = screenshot();
  ASSERT_EQ(loading.width, 320);
  // "loading tetra.obj... (0.1 s)" in white at the bottom left; the stats in the top left.
  auto whiteIn = [&](const DecodedPng& png, int x0, int y0, int x1, int y1) {
    int count = 0;
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x)
        if (near(pixel(png, x, y), {255, 255, 255}, 40)) ++count;
    return count;
  };
  EXPECT_GT(whiteIn(loading, 0, 200, 320, 240), 30);
  EXPECT_GT(whiteIn(loading, 0, 0, 200, 40), 30);
  EXPECT_FALSE(viewer_->waitForLineNow("tessera view: showing"));
  fs::remove(hold);
  ASSERT_TRUE(viewer_->waitForLine("tessera view: showing tetra.obj (4 triangles"))
      << viewer_->output() << slurp(dir_ / "viewer.err");
  // The close button (what a window manager sends for it) quits with status 0 too.
  EXPECT_EQ(tessera::test::requestClose(display_, std::stoul(window)), "");
  EXPECT_EQ(viewer_->waitExit(), 0);
}

// The window appears once, under the id it keeps: SDL makes an OpenGL renderer's window again,
// and a window shown before that flickers, and leaves a stale id to whoever found it first (this
// file's TheWindowStaysLiveWhileAModelLoads once failed on one).
TEST_F(ViewerWindow, TheWindowIsShownOnceUnderTheIdItKeeps) {
  std::string why;
  if (!startX(why)) GTEST_SKIP() << why;
  MappedWindows watcher(display_);
  ASSERT_TRUE(watcher.watching());
  ASSERT_TRUE(openCube({}, 200, 150));
  const std::vector<unsigned long> shown = watcher.mapped();
  EXPECT_EQ(shown, std::vector<unsigned long>{std::stoul(window_)})
      << shown.size() << " windows were shown";
  quit();
}

TEST_F(ViewerWindow, AModelThatFailsToLoadShowsTheCubeAndTheError) {
  std::string why;
  if (!startX(why)) GTEST_SKIP() << why;
  std::ofstream(dir_ / "broken.obj") << "v 0 0 0\nf 1 2 9\n";
  startViewer({"broken.obj", "-w", "320", "-h", "240", "-workers", "1"});
  ASSERT_TRUE(viewer_->waitForLine("tessera view: showing cube"))
      << viewer_->output() << slurp(dir_ / "viewer.err");
  EXPECT_NE(slurp(dir_ / "viewer.err").find("broken.obj"), std::string::npos);
  const std::string window = findWindow();
  ASSERT_FALSE(window.empty());
  xdotool({"mousemove", "--window", window, "160", "120"});
  const DecodedPng shown = screenshot();
  ASSERT_EQ(shown.height, 240);
  // The message sits at the bottom left in a reddish colour.
  int reddish = 0;
  for (int y = 160; y < 240; ++y)
    for (int x = 0; x < 320; ++x) {
      const Rgb p = pixel(shown, x, y);
      if (p.r > 150 && p.r > p.g + 60 && p.r > p.b + 60) ++reddish;
    }
  EXPECT_GT(reddish, 30);
  xdotool({"key", "Escape"});
  EXPECT_EQ(viewer_->waitExit(), 0);
}

TEST_F(ViewerWindow, DroppingAFileLoadsItAndABadFileKeepsTheModelAndShowsTheError) {
  std::string why;
  if (!startX(why)) GTEST_SKIP() << why;
  std::ofstream(dir_ / "tetra.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
                                       "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
  std::ofstream(dir_ / "broken.obj") << "v 0 0 0\nf 1 2 9\n";
  startViewer({"-w", "240", "-h", "180", "-workers", "1"});
  ASSERT_TRUE(viewer_->waitForLine("tessera view: showing cube"));
  const std::string window = findWindow();
  ASSERT_FALSE(window.empty());
  xdotool({"mousemove", "--window", window, "120", "90"});
  const DecodedPng cube = screenshot();

  // A real XDND drop, as from a file manager: the model loads and replaces the cube.
  EXPECT_EQ(tessera::test::dropFileOnWindow(display_, std::stoul(window),
                                            (dir_ / "tetra.obj").string(), 120, 90, 60),
            "");
  ASSERT_TRUE(viewer_->waitForLine("tessera view: showing tetra.obj (4 triangles"))
      << viewer_->output() << slurp(dir_ / "viewer.err");
  const DecodedPng tetra = screenshot();
  ASSERT_EQ(tetra.width, 240);
  ASSERT_EQ(cube.width, 240);
  EXPECT_GT(countDifferent(cube, tetra, 0, 0, 240, 180), 240 * 180 / 20);

  // A file that fails to load: the error is reported and the tetrahedron stays.
  EXPECT_EQ(tessera::test::dropFileOnWindow(display_, std::stoul(window),
                                            (dir_ / "broken.obj").string(), 120, 90, 60),
            "");
  const Clock::time_point deadline = Clock::now() + kTimeout;
  while (slurp(dir_ / "viewer.err").find("broken.obj") == std::string::npos &&
         Clock::now() < deadline)
    ::usleep(20 * 1000);
  ASSERT_NE(slurp(dir_ / "viewer.err").find("broken.obj"), std::string::npos);
  const DecodedPng after = screenshot();
  ASSERT_EQ(after.width, 240);
  // The model is untouched above the message box, and the message is drawn below.
  EXPECT_EQ(countDifferent(tetra, after, 0, 0, 240, 60), 0);
  EXPECT_GT(countDifferent(tetra, after, 0, 120, 240, 180), 100);
  xdotool({"key", "Escape"});
  EXPECT_EQ(viewer_->waitExit(), 0);
}

TEST_F(ViewerWindow, FullscreenFillsTheScreenAndTextureIsTheAlbedo) {
  std::string why;
  if (!startX(why)) GTEST_SKIP() << why;
  // A 2x2 pure blue texture: the orange cube turns blue.
  const uint32_t blue[4] = {0xffff0000u, 0xffff0000u, 0xffff0000u, 0xffff0000u};
  ASSERT_TRUE(tessera::io::writePngRgba8(dir_ / "blue.png", 2, 2, blue));
  startViewer({"-fullscreen", "-texture", "blue.png", "-workers", "1"});
  ASSERT_TRUE(viewer_->waitForLine("tessera view: showing cube"))
      << viewer_->output() << slurp(dir_ / "viewer.err");
  const std::string window = findWindow();
  ASSERT_FALSE(window.empty());
  xdotool({"mousemove", "--window", window, "512", "384"});
  const DecodedPng shot = screenshot();
  EXPECT_EQ(shot.width, 1024);  // the Xvfb screen
  EXPECT_EQ(shot.height, 768);
  if (shot.width == 1024) {
    const Rgb centre = pixel(shot, 512, 384);
    EXPECT_GT(centre.b, centre.r + 40) << centre.r << "," << centre.g << "," << centre.b;
  }
  xdotool({"key", "Escape"});
  EXPECT_EQ(viewer_->waitExit(), 0);
}

// Pixels of the overlay's MATCH (green) or MISMATCH (red) text: far greener, or far redder, than
// anything in the cube scene (grey background, an orange cube whose red leads green by < 110).
int countTinted(const DecodedPng& png, bool green) {
  int count = 0;
  for (int y = 0; y < png.height; ++y)
    for (int x = 0; x < png.width; ++x) {
      const Rgb p = pixel(png, x, y);
      count += green ? p.g > p.r + 60 && p.g > p.b + 60 : p.r > p.g + 130 && p.r > p.b + 130;
    }
  return count;
}

TEST_F(ViewerWindow, F5StoresTheFramesCrcAndF6ShowsMatchOrMismatch) {
  if (!openCube({}, 320, 240)) GTEST_SKIP() << skip_reason_;
  xdotool({"key", "F6"});
  EXPECT_TRUE(viewer_->waitForLine("tessera view: crc32 nothing stored")) << viewer_->output();

  xdotool({"key", "F5"});
  std::optional<std::string> stored = viewer_->waitForLine("tessera view: crc32 stored ");
  ASSERT_TRUE(stored) << viewer_->output() << slurp(dir_ / "viewer.err");
  const std::string crc = stored->substr(std::string("tessera view: crc32 stored ").size());
  ASSERT_EQ(crc.size(), 8u) << *stored;
  EXPECT_EQ(crc.find_first_not_of("0123456789abcdef"), std::string::npos) << crc;
  const DecodedPng plain = screenshot();
  EXPECT_EQ(countTinted(plain, true) + countTinted(plain, false), 0);

  // The same frame: MATCH, in green in the overlay.
  xdotool({"key", "F6"});
  EXPECT_TRUE(viewer_->waitForLine("tessera view: crc32 MATCH " + crc)) << viewer_->output();
  const DecodedPng match = screenshot();
  EXPECT_GT(countTinted(match, true), 30);
  EXPECT_EQ(countTinted(match, false), 0);

  // Orbited: MISMATCH with both CRCs, in red.
  xdotool({"mousemove", "--window", window_, "120", "120", "mousedown", "1", "mousemove",
           "--window", window_, "160", "130", "mouseup", "1"});
  xdotool({"key", "F6"});
  std::optional<std::string> mismatch = viewer_->waitForLine("tessera view: crc32 MISMATCH ");
  ASSERT_TRUE(mismatch) << viewer_->output();
  EXPECT_EQ(mismatch->rfind("tessera view: crc32 MISMATCH stored " + crc + " current ", 0), 0u)
      << *mismatch;
  EXPECT_EQ(mismatch->find(crc + " current " + crc), std::string::npos) << *mismatch;
  const DecodedPng different = screenshot();
  EXPECT_GT(countTinted(different, false), 30);
  EXPECT_EQ(countTinted(different, true), 0);

  // Enter puts the camera back: the very same frame again, so the same CRC.
  xdotool({"key", "Return"});
  xdotool({"key", "F6"});
  EXPECT_TRUE(viewer_->waitForLine("tessera view: crc32 MATCH " + crc)) << viewer_->output();
  quit();
}

// Runs `tessera view` without X and returns its exit status and stderr.
std::pair<int, std::string> runWithoutWindow(const std::vector<std::string>& args,
                                             const std::map<std::string, std::string>& env) {
  const fs::path dir =
      fs::temp_directory_path() / ("tessera_view_nox_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::vector<std::string> argv{TESSERA_EXE, "view"};
  argv.insert(argv.end(), args.begin(), args.end());
  Process p;
  EXPECT_TRUE(p.start(argv, dir, env, dir / "err.txt"));
  const int status = p.waitExit();
  std::string err = slurp(dir / "err.txt");
  fs::remove_all(dir);
  return {status, err};
}

TEST(ViewerErrors, NoDisplayIsAClearErrorWithStatus1) {
  auto [status, err] =
      runWithoutWindow({}, {{"DISPLAY", ""}, {"WAYLAND_DISPLAY", ""}, {"SDL_VIDEODRIVER", ""}});
  EXPECT_EQ(status, 1);
  EXPECT_NE(err.find("tessera view: error: cannot open a window"), std::string::npos) << err;
}

TEST(ViewerErrors, AnUnknownVideoDriverIsAClearErrorWithStatus1) {
  auto [status, err] = runWithoutWindow({}, {{"SDL_VIDEODRIVER", "no-such-driver"}});
  EXPECT_EQ(status, 1);
  EXPECT_NE(err.find("no-such-driver"), std::string::npos) << err;
}

TEST(ViewerErrors, AMissingModelIsAClearErrorWithStatus1) {
  auto [status, err] = runWithoutWindow({"no-such-model.obj"}, {});
  EXPECT_EQ(status, 1);
  EXPECT_NE(err.find("no-such-model.obj: no such file"), std::string::npos) << err;
}

TEST(ViewerErrors, AnUnreadableTextureIsAClearErrorWithStatus1) {
  auto [status, err] = runWithoutWindow({"-texture", "no-such-texture.png"}, {});
  EXPECT_EQ(status, 1);
  EXPECT_NE(err.find("no-such-texture.png"), std::string::npos) << err;
}

TEST(ViewerErrors, AnMsaaCountOtherThan1248IsAUsageErrorNamingThem) {
  for (const char* bad : {"3", "0", "16", "4294967298", "four"}) {
    auto [status, err] = runWithoutWindow({"-msaa", bad}, {});
    EXPECT_EQ(status, 2) << bad;
    EXPECT_NE(err.find("must be 1, 2, 4 or 8, got '" + std::string(bad) + "'"), std::string::npos)
        << err;
  }
}

TEST(ViewerErrors, ABadProjectionOrViewAngleIsAUsageErrorNamingTheChoicesOrTheRange) {
  const std::map<std::string, std::string> no_display{
      {"DISPLAY", ""}, {"WAYLAND_DISPLAY", ""}, {"SDL_VIDEODRIVER", ""}};
  for (const char* flag : {"-projection", "--projection"}) {
    auto [status, err] = runWithoutWindow({flag, "spherial"}, no_display);
    EXPECT_EQ(status, 2) << flag;
    EXPECT_NE(err.find("perspective|cylindrical|spherical|stereographic|fisheye, got 'spherial'"),
              std::string::npos)
        << err;
  }
  // Out of the start mode's range on this window: a sphere is at most 180 high and 360 around.
  const std::pair<std::vector<std::string>, std::string> bad[] = {
      {{"-projection", "spherical", "-fov", "200"}, "at most 180 degrees"},
      {{"-projection", "spherical", "-fov", "120", "-w", "800", "-h", "200"},
       "at most 360 / aspect = 90 here"},
      {{"-projection", "fisheye", "-fov", "400"}, "at most 360 degrees"},
      {{"-fov", "175"}, "between 1 and 170 in perspective"},
      {{"-fov", "0"}, "above 0"},
  };
  for (const auto& [args, message] : bad) {
    auto [status, err] = runWithoutWindow(args, no_display);
    EXPECT_EQ(status, 2) << args[1];
    EXPECT_NE(err.find(message), std::string::npos) << err;
  }
  // Within range: accepted, and then it is the missing display that stops it (status 1).
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"--projection", "fisheye", "-fov", "270"},
        std::vector<std::string>{"-projection", "cylindrical", "-fov", "170"}}) {
    auto [status, err] = runWithoutWindow(args, no_display);
    EXPECT_EQ(status, 1) << args[1] << ": " << err;
    EXPECT_NE(err.find("cannot open a window"), std::string::npos) << err;
  }
}

TEST(ViewerErrors, AnHdriThatCannotBeReadStopsBeforeTheWindowOpens) {
  auto [status, err] = runWithoutWindow({"--hdri", "/nonexistent/sky.hdr"}, {});
  EXPECT_EQ(status, 1);
  EXPECT_NE(err.find("/nonexistent/sky.hdr"), std::string::npos) << err;
  EXPECT_EQ(err.find("cannot open a window"), std::string::npos) << err;
  std::tie(status, err) = runWithoutWindow({"--hdri-background"}, {});
  EXPECT_EQ(status, 2);
  EXPECT_NE(err.find("--hdri PATH"), std::string::npos) << err;
}

TEST(ViewerErrors, BadFlagsAreAUsageErrorWithStatus2) {
  auto [status, err] = runWithoutWindow({"-fps", "0"}, {});
  EXPECT_EQ(status, 2);
  EXPECT_NE(err.find("tessera view --help"), std::string::npos) << err;
}

}  // namespace
