"""The scenes of the Mitsuba comparison's light and texture cases (tests/mitsuba/README.md),
written at test time from the built-in Cornell box's geometry as `pmrender export-scene` gives it
(metres, one OBJ per material), so nothing binary is committed:

- spot-box: the box lit by one spot light (no point light) under the ceiling, tilted towards
  the back-left corner, with a soft edge between its inner and outer cones;
- area-box: the box lit by an emitting panel 1 cm under the ceiling (the original Cornell box's
  light, facing down), no point or spot light;
- textured-box: the box with its point light 15 cm under the ceiling and a floor whose diffuse reflectance is a
  base-colour texture (MTL map_Kd, a PNG written here), coloured so that a mirrored u or v or an
  sRGB decoding error changes the image.

- env-corner: an open corner (a floor, a back wall, a lower side wall and a block on the floor)
  lit by nothing but a lat-long OpenEXR sky written here: a gradient from horizon to zenith, a
  dim ground and a small bright sun off to one side and in front, turned by rotation_deg, so a
  map mirrored, turned or flipped in the conversion moves the sun and its shadows.

make_cases() returns, per case, the scene pmrender renders, the scene export-scene writes for
Mitsuba (the textured case: its untextured twin, since export-scene refuses textures) and the
textures pm_mitsuba.scene_dict puts back."""
import json
import math
import os
import struct
import subprocess
import zlib

# The spot: in the ceiling light's place, its axis tilted from straight down towards the back
# and one side; the soft edge between the cones crosses the floor and the walls.
SPOT = {"name": "spot", "type": "spot", "position": [0.278, 0.5388, 0.2796], "power": [4.3220, 3.0, 1.0169],
        "direction": [0.2, -1.0, 0.25], "inner_cone_angle": 25.0, "outer_cone_angle": 55.0}
# The textured box's point light: the Cornell box's, lowered from 1 cm to 15 cm under the ceiling
# (a light just under the ceiling makes a bright spot that reaches the room through few paths:
# the built-in box needs the most samples of all the scenes for it).
POINT_HEIGHT = 0.3988
# The original Cornell box's light (mm 213-343 x 227-332), 1 cm under the ceiling, facing down;
# its radiance from the band averages of the light's spectrum (17.0, 11.8, 4.0), times 4.
PANEL = {"x": (0.213, 0.343), "y": 0.5388, "z": (0.227, 0.332)}
PANEL_EMISSION = [68.0, 47.2, 16.0]
# Texture: 16 x 16 texels repeated twice across the floor (u) and once along it (v); red grows
# with the column, green with the row, blue is a 4 x 4 checker (sRGB codes, at most 220: linear
# 0.72, so the floor reflects less than the walls' white at most).
TEXELS = 16
# The environment-lit corner (metres): a 2 x 2 floor, a back wall 1.5 high along z = 0, a side wall
# 0.8 high along x = 0, and a 0.5 m block standing off-centre on the floor.
CORNER_MATERIALS = {"floor": [0.5, 0.5, 0.5], "back": [0.7, 0.6, 0.45], "side": [0.35, 0.55, 0.7],
                    "block": [0.75, 0.75, 0.75]}
BLOCK = {"x": (1.1, 1.6), "y": (0.0, 0.5), "z": (0.6, 1.1)}
# The camera sees the sky above the walls; its horizon falls on the boundary between the first and
# the second pixel row at 32 x 32 (26.0 degrees down, half the field of view 27.5), so no pixel
# centre lies where the converted map blends the sky into the ground (pm_mitsuba.ENV_MAP_UPSAMPLE).
CORNER_CAMERA = {"position": [2.3, 1.7, 3.1], "look_at": [0.9, 0.365, 0.75], "up": [0.0, 1.0, 0.0],
                 "vertical_fov": 55.0, "resolution": [32, 32]}
# The sky: SKY_W x SKY_H texels (5.6 degrees each), the sun SUN_TEXELS x SUN_TEXELS texels of
# radiance SUN around the direction SUN_DIRECTION (world, after the map's turn of SKY_ROTATION
# degrees: in front of the back wall, to the side away from the side wall, 35 degrees up).
SKY_W, SKY_H, SKY_ROTATION = 64, 32, 30.0
SUN_DIRECTION = (0.55, 0.57, 0.61)
SUN_TEXELS = 2
SUN = [90.0, 80.0, 62.0]
ZENITH, HORIZON, GROUND = [0.25, 0.4, 0.8], [0.75, 0.8, 0.85], [0.2, 0.17, 0.13]


def write_png(path, rows):
    """An 8-bit RGB PNG of rows (lists of (r, g, b) tuples, top row first)."""
    raw = b"".join(b"\0" + bytes(c for px in row for c in px) for row in rows)

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    header = struct.pack(">IIBBBBB", len(rows[0]), len(rows), 8, 2, 0, 0, 0)
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(raw)) +
                chunk(b"IEND", b""))


def write_exr(path, rgb):
    """An uncompressed scanline OpenEXR file of 32-bit float R, G, B channels from rgb (rows x
    columns x 3, top row first). Written here rather than by Mitsuba's Bitmap, which does not
    return from writing OpenEXR while the render pool has one thread (pm_mitsuba.render)."""
    rows, columns = len(rgb), len(rgb[0])

    def attribute(name, kind, value):
        return name.encode() + b"\0" + kind.encode() + b"\0" + struct.pack("<i", len(value)) + value

    # Channels in alphabetical order, each FLOAT (2), not linear-perceptual, sampled 1 x 1.
    channels = b"".join(c + b"\0" + struct.pack("<iB3xii", 2, 0, 1, 1) for c in (b"B", b"G", b"R")) + b"\0"
    window = struct.pack("<iiii", 0, 0, columns - 1, rows - 1)
    header = (b"\x76\x2f\x31\x01" + struct.pack("<i", 2) + attribute("channels", "chlist", channels) +
              attribute("compression", "compression", b"\0") + attribute("dataWindow", "box2i", window) +
              attribute("displayWindow", "box2i", window) + attribute("lineOrder", "lineOrder", b"\0") +
              attribute("pixelAspectRatio", "float", struct.pack("<f", 1.0)) +
              attribute("screenWindowCenter", "v2f", struct.pack("<ff", 0.0, 0.0)) +
              attribute("screenWindowWidth", "float", struct.pack("<f", 1.0)) + b"\0")
    line_bytes = 12 * columns
    first = len(header) + 8 * rows  # after the header and the table of one offset per scanline
    offsets = struct.pack("<%dQ" % rows, *[first + y * (8 + line_bytes) for y in range(rows)])
    lines = b"".join(struct.pack("<ii", y, line_bytes) +
                     b"".join(struct.pack("<%df" % columns, *[px[c] for px in rgb[y]]) for c in (2, 1, 0))
                     for y in range(rows))
    with open(path, "wb") as f:
        f.write(header + offsets + lines)


def sky_texels():
    """The corner's sky map (rows of (r, g, b), top row = zenith), in the convention of
    docs/scene-format.md: texel (i, j) spans phi 2 pi [i, i + 1) / W, theta pi [j, j + 1) / H, its
    direction (-sin theta sin phi, cos theta, sin theta cos phi) turned by SKY_ROTATION about +y."""
    turn = math.radians(SKY_ROTATION)
    d = [c / math.sqrt(sum(x * x for x in SUN_DIRECTION)) for c in SUN_DIRECTION]
    # The sun's direction in the map's own frame (the turn undone), then its (u, v).
    x, z = d[0] * math.cos(turn) - d[2] * math.sin(turn), d[0] * math.sin(turn) + d[2] * math.cos(turn)
    u = (math.atan2(-x, z) / (2 * math.pi)) % 1.0
    v = math.acos(d[1]) / math.pi
    i0, j0 = int(round(u * SKY_W)) - SUN_TEXELS // 2, int(round(v * SKY_H)) - SUN_TEXELS // 2
    rows = []
    for j in range(SKY_H):
        theta = math.pi * (j + 0.5) / SKY_H
        row = []
        for i in range(SKY_W):
            if 0 <= (i - i0) % SKY_W < SUN_TEXELS and 0 <= j - j0 < SUN_TEXELS:
                row.append(tuple(SUN))
            elif theta < math.pi / 2:
                t = math.cos(theta)  # 0 at the horizon, 1 at the zenith
                row.append(tuple(h + (z_ - h) * t for h, z_ in zip(HORIZON, ZENITH)))
            else:
                row.append(tuple(GROUND))
        rows.append(row)
    return rows


def quad(a, b, c, d):
    return [a, b, c, d], [[0, 1, 2], [0, 2, 3]]


def box_faces(x, y, z):
    """The six faces of an axis-aligned box as (vertices, faces)."""
    (x0, x1), (y0, y1), (z0, z1) = x, y, z
    v = [[x0, y0, z0], [x1, y0, z0], [x1, y1, z0], [x0, y1, z0], [x0, y0, z1], [x1, y0, z1], [x1, y1, z1],
         [x0, y1, z1]]
    f = [[0, 2, 1], [0, 3, 2], [4, 5, 6], [4, 6, 7], [0, 4, 7], [0, 7, 3], [1, 2, 6], [1, 6, 5], [3, 7, 6],
         [3, 6, 2], [0, 1, 5], [0, 5, 4]]
    return v, f


def texture_rows():
    return [[(40 + 12 * i, 40 + 12 * j, 200 if (i // 4 + j // 4) % 2 == 0 else 60) for i in range(TEXELS)]
            for j in range(TEXELS)]


def read_obj(path):
    """Vertices and faces (0-based) of an OBJ as export-scene writes it (v and f lines only)."""
    vertices, faces = [], []
    with open(path) as f:
        for line in f:
            parts = line.split()
            if parts and parts[0] == "v":
                vertices.append([float(x) for x in parts[1:4]])
            elif parts and parts[0] == "f":
                faces.append([int(x) - 1 for x in parts[1:4]])
    return vertices, faces


def write_obj(path, vertices, faces, comment, uvs=None, material=None):
    lines = ["# " + comment]
    if material:
        lines += ["mtllib %s.mtl" % material, "usemtl " + material]
    lines += ["v %.9g %.9g %.9g" % tuple(v) for v in vertices]
    if uvs:
        lines += ["vt %.9g %.9g" % tuple(t) for t in uvs]
        lines += ["f %d/%d %d/%d %d/%d" % (a + 1, a + 1, b + 1, b + 1, c + 1, c + 1) for a, b, c in faces]
    else:
        lines += ["f %d %d %d" % (a + 1, b + 1, c + 1) for a, b, c in faces]
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


def scene(name, meshes, materials, lights, camera, environment=None):
    s = {"format": "pmrender-scene", "version": 1, "name": name, "meshes": meshes, "materials": materials,
         "lights": lights, "camera": camera}
    if environment:
        s["environment"] = environment
    return s


def write_json(path, value):
    with open(path, "w") as f:
        json.dump(value, f, indent=2)
    return path


def make_cases(pmrender, work):
    """Writes the four scenes under work/light-scenes; returns [(name, scene, exported, textures)]
    with exported None where pmrender's own export of `scene` serves."""
    folder = os.path.join(work, "light-scenes")
    os.makedirs(folder, exist_ok=True)
    base = os.path.join(folder, "box.json")
    subprocess.run([pmrender, "export-scene", "-o", base], check=True, stdout=subprocess.DEVNULL)
    with open(base) as f:
        box = json.load(f)
    materials = {name: {"diffuse": m["diffuse"]} for name, m in box["materials"].items()}
    meshes = [{"file": m["file"], "material": m["material"]} for m in box["meshes"]]
    camera, point = box["camera"], dict(box["lights"][0], name="lamp")
    point["position"] = [point["position"][0], POINT_HEIGHT, point["position"][2]]
    cases = []

    spot = scene("spot-box", meshes, materials, [SPOT], camera)
    cases.append(("spot-box", write_json(os.path.join(folder, "spot-box.json"), spot), None, None))

    (x0, x1), y, (z0, z1) = PANEL["x"], PANEL["y"], PANEL["z"]
    # Corners ordered so that (p1 - p0) x (p2 - p0) points down (-y): the emitting side.
    write_obj(os.path.join(folder, "panel.obj"), [[x0, y, z0], [x1, y, z0], [x1, y, z1], [x0, y, z1]],
              [[0, 1, 2], [0, 2, 3]], "emitting panel under the ceiling, metres")
    area = scene("area-box", meshes + [{"file": "panel.obj", "material": "lamp"}],
                 dict(materials, lamp={"diffuse": [0.78, 0.78, 0.78], "emission": PANEL_EMISSION}), [], camera)
    cases.append(("area-box", write_json(os.path.join(folder, "area-box.json"), area), None, None))

    # The floor (the white triangles at y = 0) gets its own OBJ with texture coordinates.
    white = next(m for m in box["meshes"] if m["material"] == "white")
    vertices, faces = read_obj(os.path.join(folder, white["file"]))
    floor = [f for f in faces if all(abs(vertices[i][1]) < 1e-6 for i in f)]
    rest = [f for f in faces if f not in floor]
    write_obj(os.path.join(folder, "walls.obj"), vertices, rest, "white walls and blocks without the floor, metres")
    xs = [v[0] for v in vertices]
    zs = [v[2] for v in vertices]
    uvs = [[2.0 * (v[0] - min(xs)) / (max(xs) - min(xs)), (v[2] - min(zs)) / (max(zs) - min(zs))] for v in vertices]
    write_obj(os.path.join(folder, "floor.obj"), vertices, floor, "floor with texture coordinates, metres", uvs,
              "checker")
    image = os.path.join(folder, "checker.png")
    write_png(image, texture_rows())
    with open(os.path.join(folder, "checker.mtl"), "w") as f:
        f.write("# the textured floor: base colour = the checker's texels (Kd 1)\n"
                "newmtl checker\nKd 1 1 1\nmap_Kd checker.png\n")
    walls = [m if m["material"] != "white" else {"file": "walls.obj", "material": "white"} for m in meshes]
    textured = scene("textured-box", walls + [{"file": "floor.obj"}], materials, [point], camera)
    twin = scene("textured-box", walls + [{"file": "floor.obj", "material": "checker"}],
                 dict(materials, checker={"diffuse": [1.0, 1.0, 1.0]}), [point], camera)
    textures = {"checker": {"obj": os.path.join(folder, "floor.obj"), "image": image}}
    cases.append(("textured-box", write_json(os.path.join(folder, "textured-box.json"), textured),
                  write_json(os.path.join(folder, "textured-box-untextured.json"), twin), textures))

    parts = {"floor": quad([0, 0, 0], [0, 0, 2], [2, 0, 2], [2, 0, 0]),
             "back": quad([0, 0, 0], [2, 0, 0], [2, 1.5, 0], [0, 1.5, 0]),
             "side": quad([0, 0, 0], [0, 0.8, 0], [0, 0.8, 2], [0, 0, 2]),
             "block": box_faces(BLOCK["x"], BLOCK["y"], BLOCK["z"])}
    corner_meshes = []
    for name, (vertices, faces) in parts.items():
        write_obj(os.path.join(folder, "corner-%s.obj" % name), vertices, faces, "open corner: %s, metres" % name)
        corner_meshes.append({"file": "corner-%s.obj" % name, "material": name})
    write_exr(os.path.join(folder, "sky.exr"), sky_texels())
    corner = scene("env-corner", corner_meshes, {n: {"diffuse": c} for n, c in CORNER_MATERIALS.items()}, [],
                   CORNER_CAMERA, {"map": "sky.exr", "rotation_deg": SKY_ROTATION})
    cases.append(("env-corner", write_json(os.path.join(folder, "env-corner.json"), corner), None, None))
    return cases
