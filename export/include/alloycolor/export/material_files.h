// Files for RGB renderers and material models, from RendererMaterials
// (renderer_materials.h). Every one states its colour space — linear sRGB, i.e. Rec. 709
// primaries with the D65 white, the truth computed under D65 with the CIE 1931 2-degree
// observer — and how its numbers were obtained.
//
//  - Mitsuba 3 RGB variants: <bsdf type="conductor"> with <rgb name="eta"> and
//    <rgb name="k"> (the conductor plugin takes eta and k as textures; an rgb value is
//    an sRGB-primaries spectrum in the RGB variants).
//  - Blender (4.x) Python: a Metallic BSDF node (ShaderNodeBsdfMetallic) in
//    fresnel_type 'PHYSICAL_CONDUCTOR' with its IOR and Extinction vector inputs, and in
//    'F82' mode with Base Color = F0 and Edge Tint = the F82 tint.
//  - MaterialX (1.38 and later): a conductor_bsdf (ior, extinction: color3; roughness:
//    vector2) feeding surface -> surfacematerial, in a document with
//    colorspace="lin_rec709" (MaterialX's name for linear sRGB), node definitions as in
//    libraries/pbrlib/pbrlib_defs.mtlx and stdlib_defs.mtlx.
//  - glTF 2.0: an asset with one material, pbrMetallicRoughness with metallicFactor 1,
//    roughnessFactor, baseColorFactor = F0 (clamped to [0, 1] as the schema requires,
//    with a note in extras), alpha 1. glTF colours are linear Rec. 709.
//  - JSON (RendererMaterialsJson): every fitted number and the largest CIEDE2000
//    difference of each approximation over 0-85 degrees.
#ifndef ALLOYCOLOR_EXPORT_MATERIAL_FILES_H_
#define ALLOYCOLOR_EXPORT_MATERIAL_FILES_H_

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "alloycolor/export/renderer_materials.h"

namespace alloycolor::exports {

inline constexpr char kColorSpaceNote[] =
    "linear sRGB (Rec. 709 primaries, D65 white); spectral truth under CIE D65, CIE 1931 "
    "2-degree observer";

// Every number of `m` with its fit and error, and the colour space.
nlohmann::json RendererMaterialsJson(const RendererMaterials& m, const std::string& material);

std::string MitsubaRgbConductorXml(const RendererMaterials& m, const std::string& material,
                                   const std::string& id,
                                   const std::vector<std::string>& header = {});
std::string BlenderMetallicScript(const RendererMaterials& m, const std::string& material,
                                  const std::string& name,
                                  const std::vector<std::string>& header = {});
// roughness in [0, 1] (MaterialX's and glTF's own roughness parameters).
std::string MaterialXDocument(const RendererMaterials& m, const std::string& material,
                              const std::string& name, double roughness,
                              const std::vector<std::string>& header = {});
std::string GltfMaterial(const RendererMaterials& m, const std::string& material,
                         const std::string& name, double roughness, const std::string& generator);

}  // namespace alloycolor::exports

#endif  // ALLOYCOLOR_EXPORT_MATERIAL_FILES_H_
