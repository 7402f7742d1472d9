"""Blender side of the export numbers in `make bench`: how fast a big mesh reaches the native side, and what
instancing costs.

    bin/candela-blender -b --factory-startup -noaudio --python-exit-code 1 --python bench/export_bench.py -- \
        [--triangles 1000000] [--instances 1000] [--repeats 3]

1. Export speed: a smooth-shaded grid of about --triangles triangles (one object). Timed with
   time.perf_counter(): the add-on's export of the evaluated scene (candela.export.export_scene: to_mesh, loop
   triangles, split normals, foreach_get into numpy, the material/light/camera tables) plus the native
   Session's array intake (`_native.Session(arrays, params)`: validation and copy), i.e. everything between
   Blender's data and the renderer holding it; not the BVH build. Best of --repeats (the first run warms caches);
   the per-stage times of the best run are reported too.
2. Instancing: one mesh (a subdivided ico-sphere) drawn by 1 object, then by --instances objects sharing its
   data (linked duplicates, what particle and collection instances become). For each, the bytes of the
   exported arrays and the native scene's memory after the build (Session.stats(): Embree's buffers and BVHs
   from its memory monitor, plus Candela's per-triangle shading data and per-instance records).

Prints one line `EXPORT_BENCH_JSON {...}`.
"""

import argparse
import json
import math
import sys
import time

import bpy
import numpy as np


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    ap = argparse.ArgumentParser(prog="export_bench.py")
    ap.add_argument("--triangles", type=int, default=1_000_000)
    ap.add_argument("--instances", type=int, default=1000)
    ap.add_argument("--instance-subdivisions", type=int, default=6, help="ico-sphere subdivisions (6: 20,480 tris)")
    ap.add_argument("--repeats", type=int, default=3)
    return ap.parse_args(argv)


def fresh_scene():
    bpy.ops.wm.read_homefile(use_empty=True)
    scene = bpy.context.scene
    scene.render.engine = "CANDELA"
    scene.render.resolution_x = scene.render.resolution_y = 8
    scene.render.resolution_percentage = 100
    scene.candela.samples = 1
    cam = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
    cam.location = (0.0, -30.0, 10.0)
    cam.rotation_euler = (math.radians(70.0), 0.0, 0.0)
    scene.collection.objects.link(cam)
    scene.camera = cam
    light = bpy.data.objects.new("Sun", bpy.data.lights.new("Sun", "SUN"))
    scene.collection.objects.link(light)
    return scene


def grid_mesh(triangles):
    """A smooth-shaded (n × n quads) grid with 2n² ≈ `triangles`, built from numpy arrays."""
    n = max(1, int(round(math.sqrt(triangles / 2.0))))
    xs = np.linspace(-10.0, 10.0, n + 1, dtype=np.float32)
    gx, gy = np.meshgrid(xs, xs)
    co = np.stack([gx, gy, 0.3 * np.sin(gx) * np.cos(gy)], -1).reshape(-1, 3)
    i, j = np.meshgrid(np.arange(n), np.arange(n))
    v0 = (j * (n + 1) + i).ravel()
    quads = np.stack([v0, v0 + 1, v0 + n + 2, v0 + n + 1], -1).astype(np.int32)
    me = bpy.data.meshes.new("Grid")
    me.vertices.add(len(co))
    me.vertices.foreach_set("co", co.ravel())
    me.loops.add(quads.size)
    me.loops.foreach_set("vertex_index", quads.ravel())
    me.polygons.add(len(quads))
    me.polygons.foreach_set("loop_start", np.arange(0, quads.size, 4, dtype=np.int32))
    me.polygons.foreach_set("loop_total", np.full(len(quads), 4, np.int32))
    me.polygons.foreach_set("use_smooth", np.ones(len(quads), bool))
    me.update(calc_edges=True)
    me.validate()
    return me


def stage_times(depsgraph, camera):
    """Per-stage times of one export of the (single) mesh object, for the report."""
    from candela.export.mesh import read_mesh
    ob = next(i.object for i in depsgraph.object_instances if i.object.type == 'MESH')
    t0 = time.perf_counter()
    data = read_mesh(ob)
    t1 = time.perf_counter()
    return {"read_mesh": t1 - t0, "triangles": int(len(data.triangles))}


def export_and_intake(scene):
    from candela import native
    from candela.export import export_scene, render_camera
    from candela.params import to_native_params
    nat = native.require()
    depsgraph = bpy.context.evaluated_depsgraph_get()
    camera = render_camera(scene)
    t0, c0 = time.perf_counter(), time.process_time()
    arrays = export_scene(depsgraph, camera)
    t1, c1 = time.perf_counter(), time.process_time()
    params = to_native_params(scene, camera.data, argv=[])
    session = nat.Session(arrays, params)
    t2, c2 = time.perf_counter(), time.process_time()
    return arrays, session, {"export": t1 - t0, "intake": t2 - t1, "total": t2 - t0,
                             "export_cpu": c1 - c0, "intake_cpu": c2 - c1, "total_cpu": c2 - c0}


def export_speed(a):
    scene = fresh_scene()
    ob = bpy.data.objects.new("Grid", grid_mesh(a.triangles))
    scene.collection.objects.link(ob)
    runs = []
    for _ in range(max(1, a.repeats)):
        arrays, session, t = export_and_intake(scene)
        t["triangles"] = int(len(arrays["triangles"]))
        t["array_bytes"] = int(sum(v.nbytes for v in arrays.values()))
        runs.append(t)
        del session, arrays
    best = min(runs, key=lambda r: r["total"])
    stages = stage_times(bpy.context.evaluated_depsgraph_get(), scene.camera)
    return {"runs": runs, "best": best, "read_mesh_seconds": stages["read_mesh"]}


def build_and_measure(scene):
    arrays, session, t = export_and_intake(scene)
    session.start()
    while not session.wait(0.1):
        pass
    session.join()
    if session.error:
        raise RuntimeError(session.error)
    st = session.stats()
    return {"array_bytes": int(sum(v.nbytes for v in arrays.values())),
            "arrays": {k: int(v.nbytes) for k, v in arrays.items()},
            "scene_bytes": int(st["scene_bytes"]), "embree_bytes": int(st["embree_bytes"]),
            "shading_bytes": int(st["shading_bytes"]), "unique_triangles": int(st["unique_triangles"]),
            "instanced_triangles": int(st["instanced_triangles"]), "instances": int(st["instances"]),
            "meshes": int(st["meshes"]), "build_seconds": float(st["build_seconds"]), "export_seconds": t["total"]}


def instancing(a):
    out = {}
    for count in (1, a.instances):
        scene = fresh_scene()
        bpy.ops.mesh.primitive_ico_sphere_add(subdivisions=a.instance_subdivisions, radius=0.4)
        proto = bpy.context.object
        for poly in proto.data.polygons:
            poly.use_smooth = True
        side = int(math.ceil(math.sqrt(count)))
        for k in range(1, count):
            dup = bpy.data.objects.new(f"Ball.{k:04d}", proto.data)     # linked duplicate: shares the mesh
            dup.location = ((k % side) - side / 2.0, (k // side) - side / 2.0, 0.0)
            scene.collection.objects.link(dup)
        out[str(count)] = build_and_measure(scene)
    return out


def main():
    a = parse_args()
    result = {"blender": bpy.app.version_string, "export": export_speed(a), "instancing": instancing(a),
              "instances": a.instances}
    print("EXPORT_BENCH_JSON " + json.dumps(result), flush=True)


if __name__ == "__main__":
    main()
