// A minimal XDND drag source for tests: drops one file on an X window, as a file manager would.
// Kept apart from the test files so that Xlib's macros (None, Bool, Status) stay out of them.
#pragma once

#include <string>

namespace tessera::test {

// Drags `path` (as a text/uri-list) over `window` at (x, y) in its own coordinates on X display
// `display` and drops it; returns "" once the target has finished with the drop, else why not.
std::string dropFileOnWindow(const std::string& display, unsigned long window,
                             const std::string& path, int x, int y, int timeout_seconds);

}  // namespace tessera::test
