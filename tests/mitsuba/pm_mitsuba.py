"""Mitsuba 3 as the independent renderer of pmrender's scenes (tests/mitsuba/README.md).

scene_dict() converts a scene written by `pmrender export-scene` (JSON + one OBJ per material,
metres) into a Mitsuba scene description; render() renders it with Mitsuba's own `path`
integrator through a sensor that puts every sample at its pixel's centre, as pmrender's camera
pass shades them (Mitsuba's film would jitter samples over the pixel area instead).

Conversions (docs/tradeoff.md, "Validation against Mitsuba 3"):
- point light: Mitsuba `point`, intensity = power / (4 pi) W/sr per channel (pmrender's power is
  the radiant flux of an isotropic point light);
- diffuse only: `diffuse`; mirror only: `conductor` with material "none" (a perfect mirror) and
  specular_reflectance = mirror; diffuse + mirror: `blendbsdf` of the two, every BSDF `twosided`
  because pmrender shades both sides of every triangle;
- modified Phong (glossy > 0): Mitsuba 3 has no such BSDF. `modified_phong` below is a Mitsuba
  plugin written here from Lafortune & Willems 1994 (f = rho_d / pi + rho_s (n + 2) / (2 pi)
  cos^n alpha), sampled by Mitsuba's integrator with its own mixture pdf;
- spot light: Mitsuba `spot`, intensity = power / (4 pi) W/sr on the axis, a hard cone at the
  outer angle (cutoff_angle = beam_width = outer) that projects a texture of glTF
  KHR_lights_punctual's falloff ((cos - cos outer) / (cos inner - cos outer))^2, clamped to
  [0, 1] (spot_falloff_table). Mitsuba's own falloff is linear in the angle between beam_width
  and cutoff_angle, not glTF's, so it cannot stand for pmrender's;
- emitting material: the mesh carries an `area` emitter of that radiance (Mitsuba's area lights
  emit from the front face, the side of (p1 - p0) x (p2 - p0), as pmrender's do), and the
  integrator shows emitters to the camera as pmrender's direct layer does;
- base-colour texture (scene_dict's `textures`: export-scene refuses textured scenes, so the
  caller names the textured material's own OBJ, with its texture coordinates, and its image):
  `bitmap`, sRGB decoded to linear before bilinear filtering (raw false), wrap repeat; Mitsuba's
  OBJ loader flips v (flip_tex_coords) and its bitmaps have v = 0 at the top row, which is
  pmrender's convention for OBJ texture coordinates;
- constant environment (`environment.radiance`): `constant` of that radiance;
- environment map (`environment.map`, lat-long OpenEXR, `scale`, `rotation_deg`): `envmap` of a
  resampled map (environment_map_table), `scale` as it is, to_world = a turn about +y by
  rotation_deg + 180 degrees. pmrender's map direction of (u, v) (theta = pi v from +y, phi =
  2 pi u) is (-sin theta sin phi, cos theta, sin theta cos phi) (kernels/common/environment_map.h:
  u = 1/2 faces -z), Mitsuba's is (sin theta sin phi, cos theta, -sin theta cos phi) (u = 1/2
  faces +z): the same (u, v) half a turn about +y apart, and both turn right-handed (a quarter
  turn takes -z to -x in both). pmrender's texels are piecewise constant cells, Mitsuba's map
  values are points interpolated bilinearly, at u = (i + 0.5) / W and v = j / (H - 1) (its top
  and bottom rows lie on the poles), so the same file means different skies in the two: the
  converter gives Mitsuba pmrender's map sampled 16 times finer, each sample the mean of
  pmrender's map over the sample's cell;
- camera: `perspective`, fov_axis y, the vertical field of view, to_world = look_at;
- bounces: pmrender's direct light + B diffuse/glossy bounces is Mitsuba's max_depth = B + 2
  (Mitsuba counts every path segment: 2 is direct light only), on scenes without mirrors.
"""
import json
import math
import os

import drjit as dr
import mitsuba as mi
import numpy as np

DEFAULT_VARIANT = "scalar_rgb"


def set_variant(variant=DEFAULT_VARIANT):
    """Selects the Mitsuba variant and registers this module's plugins for it."""
    mi.set_variant(variant)
    phong, sensor = modified_phong_class(), centred_sensor_class()
    mi.register_bsdf("modified_phong", lambda props: phong(props))
    mi.register_sensor("pixel_centres", lambda props: sensor(props))


def mean3(v):
    return (v[0] + v[1] + v[2]) / 3.0


def modified_phong_class():
    """The modified Phong BSDF as a Mitsuba plugin class (Mitsuba classes exist once a variant is set)."""

    class ModifiedPhong(mi.BSDF):
        """Two-sided modified Phong: rho_d / pi + rho_s (n + 2) / (2 pi) cos^n alpha, alpha between
        wo and the mirror direction of wi. Sampling: the diffuse lobe (cosine) or the glossy lobe
        (cos alpha = u^(1/(n+1))), chosen in proportion to their mean reflectances; the weight is
        f cos / (mixture pdf)."""

        def __init__(self, props):
            mi.BSDF.__init__(self, props)
            self.kd = [props["kd_r"], props["kd_g"], props["kd_b"]]
            self.ks = [props["ks_r"], props["ks_g"], props["ks_b"]]
            self.n = props["exponent"]
            pd, pg = mean3(self.kd), mean3(self.ks)
            self.p_glossy = pg / (pd + pg) if pd + pg > 0 else 0.0
            both = mi.BSDFFlags.FrontSide | mi.BSDFFlags.BackSide
            self.m_components = [mi.BSDFFlags.DiffuseReflection | both, mi.BSDFFlags.GlossyReflection | both]
            self.m_flags = self.m_components[0] | self.m_components[1]

        @staticmethod
        def _upper(si, wo):
            # Both directions mirrored into the upper hemisphere when the ray arrives from below.
            flip = si.wi.z < 0
            s = dr.select(flip, -1.0, 1.0)
            return mi.Vector3f(si.wi.x, si.wi.y, si.wi.z * s), mi.Vector3f(wo.x, wo.y, wo.z * s), s

        def _f_cos_pdf(self, wi, wo):
            valid = (wi.z > 0) & (wo.z > 0)
            cos_alpha = dr.maximum(dr.dot(mi.Vector3f(-wi.x, -wi.y, wi.z), wo), 0.0)
            lobe = dr.power(cos_alpha, self.n)
            f = mi.Color3f(*self.kd) * dr.inv_pi + mi.Color3f(*self.ks) * ((self.n + 2) * 0.5 * dr.inv_pi * lobe)
            pdf = (1.0 - self.p_glossy) * wo.z * dr.inv_pi + self.p_glossy * (self.n + 1) * 0.5 * dr.inv_pi * lobe
            return dr.select(valid, f * wo.z, 0.0), dr.select(valid, pdf, 0.0)

        def sample(self, ctx, si, sample1, sample2, active=True):
            wi, _, s = self._upper(si, si.wi)
            glossy = sample1 < self.p_glossy
            diffuse_dir = mi.warp.square_to_cosine_hemisphere(sample2)
            cos_a = dr.power(dr.maximum(sample2.x, 1e-12), 1.0 / (self.n + 1))
            sin_a = dr.safe_sqrt(1.0 - cos_a * cos_a)
            sin_phi, cos_phi = dr.sincos(2.0 * dr.pi * sample2.y)
            lobe_frame = mi.Frame3f(mi.Vector3f(-wi.x, -wi.y, wi.z))
            glossy_dir = lobe_frame.to_world(mi.Vector3f(cos_phi * sin_a, sin_phi * sin_a, cos_a))
            wo = dr.select(glossy, glossy_dir, diffuse_dir)
            value, pdf = self._f_cos_pdf(wi, wo)
            bs = dr.zeros(mi.BSDFSample3f)
            bs.wo = mi.Vector3f(wo.x, wo.y, wo.z * s)
            bs.pdf = pdf
            bs.eta = 1.0
            bs.sampled_type = dr.select(glossy, mi.UInt32(+mi.BSDFFlags.GlossyReflection),
                                        mi.UInt32(+mi.BSDFFlags.DiffuseReflection))
            bs.sampled_component = dr.select(glossy, mi.UInt32(1), mi.UInt32(0))
            ok = active & (pdf > 0)
            return bs, dr.select(ok, value / dr.select(ok, pdf, 1.0), 0.0)

        def eval(self, ctx, si, wo, active=True):
            wi, wo_up, _ = self._upper(si, wo)
            return self._f_cos_pdf(wi, wo_up)[0]

        def pdf(self, ctx, si, wo, active=True):
            wi, wo_up, _ = self._upper(si, wo)
            return self._f_cos_pdf(wi, wo_up)[1]

        def eval_pdf(self, ctx, si, wo, active=True):
            wi, wo_up, _ = self._upper(si, wo)
            return self._f_cos_pdf(wi, wo_up)

        def to_string(self):
            return "ModifiedPhong[kd=%s, ks=%s, n=%g]" % (self.kd, self.ks, self.n)

    return ModifiedPhong


# Texels a side of a spot's falloff table (1024 x 1024 floats, 4 MiB).
SPOT_TABLE_SIZE = 1024


def spot_falloff(cos_theta, cos_outer, cos_inner):
    """glTF KHR_lights_punctual's spot falloff, as docs/scene-format.md states it."""
    t = np.clip((cos_theta - cos_outer) / (cos_inner - cos_outer), 0.0, 1.0)
    return t * t


def spot_falloff_table(outer, inner, size=SPOT_TABLE_SIZE):
    """The falloff as the image a Mitsuba `spot` projects (its `texture`): Mitsuba looks the
    texture up at uv = 0.5 + 0.5 (x, y) / (z tan(cutoff_angle)) for the direction (x, y, z) in the
    light's frame (z the axis), so texel (i, j), centred at uv = ((i, j) + 0.5) / size, holds the
    falloff at cos theta = 1 / sqrt(1 + t_x^2 + t_y^2), t = (2 uv - 1) tan(outer). Bilinear
    lookups of it differ from the formula by little (tests/mitsuba/README.md gives the measured
    difference); the table is symmetric, so neither its row order nor the light's roll matters."""
    t = ((np.arange(size) + 0.5) / size * 2.0 - 1.0) * math.tan(math.radians(outer))
    cos_theta = 1.0 / np.sqrt(1.0 + t[None, :] ** 2 + t[:, None] ** 2)
    f = spot_falloff(cos_theta, math.cos(math.radians(outer)), math.cos(math.radians(inner)))
    return f.astype(np.float32)[:, :, None]


def spot_emitter(light):
    """Mitsuba `spot` of a pmrender spot light (angles in degrees, direction not normalised): a hard
    cone at the outer angle (beam_width = cutoff_angle) whose projected texture is glTF's falloff."""
    outer, inner = float(light["outer_cone_angle"]), float(light["inner_cone_angle"])
    axis = np.array(light["direction"], dtype=np.float64)
    axis /= np.linalg.norm(axis)
    up = [0.0, 1.0, 0.0] if abs(axis[1]) < 0.9 else [1.0, 0.0, 0.0]  # only the axis matters
    position = np.array(light["position"], dtype=np.float64)
    return {"type": "spot", "cutoff_angle": outer, "beam_width": outer,
            "intensity": rgb([p / (4.0 * math.pi) for p in light["power"]]),
            "texture": {"type": "bitmap", "bitmap": mi.Bitmap(spot_falloff_table(outer, inner)), "raw": True,
                        "filter_type": "bilinear", "wrap_mode": "clamp"},
            "to_world": mi.ScalarTransform4f().look_at(origin=position.tolist(), target=(position + axis).tolist(),
                                                       up=up)}


# Mitsuba samples per pmrender texel, along each axis, of a converted environment map: the
# bilinear blend between neighbouring texels then spans 1/32 of a texel on either side of a
# column boundary and 1/16 of a row boundary. Where a pixel centre sees the map inside such a
# band the two renderers' skies differ: with 8 samples, where the top pixel row of an earlier
# env-corner camera saw the sky 0.35 degrees above the horizon (sky above, dim ground below),
# Mitsuba's direct light was 0.1 darker in that row (the image mean 1 % darker).
ENV_MAP_UPSAMPLE = 16


def environment_map_table(texels, upsample=ENV_MAP_UPSAMPLE):
    """pmrender's lat-long map (H x W x 3, piecewise constant over its texels) as the bitmap of a
    Mitsuba `envmap`, (f H + 1) x f W x 3 for f = upsample. Mitsuba's column i lies at u = (i +
    0.5) / (f W), inside pmrender's texel column i // f, and takes that texel's value; its row j lies
    at v = j / (f H) and takes the mean of pmrender's map over v +- 1 / (2 f H) (clipped at the
    poles): one texel row's value, or half each of two where the row is a texel boundary. Linear
    interpolation between such means keeps each row's and column's integral."""
    f = int(upsample)
    fine = np.repeat(np.repeat(np.asarray(texels, dtype=np.float64), f, axis=1), f, axis=0)
    table = np.empty((fine.shape[0] + 1, fine.shape[1], 3))
    table[0], table[-1] = fine[0], fine[-1]
    table[1:-1] = 0.5 * (fine[:-1] + fine[1:])
    return table.astype(np.float32)


def read_environment_map(path):
    """The R, G, B texels (H x W x 3, linear) of an OpenEXR map."""
    bitmap = mi.Bitmap(path).convert(mi.Bitmap.PixelFormat.RGB, mi.Struct.Type.Float32, srgb_gamma=False)
    return np.array(bitmap, dtype=np.float64)


def environment_emitter(env):
    """Mitsuba emitter of a pmrender `environment` (export-scene's: a map by its absolute path)."""
    if "radiance" in env:
        return {"type": "constant", "radiance": rgb(env["radiance"])}
    table = environment_map_table(read_environment_map(env["map"]))
    # Half a turn besides pmrender's own: the same (u, v) faces -z in pmrender, +z in Mitsuba.
    turn = float(env.get("rotation_deg", 0.0)) + 180.0
    return {"type": "envmap", "bitmap": mi.Bitmap(table), "scale": float(env.get("scale", 1.0)),
            "to_world": mi.ScalarTransform4f().rotate(axis=[0.0, 1.0, 0.0], angle=turn)}


def rgb(v):
    return {"type": "rgb", "value": [float(x) for x in v]}


def material_bsdf(m):
    """The Mitsuba BSDF of a pmrender material (diffuse, glossy, exponent, mirror)."""
    d, g, r = m["diffuse"], m["glossy"], m["mirror"]
    has_glossy, has_mirror = max(g) > 0, max(r) > 0
    if has_glossy:
        base = {"type": "modified_phong", "exponent": float(m["exponent"])}
    else:
        base = {"type": "twosided", "bsdf": {"type": "diffuse"}}
    if not has_mirror:
        scale = 1.0
    else:
        # blendbsdf: (1 - w) base + w mirror, with the reflectances divided by their weights; w
        # between the largest mirror and 1 - the largest diffuse+glossy keeps both parts <= 1.
        w = 0.5 * (max(r) + 1.0 - max(a + b for a, b in zip(d, g)))
        w = min(max(w, 1e-3), 1.0 - 1e-3) if max(d) + max(g) > 0 else 1.0
        scale = 1.0 / (1.0 - w) if w < 1.0 else 0.0
    kd = [x * scale for x in d]
    ks = [x * scale for x in g]
    if has_glossy:
        for c, name in enumerate("rgb"):
            base["kd_" + name] = kd[c]
            base["ks_" + name] = ks[c]
    else:
        base["bsdf"]["reflectance"] = rgb(kd)
    if not has_mirror:
        return base
    mirror = {"type": "twosided", "bsdf": {"type": "conductor", "material": "none",
                                           "specular_reflectance": rgb([x / w for x in r])}}
    if w >= 1.0:
        return mirror
    return {"type": "blendbsdf", "weight": w, "bsdf_0": base, "bsdf_1": mirror}


def scene_dict(exported_json, max_depth, width=None, height=None, textures=None, sampler="independent"):
    """Mitsuba scene dict of a `pmrender export-scene` file; width/height override the camera's;
    sampler: the Mitsuba sampler plugin.
    textures: {exported material name: {"obj": OBJ with texture coordinates, "image": file}} for
    materials whose diffuse reflectance is a base-colour texture (times the material's diffuse,
    which must then be 1: Mitsuba's bitmap has no factor); that OBJ replaces the exported one."""
    folder = os.path.dirname(os.path.abspath(exported_json))
    with open(exported_json) as f:
        s = json.load(f)
    cam = s["camera"]
    w, h = width or cam["resolution"][0], height or cam["resolution"][1]
    film = {"type": "hdrfilm", "width": w, "height": h, "rfilter": {"type": "box"}, "pixel_format": "rgb"}
    camera = {"type": "perspective", "fov_axis": "y", "fov": float(cam["vertical_fov"]),
              "to_world": mi.ScalarTransform4f().look_at(origin=cam["position"], target=cam["look_at"], up=cam["up"]),
              "film": dict(film)}
    d = {"type": "scene",
         # Emitters stay visible: pmrender's direct layer shows the emitting triangles' radiance.
         "integrator": {"type": "path", "max_depth": int(max_depth), "hide_emitters": False},
         "sensor": {"type": "pixel_centres", "inner": camera, "film": film, "sampler": {"type": sampler}}}
    textures = textures or {}
    for i, mesh in enumerate(s["meshes"]):
        material = s["materials"][mesh["material"]]
        shape = {"type": "obj", "filename": os.path.join(folder, mesh["file"]), "face_normals": True,
                 "bsdf": material_bsdf(material)}
        texture = textures.get(mesh["material"])
        if texture:
            if max(material["glossy"]) > 0 or max(material["mirror"]) > 0 or min(material["diffuse"]) < 1:
                raise ValueError("textured material %s: only diffuse 1 (the texture alone) is converted" %
                                 mesh["material"])
            shape["filename"] = texture["obj"]
            shape["flip_tex_coords"] = True  # OBJ's v counts from the image's bottom row
            shape["bsdf"]["bsdf"]["reflectance"] = {"type": "bitmap", "filename": texture["image"], "raw": False,
                                                    "filter_type": "bilinear", "wrap_mode": "repeat"}
        if max(material.get("emission", [0.0])) > 0:
            shape["emitter"] = {"type": "area", "radiance": rgb(material["emission"])}
        d["mesh%d" % i] = shape
    for i, light in enumerate(s["lights"]):
        if light.get("type", "point") == "spot":
            d["light%d" % i] = spot_emitter(light)
        else:
            d["light%d" % i] = {"type": "point", "position": light["position"],
                                "intensity": rgb([p / (4.0 * math.pi) for p in light["power"]])}
    if s.get("environment"):
        d["environment"] = environment_emitter(s["environment"])
    return d


def centred_sensor_class():
    """A Mitsuba sensor that shoots every sample through the centre of its pixel, as pmrender's
    camera pass does, by handing the centre to the wrapped `perspective` sensor. Mitsuba's own
    film would average over the pixel area, which differs from a pixel-centre image wherever an
    edge crosses a pixel."""

    class CentredSensor(mi.Sensor):
        def __init__(self, props):
            mi.Sensor.__init__(self, props)
            self.inner = props["inner"]
            self.size = mi.ScalarVector2f(self.film().crop_size())

        def _centre(self, position_sample):
            return (dr.floor(position_sample * self.size) + 0.5) / self.size

        def sample_ray(self, time, sample1, sample2, sample3, active=True):
            return self.inner.sample_ray(time, sample1, self._centre(sample2), sample3, active)

        def sample_ray_differential(self, time, sample1, sample2, sample3, active=True):
            return self.inner.sample_ray_differential(time, sample1, self._centre(sample2), sample3, active)

        def bbox(self):
            return self.inner.bbox()

        def to_string(self):
            return "CentredSensor[%s]" % self.inner

    return CentredSensor


def render(scene, spp, seed=0):
    """Mitsuba's render of the scene: float64 array (height, width, 3)."""
    # One render thread: this module's sensor (and the glossy BSDF) are Python, called for every
    # sample, so Dr.Jit's worker threads queue on Python's interpreter lock. On a 32 x 32 spot-lit
    # box at 64 samples one thread took 0.35 s, two 1.63 s and the default pool 2.47 s. Only while
    # rendering: with a pool of one thread Mitsuba's Bitmap never returns from reading or writing
    # an OpenEXR file (Mitsuba 3.9.1, Dr.Jit 1.5.0), and the test reads pmrender's images with it.
    threads = dr.thread_count()
    dr.set_thread_count(1)
    try:
        return np.array(mi.render(scene, spp=spp, seed=seed), dtype=np.float64)
    finally:
        dr.set_thread_count(threads)
