// tessera: a software 3D rendering pipeline. Subcommands: cube, render, bench.
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include "commands.h"
#include "flags.h"

namespace tessera::cli {

void printError(const std::string& command, const std::string& message) {
  std::cerr << "tessera " << command << ": error: " << message << std::endl;
}

}  // namespace tessera::cli

namespace {

constexpr const char* kUsage =
    "usage: tessera <command> [flags]\n"
    "\n"
    "commands:\n"
    "  cube            render the rotating-cube demo to an animated GIF (no input needed)\n"
    "  render MODEL    render a model to PNG (colour or an AOV), GIF, MP4 or a PNG sequence\n"
    "  bench [SCENE]   time built-in scenes or models, beside Mesa's llvmpipe with --vs llvmpipe\n"
    "  info MODEL      print a model's counts, bounds and warnings without rendering it\n"
    "                  (info --readers-list: the model formats and which reader reads each)\n"
    "  view [MODEL]    look at a model (or the cube) in a window: orbit, zoom, pan, screenshots\n"
    "  devices         list the Vulkan devices and the backends each can run\n"
    "\n"
    "Run 'tessera <command> --help' for the flags of a command, 'tessera --version' for the\n"
    "version.\n";

}  // namespace

int main(int argc, char** argv) {
  using namespace tessera::cli;
  std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty()) {
    std::cerr << kUsage;
    return kExitUsage;
  }
  // --version anywhere before "--", on its own or after a command: the one answer.
  for (const std::string& arg : args) {
    if (arg == "--") break;
    if (arg == "--version") {
      std::cout << "tessera " << TESSERA_VERSION << "\n";
      return kExitOk;
    }
  }
  const std::string command = args.front();
  args.erase(args.begin());
  if (command == "cube") return runCube(args);
  if (command == "render") return runRender(args);
  if (command == "bench") return runBench(args);
  if (command == "info") return runInfo(args);
  if (command == "view") return runView(args);
  if (command == "devices") return runDevices(args);
  if (command == "--help" || command == "-h" || command == "help") {
    std::cout << kUsage;
    return kExitOk;
  }
  std::string suggestion;
  for (const char* known : {"cube", "render", "bench", "info", "view", "devices"})
    if (editDistance(command, known) <= 2) suggestion = known;
  std::cerr << "tessera: unknown command '" << command << "'"
            << (suggestion.empty() ? "" : "; did you mean '" + suggestion + "'?")
            << "\nRun 'tessera --help' for the commands.\n";
  return kExitUsage;
}
