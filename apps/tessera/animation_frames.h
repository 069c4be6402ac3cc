// Which frames of a glTF animation `tessera render --animation-index` draws, and when; the
// message for a clip index past the end (render and view).
#pragma once

#include <string>

#include <tessera/base/expected.h>
#include <tessera/scene/animation.h>

namespace tessera::cli {

struct FramePlan {
  int first = 0;  // frame numbers from the clip's start, at the frame rate
  int count = 1;
};

// The clip's frames at `fps`: its length is round(duration * fps) frames (at least one), frame
// i at start + i / fps, so a looping GIF joins its last frame to its first without a repeat.
// `range` "A:B" (inclusive, from 0) picks frames A to B instead; frames past the clip's end hold
// its last pose. A malformed or backward range is an error saying what was expected.
Expected<FramePlan> animationFrames(const Animation& clip, int fps, const std::string& range);

// `render` and `view`'s message for --animation-index `index` past the `count` clips of the model
// at `path`: how many there are.
std::string animationIndexError(const std::string& path, size_t count, int index);

// The time (seconds, the file's time line) of frame `frame` of the clip.
float frameTime(const Animation& clip, int fps, int frame);

}  // namespace tessera::cli
