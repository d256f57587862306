#!/usr/bin/env python3
"""Writes the benchmark scenes in scenes/bench/ (CSE457 YAML, see docs/performance.md):

  dense_mesh.yaml  the corpus martini glass, Loop-subdivided 3 levels, on a floor:
                   824,268 triangles (martini.ply loses 81 degenerate faces), the
                   rtk-vs-Embree ray workload
  spheres.yaml     10,000 spheres on a floor (a fixed pseudo-random layout)
  deep.yaml        mirrors and glass, Maximum Recursion Depth 10
  scale/martini_L0.yaml .. martini_L5.yaml
                   dense_mesh.yaml at 0 to 5 Loop levels (12,891 to 13,188,108
                   triangles): the cost curve of `make bench-scale`

Output is deterministic (own LCG, fixed number formatting): rerunning it rewrites the
same bytes. Usage: bench/gen_scenes.py [OUTDIR]   (default scenes/bench)
"""
import math
import os
import sys

IND = "    "


def num(x):
    """Numbers as the corpus writes them: short, no trailing zeros."""
    s = "%.6g" % x
    return "0" if s == "-0" else s


def xyz(key, v, depth):
    pad = IND * depth
    return [f"{pad}{key}:", f"{pad}{IND}X:  {num(v[0])}", f"{pad}{IND}Y:  {num(v[1])}", f"{pad}{IND}Z:  {num(v[2])}"]


def color(key, rgb, depth):
    pad = IND * depth
    return [f"{pad}{key}:", f"{pad}{IND}Color:", f"{pad}{IND * 2}A:  1",
            f"{pad}{IND * 2}B:  {num(rgb[2])}", f"{pad}{IND * 2}G:  {num(rgb[1])}", f"{pad}{IND * 2}R:  {num(rgb[0])}",
            f'{pad}{IND}Color Map: ""', f"{pad}{IND}Use Texture: false"]


def material(name, kd, ks=(0, 0, 0), ke=(0, 0, 0), kt=(0, 0, 0), shininess=20, ior=1):
    lines = [f"{IND}{name}:", f"{IND * 2}Shader: Blinn-Phong Shader", f"{IND * 2}Uniforms:"]
    lines += color("Diffuse", kd, 3) + color("Emissive", ke, 3)
    lines += [f"{IND * 3}IndexOfRefraction: {num(ior)}", f"{IND * 3}Shininess: {num(shininess)}"]
    lines += color("Specular", ks, 3) + color("Transmittence", kt, 3)
    return lines


def node(name, component, translation=(0, 0, 0), rotation=(0, 0, 0), scale=(1, 1, 1), children=None, depth=2):
    """One scene node at list depth `depth`; component is a list of lines relative to Components."""
    pad = IND * depth
    lines = [f"{pad}-   Name: {name}", f"{pad}    Enabled: true", f"{pad}    Components:",
             f"{pad}        Transform:"]
    lines += xyz("Rotation", rotation, depth + 3) + xyz("Scale", scale, depth + 3) + xyz("Translation", translation, depth + 3)
    lines += [f"{pad}        {line}" for line in component]
    if children:
        lines.append(f"{pad}    Children:")
        for child in children:
            lines += child
    else:
        lines += [f"{pad}    Children:", f"{pad}        []"]
    return lines


def shape(kind, mat, subdivision=None, mesh=None):
    if kind == "TriangleMesh":
        return ["TriangleMesh:", f"    LoopSubdivision: {subdivision}", f"    Material: {mat}", f"    Mesh: {mesh}"]
    return [f"{kind}:", f"    Material: {mat}"]


def rgba(key, rgb, depth):
    pad = IND * depth
    return [f"{pad}{key}:", f"{pad}{IND}A:  1", f"{pad}{IND}B:  {num(rgb[2])}", f"{pad}{IND}G:  {num(rgb[1])}",
            f"{pad}{IND}R:  {num(rgb[0])}"]


def point_light(rgb, atten):
    return ["PointLight:"] + rgba("Ambient", (0, 0, 0), 1) + rgba("Color", rgb, 1) + \
        [f"    Const Atten: {num(atten[0])}", f"    Linear Atten: {num(atten[1])}", f"    Quad Atten: {num(atten[2])}",
         "    Radius (Trace): 0"]


def directional_light(rgb):
    return ["DirectionalLight:"] + rgba("Ambient", (0, 0, 0), 1) + ["    Angular Size (Trace): 0"] + \
        rgba("Color", rgb, 1) + ["    Intensity Multiplier: 1"]


def camera(name, eye, target, fov, size, depth, shadows=2):
    """A camera at `eye` looking at `target`: a yaw node holding a pitched camera node."""
    d = [t - e for t, e in zip(target, eye)]
    n = math.sqrt(sum(c * c for c in d))
    d = [c / n for c in d]
    pitch = math.degrees(math.asin(d[1]))
    yaw = math.degrees(math.atan2(-d[0], -d[2]))
    cam = ["Camera:", "    FOV: " + num(fov), "    Far Plane: 1000", "    Near Plane: 0.1",
           "    Orthographic View Width: 5", "    Perspective Camera?: true",
           f"    Render Height (px): {size[1]}", f"    Render Width (px): {size[0]}", "    Trace:",
           "        Aperture Size: 0", "        Caustics: false", "        Difference Threshold: 0.02",
           "        Diffuse Reflection: false", "        Enable BVH Acceleration: true",
           "        Focus Distance: 1", f"        Maximum Recursion Depth: {depth}", "        Maximum Samples: 2",
           "        Minimum Samples: 0", "        Monte Carlo: 0", "        Random Single Branching: false",
           "        Reflections: true", "        Refractions: true", "        Sample Count Type: 0",
           "        Samples Per Pixel: 0", f"        Shadows: {shadows}", "        Std. Error Threshold: 0.02"]
    inner = node(name, cam, rotation=(pitch, 0, 0), depth=4)
    return node(name + " Yaw", [], translation=eye, rotation=(0, yaw, 0), children=[inner])


def scene(name, meshes, materials, children):
    lines = [f"Name: {name}", "Animation Length: 20", "Animation FPS: 30", "Textures:", f"{IND}{{}}",
             "Cubemaps:", f"{IND}{{}}", "Meshes:"]
    if meshes:
        for mesh_name, path in meshes:
            lines += [f"{IND}{mesh_name}:", f"{IND * 2}Path: {path}"]
    else:
        lines.append(f"{IND}{{}}")
    lines.append("Materials:")
    for m in materials:
        lines += m
    lines += ["ShaderPrograms:", f"{IND}Blinn-Phong Shader:", f'{IND * 2}Fragment: ""', f'{IND * 2}Geometry: ""',
              f"{IND * 2}Trace Compatible: true", f'{IND * 2}Vertex: ""', "Root:", f"{IND}Name: Root",
              f"{IND}Enabled: true", f"{IND}Components:", f"{IND * 2}Transform:"]
    lines += xyz("Rotation", (0, 0, 0), 3) + xyz("Scale", (1, 1, 1), 3) + xyz("Translation", (0, 0, 0), 3)
    lines.append(f"{IND}Children:")
    for child in children:
        lines += child
    return "\n".join(lines) + "\n"


# The corpus martini glass: martini.ply spans x, z [-2.53, 2.53], y [-2.94, 2.48].
MARTINI_BOTTOM = -2.93809


def dense_mesh(levels=3, name="dense_mesh"):
    """martini.ply (12,879 usable triangles, welded) at 3 Loop levels: 64 x 12,879 = 824,256, plus a floor."""
    materials = [material("floor", (0.188, 0.216, 0.2), ks=(0.3, 0.3, 0.3), shininess=128),
                 material("glass", (0.35, 0.45, 0.55), ks=(0.4, 0.4, 0.4), shininess=64)]
    scale = 0.5
    children = [
        node("Key Light", directional_light((0.8, 0.8, 0.8)), rotation=(30, 0, -35)),
        node("Point Light", point_light((1, 1, 1), (1, 0, 0.02)), translation=(1.5, 3.5, 2.5)),
        camera("Camera", (0, 3.4, 6.2), (0, 1.3, 0), 32, (512, 512), 3),
        node("Floor", shape("TriangleMesh", "floor", 0, "Cube"), translation=(0, -0.125, 0), scale=(12, 0.25, 12)),
        node("Martini", shape("TriangleMesh", "glass", levels, "martini"), translation=(0, -MARTINI_BOTTOM * scale, 0),
             scale=(scale, scale, scale)),
    ]
    return scene(name, [("martini", "assets/trace/trimeshes/martini.ply")], materials, children)


class Lcg:
    """Numerical Recipes' 32-bit LCG: the same layout on every machine and Python."""

    def __init__(self, seed):
        self.state = seed

    def uniform(self):
        self.state = (1664525 * self.state + 1013904223) % 2**32
        return self.state / 2**32


def compact_sphere(name, mat, centre, diameter):
    """One sphere node in YAML flow style (default Rotation and Enabled left out), so that
    10,000 of them stay a small file."""
    d = "%.4g" % diameter
    c = ["%.4g" % v for v in centre]
    return (f"{IND * 2}-   {{Name: {name}, Components: {{Transform: {{Scale: {{X: {d}, Y: {d}, Z: {d}}}, "
            f"Translation: {{X: {c[0]}, Y: {c[1]}, Z: {c[2]}}}}}, Sphere: {{Material: {mat}}}}}, Children: []}}")


def spheres(count_side=100):
    palette = [material("red", (0.7, 0.15, 0.1), ks=(0.2, 0.2, 0.2)),
               material("green", (0.15, 0.6, 0.2), ks=(0.2, 0.2, 0.2)),
               material("blue", (0.1, 0.2, 0.7), ks=(0.2, 0.2, 0.2)),
               material("yellow", (0.7, 0.6, 0.1), ks=(0.2, 0.2, 0.2)),
               material("mirror", (0.05, 0.05, 0.05), ks=(0.8, 0.8, 0.8), shininess=128)]
    names = ["red", "green", "blue", "yellow", "mirror"]
    materials = palette + [material("floor", (0.5, 0.5, 0.5), shininess=10)]
    rng = Lcg(457)
    children = [
        node("Sun", directional_light((0.7, 0.7, 0.7)), rotation=(25, 0, 30)),
        node("Lamp", point_light((0.6, 0.6, 0.6), (1, 0, 0.0005)), translation=(0, 30, 0)),
        camera("Camera", (0, 22, 58), (0, 0, 5), 45, (512, 512), 3),
        node("Floor", shape("TriangleMesh", "floor", 0, "Cube"), translation=(0, -0.5, 0), scale=(110, 1, 110)),
    ]
    half = (count_side - 1) / 2
    for i in range(count_side):
        for j in range(count_side):
            r = 0.25 + 0.2 * rng.uniform()
            x = i - half + 0.2 * (rng.uniform() - 0.5)
            z = j - half + 0.2 * (rng.uniform() - 0.5)
            mat = names[int(rng.uniform() * len(names))]
            children.append([compact_sphere(f"S{i * count_side + j}", mat, (x, r, z), 2 * r)])
    return scene("spheres", [], materials, children)


def deep():
    materials = [material("floor", (0.4, 0.4, 0.4), ks=(0.3, 0.3, 0.3), shininess=64),
                 material("mirror", (0.02, 0.02, 0.02), ks=(0.9, 0.9, 0.9), shininess=256),
                 material("glass", (0.02, 0.02, 0.02), ks=(0.1, 0.1, 0.1), kt=(0.85, 0.85, 0.85), shininess=128, ior=1.5),
                 material("tinted", (0.05, 0.05, 0.05), ks=(0.1, 0.1, 0.1), kt=(0.6, 0.8, 0.9), shininess=64, ior=1.5),
                 material("red", (0.7, 0.1, 0.1), ks=(0.3, 0.3, 0.3), shininess=32),
                 material("gold", (0.6, 0.45, 0.1), ks=(0.5, 0.45, 0.2), shininess=64)]
    children = [
        node("Sun", directional_light((0.5, 0.5, 0.5)), rotation=(20, 0, 40)),
        node("Lamp", point_light((1, 1, 1), (1, 0.05, 0.01)), translation=(0, 5, 3)),
        camera("Camera", (1.2, 2.4, 9), (0, 1, 0), 50, (512, 512), 10),
        node("Floor", shape("TriangleMesh", "floor", 0, "Cube"), translation=(0, -0.1, 0), scale=(20, 0.2, 20)),
        node("Left Mirror", shape("TriangleMesh", "mirror", 0, "Cube"), translation=(-4, 3, 0), scale=(0.2, 6, 20)),
        node("Right Mirror", shape("TriangleMesh", "mirror", 0, "Cube"), translation=(4, 3, 0), scale=(0.2, 6, 20)),
        node("Back Mirror", shape("TriangleMesh", "mirror", 0, "Cube"), translation=(0, 3, -6), scale=(8, 6, 0.2)),
        node("Glass Ball 1", shape("Sphere", "glass"), translation=(-1.6, 0.8, 0), scale=(1.6, 1.6, 1.6)),
        node("Glass Ball 2", shape("Sphere", "tinted"), translation=(1.5, 0.7, 1.5), scale=(1.4, 1.4, 1.4)),
        node("Glass Ball 3", shape("Sphere", "glass"), translation=(0.3, 0.5, 3), scale=(1, 1, 1)),
        node("Glass Column", shape("Cylinder", "glass"), translation=(0.8, 1.25, -2), scale=(1.2, 2.5, 1.2)),
        node("Red Ball", shape("Sphere", "red"), translation=(-0.5, 0.6, -3.5), scale=(1.2, 1.2, 1.2)),
        node("Gold Ball", shape("Sphere", "gold"), translation=(-2.5, 0.5, -2.5), scale=(1, 1, 1)),
    ]
    return scene("deep", [], materials, children)


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", "scenes", "bench")
    os.makedirs(out, exist_ok=True)
    scenes = [("dense_mesh.yaml", dense_mesh()), ("spheres.yaml", spheres()), ("deep.yaml", deep())]
    scenes += [(f"scale/martini_L{n}.yaml", dense_mesh(n, f"martini_L{n}")) for n in range(6)]
    os.makedirs(os.path.join(out, "scale"), exist_ok=True)
    for name, text in scenes:
        with open(os.path.join(out, name), "w", newline="\n") as f:
            f.write(text)


if __name__ == "__main__":
    main()
