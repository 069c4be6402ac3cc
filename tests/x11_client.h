// What other X clients do to a window, for tests: a file manager dropping a file (XDND) and a
// window manager's close button (WM_DELETE_WINDOW). Kept apart from the test files so that
// Xlib's macros (None, Bool, Status) stay out of them.
#pragma once

#include <string>

namespace tessera::test {

// Drags `path` (as a text/uri-list) over `window` at (x, y) in its own coordinates on X display
// `display` and drops it; returns "" once the target has finished with the drop, else why not.
std::string dropFileOnWindow(const std::string& display, unsigned long window,
                             const std::string& path, int x, int y, int timeout_seconds);

// Asks `window` to close as a window manager does when its close button is clicked (ICCCM
// WM_PROTOCOLS / WM_DELETE_WINDOW); returns "" once sent, else why not.
std::string requestClose(const std::string& display, unsigned long window);

}  // namespace tessera::test
