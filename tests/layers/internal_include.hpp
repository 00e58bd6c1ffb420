#pragma once
// Not built: tests/layers/CMakeLists.txt checks it as if it were an app/ file, to prove that
// the layer check fails on an include of a header internal to another layer (the mesh pass
// is not on frame/'s public face).
#include "frame/mesh_pass.hpp"
