// What other X clients do to a window, for tests: a file manager dropping a file (XDND), a
// window manager's close button (WM_DELETE_WINDOW) and its view of the windows that appear. Kept
// apart from the test files so that Xlib's macros (None, Bool, Status) stay out of them.
#pragma once

#include <string>
#include <vector>

namespace tessera::test {

// Drags `path` (as a text/uri-list) over `window` at (x, y) in its own coordinates on X display
// `display` and drops it; returns "" once the target has finished with the drop, else why not.
std::string dropFileOnWindow(const std::string& display, unsigned long window,
                             const std::string& path, int x, int y, int timeout_seconds);

// Asks `window` to close as a window manager does when its close button is clicked (ICCCM
// WM_PROTOCOLS / WM_DELETE_WINDOW); returns "" once sent, else why not.
std::string requestClose(const std::string& display, unsigned long window);

// The top-level windows mapped on a display from the watcher's construction on, as a window
// manager sees them appear (MapNotify on the root window).
class MappedWindows {
 public:
  explicit MappedWindows(const std::string& display);
  ~MappedWindows();
  MappedWindows(const MappedWindows&) = delete;
  MappedWindows& operator=(const MappedWindows&) = delete;
  bool watching() const { return display_ != nullptr; }
  // Every window mapped so far, in order (one mapped twice is listed twice).
  std::vector<unsigned long> mapped();

 private:
  void* display_ = nullptr;  // Display*
  std::vector<unsigned long> mapped_;
};

}  // namespace tessera::test
