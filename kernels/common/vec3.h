/* Three-component float vectors for the shared kernel code. Vec3 is a plain 12-byte struct on
   every backend (never float3, which is 16 bytes in OpenCL), so it can sit in shared structs. */
#ifndef PM_VEC3_H
#define PM_VEC3_H

typedef struct Vec3 { float x, y, z; } Vec3;

PM_DEVICE Vec3 vec3(float x, float y, float z) { Vec3 r; r.x = x; r.y = y; r.z = z; return r; }
PM_DEVICE Vec3 vec3_splat(float s) { return vec3(s, s, s); }
PM_DEVICE Vec3 vec3_from_float4(float4 v) { return vec3(v.x, v.y, v.z); }
PM_DEVICE float4 vec3_to_float4(Vec3 v, float w) { return PM_MAKE_FLOAT4(v.x, v.y, v.z, w); }
PM_DEVICE Vec3 vec3_add(Vec3 a, Vec3 b) { return vec3(a.x + b.x, a.y + b.y, a.z + b.z); }
PM_DEVICE Vec3 vec3_sub(Vec3 a, Vec3 b) { return vec3(a.x - b.x, a.y - b.y, a.z - b.z); }
PM_DEVICE Vec3 vec3_mul(Vec3 a, Vec3 b) { return vec3(a.x * b.x, a.y * b.y, a.z * b.z); }
PM_DEVICE Vec3 vec3_scale(Vec3 a, float s) { return vec3(a.x * s, a.y * s, a.z * s); }
PM_DEVICE Vec3 vec3_neg(Vec3 a) { return vec3(-a.x, -a.y, -a.z); }
/* a + b * s, the ray-march and differential-transfer update. */
PM_DEVICE Vec3 vec3_madd(Vec3 a, Vec3 b, float s) { return vec3(a.x + b.x * s, a.y + b.y * s, a.z + b.z * s); }
PM_DEVICE float vec3_dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
PM_DEVICE Vec3 vec3_cross(Vec3 a, Vec3 b)
{
  return vec3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
PM_DEVICE float vec3_length(Vec3 a) { return pm_sqrtf(vec3_dot(a, a)); }
PM_DEVICE Vec3 vec3_normalize(Vec3 a)
{
  float len2 = vec3_dot(a, a);
  return len2 > 0.0f ? vec3_scale(a, 1.0f / pm_sqrtf(len2)) : a;
}
PM_DEVICE Vec3 vec3_min(Vec3 a, Vec3 b) { return vec3(pm_fminf(a.x, b.x), pm_fminf(a.y, b.y), pm_fminf(a.z, b.z)); }
PM_DEVICE Vec3 vec3_max(Vec3 a, Vec3 b) { return vec3(pm_fmaxf(a.x, b.x), pm_fmaxf(a.y, b.y), pm_fmaxf(a.z, b.z)); }
PM_DEVICE float vec3_max_component(Vec3 a) { return pm_fmaxf(a.x, pm_fmaxf(a.y, a.z)); }
PM_DEVICE float vec3_max_abs(Vec3 a) { return pm_fmaxf(pm_fabsf(a.x), pm_fmaxf(pm_fabsf(a.y), pm_fabsf(a.z))); }
PM_DEVICE float vec3_luminance(Vec3 c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }
/* Mirror direction d about normal n (n unit length). */
PM_DEVICE Vec3 vec3_reflect(Vec3 d, Vec3 n) { return vec3_madd(d, n, -2.0f * vec3_dot(d, n)); }
PM_DEVICE float vec3_component(Vec3 v, int axis) { return axis == 0 ? v.x : (axis == 1 ? v.y : v.z); }

/* Orthonormal basis (t, b, n) around unit n: Duff et al. 2017, "Building an Orthonormal Basis,
   Revisited", applied to n in a fixed skew frame (rows PM_ONB_M*) and rotated back. The method's
   one discontinuity is where the frame's z changes sign. On n.z = 0 it would cut through the
   normals of every vertical wall of an axis-aligned scene, where the sign of a zero (+0 or -0,
   which each compiler's rounding and FMA contraction decide) flips the whole frame; CUDA and
   OpenCL then turned the same random numbers into different directions on such walls. In the skew
   frame it lies on a plane no normal with components in {0, +-1/2, +-1} (normalised) comes within
   0.065 of. */
#define PM_ONB_M1 vec3(0.978347397f, -0.170295026f, 0.117626417f)
#define PM_ONB_M2 vec3(0.196278149f, 0.943703233f, -0.266268841f)
#define PM_ONB_M3 vec3(-0.065660171f, 0.283590923f, 0.956694795f)
PM_DEVICE void vec3_onb(Vec3 n, Vec3* t, Vec3* b)
{
  Vec3 m1 = PM_ONB_M1, m2 = PM_ONB_M2, m3 = PM_ONB_M3;
  Vec3 r = vec3(vec3_dot(m1, n), vec3_dot(m2, n), vec3_dot(m3, n));
  float sign = pm_copysignf(1.0f, r.z);
  float a = -1.0f / (sign + r.z);
  float c = r.x * r.y * a;
  Vec3 tr = vec3(1.0f + sign * r.x * r.x * a, sign * c, -sign * r.x);
  Vec3 br = vec3(c, sign + r.y * r.y * a, -r.y);
  /* Back to world space: the transpose of the rotation. */
  *t = vec3_add(vec3_add(vec3_scale(m1, tr.x), vec3_scale(m2, tr.y)), vec3_scale(m3, tr.z));
  *b = vec3_add(vec3_add(vec3_scale(m1, br.x), vec3_scale(m2, br.y)), vec3_scale(m3, br.z));
}

/* Local coordinates (x, y, z) in the orthonormal frame (t, b, axis) as a world vector. */
PM_DEVICE Vec3 vec3_frame_to_world(Vec3 t, Vec3 b, Vec3 axis, Vec3 v)
{
  return vec3_add(vec3_add(vec3_scale(t, v.x), vec3_scale(b, v.y)), vec3_scale(axis, v.z));
}

#endif
