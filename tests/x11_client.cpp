// XDND version 5 as the source side (freedesktop.org's Drag-and-Drop Protocol for the X Window
// System): XdndEnter, XdndPosition, wait for XdndStatus, XdndDrop, serve the selection, wait for
// XdndFinished. The ICCCM close request, and the root window's MapNotify events.
#include "x11_client.h"

#include <X11/Xatom.h>
#include <X11/Xlib.h>
#include <sys/select.h>

#include <chrono>
#include <cstdio>

namespace tessera::test {

namespace {

void sendClientMessage(Display* display, Window to, Atom type, long l0, long l1, long l2, long l3,
                       long l4) {
  XEvent event{};
  event.xclient.type = ClientMessage;
  event.xclient.display = display;
  event.xclient.window = to;
  event.xclient.message_type = type;
  event.xclient.format = 32;
  event.xclient.data.l[0] = l0;
  event.xclient.data.l[1] = l1;
  event.xclient.data.l[2] = l2;
  event.xclient.data.l[3] = l3;
  event.xclient.data.l[4] = l4;
  XSendEvent(display, to, False, NoEventMask, &event);
  XFlush(display);
}

// "file://" + the path, with the characters a URI cannot hold percent-encoded.
std::string fileUri(const std::string& path) {
  std::string uri = "file://";
  for (unsigned char c : path) {
    if (c <= ' ' || c == '%' || c >= 0x7f) {
      char escaped[4];
      std::snprintf(escaped, sizeof escaped, "%%%02X", c);
      uri += escaped;
    } else {
      uri += static_cast<char>(c);
    }
  }
  return uri + "\r\n";
}

}  // namespace

std::string dropFileOnWindow(const std::string& display_name, unsigned long target,
                             const std::string& path, int x, int y, int timeout_seconds) {
  Display* display = XOpenDisplay(display_name.c_str());
  if (display == nullptr) return "cannot open display " + display_name;
  const Window root = DefaultRootWindow(display);
  const Window source = XCreateSimpleWindow(display, root, 0, 0, 1, 1, 0, 0, 0);
  auto atom = [&](const char* name) { return XInternAtom(display, name, False); };
  const Atom selection = atom("XdndSelection"), enter = atom("XdndEnter"),
             position = atom("XdndPosition"), status = atom("XdndStatus"), drop = atom("XdndDrop"),
             finished = atom("XdndFinished"), leave = atom("XdndLeave"),
             copy = atom("XdndActionCopy"), uri_list = atom("text/uri-list");
  XSetSelectionOwner(display, selection, source, CurrentTime);

  int root_x = 0, root_y = 0;
  Window child;
  XTranslateCoordinates(display, target, root, x, y, &root_x, &root_y, &child);
  const long src = static_cast<long>(source);
  sendClientMessage(display, target, enter, src, 5L << 24, static_cast<long>(uri_list), 0, 0);
  sendClientMessage(display, target, position, src, 0, (long{root_x} << 16) | root_y, CurrentTime,
                    static_cast<long>(copy));

  const std::string data = fileUri(path);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(timeout_seconds);
  std::string result = "timed out waiting for the drop target";
  bool dropped = false;
  while (std::chrono::steady_clock::now() < deadline) {
    if (XPending(display) == 0) {
      fd_set fds;
      FD_ZERO(&fds);
      FD_SET(ConnectionNumber(display), &fds);
      timeval tv{0, 100 * 1000};
      select(ConnectionNumber(display) + 1, &fds, nullptr, nullptr, &tv);
      continue;
    }
    XEvent event;
    XNextEvent(display, &event);
    if (event.type == ClientMessage && event.xclient.message_type == status && !dropped) {
      if ((event.xclient.data.l[1] & 1) == 0) {
        sendClientMessage(display, target, leave, src, 0, 0, 0, 0);
        result = "the window refused the drop (it took no text/uri-list)";
        break;
      }
      sendClientMessage(display, target, drop, src, 0, CurrentTime, 0, 0);
      dropped = true;
    } else if (event.type == SelectionRequest) {
      // The target asks for the dragged data: put it on its property and tell it so.
      const XSelectionRequestEvent& request = event.xselectionrequest;
      XEvent reply{};
      reply.xselection.type = SelectionNotify;
      reply.xselection.display = display;
      reply.xselection.requestor = request.requestor;
      reply.xselection.selection = request.selection;
      reply.xselection.target = request.target;
      reply.xselection.time = request.time;
      reply.xselection.property = None;
      if (request.target == uri_list && request.property != None) {
        XChangeProperty(display, request.requestor, request.property, uri_list, 8, PropModeReplace,
                        reinterpret_cast<const unsigned char*>(data.data()),
                        static_cast<int>(data.size()));
        reply.xselection.property = request.property;
      }
      XSendEvent(display, request.requestor, False, NoEventMask, &reply);
      XFlush(display);
    } else if (event.type == ClientMessage && event.xclient.message_type == finished) {
      result = "";
      break;
    }
  }
  XDestroyWindow(display, source);
  XCloseDisplay(display);
  return result;
}

std::string requestClose(const std::string& display_name, unsigned long window) {
  Display* display = XOpenDisplay(display_name.c_str());
  if (display == nullptr) return "cannot open display " + display_name;
  const Atom protocols = XInternAtom(display, "WM_PROTOCOLS", False);
  const Atom delete_window = XInternAtom(display, "WM_DELETE_WINDOW", False);
  sendClientMessage(display, window, protocols, static_cast<long>(delete_window), CurrentTime, 0, 0,
                    0);
  XSync(display, False);
  XCloseDisplay(display);
  return "";
}

MappedWindows::MappedWindows(const std::string& display_name) {
  Display* display = XOpenDisplay(display_name.c_str());
  if (display == nullptr) return;
  XSelectInput(display, DefaultRootWindow(display), SubstructureNotifyMask);
  XSync(display, False);  // selected before anything the caller starts next maps a window
  display_ = display;
}

MappedWindows::~MappedWindows() {
  if (display_) XCloseDisplay(static_cast<Display*>(display_));
}

std::vector<unsigned long> MappedWindows::mapped() {
  Display* display = static_cast<Display*>(display_);
  if (display == nullptr) return mapped_;
  XSync(display, False);
  while (XPending(display) > 0) {
    XEvent event;
    XNextEvent(display, &event);
    if (event.type == MapNotify) mapped_.push_back(event.xmap.window);
  }
  return mapped_;
}

}  // namespace tessera::test
