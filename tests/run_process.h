// Test helper: run an executable as a real process in a folder and capture what it did.
#pragma once

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace tessera::test {

struct RunResult {
  int exit_code = -1;  // -1 when the process did not exit normally
  std::string out, err;
};

// The whole content of the file at `path`; empty if it cannot be read.
inline std::string slurp(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Runs `executable` with `args` (a shell-quoted string) in `folder`, stdin from /dev/null, with
// `environment` (NAME=value ..., or empty) added to its environment. stdout and stderr pass
// through files in `folder`, removed again before returning.
inline RunResult runInFolder(const std::filesystem::path& folder, const std::string& executable,
                             const std::string& args, const std::string& environment = "") {
  const std::filesystem::path out = folder / "stdout.txt", err = folder / "stderr.txt";
  const std::string command = "cd '" + folder.string() + "' && " + environment + " '" + executable +
                              "' " + args + " > '" + out.string() + "' 2> '" + err.string() +
                              "' < /dev/null";
  const int status = std::system(command.c_str());
  RunResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = slurp(out);
  r.err = slurp(err);
  std::filesystem::remove(out);
  std::filesystem::remove(err);
  return r;
}

}  // namespace tessera::test
