// Command-line flags, one grammar for every subcommand: `--name value` and `--name=value`, with
// one dash accepted too (the cube demo's `-w 480`, kept as aliases). `-h` and `--help` ask for
// help, except that `-h` followed by a number is the height where a command has `-h|height` (the
// seed demo's flag). Bad input is a returned error: the caller prints it and hint(), one line
// pointing to --help (not the whole usage), and exits 2. An unknown flag's error suggests the
// nearest known name.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <tessera/base/expected.h>
#include <tessera/math/vec.h>

namespace tessera::cli {

class FlagSet {
 public:
  // single_dash: show long names as -name in the usage (the cube demo's style).
  explicit FlagSet(std::string synopsis, bool single_dash = false)
      : synopsis_(std::move(synopsis)), single_dash_(single_dash) {}

  // `names` is a list separated by '|', e.g. "o|output". One-letter names and the rest are
  // accepted with one or two dashes alike.
  void addInt(const std::string& names, int* out, const std::string& help, int min, int max);
  void addFloat(const std::string& names, float* out, const std::string& help, float min,
                float max);
  void addString(const std::string& names, std::string* out, const std::string& help);
  void addSwitch(const std::string& names, bool* out, const std::string& help);
  // "X,Y,Z" (finite numbers); *given is set when the flag appears.
  void addFloat3(const std::string& names, float3* out, bool* given, const std::string& help);
  // One of `choices`.
  void addChoice(const std::string& names, std::string* out, std::vector<std::string> choices,
                 const std::string& help);
  // A duration: "4s", "500ms" or a plain number of seconds.
  void addSeconds(const std::string& names, float* out, const std::string& help);
  // Any flag with a custom parser returning an error message or "".
  void addCustom(const std::string& names, const std::string& value_name, const std::string& help,
                 std::function<std::string(const std::string&)> parse);

  // Parses the arguments; returns the positional ones. `--help` sets helpRequested().
  Expected<std::vector<std::string>> parse(const std::vector<std::string>& args);
  bool helpRequested() const { return help_; }
  std::string usage() const;
  // "Run 'tessera render --help' for the flags.\n": what follows a usage error.
  std::string hint() const;

 private:
  struct Flag {
    std::vector<std::string> names;
    std::string value_name;  // empty for switches
    std::string help;
    std::function<std::string(const std::string&)> parse;
  };
  const Flag* find(const std::string& name) const;
  // "unknown flag '--resoltion'; did you mean '--resolution'?" (when a name is near enough).
  std::string unknownFlag(const std::string& arg, const std::string& name) const;

  std::string synopsis_;
  bool single_dash_ = false;
  std::vector<Flag> flags_;
  bool help_ = false;
};

// Helpers shared by the subcommands.
Expected<float3> parseFloat3(const std::string& text);
bool parseIntStrict(const std::string& text, long long& out);
bool parseFloatStrict(const std::string& text, float& out);
// An image size "W,H" or "WxH", each side 1..16384: "" or what is wrong.
std::string parseSize(const std::string& text, int& width, int& height);
// The number of single-character edits (insert, delete, replace, swap of neighbours) from a to b.
size_t editDistance(const std::string& a, const std::string& b);

}  // namespace tessera::cli
