#pragma once
// A bake made by another tool, read as an environment: `--env` takes one wherever it takes a
// map. loadEnvironment() hands such a spec here; the Environment it returns carries the
// bake's cubes (turned into iblab's orientation and units) in Environment::imported, and an
// equirect made from its sky for what needs pixels (the sky pass, the reference renderer);
// BakeJob then uploads the cubes instead of baking them (bake/bake_job.cpp).
//
// Accepted specs (docs/engine-import.md has the conventions and where each comes from):
//   NAME_ibl.ktx                     Filament cmgen --format=ktx: prefiltered cube (KTX1), the
//                                    SH in its `sh` key, NAME_skybox.ktx beside it for the sky
//   DIR with specular.ktx2 and       the glTF-IBL-Sampler / glTF Sample Viewer pair (KTX2):
//   diffuse.ktx2 (or ggx/ and        GGX specular cube with lod = roughness x (levels - 1),
//   lambertian/ subfolders)          Lambertian diffuse cube
//   SPECULAR.ktx2,DIFFUSE.ktx2       the same pair named explicitly
//   DIR with bake.json               iblab's own `iblab bake --out DIR` (bake/bake_files.hpp)
// Every failure is an iblab::Error naming the file and the problem.
#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "ibl/image.hpp"
#include "ibl/sh.hpp"

namespace iblab {

enum class ImportedBakeKind { Cmgen, Khronos, Iblab };

struct ImportedBake {
    ImportedBakeKind kind = ImportedBakeKind::Cmgen;
    std::vector<std::string> files; // what was read, for messages and metadata
    // Cube levels as KtxCube strips (ktx_cube.hpp), already in iblab's orientation: the texel
    // at GL direction d holds the radiance arriving from iblab's world direction d
    // (conventions.glsl), as iblab's own bakes do.
    std::vector<ImageRGB32F> prefiltered;
    // How roughness is spread over the mips: the values of bake::RoughnessLayout (0 linear:
    // m / (levels - 1), the glTF-IBL-Sampler's; 1 quadratic, Filament's).
    int roughnessLayout = 0;
    ImageRGB32F sky;                       // level 0 of the radiance cube, a strip
    std::optional<ImageRGB32F> irradiance; // E (a white sky of radiance 1 gives pi), a strip
    std::optional<SH9Color> shIrradiance;  // E_lm in kSh9Convention
    // iblab's own bakes also carry their windowed SH (what their shading reads); others none.
    struct WindowedSh {
        SH9Color irradiance;
        ShWindow window = ShWindow::None;
        double width = 0.0;
    };
    std::optional<WindowedSh> shWindowed;
    std::vector<std::string> notes;        // one line each: what the import assumed or repaired
};

// What made the bake and in which format, for status lines: "Filament cmgen bake (KTX1)".
const char* importedBakeFormat(ImportedBakeKind kind);

// Whether loadEnvironment should read spec as another tool's bake.
bool isImportedBakeSpec(const std::string& spec);

// Reads the bake; `equirect` gets its sky as a 4 face x 2 face equirect (nearest texel: it
// is what the sky and reference show, not what any error is measured against).
std::shared_ptr<const ImportedBake> loadImportedBake(const std::string& spec, ImageRGB32F& equirect);

// Orientation: a cube whose texel at GL direction s holds iblab's world direction
// fileToWorld(s) (a signed axis permutation), resampled so that the texel at d holds d.
// Exact (texel centres map onto texel centres): no filtering.
struct AxisMap {
    int axis[3] = {0, 1, 2};      // world component k comes from file component axis[k]
    double sign[3] = {1, 1, 1};
    glm::dvec3 apply(glm::dvec3 v) const { return {sign[0] * v[axis[0]], sign[1] * v[axis[1]], sign[2] * v[axis[2]]}; }
    AxisMap inverse() const;
};
ImageRGB32F reorientCubeStrip(const ImageRGB32F& strip, const AxisMap& fileToWorld);
// The equirect of a cube strip, nearest texel.
ImageRGB32F cubeStripToEquirect(const ImageRGB32F& strip, int width);

// Filament's SH as cmgen writes it (`sh` key, sh.txt): nine RGB coefficients c_i, "pre-scaled"
// so that sum c_i p_i(n) = E(n) / pi, p = 1, y, z, x, xy, yz, 3z^2 - 1, xz, x^2 - y^2 in the
// cube's own frame. Returns iblab's E_lm in world axes (fileToWorld as for the cube).
SH9Color shFromFilament(const std::array<glm::dvec3, 9>& coefficients, const AxisMap& fileToWorld);
// Parses the `sh` value: nine lines of three numbers. Throws Error naming `file`.
std::array<glm::dvec3, 9> parseFilamentSh(const std::string& text, const std::string& file);

// The orientations of the tools' cubes (docs/engine-import.md says how each was found).
AxisMap cmgenFileToWorld();
AxisMap khronosFileToWorld();

} // namespace iblab
