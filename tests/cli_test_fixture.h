// The CLI tests' fixture: a fresh folder per test and the tessera executable run in it
// (cli_test.cpp: cube, flags, help, errors, MSAA, projections; cli_render_test.cpp: render's
// outputs, AOVs, cameras and reference images).
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include <tessera/io/image_writer.h>

#include "decode.h"
#include "reference.h"
#include "run_process.h"
#include "temp_folder.h"

namespace fs = std::filesystem;
using tessera::test::DecodedGif;
using tessera::test::DecodedPng;
using tessera::test::RunResult;
using tessera::test::slurp;

namespace {

class Cli : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = tessera::test::makeTestFolder("tessera_cli"); }
  void TearDown() override { fs::remove_all(dir_); }

  // Runs tessera with `args` (a shell-quoted string) in the test's folder.
  RunResult run(const std::string& args) {
    return tessera::test::runInFolder(dir_, TESSERA_EXE, args);
  }

  void writeFile(const std::string& name, const std::string& text) {
    tessera::test::writeFile(dir_ / name, text);
  }

  // A unit quad facing +Z split into two triangles, and a tetrahedron behind it.
  void writeQuadObj(const std::string& name) {
    writeFile(name,
              "# a quad in the XY plane\n"
              "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\n"
              "f 1 2 3 4\n");
  }

  std::set<std::string> filesInDir() {
    std::set<std::string> names;
    for (const auto& e : fs::directory_iterator(dir_)) names.insert(e.path().filename().string());
    return names;
  }

  fs::path dir_;
};

}  // namespace
