// Progress of long work (`render` turntables, animations and sequences; `cube`) on stderr.
// On a terminal: one line rewritten in place. Elsewhere (a log, a pipe, CI): a line every few
// seconds and one at the end, so a log shows the work is moving. Each line says the frames done
// and the total, the rate in frames per second and the time left.
#pragma once

#include <chrono>
#include <string>

namespace tessera::cli {

class FlagSet;

// --quiet and --progress (f3d's names). Quiet wins when both are given.
struct ProgressFlags {
  bool quiet = false;     // no progress and no "wrote ..." summary; errors and warnings stay
  bool progress = false;  // progress for a single frame too (by default: work of 2+ frames)
};

void addProgressFlags(FlagSet& flags, ProgressFlags& p);

class Progress {
 public:
  Progress(std::string label, int total, const ProgressFlags& flags = {});
  void update(int done);
  void finish();

  // "cube: frame 12/120, 8.5 frames/s, 13s left": what each line says.
  static std::string line(const std::string& label, int done, int total, double seconds);

 private:
  using Clock = std::chrono::steady_clock;
  double elapsedSeconds() const;

  std::string label_;
  int total_;
  bool enabled_;
  bool terminal_;
  int done_ = 0;
  size_t last_length_ = 0;  // of the line on the terminal, to blank what a shorter one leaves
  Clock::time_point start_;
  double last_line_seconds_ = 0.0;  // when the last line went out (not on a terminal)
};

}  // namespace tessera::cli
