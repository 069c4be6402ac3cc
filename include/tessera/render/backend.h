// The seam every backend implements.
#pragma once

#include <tessera/base/expected.h>
#include <tessera/render/frame.h>
#include <tessera/render/options.h>
#include <tessera/scene/scene.h>

namespace tessera {

class Backend {
 public:
  virtual ~Backend() = default;
  virtual const char* name() const = 0;
  virtual void render(const Scene& scene, const RenderOptions& options, Frame& frame) = 0;
  // Whether the last render() succeeded. A backend that can fail at run time (a GPU that timed
  // out or was lost, a scene beyond a device's limits) leaves the frame cleared and says why.
  virtual Expected<void> lastResult() const { return {}; }
};

}  // namespace tessera
