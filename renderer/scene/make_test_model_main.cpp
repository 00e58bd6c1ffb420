// iblab_make_test_model OUT.glb: regenerates the textured test model (see test_model.hpp).
#include <cstdio>
#include <exception>

#include "scene/test_model.hpp"

int main(int argc, char** argv)
{
    if (argc != 2) {
        std::fprintf(stderr, "usage: %s OUT.glb   (the bundled copy is assets/models/material_spheres.glb)\n", argv[0]);
        return 2;
    }
    try {
        iblab::writeMaterialSpheresGlb(argv[1]);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s\n", e.what());
        return 1;
    }
    std::printf("wrote %s\n", argv[1]);
    return 0;
}
