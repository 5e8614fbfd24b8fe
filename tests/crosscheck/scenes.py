"""Scene descriptions for the fogrt / Mitsuba 3 cross-check.

Each scene is one plain Python dict. From it `write_dae` writes the COLLADA file (and
`write_camera` the CS184 camera file) that the fogrt command reads, and `mitsuba_dict`
builds the equivalent Mitsuba 3 scene. Nothing here is copied from a shipped scene: the box,
lamp and spheres are made from the numbers below.

Conventions shared by both renderers (see fogrt.h, CONVENTIONS, and docs/loading.md):
  - y up, metres-free "scene units"; sigma_t per scene unit;
  - fog fills all space outside refractive objects and the camera sits in it. Mitsuba needs
    a boundary for that: a large cube with a `null` BSDF whose interior is the fog; every
    other shape has the fog outside (opaque shapes also inside, so a ray leaving them from
    either side is in the fog), glass has no medium inside;
  - area lights emit from the counter-clockwise (front) side only, as Mitsuba's `area` does;
  - reflecting surfaces are two-sided in fogrt, so Mitsuba's are wrapped in `twosided`;
  - point and spot lights give radiant intensity I with 1/r^2 falloff in both; the spot's
    intensity falls linearly in the angle from beam to cutoff in both (Mitsuba's spot.cpp
    falloff_curve is (cutoff - theta) / (cutoff - beam), the same ramp as fogrt);
  - fogrt's -m N counts bounces after the camera ray; Mitsuba's max_depth counts path
    segments, so fogrt -m N matches Mitsuba max_depth N + 1;
  - a fog's sigma_t is one number or, for chromatic fog, one per colour channel (fogrt
    --density R,G,B; Mitsuba an rgb sigma_t, rendered by volpathmis, whose spectral MIS
    weighs such a medium as fogrt does; volpath also picks one channel per path, but divides
    by that channel's density alone, which is unbiased and noisier).
"""
import math
import os

WHITE = (0.725, 0.71, 0.68)
RED = (0.63, 0.065, 0.05)
GREEN = (0.14, 0.45, 0.09)

# ---------------------------------------------------------------------------------------
# Geometry helpers
# ---------------------------------------------------------------------------------------


def quad(a, b, c, d):
    """A quad a-b-c-d (counter-clockwise seen from its front) as two triangles."""
    return {"verts": [a, b, c, d], "faces": [(0, 1, 2), (0, 2, 3)]}


def box_shapes(lamp_radiance=None, lamp_half=0.3):
    """The box x in [-1, 1], y in [0, 2], z in [-1, 1], open at z = +1 (towards the camera):
    white floor, ceiling and back wall, red left wall, green right wall, and optionally a
    square lamp just under the ceiling that faces down."""
    s = [
        dict(kind="mesh", name="floor", material="white",
             **quad((-1, 0, -1), (-1, 0, 1), (1, 0, 1), (1, 0, -1))),
        dict(kind="mesh", name="ceiling", material="white",
             **quad((-1, 2, -1), (1, 2, -1), (1, 2, 1), (-1, 2, 1))),
        dict(kind="mesh", name="back", material="white",
             **quad((-1, 0, -1), (1, 0, -1), (1, 2, -1), (-1, 2, -1))),
        dict(kind="mesh", name="left", material="red",
             **quad((-1, 0, -1), (-1, 2, -1), (-1, 2, 1), (-1, 0, 1))),
        dict(kind="mesh", name="right", material="green",
             **quad((1, 0, -1), (1, 0, 1), (1, 2, 1), (1, 2, -1))),
    ]
    if lamp_radiance is not None:
        h, y = lamp_half, 1.98
        # counter-clockwise seen from below: the front faces down (-y)
        s.append(dict(kind="mesh", name="lamp", material="lamp",
                      **quad((-h, y, -h), (h, y, -h), (h, y, h), (-h, y, h))))
    return s


BOX_MATERIALS = {
    "white": dict(type="diffuse", reflectance=WHITE),
    "red": dict(type="diffuse", reflectance=RED),
    "green": dict(type="diffuse", reflectance=GREEN),
    "lamp": dict(type="emitter", radiance=(20.0, 20.0, 20.0)),
    "grey": dict(type="diffuse", reflectance=(0.6, 0.6, 0.6)),
    "mirror": dict(type="mirror", reflectance=(0.95, 0.95, 0.95)),
    "glass": dict(type="glass", ior=1.5, reflectance=(1.0, 1.0, 1.0), transmittance=(1.0, 1.0, 1.0)),
    # the surface of a fog volume: fogrt's --interface, Mitsuba's null BSDF (the .dae holds a
    # diffuse stand-in, which --interface replaces)
    "interface": dict(type="interface"),
}


def cube(name, lo, hi, material):
    """A closed axis-aligned box mesh, its faces wound outward."""
    (x0, y0, z0), (x1, y1, z1) = lo, hi
    v = [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0), (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]
    f = [(0, 3, 2), (0, 2, 1), (4, 5, 6), (4, 6, 7), (0, 1, 5), (0, 5, 4),
         (3, 7, 6), (3, 6, 2), (0, 4, 7), (0, 7, 3), (1, 2, 6), (1, 6, 5)]
    return dict(kind="mesh", name=name, material=material, verts=v, faces=f)

BOX_CAMERA = dict(position=(0.0, 1.0, 3.2), target=(0.0, 1.0, 0.0), up=(0.0, 1.0, 0.0), vfov=40.0)


def box_scene(name, title, fog, spheres, lamp=True, lights=(), camera=None, max_depth=64):
    shapes = box_shapes(BOX_MATERIALS["lamp"]["radiance"] if lamp else None)
    for (c, r, m) in spheres:
        shapes.append(dict(kind="sphere", name="sphere%d" % len(shapes), center=c, radius=r, material=m))
    return dict(name=name, title=title, fog=fog, shapes=shapes, materials=dict(BOX_MATERIALS),
                lights=list(lights), camera=dict(camera or BOX_CAMERA), max_depth=max_depth,
                analytic=None, fresnel="exact")


def chromatic(fog):
    """Whether the fog has a sigma_t per colour channel."""
    return bool(fog) and isinstance(fog["sigma_t"], (tuple, list))


def sigma_text(fog):
    """The fog's sigma_t as the fogrt flag and the tables write it."""
    st = fog["sigma_t"]
    return ",".join("%.9g" % x for x in st) if chromatic(fog) else "%.9g" % st


# ---------------------------------------------------------------------------------------
# The scenes
# ---------------------------------------------------------------------------------------


def all_scenes():
    diffuse_ball = [((-0.4, 0.45, -0.3), 0.45, "grey")]
    spheres2 = [((-0.45, 0.4, -0.35), 0.4, "mirror"), ((0.45, 0.4, 0.25), 0.4, "glass")]
    fog_iso = dict(sigma_t=0.5, albedo=(0.8, 0.8, 0.8), g=0.0)
    fog_fwd = dict(sigma_t=0.5, albedo=(0.8, 0.8, 0.8), g=0.7)
    fog_back = dict(sigma_t=0.5, albedo=(0.8, 0.8, 0.8), g=-0.7)
    spot = dict(type="spot", position=(0.0, 1.9, 0.0), direction=(0.2, -1.0, 0.1),
                intensity=(6.0, 6.0, 6.0), cutoff_deg=30.0, beam_deg=20.0)
    point = dict(type="point", position=(0.3, 1.3, 0.2), intensity=(1.5, 1.5, 1.5))
    scenes = [
        box_scene("fog_iso", "Isotropic fog (g = 0), ceiling lamp, diffuse sphere", fog_iso, diffuse_ball),
        box_scene("fog_forward", "Forward-scattering fog (g = +0.7)", fog_fwd, diffuse_ball),
        box_scene("fog_back", "Back-scattering fog (g = -0.7)", fog_back, diffuse_ball),
        box_scene("spot_fog", "Spot light in fog (cutoff 30, beam 20 degrees), no lamp",
                  dict(sigma_t=0.4, albedo=(0.9, 0.85, 0.8), g=0.4), diffuse_ball, lamp=False, lights=[spot]),
        box_scene("point_fog", "Point light in fog, no lamp",
                  dict(sigma_t=0.4, albedo=(0.9, 0.9, 0.9), g=0.5), diffuse_ball, lamp=False, lights=[point]),
        box_scene("glass_fog", "Glass sphere (ior 1.5, exact Fresnel) in fog, ceiling lamp",
                  dict(sigma_t=0.2, albedo=(0.9, 0.9, 0.9), g=0.5), [((0.0, 0.6, 0.2), 0.6, "glass")]),
        dict(box_scene("glass_fog_schlick", "The same glass sphere in fog, fogrt with its default Schlick Fresnel",
                       dict(sigma_t=0.2, albedo=(0.9, 0.9, 0.9), g=0.5), [((0.0, 0.6, 0.2), 0.6, "glass")]),
             fresnel="schlick"),
        box_scene("cornell_nofog", "Fog-free box with a mirror and a glass sphere, ceiling lamp",
                  None, spheres2),
        box_scene("chroma_fog", "Chromatic fog (sigma_t per channel), ceiling lamp, diffuse sphere",
                  dict(sigma_t=(0.15, 0.4, 0.9), albedo=(0.85, 0.85, 0.85), g=0.3), diffuse_ball),
        box_scene("chroma_spot", "Chromatic fog, spot light (cutoff 30, beam 20 degrees), no lamp",
                  dict(sigma_t=(0.2, 0.4, 0.8), albedo=(0.9, 0.85, 0.8), g=0.4), diffuse_ball, lamp=False, lights=[spot]),
    ]
    # Media inside shapes (fogrt.h, appendix H): smoke in a glass sphere in a fog-free box,
    # and a fog cube behind an interface inside the box's thinner fog.
    smoke = dict(box_scene("smoke_in_glass", "Glass sphere (ior 1.5) filled with smoke, no fog outside, ceiling lamp",
                           None, [((0.0, 0.6, 0.0), 0.6, "glass")]),
                 interiors=[])
    smoke["interiors"].append(dict(shape=smoke["shapes"][-1]["name"], medium=dict(sigma_t=2.0, albedo=(0.9, 0.9, 0.9), g=0.5)))
    fog_cube = box_scene("fog_cube", "A fog cube (interface surface, sigma_t 3, albedo 0.6, g -0.3) in the box's thin fog (0.15)",
                         dict(sigma_t=0.15, albedo=(0.9, 0.9, 0.9), g=0.3), [])
    fog_cube["shapes"].append(cube("fogcube", (-0.5, 0.2, -0.6), (0.4, 1.1, 0.2), "interface"))
    fog_cube["interiors"] = [dict(shape="fogcube", interface=True,
                                  medium=dict(sigma_t=3.0, albedo=(0.6, 0.6, 0.6), g=-0.3))]
    # Both together with B's samplers: a spot lamp in the box's fog above a glass sphere
    # filled with smoke (one Algorithm 1 runs equiangular sampling, the glow and the
    # footprint in the world's fog, and the smoke's free flights inside the sphere).
    spot_smoke = dict(box_scene("spot_smoke", "Spot light in fog above a glass sphere filled with smoke, no lamp",
                                dict(sigma_t=0.3, albedo=(0.9, 0.9, 0.9), g=0.4), [((0.0, 0.5, 0.0), 0.45, "glass")],
                                lamp=False, lights=[spot]),
                      interiors=[])
    spot_smoke["interiors"].append(dict(shape=spot_smoke["shapes"][-1]["name"],
                                        medium=dict(sigma_t=3.0, albedo=(0.9, 0.9, 0.9), g=0.3)))
    scenes += [smoke, fog_cube, spot_smoke]
    # Appendix G's phase functions: two HG lobes (Mitsuba's blendphase) and Rayleigh.
    scenes += [
        box_scene("fog_hg2", "Two-lobe HG fog, 0.7 HG(+0.8) + 0.3 HG(-0.5)",
                  dict(sigma_t=0.5, albedo=(0.85, 0.85, 0.85), g=0.8, g2=-0.5, w=0.7), diffuse_ball),
        box_scene("fog_rayleigh", "Rayleigh fog",
                  dict(sigma_t=0.5, albedo=(0.85, 0.85, 0.85), g=0.0, phase="rayleigh"), diffuse_ball),
    ]
    # Single scattering in unbounded fog, no geometry: the closed-form check (quadrature).
    cam = dict(position=(0.0, 0.0, 3.0), target=(0.0, 0.0, 0.0), up=(0.0, 1.0, 0.0), vfov=40.0)
    for nm, g, light in (
        ("single_point_g+0.8", 0.8, dict(type="point", position=(0.35, 0.25, -0.5), intensity=(1.0, 1.0, 1.0))),
        ("single_spot_g-0.5", -0.5, dict(type="spot", position=(-0.6, 0.6, 0.0), direction=(1.0, -0.6, 0.3),
                                         intensity=(2.0, 2.0, 2.0), cutoff_deg=25.0, beam_deg=10.0)),
    ):
        scenes.append(dict(name=nm, title="Single scattering only, %s light in unbounded fog, g = %+.1f"
                           % (light["type"], g),
                           fog=dict(sigma_t=0.5, albedo=(0.7, 0.7, 0.7), g=g), shapes=[], materials={},
                           lights=[light], camera=cam, max_depth=1, analytic=True, fresnel="exact"))
    return scenes


# ---------------------------------------------------------------------------------------
# fogrt: COLLADA writer and CS184 camera file
# ---------------------------------------------------------------------------------------


def _f(v):
    return " ".join("%.9g" % x for x in v)


def _normalize(v):
    n = math.sqrt(sum(x * x for x in v))
    return tuple(x / n for x in v)


def _cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def _sub(a, b):
    return tuple(x - y for x, y in zip(a, b))


def light_frame(direction):
    """An orthonormal frame (x, y, z) whose z axis is -direction (COLLADA lights shine
    along their local -Z)."""
    z = _normalize(tuple(-c for c in direction))
    hint = (0.0, 1.0, 0.0) if abs(z[1]) < 0.9 else (1.0, 0.0, 0.0)
    x = _normalize(_cross(hint, z))
    y = _cross(z, x)
    return x, y, z


def write_dae(scene, path):
    fx, mats, geoms, nodes, lights = [], [], [], [], []
    for mname, m in sorted(scene["materials"].items()):
        if m["type"] == "diffuse":
            body = ("<profile_COMMON><technique sid=\"common\"><lambert><diffuse><color>%s 1</color>"
                    "</diffuse></lambert></technique></profile_COMMON>" % _f(m["reflectance"]))
        elif m["type"] == "emitter":
            body = ("<extra><technique profile=\"CGL\"><emission><radiance>%s</radiance></emission>"
                    "</technique></extra>" % _f(m["radiance"]))
        elif m["type"] == "mirror":
            body = ("<extra><technique profile=\"CGL\"><mirror><reflectance>%s</reflectance></mirror>"
                    "</technique></extra>" % _f(m["reflectance"]))
        elif m["type"] == "glass":
            body = ("<extra><technique profile=\"CGL\"><glass><reflectance>%s</reflectance>"
                    "<transmittance>%s</transmittance><roughness>0</roughness><ior>%.9g</ior></glass>"
                    "</technique></extra>" % (_f(m["reflectance"]), _f(m["transmittance"]), m["ior"]))
        elif m["type"] == "interface":
            body = ("<profile_COMMON><technique sid=\"common\"><lambert><diffuse><color>0.5 0.5 0.5 1</color>"
                    "</diffuse></lambert></technique></profile_COMMON>")
        else:
            raise ValueError("unknown material type " + m["type"])
        fx.append("    <effect id=\"%s-fx\">%s</effect>" % (mname, body))
        mats.append("    <material id=\"%s-mat\"><instance_effect url=\"#%s-fx\"/></material>" % (mname, mname))

    def bind(mname):
        return ("<bind_material><technique_common><instance_material symbol=\"m\" target=\"#%s-mat\"/>"
                "</technique_common></bind_material>" % mname)

    for s in scene["shapes"]:
        n = s["name"]
        if s["kind"] == "mesh":
            flat = [c for v in s["verts"] for c in v]
            idx = [i for f in s["faces"] for i in f]
            geoms.append(
                "    <geometry id=\"%s-geo\"><mesh>\n"
                "      <source id=\"%s-pos\"><float_array id=\"%s-pos-array\" count=\"%d\">%s</float_array>\n"
                "        <technique_common><accessor source=\"#%s-pos-array\" count=\"%d\" stride=\"3\">"
                "<param name=\"X\" type=\"float\"/><param name=\"Y\" type=\"float\"/><param name=\"Z\" type=\"float\"/>"
                "</accessor></technique_common></source>\n"
                "      <vertices id=\"%s-vtx\"><input semantic=\"POSITION\" source=\"#%s-pos\"/></vertices>\n"
                "      <triangles count=\"%d\" material=\"m\"><input semantic=\"VERTEX\" source=\"#%s-vtx\" offset=\"0\"/>"
                "<p>%s</p></triangles>\n"
                "    </mesh></geometry>"
                % (n, n, n, len(flat), _f(flat), n, len(s["verts"]), n, n, len(s["faces"]), n,
                   " ".join(str(i) for i in idx)))
            nodes.append("      <node id=\"%s\" name=\"%s\"><instance_geometry url=\"#%s-geo\">%s</instance_geometry></node>"
                         % (n, n, n, bind(s["material"])))
        else:
            geoms.append("    <geometry id=\"%s-geo\"><extra><technique profile=\"CGL\"><sphere><radius>%.9g"
                         "</radius></sphere></technique></extra></geometry>" % (n, s["radius"]))
            c = s["center"]
            nodes.append("      <node id=\"%s\" name=\"%s\"><matrix>1 0 0 %.9g  0 1 0 %.9g  0 0 1 %.9g  0 0 0 1</matrix>"
                         "<instance_geometry url=\"#%s-geo\">%s</instance_geometry></node>"
                         % (n, n, c[0], c[1], c[2], n, bind(s["material"])))
    for i, l in enumerate(scene["lights"]):
        lid = "light%d" % i
        p = l["position"]
        if l["type"] == "point":
            lights.append("    <light id=\"%s\"><technique_common><point><color>%s</color></point>"
                          "</technique_common></light>" % (lid, _f(l["intensity"])))
            m = (1, 0, 0, p[0], 0, 1, 0, p[1], 0, 0, 1, p[2], 0, 0, 0, 1)
        else:
            # Blender's COLLADA: falloff_angle = the full cone, falloff_exponent = the blend,
            # which fogrt_load.h maps to cutoff = angle / 2, beam = cutoff (1 - blend).
            blend = 1.0 - l["beam_deg"] / l["cutoff_deg"]
            lights.append("    <light id=\"%s\"><technique_common><spot><color>%s</color>"
                          "<falloff_angle>%.9g</falloff_angle><falloff_exponent>%.9g</falloff_exponent>"
                          "</spot></technique_common></light>" % (lid, _f(l["intensity"]), 2 * l["cutoff_deg"], blend))
            x, y, z = light_frame(l["direction"])
            m = (x[0], y[0], z[0], p[0], x[1], y[1], z[1], p[1], x[2], y[2], z[2], p[2], 0, 0, 0, 1)
        nodes.append("      <node id=\"%s-node\"><matrix>%s</matrix><instance_light url=\"#%s\"/></node>"
                     % (lid, _f(m), lid))
    text = "\n".join([
        "<?xml version=\"1.0\" encoding=\"utf-8\"?>",
        "<!-- Written by tests/crosscheck/scenes.py for the fogrt / Mitsuba 3 cross-check: %s -->" % scene["title"],
        "<COLLADA xmlns=\"http://www.collada.org/2005/11/COLLADASchema\" version=\"1.4.1\">",
        "  <asset><up_axis>Y_UP</up_axis></asset>",
        "  <library_effects>", *fx, "  </library_effects>",
        "  <library_materials>", *mats, "  </library_materials>",
        "  <library_geometries>", *geoms, "  </library_geometries>",
        "  <library_lights>", *lights, "  </library_lights>",
        "  <library_visual_scenes><visual_scene id=\"scene\">", *nodes, "  </visual_scene></library_visual_scenes>",
        "  <scene><instance_visual_scene url=\"#scene\"/></scene>",
        "</COLLADA>", ""])
    with open(path, "w") as f:
        f.write(text)


def write_camera(scene, width, height, path):
    """CS184's camera settings file (fogrt -c): pos, target, the camera-to-world rotation
    (its second column is the up vector) and screenW screenH screenDist, which set the
    vertical field of view: tan(vfov / 2) = (screenH / 2) / screenDist."""
    c = scene["camera"]
    fwd = _normalize(_sub(c["target"], c["position"]))
    right = _normalize(_cross(fwd, c["up"]))
    up = _cross(right, fwd)
    back = tuple(-x for x in fwd)
    dist = 0.5 * height / math.tan(math.radians(c["vfov"]) / 2)
    hfov = 2 * math.degrees(math.atan(math.tan(math.radians(c["vfov"]) / 2) * width / height))
    r = math.sqrt(sum(x * x for x in _sub(c["position"], c["target"])))
    rows = [
        (hfov, c["vfov"], width / height, 0.01, 100.0),
        tuple(c["position"]) + tuple(c["target"]),
        (0.0, 0.0, r, 0.1, 100.0),
        (right[0], up[0], back[0], right[1], up[1], back[1], right[2], up[2], back[2]),
        (width, height, dist),
    ]
    with open(path, "w") as f:
        for row in rows:
            f.write(_f(row) + "\n")


def fogrt_args(scene):
    """Fog and method flags of the fogrt command for this scene."""
    a = ["-m", str(scene["max_depth"]), "--fresnel", scene.get("fresnel", "exact")]
    def fog_flags(fog):
        a = ["--density", sigma_text(fog), "--albedo", ",".join("%.9g" % x for x in fog["albedo"])]
        if fog.get("phase") == "rayleigh":
            return a + ["--phase", "rayleigh"]
        if "g2" in fog:
            return a + ["--g", "%.9g,%.9g,%.9g" % (fog["g"], fog["g2"], fog["w"])]
        return a + ["--g", "%.9g" % fog["g"]]
    if scene["fog"]:
        a += fog_flags(scene["fog"])
    for it in scene.get("interiors", []):           # media inside shapes: after the world's fog
        a += ["--medium", it["shape"]] + (["--interface"] if it.get("interface") else []) + fog_flags(it["medium"])
    return a


# ---------------------------------------------------------------------------------------
# Mitsuba 3
# ---------------------------------------------------------------------------------------


def _rgb(v):
    return {"type": "rgb", "value": list(v)}


def write_obj(shape, path):
    with open(path, "w") as f:
        for v in shape["verts"]:
            f.write("v %.9g %.9g %.9g\n" % tuple(v))
        for t in shape["faces"]:
            f.write("f %d %d %d\n" % (t[0] + 1, t[1] + 1, t[2] + 1))


def mitsuba_phase(fog):
    """Mitsuba's phase function for a fog dict: hg, blendphase of two hg (weight = the second
    lobe's share), or rayleigh."""
    if fog.get("phase") == "rayleigh":
        return {"type": "rayleigh"}
    if "g2" in fog:
        return {"type": "blendphase", "weight": 1.0 - fog["w"],
                "phase1": {"type": "hg", "g": fog["g"]}, "phase2": {"type": "hg", "g": fog["g2"]}}
    return {"type": "hg", "g": fog["g"]}


def mitsuba_dict(mi, scene, width, height, mesh_dir, fog_box=50.0):
    T = mi.ScalarTransform4f
    c = scene["camera"]
    fog = scene["fog"]
    d = {"type": "scene",
         "integrator": {"type": "volpathmis" if chromatic(fog) else "volpath", "max_depth": scene["max_depth"] + 1},
         "sensor": {"type": "perspective", "fov": c["vfov"], "fov_axis": "y",
                    "near_clip": 1e-5, "far_clip": 1e4,
                    "to_world": T().look_at(origin=list(c["position"]), target=list(c["target"]), up=list(c["up"])),
                    "film": {"type": "hdrfilm", "width": width, "height": height, "pixel_format": "rgb",
                             "rfilter": {"type": "box"}},
                    "sampler": {"type": "independent"}}}
    inside = {}
    if fog:
        d["fog"] = {"type": "homogeneous", "albedo": _rgb(fog["albedo"]),
                    "sigma_t": _rgb(fog["sigma_t"]) if chromatic(fog) else fog["sigma_t"],
                    "phase": mitsuba_phase(fog)}
        ref = {"type": "ref", "id": "fog"}
        d["sensor"]["medium"] = ref
        d["fog_boundary"] = {"type": "cube", "to_world": T().scale(fog_box), "bsdf": {"type": "null"},
                             "interior": ref}
        inside = {"exterior": ref}
    for mname, m in scene["materials"].items():
        if m["type"] == "diffuse":
            b = {"type": "twosided", "bsdf": {"type": "diffuse", "reflectance": _rgb(m["reflectance"])}}
        elif m["type"] == "mirror":
            b = {"type": "twosided", "bsdf": {"type": "conductor", "material": "none",
                                              "specular_reflectance": _rgb(m["reflectance"])}}
        elif m["type"] == "glass":
            b = {"type": "dielectric", "int_ior": m["ior"], "ext_ior": 1.0,
                 "specular_reflectance": _rgb(m["reflectance"]), "specular_transmittance": _rgb(m["transmittance"])}
        elif m["type"] == "interface":
            b = {"type": "null"}
        else:   # an emitter reflects nothing
            b = {"type": "diffuse", "reflectance": _rgb((0.0, 0.0, 0.0))}
        d["bsdf_" + mname] = dict(b, id="bsdf_" + mname)
    for s in scene["shapes"]:
        m = scene["materials"][s["material"]]
        if s["kind"] == "mesh":
            p = os.path.join(mesh_dir, "%s_%s.obj" % (scene["name"], s["name"]))
            write_obj(s, p)
            sh = {"type": "obj", "filename": p, "face_normals": True}
        else:
            sh = {"type": "sphere", "center": list(s["center"]), "radius": s["radius"]}
        sh["bsdf"] = {"type": "ref", "id": "bsdf_" + s["material"]}
        if m["type"] == "emitter":
            sh["emitter"] = {"type": "area", "radiance": _rgb(m["radiance"])}
        sh.update(inside)
        if fog and m["type"] not in ("glass", "interface"):
            sh["interior"] = inside["exterior"]      # opaque: the fog on both sides
        for it in scene.get("interiors", []):       # a medium of its own inside the shape
            if it["shape"] == s["name"]:
                f = it["medium"]
                sh["interior"] = {"type": "homogeneous", "sigma_t": f["sigma_t"], "albedo": _rgb(f["albedo"]),
                                  "phase": mitsuba_phase(f)}
        d["shape_" + s["name"]] = sh
    for i, l in enumerate(scene["lights"]):
        if l["type"] == "point":
            d["light%d" % i] = {"type": "point", "position": list(l["position"]), "intensity": _rgb(l["intensity"])}
        else:
            p = l["position"]
            tgt = [p[k] + l["direction"][k] for k in range(3)]
            dn = _normalize(l["direction"])
            up = [0.0, 1.0, 0.0] if abs(dn[1]) < 0.9 else [1.0, 0.0, 0.0]
            d["light%d" % i] = {"type": "spot", "intensity": _rgb(l["intensity"]),
                                "cutoff_angle": l["cutoff_deg"], "beam_width": l["beam_deg"],
                                "to_world": T().look_at(origin=list(p), target=tgt, up=up)}
    return d
