/* Base-colour textures and alpha masks (docs/scene-format.md, "Textures and alpha masks"): the
   bilinear texture lookup and the two things every stage asks of it, the reflectances of a
   surface point (surface_material: camera pass, photon hits, path vertices, shading points of
   the gather and the path tracer, film layers, radiosity's image) and whether a ray hit on a
   masked triangle counts (surface_alpha_visible: scene traversal, so every ray agrees).

   Layout (render/scene_textures.h packs it): texture_info[i] = (first texel, width, height,
   wrap_u | wrap_v << 8); texels are RGBA8 words r | g << 8 | b << 16 | a << 24, each image's rows
   top first, so v = 0 is an image's top row (glTF's convention; the OBJ loader flips vt's v);
   triangle_uvs holds 2 float4 per leaf-order triangle, (u0, v0, u1, v1), (u2, v2, 0, 0).
   Colour channels are sRGB-encoded and linearised texel by texel before the bilinear blend, so
   the filter averages reflectances, not encoded values; alpha is linear. The linear value of each
   8-bit code comes from a 256-entry table (texture_srgb_table, computed in double on the host):
   a load instead of a pow per channel and texel, which made Sponza's camera pass 2.6 times as
   slow on PoCL (docs/scene-format.md has the measurement). There are no mipmaps:
   a distant textured surface is sampled at one point per shading point, which the film's passes
   (and the camera pass's one ray per pixel) do not average away: aliasing, not bias. */
#ifndef PM_TEXTURE_H
#define PM_TEXTURE_H

#include "brdf.h"
#include "kernel_globals.h"
#include "triangles.h"

/* Texel column (or row) i of an image `size` texels wide under a wrap mode, in [0, size). i is
   a whole number in float, already limited to +-2^24, so the arithmetic stays exact. */
PM_DEVICE int texture_wrap(float i, uint size, uint mode)
{
  float n = (float)size, m;
  if (mode == PM_WRAP_CLAMP) {
    m = pm_fminf(pm_fmaxf(i, 0.0f), n - 1.0f);
  } else if (mode == PM_WRAP_MIRROR) {
    /* Period 2n: 0 .. n-1 forwards, then n-1 .. 0 backwards. */
    m = i - 2.0f * n * pm_floorf(i / (2.0f * n));
    if (m >= n) m = 2.0f * n - 1.0f - m;
  } else {
    m = i - n * pm_floorf(i / n);
  }
  return pm_min_i(pm_max_i((int)m, 0), (int)size - 1);
}

/* Texel (x, y) of the image `info` describes: rgb linearised through srgb_table when srgb is
   set, else as stored (over 255); alpha as stored. */
PM_DEVICE float4 texture_texel(PM_GLOBAL const uint* texels, PM_GLOBAL const float* srgb_table, uint4 info, int x, int y,
                               int srgb)
{
  uint t = PM_LOAD(&texels[info.x + (uint)y * info.y + (uint)x]);
  uint r = t & 255u, g = (t >> 8) & 255u, b = (t >> 16) & 255u;
  float a = (float)(t >> 24) * (1.0f / 255.0f);
  if (srgb) return PM_MAKE_FLOAT4(PM_LOAD(&srgb_table[r]), PM_LOAD(&srgb_table[g]), PM_LOAD(&srgb_table[b]), a);
  return PM_MAKE_FLOAT4((float)r * (1.0f / 255.0f), (float)g * (1.0f / 255.0f), (float)b * (1.0f / 255.0f), a);
}

/* Bilinear lookup of texture `texture` at (u, v): the four texels around u * width - 0.5,
   v * height - 0.5 (texel centres at half-integers), wrapped by the texture's modes. */
PM_DEVICE float4 texture_sample(PM_GLOBAL const uint4* texture_info, PM_GLOBAL const uint* texels,
                                PM_GLOBAL const float* srgb_table, uint texture, float u, float v, int srgb)
{
  uint4 info = PM_LOAD(&texture_info[texture]);
  if (!pm_isfinite(u)) u = 0.0f;
  if (!pm_isfinite(v)) v = 0.0f;
  /* Beyond 2^24 texels floats no longer hold whole texel positions; such coordinates are
     broken input, and the limit keeps the wrap's arithmetic and int conversions defined. */
  float x = pm_fminf(pm_fmaxf(u * (float)info.y - 0.5f, -16777216.0f), 16777216.0f);
  float y = pm_fminf(pm_fmaxf(v * (float)info.z - 0.5f, -16777216.0f), 16777216.0f);
  float x0 = pm_floorf(x), y0 = pm_floorf(y);
  float fx = x - x0, fy = y - y0;
  uint wrap_u = info.w & 255u, wrap_v = (info.w >> 8) & 255u;
  int xa = texture_wrap(x0, info.y, wrap_u), xb = texture_wrap(x0 + 1.0f, info.y, wrap_u);
  int ya = texture_wrap(y0, info.z, wrap_v), yb = texture_wrap(y0 + 1.0f, info.z, wrap_v);
  float4 t00 = texture_texel(texels, srgb_table, info, xa, ya, srgb), t10 = texture_texel(texels, srgb_table, info, xb, ya, srgb);
  float4 t01 = texture_texel(texels, srgb_table, info, xa, yb, srgb), t11 = texture_texel(texels, srgb_table, info, xb, yb, srgb);
  float w00 = (1.0f - fx) * (1.0f - fy), w10 = fx * (1.0f - fy), w01 = (1.0f - fx) * fy, w11 = fx * fy;
  return PM_MAKE_FLOAT4(w00 * t00.x + w10 * t10.x + w01 * t01.x + w11 * t11.x,
                        w00 * t00.y + w10 * t10.y + w01 * t01.y + w11 * t11.y,
                        w00 * t00.z + w10 * t10.z + w01 * t01.z + w11 * t11.z,
                        w00 * t00.w + w10 * t10.w + w01 * t01.w + w11 * t11.w);
}

/* Texture coordinates at barycentrics (b1, b2) of leaf-order triangle tri. */
PM_DEVICE void triangle_uv_at(PM_GLOBAL const float4* triangle_uvs, int tri, float b1, float b2, float* u, float* v)
{
  float4 a = PM_LOAD(&triangle_uvs[2 * tri]), c = PM_LOAD(&triangle_uvs[2 * tri + 1]);
  float b0 = 1.0f - b1 - b2;
  *u = b0 * a.x + b1 * a.z + b2 * c.x;
  *v = b0 * a.y + b1 * a.w + b2 * c.y;
}

PM_DEVICE uint material_flags(const Material* m) { return PM_AS_UINT(m->diffuse.w); }
PM_DEVICE uint material_base_texture(const Material* m) { return PM_AS_UINT(m->texture.x); } /* texture + 1, 0: none */

/* A texel's colour applied to a material: rho_d, and with PM_MATERIAL_TINT_SPECULAR (glTF's base
   colour, which colours the metallic lobe too) rho_s and the mirror. */
PM_DEVICE void material_apply_tint(Material* m, Vec3 tint)
{
  m->diffuse.x *= tint.x;
  m->diffuse.y *= tint.y;
  m->diffuse.z *= tint.z;
  if (material_flags(m) & PM_MATERIAL_TINT_SPECULAR) {
    m->glossy.x *= tint.x;
    m->glossy.y *= tint.y;
    m->glossy.z *= tint.z;
    m->mirror.x *= tint.x;
    m->mirror.y *= tint.y;
    m->mirror.z *= tint.z;
  }
}

/* The material at point pos of leaf-order triangle tri: material_index's reflectances, times its
   base-colour texture there when it has one (untextured materials read nothing more). */
PM_DEVICE Material surface_material(const KernelGlobals* kg, int material_index, int tri, Vec3 pos)
{
  Material m = material_load(kg->materials, material_index);
  uint texture = material_base_texture(&m);
  if (texture == 0u || tri < 0) return m;
  float b1, b2, u, v;
  scene_triangle_barycentrics(kg->triangles, tri, pos, &b1, &b2);
  triangle_uv_at(kg->triangle_uvs, tri, b1, b2, &u, &v);
  float4 t = texture_sample(kg->texture_info, kg->texels, kg->texture_srgb_table, texture - 1u, u, v, 1);
  material_apply_tint(&m, vec3(t.x, t.y, t.z));
  return m;
}

/* Whether a hit at barycentrics (b1, b2) of triangle tri, whose material m has an alpha mask,
   is there: factor * the mask texel's channel (1 without a mask texture) >= cutoff (glTF
   alphaMode MASK; MTL map_d). Below the cutoff every ray passes through. */
PM_DEVICE int material_alpha_visible(const KernelGlobals* kg, const Material* m, int tri, float b1, float b2)
{
  float alpha = m->texture.z;
  uint mask = PM_AS_UINT(m->texture.y);
  if (mask != 0u) {
    float u, v;
    triangle_uv_at(kg->triangle_uvs, tri, b1, b2, &u, &v);
    float4 t = texture_sample(kg->texture_info, kg->texels, kg->texture_srgb_table, mask - 1u, u, v, 0);
    uint channel = (material_flags(m) >> PM_MATERIAL_ALPHA_CHANNEL_SHIFT) & 3u;
    alpha *= channel == 0u ? t.x : channel == 1u ? t.y : channel == 2u ? t.z : t.w;
  }
  return alpha >= m->texture.w;
}

/* The alpha test of a hit at pos on leaf-order triangle tri (its record flagged
   PM_TRIANGLE_MASKED) with material material_index. */
PM_DEVICE int surface_alpha_visible(const KernelGlobals* kg, int material_index, int tri, Vec3 pos)
{
  Material m = material_load(kg->materials, material_index);
  float b1, b2;
  scene_triangle_barycentrics(kg->triangles, tri, pos, &b1, &b2);
  return material_alpha_visible(kg, &m, tri, b1, b2);
}

#endif
