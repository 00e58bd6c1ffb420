#pragma once
// PRIVATE to iblab_scene (includes tinygltf): glTF materials as PbrMaterial, and the
// textures they use. Factors are clamped to their ranges (non-finite ones fall back to the
// spec's defaults), KHR_materials_emissive_strength scales the emissive factor, and each
// image is decoded on first use, once per colour interpretation (sRGB for base colour and
// emission, linear for the rest), within ModelLoadOptions' texture budgets. Nothing here
// fails the load: a texture that is missing, undecodable or over budget leaves its slot
// empty, so that the material falls back to its factors, with one warning per image.
#include <vector>

#include <tiny_gltf.h>

#include "scene/gltf_model.hpp"
#include "scene/internal/gltf_document.hpp"

namespace iblab::scene_detail {

// Appends the file's materials to out.materials (index for index), the decoded textures
// they reference to out.textures and the problems met to out.warnings.
void convertMaterials(const ModelLoadOptions& options, const tinygltf::Model& gltf, const std::vector<ImageSource>& images,
                      ModelData& out);

} // namespace iblab::scene_detail
