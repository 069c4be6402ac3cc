#include "progress.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "flags.h"

namespace tessera::cli {

namespace {

// Off a terminal, a line at most this often: enough to see movement in a CI log without
// flooding it (a 1,000-frame turntable at 50 frames/s writes 7 lines, not 1,000).
constexpr double kLogIntervalSeconds = 3.0;

std::string formatSeconds(double seconds) {
  const long long whole = std::llround(std::max(seconds, 0.0));
  char text[48];
  if (whole >= 3600)
    std::snprintf(text, sizeof text, "%lldh%02lldm", whole / 3600, whole / 60 % 60);
  else if (whole >= 60)
    std::snprintf(text, sizeof text, "%lldm%02llds", whole / 60, whole % 60);
  else
    std::snprintf(text, sizeof text, "%llds", whole);
  return text;
}

}  // namespace

void addProgressFlags(FlagSet& flags, ProgressFlags& p) {
  flags.addSwitch("quiet", &p.quiet,
                  "no progress and no summary line; errors and warnings are still printed");
  flags.addSwitch("progress", &p.progress,
                  "show progress on stderr for a single frame too (on by default for 2 or more)");
}

std::string Progress::line(const std::string& label, int done, int total, double seconds) {
  // The rate over the whole run so far: steady enough for a time left without smoothing.
  const double rate = seconds > 0.0 ? done / seconds : 0.0;
  char text[160];
  std::snprintf(text, sizeof text, "%s %d/%d, %.*f frames/s, ", label.c_str(), done, total,
                rate < 10.0 ? 1 : 0, rate);
  std::string out = text;
  if (rate > 0.0)
    out += formatSeconds((total - done) / rate) + " left";
  else
    out += "time left unknown";
  return out;
}

Progress::Progress(std::string label, int total, const ProgressFlags& flags)
    : label_(std::move(label)),
      total_(total),
      enabled_(!flags.quiet && (total > 1 || flags.progress)),
      terminal_(isatty(STDERR_FILENO) == 1),
      start_(Clock::now()) {}

double Progress::elapsedSeconds() const {
  return std::chrono::duration<double>(Clock::now() - start_).count();
}

void Progress::update(int done) {
  done_ = done;
  if (!enabled_) return;
  const double seconds = elapsedSeconds();
  if (terminal_) {
    const std::string text = line(label_, done, total_, seconds);
    std::fprintf(stderr, "\r%s%*s", text.c_str(),
                 static_cast<int>(last_length_ > text.size() ? last_length_ - text.size() : 0), "");
    last_length_ = text.size();
    std::fflush(stderr);
    return;
  }
  if (seconds - last_line_seconds_ < kLogIntervalSeconds || done >= total_) return;
  last_line_seconds_ = seconds;
  std::fprintf(stderr, "%s\n", line(label_, done, total_, seconds).c_str());
}

void Progress::finish() {
  if (!enabled_) return;
  const double seconds = elapsedSeconds();
  const std::string text =
      line(label_, done_, total_, seconds) + ", done in " + formatSeconds(seconds);
  if (terminal_)
    std::fprintf(stderr, "\r%s%*s\n", text.c_str(),
                 static_cast<int>(last_length_ > text.size() ? last_length_ - text.size() : 0), "");
  else
    std::fprintf(stderr, "%s\n", text.c_str());
}

}  // namespace tessera::cli
