// The seam every backend implements.
#pragma once

#include <tessera/render/frame.h>
#include <tessera/render/options.h>
#include <tessera/scene/scene.h>

namespace tessera {

class Backend {
 public:
  virtual ~Backend() = default;
  virtual const char* name() const = 0;
  virtual void render(const Scene& scene, const RenderOptions& options, Frame& frame) = 0;
};

}  // namespace tessera
