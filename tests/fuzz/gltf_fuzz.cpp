// libFuzzer target: any bytes, as a .glb or .gltf model. The loader must return a model
// whose meshes validate or throw iblab::Error; anything else is a bug.
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>

#include <unistd.h>

#include "io/error.hpp"
#include "scene/gltf_model.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    const bool binary = size >= 4 && data[0] == 'g' && data[1] == 'l' && data[2] == 'T' && data[3] == 'F';
    const std::string path = "/tmp/iblab-fuzz-model-" + std::to_string(::getpid()) + (binary ? ".glb" : ".gltf");
    std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(data), std::streamsize(size));
    try {
        iblab::ModelLoadOptions options;
        options.maxVertices = 1u << 20; // budgets small enough that no input can make a run slow
        options.maxIndices = 1u << 22;
        options.maxInputBytes = 64u << 20;
        options.maxTextureBytes = 64u << 20;
        const iblab::ModelData model = iblab::loadGltfModel(path, options);
        for (const iblab::MeshInstance& instance : model.instances) instance.mesh.validate("fuzz");
    } catch (const iblab::Error&) {
    }
    std::remove(path.c_str());
    return 0;
}
