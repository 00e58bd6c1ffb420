#include "cycle_a.glsl"
void main() {}
