#include "budget_flags.h"

#include <cctype>
#include <string>

namespace tessera::cli {

namespace {

// A byte count with an optional binary suffix: 1073741824, 1024M, 1G, 1GiB.
bool parseByteSize(std::string text, uint64_t& out) {
  uint64_t unit = 1;
  if (text.ends_with("iB") || text.ends_with("ib")) text.resize(text.size() - 2);
  if (!text.empty()) {
    switch (std::toupper(static_cast<unsigned char>(text.back()))) {
      case 'K':
        unit = uint64_t{1} << 10;
        break;
      case 'M':
        unit = uint64_t{1} << 20;
        break;
      case 'G':
        unit = uint64_t{1} << 30;
        break;
      case 'T':
        unit = uint64_t{1} << 40;
        break;
      default:
        break;
    }
    if (unit != 1) text.pop_back();
  }
  long long value = 0;
  if (!parseIntStrict(text, value) || value < 1) return false;
  if (static_cast<uint64_t>(value) > UINT64_MAX / unit) return false;
  out = static_cast<uint64_t>(value) * unit;
  return true;
}

}  // namespace

void addBudgetFlags(FlagSet& flags, io::LoadBudget& budget) {
  flags.addCustom("memory-limit", "SIZE",
                  "what a model may cost in memory, from which every other budget follows "
                  "(default 1G; K, M, G suffixes)",
                  [&budget](const std::string& v) -> std::string {
                    uint64_t bytes = 0;
                    if (!parseByteSize(v, bytes) || bytes < (uint64_t{1} << 20))
                      return "expected a size of at least 1M such as 512M or 2G, got '" + v + "'";
                    budget.memory_bytes = bytes;
                    return "";
                  });
  auto addCount = [&flags](const std::string& name, uint64_t* out, const std::string& help) {
    flags.addCustom(name, "N", help, [out](const std::string& v) -> std::string {
      long long n = 0;
      if (!parseIntStrict(v, n) || n < 1) return "expected a positive count, got '" + v + "'";
      *out = static_cast<uint64_t>(n);
      return "";
    });
  };
  addCount("max-triangles", &budget.max_triangles,
           "the most triangles a model may draw, after instancing (default: memory limit / 512, "
           "2097152)");
  addCount("max-texture-pixels", &budget.max_texture_pixels,
           "the most pixels one decoded texture may have (default: memory limit / 16, "
           "67108864 = 8192x8192)");
}

}  // namespace tessera::cli
