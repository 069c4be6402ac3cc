#include "flags.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>

namespace tessera::cli {

namespace {

std::vector<std::string> splitNames(const std::string& names) {
  std::vector<std::string> out;
  std::stringstream in(names);
  std::string name;
  while (std::getline(in, name, '|')) out.push_back(name);
  return out;
}

}  // namespace

bool parseIntStrict(const std::string& text, long long& out) {
  if (text.empty()) return false;
  errno = 0;
  char* end = nullptr;
  out = std::strtoll(text.c_str(), &end, 10);
  return errno == 0 && end && *end == '\0';
}

bool parseFloatStrict(const std::string& text, float& out) {
  if (text.empty()) return false;
  errno = 0;
  char* end = nullptr;
  out = std::strtof(text.c_str(), &end);
  return errno == 0 && end && *end == '\0' && std::isfinite(out);
}

std::string parseSize(const std::string& text, int& width, int& height) {
  size_t split = text.find(',');
  if (split == std::string::npos) split = text.find_first_of("xX");
  long long w = 0, h = 0;
  if (split == std::string::npos || !parseIntStrict(text.substr(0, split), w) ||
      !parseIntStrict(text.substr(split + 1), h))
    return "expected W,H or WxH (such as 1920,1080 or 1920x1080), got '" + text + "'";
  if (w < 1 || h < 1 || w > 16384 || h > 16384) return "each side must be between 1 and 16384";
  width = static_cast<int>(w);
  height = static_cast<int>(h);
  return "";
}

size_t editDistance(const std::string& a, const std::string& b) {
  // Optimal string alignment: Levenshtein plus the swap of two neighbours ("resoltion").
  std::vector<std::vector<size_t>> d(a.size() + 1, std::vector<size_t>(b.size() + 1));
  for (size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  }
  return d[a.size()][b.size()];
}

Expected<float3> parseFloat3(const std::string& text) {
  std::vector<std::string> parts;
  std::stringstream in(text);
  std::string part;
  while (std::getline(in, part, ',')) parts.push_back(part);
  float3 v;
  if (parts.size() != 3 || !parseFloatStrict(parts[0], v.x) || !parseFloatStrict(parts[1], v.y) ||
      !parseFloatStrict(parts[2], v.z))
    return makeError("expected three numbers X,Y,Z, got '" + text + "'");
  return v;
}

void FlagSet::addCustom(const std::string& names, const std::string& value_name,
                        const std::string& help,
                        std::function<std::string(const std::string&)> parse) {
  flags_.push_back({splitNames(names), value_name, help, std::move(parse)});
}

void FlagSet::addInt(const std::string& names, int* out, const std::string& help, int min,
                     int max) {
  addCustom(names, "N", help, [=](const std::string& v) -> std::string {
    long long n;
    if (!parseIntStrict(v, n)) return "expected a whole number, got '" + v + "'";
    if (n < min || n > max)
      return "must be between " + std::to_string(min) + " and " + std::to_string(max);
    *out = static_cast<int>(n);
    return "";
  });
}

void FlagSet::addFloat(const std::string& names, float* out, const std::string& help, float min,
                       float max) {
  addCustom(names, "X", help, [=](const std::string& v) -> std::string {
    float f;
    if (!parseFloatStrict(v, f)) return "expected a number, got '" + v + "'";
    if (f < min || f > max) {
      std::ostringstream s;
      s << "must be between " << min << " and " << max;
      return s.str();
    }
    *out = f;
    return "";
  });
}

void FlagSet::addString(const std::string& names, std::string* out, const std::string& help) {
  addCustom(names, "PATH", help, [=](const std::string& v) -> std::string {
    if (v.empty()) return "must not be empty";
    *out = v;
    return "";
  });
}

void FlagSet::addSwitch(const std::string& names, bool* out, const std::string& help) {
  flags_.push_back({splitNames(names), "", help, [=](const std::string& v) -> std::string {
                      if (v.empty() || v == "true" || v == "1") {
                        *out = true;
                      } else if (v == "false" || v == "0") {
                        *out = false;
                      } else {
                        return "expected true or false, got '" + v + "'";
                      }
                      return "";
                    }});
}

void FlagSet::addFloat3(const std::string& names, float3* out, bool* given,
                        const std::string& help) {
  addCustom(names, "X,Y,Z", help, [=](const std::string& v) -> std::string {
    Expected<float3> parsed = parseFloat3(v);
    if (!parsed) return parsed.error().message;
    *out = *parsed;
    if (given) *given = true;
    return "";
  });
}

void FlagSet::addChoice(const std::string& names, std::string* out,
                        std::vector<std::string> choices, const std::string& help) {
  std::string joined;
  for (const std::string& c : choices) joined += (joined.empty() ? "" : "|") + c;
  addCustom(names, joined, help, [=](const std::string& v) -> std::string {
    for (const std::string& c : choices)
      if (v == c) {
        *out = v;
        return "";
      }
    return "expected one of " + joined + ", got '" + v + "'";
  });
}

void FlagSet::addSeconds(const std::string& names, float* out, const std::string& help) {
  addCustom(names, "DURATION", help, [=](const std::string& v) -> std::string {
    std::string number = v;
    float scale = 1.0f;
    if (number.size() > 2 && number.compare(number.size() - 2, 2, "ms") == 0) {
      number.resize(number.size() - 2);
      scale = 0.001f;
    } else if (number.size() > 1 && number.back() == 's') {
      number.pop_back();
    }
    float seconds;
    if (!parseFloatStrict(number, seconds) || seconds <= 0.0f)
      return "expected a positive duration such as 4s or 500ms, got '" + v + "'";
    *out = seconds * scale;
    return "";
  });
}

const FlagSet::Flag* FlagSet::find(const std::string& name) const {
  for (const Flag& f : flags_)
    for (const std::string& n : f.names)
      if (n == name) return &f;
  return nullptr;
}

Expected<std::vector<std::string>> FlagSet::parse(const std::vector<std::string>& args) {
  std::vector<std::string> positional;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    if (arg == "--") {
      positional.insert(positional.end(), args.begin() + i + 1, args.end());
      break;
    }
    if (arg.size() < 2 || arg[0] != '-' || (arg[1] >= '0' && arg[1] <= '9') || arg[1] == '.') {
      positional.push_back(arg);
      continue;
    }
    std::string body = arg.substr(arg[1] == '-' ? 2 : 1);
    std::string value;
    bool has_value = false;
    if (size_t eq = body.find('='); eq != std::string::npos) {
      value = body.substr(eq + 1);
      body.resize(eq);
      has_value = true;
    }
    if (body == "help") {
      help_ = true;
      continue;
    }
    // -h: help, or the height when a number follows and the command has -h|height.
    if (body == "h" && !has_value) {
      long long number = 0;
      const bool height =
          find("h") != nullptr && i + 1 < args.size() && parseIntStrict(args[i + 1], number);
      if (!height) {
        help_ = true;
        continue;
      }
    }
    const Flag* flag = find(body);
    if (!flag) return makeError(unknownFlag(arg, body));
    if (!flag->value_name.empty() && !has_value) {
      if (i + 1 >= args.size()) return makeError("flag '" + arg + "' needs a value");
      value = args[++i];
    }
    if (std::string problem = flag->parse(value); !problem.empty())
      return makeError("flag '" + arg + "': " + problem);
  }
  return positional;
}

std::string FlagSet::unknownFlag(const std::string& arg, const std::string& name) const {
  std::string message = "unknown flag '" + arg + "'";
  // The nearest name, when it is a few edits away (a third of its length, at least one), or
  // when the flag given is the start of exactly that name.
  const Flag* best = nullptr;
  std::string best_name;
  size_t best_distance = std::string::npos;
  for (const Flag& f : flags_) {
    for (const std::string& n : f.names) {
      if (n.size() == 1) continue;
      size_t distance = editDistance(name, n);
      if (name.size() >= 3 && n.compare(0, name.size(), name) == 0) distance = 1;
      if (distance < best_distance) {
        best = &f;
        best_name = n;
        best_distance = distance;
      }
    }
  }
  if (best && best_distance <= std::max<size_t>(1, best_name.size() / 3))
    message += "; did you mean '--" + best_name + "'?";
  return message;
}

std::string FlagSet::hint() const {
  // The synopsis starts with the command: "tessera render MODEL ..." -> "tessera render".
  std::string command = synopsis_.substr(0, synopsis_.find(' ', synopsis_.find(' ') + 1));
  return "Run '" + command + " --help' for the flags.\n";
}

std::string FlagSet::usage() const {
  std::ostringstream out;
  out << "usage: " << synopsis_ << "\n\nflags:\n";
  if (single_dash_)
    out << "  (one dash works as well: -fps 30 is --fps 30, as in the first demo)\n";
  for (const Flag& f : flags_) {
    std::string line = "  ";
    for (size_t i = 0; i < f.names.size(); ++i) {
      if (i) line += ", ";
      line += (f.names[i].size() == 1 ? "-" : "--") + f.names[i];
    }
    if (!f.value_name.empty()) line += " " + f.value_name;
    if (line.size() < 34)
      line.resize(34, ' ');
    else
      line += "  ";
    out << line << f.help << "\n";
  }
  out << "  -h, --help                      show this message\n";
  out << "  --version                       print tessera's version\n";
  return out.str();
}

}  // namespace tessera::cli
