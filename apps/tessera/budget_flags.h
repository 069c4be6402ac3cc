// The flags that bound what a model may cost (io::LoadBudget), shared by every command that
// loads models: render, info, view and bench.
#pragma once

#include <tessera/io/model_loader.h>

#include "flags.h"

namespace tessera::cli {

// --memory-limit SIZE (bytes, or with K, M, G: 1536M, 2G), --max-triangles N and
// --max-texture-pixels N.
void addBudgetFlags(FlagSet& flags, io::LoadBudget& budget);

}  // namespace tessera::cli
