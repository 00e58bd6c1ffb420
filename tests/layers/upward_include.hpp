// Not compiled: the layer check's own test reads this file as if it were part of the ibl layer
// (the math), which must not reach the frame renderer above it.
#pragma once
#include "ibl/sampling.hpp"
#include "frame/renderer.hpp"
