// The example commands of README.md, docs/usage.md, docs/rendering.md and docs/viewer.md, run
// exactly as written, so the docs cannot drift from the code again. Every `tessera ...` line of
// their ```sh blocks is run in a fresh folder holding small stand-ins for the models and textures
// they name (model.obj, bunny.obj, part.obj, room.obj: a box; orbit.gltf: an animated cube;
// wood.png: a texture; studio.hdr: an environment). Lines that cannot run here are skipped with
// the reason printed: the viewer (a window), Vulkan backends, built-in
// benchmark scenes (minutes at 4K), MP4 without ffmpeg, and models no stand-in is made for.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <tessera/io/image_writer.h>

#include "animated_cube_file.h"
#include "run_process.h"
#include "stb_image_write.h"
#include "temp_folder.h"

namespace fs = std::filesystem;
using tessera::test::RunResult;

namespace {

struct DocCommand {
  std::string file;  // README.md or a file of docs/
  std::string line;  // after "tessera ", without the comment
  std::vector<std::string> words;
};

// The `tessera ...` lines of the file's ```sh blocks, continuation lines joined.
std::vector<DocCommand> docCommands(const std::string& name) {
  std::istringstream in(tessera::test::slurp(fs::path(TESSERA_SOURCE_DIR) / name));
  std::vector<DocCommand> out;
  std::string text, pending;
  bool in_sh = false;
  while (std::getline(in, text)) {
    if (text.rfind("```", 0) == 0) {
      in_sh = !in_sh && text == "```sh";
      continue;
    }
    if (!in_sh) continue;
    if (!pending.empty()) {
      text = pending + " " + text;
      pending.clear();
    }
    if (size_t hash = text.find(" #"); hash != std::string::npos) text.resize(hash);
    while (!text.empty() && (text.back() == ' ' || text.back() == '\t')) text.pop_back();
    if (!text.empty() && text.back() == '\\') {
      text.pop_back();
      pending = text;
      continue;
    }
    const size_t start = text.find_first_not_of(' ');
    if (start == std::string::npos || text.compare(start, 8, "tessera ") != 0) continue;
    DocCommand c{name, text.substr(start + 8), {}};
    std::istringstream words(c.line);
    for (std::string w; words >> w;) c.words.push_back(w);
    out.push_back(c);
  }
  return out;
}

bool has(const DocCommand& c, const std::string& word) {
  for (const std::string& w : c.words)
    if (w == word || w.rfind(word + "=", 0) == 0) return true;
  return false;
}

// The value after `flag`, or "".
std::string valueOf(const DocCommand& c, const std::string& flag) {
  for (size_t i = 0; i + 1 < c.words.size(); ++i)
    if (c.words[i] == flag) return c.words[i + 1];
  return "";
}

const char* kStandIns[] = {"model.obj", "bunny.obj", "part.obj", "room.obj", "orbit.gltf"};

// Why the command cannot run here, or "" when it can.
std::string skipReason(const DocCommand& c) {
  const std::string& command = c.words.at(0);
  if (command == "view") return "the viewer needs a window (tests/viewer_window_*_test.cpp)";
  if (command == "devices" || c.line.find("--backend vulkan") != std::string::npos)
    return "needs Vulkan (tests/vulkan_*_test.cpp)";
  if (command == "bench") {
    bool model = false;
    for (const std::string& w : c.words)
      for (const char* s : kStandIns) model = model || w == s;
    if (!model || has(c, "--vs")) return "built-in benchmark scenes at up to 4K take minutes";
  }
  if (has(c, "-o") && valueOf(c, "-o").ends_with(".mp4") &&
      std::system("command -v ffmpeg > /dev/null") != 0)
    return "MP4 needs the ffmpeg program";
  for (const std::string& w : c.words) {
    const std::string ext = fs::path(w).extension().string();
    if (w[0] == '-' || (ext != ".obj" && ext != ".gltf" && ext != ".glb" && ext != ".stl"))
      continue;
    bool made = false;
    for (const char* s : kStandIns) made = made || w == s;
    if (!made) return "no stand-in for " + w;
  }
  return "";
}

// What the command should have written, relative to its folder ("" when nothing is checked).
std::string expectedOutput(const DocCommand& c) {
  const std::string& command = c.words.at(0);
  std::string out = command == "cube" ? valueOf(c, "-out") : valueOf(c, "-o");
  if (out.empty() && command == "cube") out = "cube.gif";
  if (out.empty() && command == "render" && !has(c, "--info"))
    out = fs::path(c.words.at(1)).stem().string() + ".png";
  if (size_t at = out.find("{frame}"); at != std::string::npos) out.replace(at, 7, "0000");
  return out;
}

class CliDocs : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = tessera::test::makeTestFolder("tessera_cli_docs");
    // A box from -2 to 2 (room.obj's camera at 0,1.6,0 is inside it and sees the walls).
    std::string box;
    for (int i = 0; i < 8; ++i)
      box += std::string("v ") + (i & 1 ? "2" : "-2") + (i & 2 ? " 2" : " -2") +
             (i & 4 ? " 2" : " -2") + " " + "\n";
    box += "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n";
    const int faces[6][4] = {{1, 3, 4, 2}, {5, 6, 8, 7}, {1, 2, 6, 5},
                             {3, 7, 8, 4}, {1, 5, 7, 3}, {2, 4, 8, 6}};
    for (const auto& f : faces)
      box += "f " + std::to_string(f[0]) + "/1 " + std::to_string(f[1]) + "/2 " +
             std::to_string(f[2]) + "/3 " + std::to_string(f[3]) + "/4\n";
    for (const char* name : kStandIns)
      if (fs::path(name).extension() == ".obj") tessera::test::writeFile(dir_ / name, box);
    // orbit.gltf: an animated glTF, the cube of animated_cube_file.h with its 2 s clip.
    tessera::test::AnimatedCubeFile().write(dir_);
    fs::rename(dir_ / "cube.gltf", dir_ / "orbit.gltf");
    std::vector<uint32_t> wood(16 * 16);
    for (size_t i = 0; i < wood.size(); ++i) wood[i] = (i / 16 + i) % 2 ? 0xff2060a0u : 0xffffffffu;
    EXPECT_TRUE(tessera::io::writePngRgba8(dir_ / "wood.png", 16, 16, wood.data()));
    // studio.hdr: a sky over a darker ground, 16 x 8.
    std::vector<float> studio;
    for (int i = 0; i < 16 * 8; ++i)
      for (float v : {i < 64 ? 2.0f : 0.2f, i < 64 ? 2.0f : 0.2f, i < 64 ? 2.5f : 0.1f})
        studio.push_back(v);
    EXPECT_NE(stbi_write_hdr((dir_ / "studio.hdr").string().c_str(), 16, 8, 3, studio.data()), 0);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // Runs every command of the file that can run here; returns how many ran, by subcommand. The
  // file holds at least `least` examples.
  std::map<std::string, int> runAll(const std::string& file, size_t least = 10) {
    std::map<std::string, int> ran;
    const std::vector<DocCommand> commands = docCommands(file);
    EXPECT_GE(commands.size(), least) << file << ": the examples were not found";
    for (const DocCommand& c : commands) {
      if (std::string why = skipReason(c); !why.empty()) {
        std::cout << "[ skipped  ] " << file << ": tessera " << c.line << " (" << why << ")\n";
        continue;
      }
      const RunResult r = tessera::test::runInFolder(dir_, TESSERA_EXE, c.line);
      EXPECT_EQ(r.exit_code, 0) << file << ": tessera " << c.line << "\n" << r.err;
      if (const std::string out = expectedOutput(c); !out.empty()) {
        EXPECT_TRUE(fs::exists(dir_ / out))
            << file << ": tessera " << c.line << " wrote no " << out;
      }
      ++ran[c.words.at(0)];
    }
    return ran;
  }

  fs::path dir_;
};

TEST_F(CliDocs, ReadmeCommandsRunAsWritten) {
  std::map<std::string, int> ran = runAll("README.md");
  EXPECT_GE(ran["cube"], 3);
  EXPECT_GE(ran["render"], 8);
  EXPECT_GE(ran["info"], 1);
}

TEST_F(CliDocs, UsageCommandsRunAsWritten) {
  std::map<std::string, int> ran = runAll("docs/usage.md");
  EXPECT_GE(ran["cube"], 1);
  EXPECT_GE(ran["render"], 5);
}

TEST_F(CliDocs, RenderingCommandsRunAsWritten) {
  std::map<std::string, int> ran = runAll("docs/rendering.md");
  EXPECT_GE(ran["render"], 20);
}

// The viewer's lines open a window and are skipped (with the reason printed); any other line of
// its page runs as written.
TEST_F(CliDocs, ViewerCommandsRunAsWritten) {
  const std::map<std::string, int> ran = runAll("docs/viewer.md", 5);
  EXPECT_EQ(ran.count("view"), 0u);
}

}  // namespace
