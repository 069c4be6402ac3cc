// The hostile corpus (tests/hostile/make_hostile.py, issue 22): every case through `tessera
// render` and `tessera info` as real processes, each held to its expected exit status and
// message, to a time bound (a FIFO must not block), to a peak-memory bound (its max RSS, from
// wait4), and to leaving no partial output behind.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <filesystem>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "decode.h"
#include "run_process.h"
#include "temp_folder.h"

namespace tessera::test {
namespace {

namespace fs = std::filesystem;

// Peak memory of any one case. Sanitizers multiply a process's memory (shadow memory, the
// quarantine of freed blocks), so their builds are held to a bound scaled by that overhead.
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
constexpr long kMaxRssKib = 4L << 20;  // 4 GiB: 1.5 GiB at ASan's overhead of up to ~2.5x
#else
constexpr long kMaxRssKib = 1536L << 10;  // 1.5 GiB
#endif
// A case that takes longer has hung (the slowest, at the budget, takes a few seconds).
constexpr auto kTimeout = std::chrono::seconds(120);

struct Finished {
  int exit_code = -1;  // -1: killed or crashed
  bool timed_out = false;
  long max_rss_kib = 0;
  double seconds = 0;
  std::string out, err;
};

// Runs TESSERA_EXE with `args` in `folder`, stdin from /dev/null; kills it after kTimeout.
Finished runTessera(const fs::path& folder, const std::vector<std::string>& args) {
  const fs::path out = folder / "stdout.txt", err = folder / "stderr.txt";
  const auto start = std::chrono::steady_clock::now();
  // Nothing buffered may be written twice, once by the child.
  std::cout.flush();
  std::fflush(nullptr);
  const pid_t pid = ::fork();
  if (pid == 0) {
    if (::chdir(folder.c_str()) != 0) ::_exit(126);
    if (!std::freopen("/dev/null", "r", stdin) || !std::freopen(out.c_str(), "w", stdout) ||
        !std::freopen(err.c_str(), "w", stderr))
      ::_exit(126);
    std::vector<char*> argv{const_cast<char*>(TESSERA_EXE)};
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    ::execv(TESSERA_EXE, argv.data());
    ::_exit(127);
  }
  Finished f;
  int status = 0;
  struct rusage usage {};
  while (true) {
    const pid_t done = ::wait4(pid, &status, WNOHANG, &usage);
    if (done == pid) break;
    if (std::chrono::steady_clock::now() - start > kTimeout) {
      f.timed_out = true;
      ::kill(pid, SIGKILL);
      ::wait4(pid, &status, 0, &usage);
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  f.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  f.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  f.max_rss_kib = usage.ru_maxrss;  // Linux: kibibytes
  f.out = slurp(out);
  f.err = slurp(err);
  fs::remove(out);
  fs::remove(err);
  return f;
}

// The image shows a shaded model: many colours, and a good share of pixels that are not the
// background. A model drawn as background or in one flat colour fails.
void expectDrawnWithShading(const fs::path& png, const std::string& label) {
  std::optional<DecodedPng> image = decodePng(png.string());
  ASSERT_TRUE(image.has_value()) << label << ": cannot decode " << png;
  std::set<std::array<int, 3>> colours;
  size_t not_background = 0;
  const size_t pixels = static_cast<size_t>(image->width) * image->height;
  const std::array<int, 3> background = image->rgb(0, 0);
  for (int y = 0; y < image->height; ++y)
    for (int x = 0; x < image->width; ++x) {
      colours.insert(image->rgb(x, y));
      not_background += image->rgb(x, y) != background;
    }
  EXPECT_GE(colours.size(), 20u) << label << ": the model is drawn in " << colours.size()
                                 << " colours";
  EXPECT_GE(not_background, pixels / 20) << label << ": the model covers " << not_background
                                         << " of " << pixels << " pixels";
}

class HostileCorpus : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    corpus_ = new fs::path(fs::temp_directory_path() /
                           ("tessera_hostile_" + std::to_string(::getpid())));
    fs::remove_all(*corpus_);
    const std::string command = "python3 '" TESSERA_HOSTILE_SCRIPT "' '" + corpus_->string() + "'";
    ASSERT_EQ(std::system(command.c_str()), 0) << command;
    cases_ = new nlohmann::json(nlohmann::json::parse(slurp(*corpus_ / "cases.json")));
  }
  static void TearDownTestSuite() {
    fs::remove_all(*corpus_);
    delete corpus_;
    delete cases_;
  }

  const nlohmann::json& findCase(const std::string& name) {
    for (const nlohmann::json& c : *cases_)
      if (c["name"] == name) return c;
    ADD_FAILURE() << "no case '" << name << "' in cases.json";
    static const nlohmann::json kNone;
    return kNone;
  }

  // Runs one case with each of its commands and checks everything it says.
  void runCase(const std::string& name) {
    const nlohmann::json& c = findCase(name);
    if (c.is_null()) return;
    const fs::path folder = *corpus_ / c["dir"].get<std::string>();
    for (const std::string command : c["commands"]) {
      const std::string label = name + " (" + command + ")";
      const fs::path output = folder / (command + "_out.png");
      std::vector<std::string> args{command, c["model"].get<std::string>()};
      if (command == "render") args.insert(args.end(), {"-o", output.filename().string()});
      for (const std::string arg : c["args"]) args.push_back(arg);
      if (command == "render")
        for (const std::string arg : c["render_args"]) args.push_back(arg);
      const Finished run = runTessera(folder, args);
      std::cout << "[ hostile  ] " << label << ": exit " << run.exit_code << ", "
                << run.max_rss_kib / 1024 << " MiB peak, " << run.seconds << " s\n";
      ASSERT_FALSE(run.timed_out) << label << " did not finish in " << kTimeout.count() << " s";
      EXPECT_EQ(run.exit_code, c["exit"].get<int>()) << label << "\n" << run.err;
      EXPECT_LT(run.max_rss_kib, kMaxRssKib) << label << ": peak memory";
      // info lists a model's warnings in its report, on stdout.
      const std::string messages = command == "info" ? run.err + run.out : run.err;
      for (const std::string words : c["err_has"])
        EXPECT_NE(messages.find(words), std::string::npos) << label << " lacks: " << words
                                                           << "\n" << messages;
      for (const std::string words : c["err_lacks"])
        EXPECT_EQ(run.err.find(words), std::string::npos) << label << " holds: " << words
                                                          << "\n" << run.err.substr(0, 2000);
      // One line a message: no megabytes of echoed file content.
      EXPECT_LT(run.err.size(), 4000u) << label;
      if (command == "info") {
        for (const std::string words : c["out_has"])
          EXPECT_NE(run.out.find(words), std::string::npos) << label << " lacks: " << words
                                                            << "\n" << run.out;
      } else if (run.exit_code != 0) {
        EXPECT_FALSE(fs::exists(output)) << label << " left a partial output";
      } else if (c["drawn"].get<bool>()) {
        expectDrawnWithShading(output, label);
      }
      fs::remove(output);
    }
  }

  static fs::path* corpus_;
  static nlohmann::json* cases_;
};

fs::path* HostileCorpus::corpus_ = nullptr;
nlohmann::json* HostileCorpus::cases_ = nullptr;

// The cases each test runs, by class of failure.
const std::vector<std::string> kFifosAndFolders = {
    "fifo_obj_texture", "fifo_mtl", "directory_obj_texture", "fifo_gltf_buffer",
    "directory_gltf_image", "fifo_model"};
const std::vector<std::string> kMemoryBombs = {
    "png_bomb_obj", "two_png_bombs_gltf", "png_claims_huge", "gltf_instancing_bomb",
    "obj_over_max_triangles", "stl_over_max_triangles"};
const std::vector<std::string> kAtTheBudget = {"gltf_instancing_at_budget"};
const std::vector<std::string> kWideIntegers = {
    "obj_index_2pow32_plus_3", "obj_index_20_digits", "gltf_node_mesh_2pow32",
    "gltf_scene_node_2pow32", "gltf_view_buffer_2pow32", "gltf_indices_2pow32",
    "gltf_sparse_count_2pow31", "gltf_sparse_offset_2pow32"};
const std::vector<std::string> kNonFinite = {"obj_nan_inf"};
const std::vector<std::string> kExtremeScales = {"obj_scale_1e10", "obj_scale_3e38",
                                                 "obj_scale_1e-42", "obj_scale_3e38_camera"};
const std::vector<std::string> kMessages = {"gltf_short_buffer", "glb_empty_bin",
                                            "gltf_huge_bad_data_uri"};

TEST_F(HostileCorpus, FifosAndFoldersAreRefusedWithoutBlocking) {
  for (const std::string& name : kFifosAndFolders) runCase(name);
}

TEST_F(HostileCorpus, MemoryBombsAreRefusedBeforeTheyAllocate) {
  for (const std::string& name : kMemoryBombs) runCase(name);
}

TEST_F(HostileCorpus, ModelAtTheBudgetStaysUnderThePeakMemoryBound) {
  for (const std::string& name : kAtTheBudget) runCase(name);
}

TEST_F(HostileCorpus, IntegersPast32BitsAreRefusedNotWrapped) {
  for (const std::string& name : kWideIntegers) runCase(name);
}

TEST_F(HostileCorpus, NanAndInfInObjDropTheirTriangles) {
  for (const std::string& name : kNonFinite) runCase(name);
}

TEST_F(HostileCorpus, ExtremeFiniteScalesAreDrawnAndInfoPrintsTrueBounds) {
  for (const std::string& name : kExtremeScales) runCase(name);
}

TEST_F(HostileCorpus, MessagesAreInTesserasOwnWords) {
  for (const std::string& name : kMessages) runCase(name);
}

// A case added to the script must be run by a test too.
TEST_F(HostileCorpus, EveryCaseIsRunByATest) {
  std::set<std::string> listed;
  for (const auto* list : {&kFifosAndFolders, &kMemoryBombs, &kAtTheBudget, &kWideIntegers,
                           &kNonFinite, &kExtremeScales, &kMessages})
    listed.insert(list->begin(), list->end());
  ASSERT_FALSE(cases_->empty());
  for (const nlohmann::json& c : *cases_)
    EXPECT_TRUE(listed.contains(c["name"].get<std::string>())) << c["name"] << " is never run";
}

}  // namespace
}  // namespace tessera::test
