// The whole math module.
#pragma once

#include <tessera/math/mat.h>
#include <tessera/math/projection.h>
#include <tessera/math/quat.h>
#include <tessera/math/vec.h>
