#include "animation_frames.h"

#include <algorithm>
#include <cmath>

#include "flags.h"

namespace tessera::cli {

Expected<FramePlan> animationFrames(const Animation& clip, int fps, const std::string& range) {
  FramePlan plan;
  if (range.empty()) {
    const double frames = std::round(static_cast<double>(clip.duration()) * fps);
    plan.count = static_cast<int>(std::clamp(frames, 1.0, 1e6));
    return plan;
  }
  const size_t colon = range.find(':');
  long long a = 0, b = 0;
  if (colon == std::string::npos || !parseIntStrict(range.substr(0, colon), a) ||
      !parseIntStrict(range.substr(colon + 1), b))
    return makeError("--frame-range: expected A:B (frame numbers from 0), got '" + range + "'");
  if (a < 0 || b < a || b >= 1000000)
    return makeError("--frame-range: expected 0 <= A <= B < 1000000, got " + range);
  plan.first = static_cast<int>(a);
  plan.count = static_cast<int>(b - a + 1);
  return plan;
}

std::string animationIndexError(const std::string& path, size_t count, int index) {
  const std::string n = std::to_string(count);
  return path +
         (count == 0 ? std::string(" has no animations")
                     : " has " + n + " animation" + (count == 1 ? "" : "s") +
                           " (--animation-index 0 to " + std::to_string(count - 1) + ")") +
         "; --animation-index " + std::to_string(index) + " is past the end";
}

float frameTime(const Animation& clip, int fps, int frame) {
  return clip.startTime() + static_cast<float>(static_cast<double>(frame) / fps);
}

}  // namespace tessera::cli
