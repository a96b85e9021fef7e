#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""Real meshes end to end (ctest -L workloads): scripts/workloads converts and places
glmark2's meshes, then

- bunny.obj (Stanford bunny) on configs/d3d11.toml: the loader reads all 69,666
  triangles (the published count, and the file's own 'f' lines, every one a triangle);
  the reference model, the SystemC model and the RTL (cosim: no fragment mismatch) give
  the same framebuffer CRC; command fetch costs what its equation gives, worked by
  hand, with one command a face and with the mesh in one command
  (scene.obj_faces_per_command), which leaves the image alone; the image
  is not empty and the silhouette's bounding box lies inside the viewport and matches the
  bounding box of the vertices projected here with numpy (an independent placement:
  centre, radius, yaw, pitch, orthographic, to within a pixel and a half);
- horse.3ds (7,172 triangles; reference = SystemC) and cat.3ds converted by assimp,
  placed with their NAME.set (obj_up = -z, from the side), stand upright: each rests on
  a base, its lowest rows (1/30 of its height) spanning at least half its width and more
  than twice what its highest rows span (the horse rears on its hind legs, hooves and
  tail on the ground, head and forelegs up; the cat lies on a flat cut). From the side
  the cat is wider than tall and the rearing horse taller than wide. The same meshes
  turned upside down (obj_up = z) and left Y-up (the default) fail the check, so it can
  tell;
- the bunny and the horse through the perspective camera (scene.camera = perspective),
  from outside and from inside the mesh (check_perspective);
- the textured crate (cube.3ds with crate-base.png, its MTL's map_Kd pointed at the PNG):
  12 triangles, every fragment a bilinear sample of 4 texel fetches, and the wood's grain
  on screen: many more sharp steps between neighbouring pixels than the same mesh drawn
  without its map_Kd (Gouraud shading alone is smooth).

usage: test_workloads.py RASTSIM SOURCE_DIR. Exits 77 (ctest: skipped) without
glmark2-data or assimp-utils.
"""
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile

import numpy as np
from PIL import Image

MODELS = os.environ.get("RASTSIM_GLMARK2_MODELS", "/usr/share/glmark2/models")  # as scripts/workloads
BUNNY_TRIANGLES = 69666   # the Stanford bunny as glmark2 ships it (published count)
HORSE_TRIANGLES = 7172    # horse.3ds through assimp 5.2 (docs/exploration.md)

failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what, flush=True)
    if not ok:
        failures.append(what)


def run(cmd):
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit("workloads test: %s failed (%d):\n%s%s" % (" ".join(cmd), r.returncode, r.stdout, r.stderr))
    return r.stdout


def read_sets(path):
    return [kv for kv in open(path).read().split() if kv]


def rastsim(binary, cmd, cfg, scene, sets, out_dir, tag):
    png, stats = os.path.join(out_dir, tag + ".png"), os.path.join(out_dir, tag + ".json")
    # memory.model = fixed: the checks are the meshes' loading, placement and images (the
    # SystemC image is the reference's); through the configs' DRAM model the real meshes
    # took 117 s against 22 s on 2 loaded cores (docs/memory.md, "The shipped configs").
    args = [binary, cmd, "--config", cfg, "--scene", scene, "--set", "raster.depth_func=less",
            "--set", "memory.model=fixed", "-q", "-o", png, "--stats", stats]
    for kv in sets:
        args += ["--set", kv]
    run(args)
    return np.asarray(Image.open(png).convert("RGB")), json.load(open(stats))


def ink_bbox(img):
    """(x0, y0, x1, y1) inclusive of the pixels that are not the clear colour (black)."""
    ys, xs = np.nonzero(img.any(axis=2))
    if len(xs) == 0:
        return None
    return xs.min(), ys.min(), xs.max(), ys.max()


def projected_bbox(obj_path, width, height, yaw_deg, pitch_deg, fill):
    """The placement of docs/trace-format.md done independently: Y-up vertices used by
    faces, bounding-box centre, bounding-sphere radius, yaw about y then pitch about x,
    orthographic, y down. Returns the vertices' screen bounding box."""
    verts, used = [], set()
    for line in open(obj_path):
        t = line.split()
        if t and t[0] == "v":
            verts.append([float(x) for x in t[1:4]])
        elif t and t[0] == "f":
            used.update(int(c.split("/")[0]) - 1 for c in t[1:])
    p = np.array(verts)[sorted(used)]
    centre = (p.min(axis=0) + p.max(axis=0)) / 2
    q = (p - centre) / np.linalg.norm(p - centre, axis=1).max()
    a, b = math.radians(yaw_deg), math.radians(pitch_deg)
    x1 = q[:, 0] * math.cos(a) + q[:, 2] * math.sin(a)
    z1 = -q[:, 0] * math.sin(a) + q[:, 2] * math.cos(a)
    y2 = q[:, 1] * math.cos(b) - z1 * math.sin(b)
    s = fill * min(width, height) / 2
    sx, sy = width / 2 + s * x1, height / 2 - s * y2
    return sx.min(), sy.min(), sx.max(), sy.max()


UP_AXES = {"y": lambda x, y, z: (x, y, z), "-y": lambda x, y, z: (x, -y, -z), "z": lambda x, y, z: (x, z, -y),
           "-z": lambda x, y, z: (x, -z, y), "x": lambda x, y, z: (-y, x, z), "-x": lambda x, y, z: (y, -x, z)}


def view_space(obj_path, up, yaw_deg, pitch_deg):
    """Steps 0 to 2 of docs/trace-format.md's placement done independently: every face's
    corners turned to the up axis, centred on the bounding-box centre, scaled by the
    bounding-sphere radius, yaw about y then pitch about x. Returns (x2, y2, z2) of every
    vertex and the faces as lists of vertex indices."""
    verts, faces = [], []
    for line in open(obj_path):
        t = line.split()
        if t and t[0] == "v":
            verts.append(UP_AXES[up](*[float(x) for x in t[1:4]]))
        elif t and t[0] == "f":
            faces.append([int(c.split("/")[0]) - 1 for c in t[1:]])
    p = np.array(verts)
    used = sorted({i for f in faces for i in f})
    centre = (p[used].min(axis=0) + p[used].max(axis=0)) / 2
    q = (p - centre) / np.linalg.norm(p[used] - centre, axis=1).max()
    a, b = math.radians(yaw_deg), math.radians(pitch_deg)
    x1 = q[:, 0] * math.cos(a) + q[:, 2] * math.sin(a)
    z1 = -q[:, 0] * math.sin(a) + q[:, 2] * math.cos(a)
    y2 = q[:, 1] * math.cos(b) - z1 * math.sin(b)
    z2 = q[:, 1] * math.sin(b) + z1 * math.cos(b)
    return x1, y2, z2, faces


def check_perspective(binary, cfg, name, mesh, sets, width, height, tmp):
    """The perspective camera (docs/trace-format.md) on a real mesh, from outside (the
    default scene.distance, 2.5 radii) and from inside (0.5: the eye between the centre and
    the front): the reference and SystemC give the same CRC; from outside the silhouette's
    box is the box of the vertices projected here (f = 1 / tan(fov / 2), x_c = f/a x2,
    y_c = -f y2, w_c = d - z2, viewport transform) to within a pixel and a half; from
    inside the front end culls exactly the faces whose corners all have w_c <= 0, counted
    here, and clips some, and the mesh's inner side fills most of the view."""
    kv = dict(a.split("=", 1) for a in sets)
    x2, y2, z2, faces = view_space(mesh, kv.get("scene.obj_up", "y"), float(kv.get("scene.obj_yaw_deg", 0)),
                                   float(kv.get("scene.obj_pitch_deg", 0)))
    f, aspect = 1 / math.tan(math.radians(60) / 2), width / height
    for d, where in ((2.5, "outside"), (0.5, "inside")):
        view = sets + ["scene.camera=perspective", "scene.distance=%g" % d]
        img, ref = rastsim(binary, "render", cfg, mesh, view, tmp, "%s_persp_%s" % (name, where))
        _, sc = rastsim(binary, "simulate", cfg, mesh, view, tmp, "%s_persp_%s_sc" % (name, where))
        check(ref["framebuffer_crc32"] == sc["framebuffer_crc32"] and ref["fragments"] > 0,
              "%s, perspective camera %s: %d fragments, CRC reference %s, SystemC %s" %
              (name, where, ref["fragments"], ref["framebuffer_crc32"], sc["framebuffer_crc32"]))
        w = (d - z2).astype(np.float32)
        if where == "outside":
            sx = width / 2 + width / 2 * (f / aspect) * x2 / w
            sy = height / 2 - height / 2 * f * y2 / w
            used = sorted({i for fc in faces for i in fc})
            want = (sx[used].min() - 0.5, sy[used].min() - 0.5, sx[used].max() - 0.5, sy[used].max() - 0.5)
            bb = ink_bbox(img)
            check(bb is not None and all(abs(g - e) <= 1.5 for g, e in zip(bb, want)),
                  "%s perspective silhouette %s = projected vertices' box %s within 1.5 px" %
                  (name, bb, tuple(round(e, 1) for e in want)))
        else:
            # A face of n corners is n - 2 triangles, all behind when every corner is; a
            # polygon with corners on both sides, or a corner within 1e-6 of w = 0 (where
            # numpy's cos and sin may round otherwise), is left as a tolerance.
            behind = sum(len(fc) - 2 for fc in faces if all(w[i] <= 0 for i in fc))
            near_zero = sum(len(fc) - 2 for fc in faces if any(abs(w[i]) < 1e-6 for i in fc) or
                            (len(fc) > 3 and any(w[i] <= 0 for i in fc) and not all(w[i] <= 0 for i in fc)))
            check(abs(ref["triangles_behind"] - behind) <= near_zero and ref["triangles_clipped"] > 0,
                  "%s, camera inside: %d triangles behind the eye (counted here: %d), %d clipped" %
                  (name, ref["triangles_behind"], behind, ref["triangles_clipped"]))
            covered = np.count_nonzero(img.any(axis=2)) / (width * height)
            check(covered > 0.25, "%s, camera inside: the inner side covers %.0f %% of the view" % (name, 100 * covered))


def faces_of(obj_path):
    n, corners = 0, set()
    for line in open(obj_path):
        if line.startswith("f "):
            n += 1
            corners.add(len(line.split()) - 1)
    return n, corners


def stands(img):
    """(upright, width, height, base span, top span): upright when the lowest 1/30 of
    the silhouette's rows spans at least half its width and more than twice the span of
    the highest 1/30 (spans in pixels, leftmost to rightmost ink)."""
    ink = img.any(axis=2)
    x0, y0, x1, y1 = ink_bbox(img)
    w, h = x1 - x0 + 1, y1 - y0 + 1
    k = max(1, h // 30)

    def span(rows):
        cols = np.nonzero(ink[rows].any(axis=0))[0]
        return cols.max() - cols.min() + 1

    base, top = span(slice(y1 - k + 1, y1 + 1)), span(slice(y0, y0 + k))
    return base >= w / 2 and base > 2 * top, w, h, base, top


def sharp_steps(img):
    """Horizontally neighbouring pixels, both not black, whose channel sums differ by more than 24."""
    g = img.astype(int).sum(axis=2)
    ink = (g[:, 1:] > 0) & (g[:, :-1] > 0)
    return int(((abs(g[:, 1:] - g[:, :-1]) > 24) & ink).sum())


def check_crate(binary, cfg, tmp):
    crate, sets = os.path.join(tmp, "crate.obj"), read_sets(os.path.join(tmp, "crate.set"))
    mtl = open(os.path.join(tmp, "crate.mtl")).read()
    check("map_Kd crate-base.png" in mtl and os.path.isfile(os.path.join(tmp, "crate-base.png")),
          "crate.mtl's map_Kd names the linked crate-base.png")
    img, st = rastsim(binary, "render", cfg, crate, sets, tmp, "crate")
    samples = st.get("texture_samples", {}).get("bilinear", 0)
    check(st["triangles_in"] == 12 and samples == st["fragments"] > 0 and st["texel_fetches"] == 4 * samples,
          "crate: %d triangles, %d fragments, %d bilinear samples, %d texel fetches" %
          (st["triangles_in"], st["fragments"], samples, st.get("texel_fetches", 0)))
    # The same mesh without its texture: the control.
    plain = os.path.join(tmp, "plain")
    os.makedirs(plain, exist_ok=True)
    shutil.copy(crate, plain)
    with open(os.path.join(plain, "crate.mtl"), "w") as f:
        f.write("".join(l for l in mtl.splitlines(True) if not l.startswith("map_Kd")))
    img_plain, _ = rastsim(binary, "render", cfg, os.path.join(plain, "crate.obj"), sets, tmp, "crate_plain")
    steps, steps_plain = sharp_steps(img), sharp_steps(img_plain)
    check(steps > 2000 and steps > 20 * max(1, steps_plain),
          "crate textured: %d sharp steps between neighbours, untextured %d" % (steps, steps_plain))


def main():
    binary, src = sys.argv[1], sys.argv[2]
    if not os.path.isfile(os.path.join(MODELS, "bunny.obj")):
        print("workloads test: SKIPPED: glmark2-data is not installed (%s/bunny.obj); "
              "scripts/setup.sh installs it (apt-get install glmark2-data assimp-utils)" % MODELS)
        return 77
    if shutil.which("assimp") is None:
        print("workloads test: SKIPPED: assimp is not installed (package assimp-utils, in scripts/setup.sh)")
        return 77
    cfg = os.path.join(src, "configs", "d3d11.toml")
    width, height, fill = 640, 480, 0.9  # configs/d3d11.toml's display; the schema's default fill
    with tempfile.TemporaryDirectory() as tmp:
        run([os.path.join(src, "scripts", "workloads"), "--out", tmp, "--no-render"])

        # ---- the bunny: every triangle read, reference = SystemC, placed where expected
        bunny = os.path.join(tmp, "bunny.obj")
        faces, corners = faces_of(bunny)
        check(faces == BUNNY_TRIANGLES and corners == {3},
              "bunny.obj has %d faces, all triangles (%s)" % (faces, corners))
        sets = read_sets(os.path.join(tmp, "bunny.set"))
        ref_img, ref = rastsim(binary, "render", cfg, bunny, sets, tmp, "bunny_ref")
        sc_img, sc = rastsim(binary, "simulate", cfg, bunny, sets, tmp, "bunny_sc")
        check(ref["triangles_in"] == BUNNY_TRIANGLES,
              "reference read %d triangles, want %d" % (ref["triangles_in"], BUNNY_TRIANGLES))
        check(ref["framebuffer_crc32"] == sc["framebuffer_crc32"] and (ref_img == sc_img).all(),
              "bunny CRC reference %s, SystemC %s" % (ref["framebuffer_crc32"], sc["framebuffer_crc32"]))
        print("     bunny: %d fragments, SystemC %d cycles" % (ref["fragments"], sc["cycles"]))
        # Command fetch's cost, worked from its documented equation (d3d11.toml keeps the
        # schema's fetch keys: 1 cycle a command header, 3 vertices a cycle, a List
        # triangle's 3 vertices in 1 cycle; the two clears 1 cycle each): one command a
        # face 2 x 69,666 + 2; the whole mesh in one command 1 + 69,666 + 2. The image
        # does not change.
        busy = sc["stages"]["command_fetch"]["busy"]
        check(busy == 2 * BUNNY_TRIANGLES + 2, "bunny, one command a face: fetch busy %d cycles" % busy)
        _, one = rastsim(binary, "simulate", cfg, bunny, sets + ["scene.obj_faces_per_command=%d" % BUNNY_TRIANGLES],
                         tmp, "bunny_one_command")
        busy = one["stages"]["command_fetch"]["busy"]
        check(busy == BUNNY_TRIANGLES + 3 and one["framebuffer_crc32"] == ref["framebuffer_crc32"],
              "bunny as one command: fetch busy %d cycles, CRC %s" % (busy, one["framebuffer_crc32"]))
        # The RTL too (verilated, fragment by fragment against the reference; ~4 s with
        # memory.model = fixed, about a minute through the config's DRAM model).
        args = [binary, "cosim", "--config", cfg, "--scene", bunny, "--set", "raster.depth_func=less",
                "--set", "memory.model=fixed", "--stats", os.path.join(tmp, "bunny_rtl.json")]
        for kv in sets:
            args += ["--set", kv]
        run(args)
        rtl = json.load(open(os.path.join(tmp, "bunny_rtl.json")))
        check(rtl["mismatches"] == 0 and rtl["framebuffer_crc32_rtl"] == ref["framebuffer_crc32"],
              "bunny through the RTL: %d mismatches, CRC %s" % (rtl["mismatches"], rtl["framebuffer_crc32_rtl"]))
        check_perspective(binary, cfg, "bunny", bunny, sets, width, height, tmp)
        bb = ink_bbox(ref_img)
        check(bb is not None and bb[0] > 0 and bb[1] > 0 and bb[2] < width - 1 and bb[3] < height - 1,
              "bunny silhouette %s inside the %dx%d viewport" % (bb, width, height))
        kv = dict(a.split("=", 1) for a in sets)
        check(kv.get("scene.obj_up", "y") == "y", "bunny.set keeps OBJ's Y-up: %s" % sets)
        want = projected_bbox(bunny, width, height, float(kv["scene.obj_yaw_deg"]),
                              float(kv["scene.obj_pitch_deg"]), fill)
        # A pixel is inked when its centre (x + 0.5) is inside: the ink spans the pixels
        # whose centres lie in [min, max] of the projected vertices, give or take one.
        expect = (want[0] - 0.5, want[1] - 0.5, want[2] - 0.5, want[3] - 0.5)
        check(bb is not None and all(abs(g - e) <= 1.5 for g, e in zip(bb, expect)),
              "bunny silhouette %s = projected vertices' box %s within 1.5 px" %
              (bb, tuple(round(e, 1) for e in expect)))

        # ---- horse and cat: converted by assimp, upright from the side
        for name in ("horse", "cat"):
            mesh = os.path.join(tmp, name + ".obj")
            sets = read_sets(os.path.join(tmp, name + ".set"))
            check("scene.obj_up=-z" in sets, "%s.set stands it along -z: %s" % (name, sets))
            img, st = rastsim(binary, "render", cfg, mesh, sets, tmp, name)
            if name == "horse":
                check(st["triangles_in"] == HORSE_TRIANGLES,
                      "horse: %d triangles, want %d" % (st["triangles_in"], HORSE_TRIANGLES))
                _, sc = rastsim(binary, "simulate", cfg, mesh, sets, tmp, "horse_sc")
                check(st["framebuffer_crc32"] == sc["framebuffer_crc32"],
                      "horse CRC reference %s, SystemC %s" % (st["framebuffer_crc32"], sc["framebuffer_crc32"]))
                check_perspective(binary, cfg, "horse", mesh, sets, width, height, tmp)
            up, w, h, base, top = stands(img)
            check(up, "%s stands upright: base %d px of width %d, top %d px" % (name, base, w, top))
            check(w > h if name == "cat" else h > w,
                  "%s from the side: %d wide, %d tall (%s)" % (name, w, h, "lying cat" if name == "cat" else "rearing horse"))
            # The controls: upside down and Y-up must not pass as upright.
            for wrong in ("z", "y"):
                bad = [kv for kv in sets if not kv.startswith("scene.obj_up=")] + ["scene.obj_up=" + wrong]
                img, _ = rastsim(binary, "render", cfg, mesh, bad, tmp, name + "_" + wrong)
                up, w, h, base, top = stands(img)
                check(not up, "%s placed with obj_up = %s is not upright (base %d px of width %d, top %d px)" %
                      (name, wrong, base, w, top))
        check_crate(binary, cfg, tmp)
    if failures:
        print("workloads test: %d check(s) failed" % len(failures))
        return 1
    print("workloads test: all checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
