// assimp's readers in a process of their own (assimp_loader.cpp): assimp 5.2 crashes, aborts on
// an assertion or loops forever on some broken files (fuzz/assimp_fuzz.cpp finds them within
// seconds), and no check before it can rule every one out. A child process reads the file first,
// with its memory capped and its time limited; only a file it read without harm is read again in
// tessera's own process. Private to tessera_io.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include <tessera/base/expected.h>

namespace tessera::io {

// Runs `work` in a forked child whose address space may grow by at most `memory_bytes` (not in
// sanitizer builds, whose shadow memory the limit would break) and which is killed after
// `seconds`. `work`'s error, a crash, an exhausted memory cap or the time running out each come
// back as one line naming `name`.
Expected<void> runIsolated(const std::function<Expected<void>()>& work, const std::string& name,
                           uint64_t memory_bytes, int seconds);

}  // namespace tessera::io
