// The subcommands of the tessera executable, and what they share.
#pragma once

#include <cstdio>
#include <ostream>
#include <string>
#include <vector>

#include <tessera/math/vec.h>

namespace tessera::io {
struct Model;
}

namespace tessera::cli {

constexpr int kExitOk = 0;
constexpr int kExitFailure = 1;  // the work could not be done (bad model, unwritable output)
constexpr int kExitUsage = 2;    // the command line was wrong

int runCube(const std::vector<std::string>& args);
int runRender(const std::vector<std::string>& args);
int runBench(const std::vector<std::string>& args);
int runInfo(const std::vector<std::string>& args);
int runView(const std::vector<std::string>& args);

// The demo cube's colour (sRGB 0.95, 0.55, 0.15), linear: `tessera cube` and the viewer's
// built-in model.
float4 demoCubeColor();

// Counts, bounds and warnings of a loaded model.
void printModelInfo(const std::string& path, const io::Model& model, std::ostream& out);
int runDevices(const std::vector<std::string>& args);

// Prints "tessera <command>: error: <message>" to stderr.
void printError(const std::string& command, const std::string& message);

}  // namespace tessera::cli
