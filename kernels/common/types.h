/* Structs shared between the host and every device backend. Only 4-byte scalars and 16-byte
   float4/uint4 members, in an order that needs no padding, so the layout is identical in C++,
   CUDA and OpenCL C. render/kernel_abi.h static_asserts each size on the host, and the
   layout_probe kernel lets tests/opencl and tests/gpu check each device compiler's view. */
#ifndef PM_TYPES_H
#define PM_TYPES_H

/* The one definition of pi, for device and host code alike. */
#define PM_PI 3.14159265358979323846f
#define PM_TWO_PI 6.28318530717958647692f
#define PM_INV_PI 0.31830988618379067154f

/* Modified Phong material (Lafortune & Willems 1994) with a perfect-mirror term.
   diffuse.rgb = rho_d and diffuse.w = PM_MATERIAL_* flags as uint bits, glossy.rgb = rho_s and
   glossy.w = Phong exponent, mirror.rgb = mirror reflectance. Energy conservation (rho_d + rho_s +
   mirror <= 1 per channel) is checked on load; texels are at most 1, so textures keep it.
   texture (texture.h): x = base-colour texture + 1 as uint bits (0: none), whose linear rgb
   multiplies rho_d (and rho_s and the mirror with PM_MATERIAL_TINT_SPECULAR); y = alpha-mask
   texture + 1 as uint bits (0: none); z = alpha factor; w = alpha cutoff. With PM_MATERIAL_MASKED
   a point is there when factor * (mask texel channel, or 1 without a mask texture) >= cutoff. */
typedef struct Material {
  float4 diffuse;
  float4 glossy;
  float4 mirror;
  float4 texture;
} Material;

#define PM_MATERIAL_TINT_SPECULAR 1u /* the base-colour texture tints glossy and mirror too (glTF) */
#define PM_MATERIAL_MASKED 2u        /* alpha mask: rays pass where alpha < cutoff */
#define PM_MATERIAL_ALPHA_CHANNEL_SHIFT 4u /* bits 4-5: the mask texture's channel (0 red .. 3 alpha) */

/* Triangle records (render/scene_bvh.h): v0.w holds the material index, with this bit set when
   the material has an alpha mask, so traversal tests a mask only on such triangles. */
#define PM_TRIANGLE_MASKED 0x40000000u
#define PM_TRIANGLE_MATERIAL_BITS 0x3fffffffu

/* Texture wrap modes (glTF sampler wrapS / wrapT), packed into a texture_info entry's w as
   wrap_u | wrap_v << 8. */
#define PM_WRAP_REPEAT 0u
#define PM_WRAP_CLAMP 1u
#define PM_WRAP_MIRROR 2u

/* A point light, isotropic or a spot (a point light whose intensity is restricted to a cone
   about its axis, with the glTF KHR_lights_punctual falloff; spot_light.h).
   position.xyz in metres, w = cos of the spot's outer cone angle (-1: isotropic point light);
   power.rgb in watts: the radiant flux of the isotropic light of the same (on-axis) intensity,
   so the intensity towards a direction is power / (4 pi) times the spot falloff (1 for a point
   light); power.w = cos of the spot's inner cone angle (-1: point light);
   axis.xyz = the spot's unit axis (where it points), w unused.
   (Photon emission keeps each light's share of a pass's photons in its own buffer,
   photon_emitters.) */
typedef struct PointLight {
  float4 position;
  float4 power;
  float4 axis;
} PointLight;

/* Area lights (area_lights.h): one record of PM_EMITTER_FLOAT4S float4 per emitting triangle. */
#define PM_EMITTER_FLOAT4S 4

/* Pinhole camera. right and up are scaled so that a pixel's ray direction is
   forward + u * right + v * up with u, v in [-1, 1]. */
typedef struct CameraParams {
  float4 position;
  float4 forward;
  float4 right;
  float4 up;
} CameraParams;

/* Photon hit flags: a hit slot's word (hit_slots) holds them below the index of the hit's record
   (above PM_HIT_RECORD_SHIFT, photon_trace.h); the gather data keeps them as uint bits in the w of
   map_center. */
#define PM_HIT_VALID 1u
#define PM_HIT_CAUSTIC 2u /* path from the light was specular only */
#define PM_HIT_SLOT_FLAGS 3u /* the flags a hit slot carries */
#define PM_HIT_RECORD_SHIFT 2u
#define PM_HIT_SECOND_CUT 4u /* footprint data: the footprint has a second cut (footprint_clip.h) */
#define PM_HIT_RIM 8u /* footprint data: the second cut slot (map_cut) holds a rim it folds at (footprint_rim.h) */

/* A hit record (photon_trace.h): five float4 side by side in hit_records, at PM_RECORD_FLOAT4S *
   record; the photon map's inner nodes take the same memory, four float4 each (buffers.h). */
#define PM_RECORD_FLOAT4S 5u
#define PM_RECORD_NORMAL 0u   /* xyz facing the photon's side, w = flux red (watts) */
#define PM_RECORD_INCIDENT 1u /* xyz unit direction back to its origin, w = Delta */
#define PM_RECORD_DP_U 2u     /* positional differentials (eq. 8 scaling), w = flux green */
#define PM_RECORD_DP_V 3u     /* w = flux blue */
#define PM_RECORD_POSITION 4u /* xyz where the photon hit, w = 0 */

/* Coverage probes per footprint (footprint_coverage.h): the first pattern, and the whole pattern,
   which holds the first, for footprints that the first finds partly covered. The photon map's
   footprints trace the first with a work item per probe (footprint_probes.h), and the host sizes
   those launches by it. */
#define PM_FOOTPRINT_PROBES 16u
#define PM_FOOTPRINT_EDGE_PROBES 64u

/* Density estimators (--estimator) and kernel shapes (--kernel) of the gather. */
#define PM_ESTIMATOR_PD 0     /* photon-differential footprints (the paper) */
#define PM_ESTIMATOR_RADIUS 1 /* fixed-radius gathering */
#define PM_ESTIMATOR_KNN 2    /* k nearest neighbours within rmax */
#define PM_KERNEL_CONSTANT 0
#define PM_KERNEL_EPANECHNIKOV 1

/* Every scalar a kernel launch needs, passed by value to every kernel. */
typedef struct LaunchParams {
  CameraParams camera;
  float4 hit_bounds_lo; /* photon map: bounds of the hit positions for Morton codes */
  float4 hit_bounds_hi;

  uint width;
  uint height;
  uint triangle_count;
  uint light_count;

  uint mirror_depth;    /* eye-ray mirror bounces followed (default 1) */
  uint seed;
  uint frame;
  uint pass_index;      /* the method's pass within the frame (0, 1, ...) */

  float ray_epsilon;    /* scale of the scene, for robust ray offsets (metres) */
  uint sort_count;      /* portable radix sort: number of keys */
  uint sort_shift;      /* portable radix sort: bit offset of the current digit */
  uint sort_tile_count; /* portable radix sort: tiles of PM_SORT_TILE keys */

  uint photon_count;         /* photons emitted in this pass, all lights */
  uint photon_offset;        /* index of the pass's first photon within the frame (random stream) */
  uint hit_slots_per_photon; /* hit records reserved per photon */
  uint max_bounces;          /* diffuse bounces a recorded photon may have undergone */

  float smoothing;      /* s of section 4.3 for diffusely reflected photons */
  float rmax;           /* footprint semiaxis clamp, metres */
  float gather_radius;  /* radius estimator, metres */
  uint knn_k;           /* knn estimator */

  uint estimator;       /* PM_ESTIMATOR_* */
  uint kernel_shape;    /* PM_KERNEL_* */
  uint hit_count;       /* valid hits of the pass: the sorted prefix the photon map covers */
  uint leaf_threshold;  /* T: subtrees of at most T hits become one leaf */

  uint film_passes;     /* passes summed in the film: the resolve divides the sums by it */
  uint collect_stats;   /* gather counts photons per shading point (benchmarks) */
  uint photon_frame;    /* the frame whose random numbers the photons draw (animations: camera-only
                           runs share the photons of their first frame; docs/animation.md) */
  uint photon_sequence; /* PM_PHOTON_SEQUENCE_*: how emission directions are drawn */

  float footprint_scale; /* progressive shrink: this pass's footprint semiaxis / gather radius factor (1: none) */
  uint photon_offset_hi; /* high 32 bits of the pass's first photon index (frames of 2^32 photons and more) */
  uint film_odd_passes;  /* of film_passes, those with an odd pass number (film_odd_sum's) */
  uint footprint_clip;   /* 1: footprints stop at walls (footprint_clip.h); 0: the paper's unclipped ellipses */

  uint path_samples;      /* path tracer: paths per shading point in this pass */
  uint path_first_sample; /* path tracer: index of the pass's first path (random stream) */
  uint path_frame;        /* path tracer: the frame whose random numbers the paths draw */
  uint path_mis;          /* path tracer: 1: area lights and environment by MIS of light and BSDF sampling; 0: light sampling only */

  uint element_count;    /* radiosity: elements (vertices split by side, feature edges and material) */
  uint link_directions;  /* radiosity: nC, hemisphere directions shot per element */
  uint batch_first;      /* radiosity link build: first element of the batch */
  uint batch_count;      /* radiosity link build: elements in the batch */

  uint radiosity_source; /* radiosity: which half of a ping-pong buffer holds the input (0 or 1) */
  uint light_sampling;   /* radiosity: PM_RADIOSITY_LIGHT_* */
  float feature_cos;     /* radiosity: cos alpha_f, the feature angle of the smoothing (eq. 6) */
  uint link_origins;     /* radiosity: PM_RADIOSITY_ORIGINS_*, where link rays start */

  uint footprint_coverage; /* 1: footprints' area is the part on a surface (footprint_coverage.h) */
  uint control_stride;     /* bias control: one control pixel per stride x stride block (bias_control.h) */
  uint control_samples;    /* bias control: paths per control pixel in this launch */
  uint control_first_sample; /* bias control: index of the launch's first path (random stream) */

  float footprint_thickness; /* normal half-axis / shorter in-plane semiaxis of pd footprints (footprint.h) */
  uint emitter_count;        /* area lights: emitting triangles in the emitters buffer (0: none) */
  float emitter_power;       /* area lights: total flux, sum over emitters of pi A mean(L_e) (watts, channel mean) */
  uint area_light_samples;   /* area lights and the environment: samples per shading point in the camera pass and radiosity */

  uint environment;          /* PM_ENVIRONMENT_*: light from infinitely far away (environment_light.h) */
  uint environment_width;    /* map: texels per row */
  uint environment_height;   /* map: rows */
  float environment_rotation; /* map: radians about +y (environment_map.h) */
  float4 environment_radiance; /* constant: rgb radiance (W sr^-1 m^-2), w = channel mean */
  float4 environment_sphere;   /* the scene's bounding sphere: xyz centre, w radius (photon emission) */

  float link_hidden_distance; /* radiosity: a link ray meeting a back face nearer than this started inside
                                 geometry (radiosity_links.h); 0: no origin is hidden */
  uint final_gather_rays;     /* photon mapping: gather rays per shading point and pass (final_gather.h); 0: off */
  uint facet_weighting;       /* photon mapping: 1: a photon counts on a tilted facet by what its beam delivers there
                                 and its footprint's area is the lit surface area (gather_reach.h); 0: in full */
  uint control_lanes;         /* bias control: work items per control pixel, each a share of its paths (bias_control.h) */
  uint film_caustic;          /* 1: the film has a caustic sum (a scene with mirrors, film.h); 0: caustics are none */
  float tile_gather_reach;    /* photon gather: a tile whose first shading points' box has at most this diagonal
                                 walks the photon map as one box (gather_tiles.h), metres; 0: every point alone */
} LaunchParams;

/* Environment lights (environment_light.h): none, one radiance from every direction, or an
   equirectangular map (environment_map.h). */
#define PM_ENVIRONMENT_NONE 0u
#define PM_ENVIRONMENT_CONSTANT 1u
#define PM_ENVIRONMENT_MAP 2u

/* Photon emission sequences (--photon-sequence). RANDOM: Philox keyed by (seed, photon_frame).
   HALTON: directions from the Halton sequence (bases 2, 3) indexed by the photon's number within
   its light, and every later random decision keyed by (seed, light, that number) only, never the
   frame: the same lights give the same photons in every frame. */
#define PM_PHOTON_SEQUENCE_RANDOM 0
#define PM_PHOTON_SEQUENCE_HALTON 1

/* Vertex link radiosity (docs/radiosity.md). An element index that does not exist (the back side
   of a one-sided surface, an empty link slot). */
#define PM_RADIOSITY_NONE 0xffffffffu
/* A link slot whose ray started inside other geometry (radiosity_links.h); sorts just before NONE. */
#define PM_RADIOSITY_HIDDEN 0xfffffffeu
/* Light links (section 3.3): the vertex alone, or the centroids of the paper's 1:4 subdivision
   of its one-ring triangles, weighted as a quadrature of the vertex's hat function. */
#define PM_RADIOSITY_LIGHT_VERTEX 0
#define PM_RADIOSITY_LIGHT_ONE_RING 1
/* Link rays (section 3.2): all from the vertex, or each from a point of the vertex's one-ring
   drawn in proportion to the vertex's hat function (radiosity_links.h). */
#define PM_RADIOSITY_ORIGINS_VERTEX 0
#define PM_RADIOSITY_ORIGINS_ONE_RING 1
/* Deepest refinement tree (render/radiosity/mesh_refinement.h guarantees it). */
#define PM_RADIOSITY_MAX_TREE_DEPTH 128

/* The portable radix sort (radix_sort.h): 5-bit digits, so that a tile's 32 digit lanes fill a
   GPU warp and 30-bit Morton keys take 6 passes; tiles of 256 keys; a digit's counts summed in
   groups of 64 tiles. */
#define PM_SORT_RADIX_BITS 5
#define PM_SORT_RADIX (1 << PM_SORT_RADIX_BITS)
#define PM_SORT_TILE 256
#define PM_SORT_GROUP 64

/* Perfect-mirror reflections a light path may take besides its diffuse and glossy bounces (caps
   mirror-to-mirror loops): the photon tracer and the path tracer count the same paths. */
#define PM_PHOTON_MAX_SPECULAR 8

/* Bounds of the per-ray traversal stack; the host BVH builder guarantees depth below this. */
#define PM_TRAVERSAL_STACK 64

#endif
