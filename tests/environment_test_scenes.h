// Environments for the tests that light or show one (composite_test, pbr_test).
#pragma once

#include <memory>
#include <utility>

#include <tessera/scene/environment.h>

namespace tessera::test {

// A 64 x 32 panorama: `sky` above the horizon, `ground` below.
inline std::shared_ptr<const Environment> skyEnvironment(float3 sky, float3 ground) {
  EnvironmentImage image;
  image.width = 64;
  image.height = 32;
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 64; ++x) image.texels.push_back(y < 16 ? sky : ground);
  return std::make_shared<const Environment>(std::move(image));
}

}  // namespace tessera::test
