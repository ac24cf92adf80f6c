// The texture colour of each radiosity element (rad_texture_tint): an element is a vertex of the
// refined mesh standing for the surface around it, weighted by its hat function (1 at the
// vertex, falling linearly to 0 at the one-ring's far edges). Its reflectance is therefore the
// material's times the texture's hat-weighted mean over the one-ring,
//   tint_e = sum_r A_r sum_s b_k(s) t(s) / sum_r A_r sum_s b_k(s),
// over the element's one-ring triangles r (area A_r, the element at corner k), with t the linear
// texture colour (kernels/common/texture.h, the same lookup the device makes) at 16 points s per
// triangle: the centroids of its 4 x 4 subdivision into equal triangles, b_k the hat function
// there. A uniform texture gives its colour exactly; detail finer than a sub-triangle averages
// out, which is what the element can represent. The image still shows every texel: the camera
// pass's shading points read the texture themselves (radiosity_interpolate.h).
#pragma once

#include <vector>

#include "render/radiosity/mesh_refinement.h"
#include "render/radiosity/radiosity_elements.h"
#include "render/scene_textures.h"

namespace pm {

// One float4 per element: (mean linear r, g, b, 0); (1, 1, 1, 0) for elements of untextured
// materials (nothing reads those). textures: the scene's packed images (pack_texture_images).
std::vector<float4> radiosity_texture_tints(const Scene& scene, const RefinedMesh& mesh,
                                            const RadiosityElements& elements, const DeviceTextures& textures);

}  // namespace pm
