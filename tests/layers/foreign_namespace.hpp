// An ibl header that defines a function in bake's namespace, as
// layers.namespace_check_catches_a_foreign_namespace checks it: the namespace check must
// fail on it. The forward declaration beside it is allowed. Nothing compiles this file.
#pragma once

namespace iblab::bake {

struct BakeSettings;

inline float mipRoughness(int level, int levels) { return float(level) / float(levels - 1); }

} // namespace iblab::bake
