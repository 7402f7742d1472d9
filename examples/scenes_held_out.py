"""The second held-out set of AUTO's acceptance measurement (docs/auto.md, "Acceptance"; examples/scenes.py
HELD_OUT_2): written after the policy was tuned on the first held-out set (HELD_OUT) and not used for any tuning.

"glossy_atrium" (a glossy interior open to a uniform sky: a glossy floor, a near-mirror panel, metal spheres; no delta
surface), "window_glass" (a room lit by a 1° sun and the sky through a window, a glass sphere on a table in the sun:
the sun's caustic is a path a path tracer cannot build), "table_caustic" (a closed room lit by a small area light
over a table with a glass sphere: a small-light caustic on the table, indirect light around it).
"""

import math

from mathutils import Matrix, Vector

import scenes as sc


def _walls(scene, material, half, height, names=("Back", "Front", "Left", "Right")):
    """The walls of a room [-half, half]² × [0, height] facing inward, the ones named."""
    deg = math.radians
    placements = {"Back": Matrix.Translation((0, half, height / 2)) @ Matrix.Rotation(deg(90), 4, "X"),
                  "Front": Matrix.Translation((0, -half, height / 2)) @ Matrix.Rotation(deg(-90), 4, "X"),
                  "Left": Matrix.Translation((-half, 0, height / 2)) @ Matrix.Rotation(deg(90), 4, "Y") @
                  Matrix.Rotation(deg(90), 4, "Z"),
                  "Right": Matrix.Translation((half, 0, height / 2)) @ Matrix.Rotation(deg(-90), 4, "Y") @
                  Matrix.Rotation(deg(90), 4, "Z")}
    for name in names:
        sc.rectangle(scene, name, material, placements[name] @ Matrix.Diagonal((half, height / 2, 1, 1)))


def _sun(scene, direction, energy, angle_deg):
    sun = sc.bpy.data.lights.new("Sun", 'SUN')
    sun.energy, sun.angle = energy, math.radians(angle_deg)
    ob = sc.bpy.data.objects.new("Sun", sun)
    ob.rotation_euler = Vector(direction).normalized().to_track_quat('-Z', 'Y').to_euler()
    scene.collection.objects.link(ob)


def build_glossy_atrium(scene):
    """A 6 × 6 m court with 3 m walls and no roof under a uniform sky: a glossy floor (GGX 0.2), a near-mirror
    panel on the back wall (GGX 0.04), a gold sphere (GGX 0.1) and a rough steel one (GGX 0.4), a diffuse block.
    The sky is the only light; glossy reflections of it and of the walls, no delta surface."""
    walls = sc.diffuse("Walls", (0.7, 0.68, 0.62))
    sc.rectangle(scene, "Floor", sc.glossy("Floor", (0.5, 0.45, 0.4), 0.2, "GGX"), Matrix.Diagonal((3.0, 3.0, 1, 1)))
    _walls(scene, walls, 3.0, 3.0, names=("Back", "Left", "Right"))
    sc.rectangle(scene, "Panel", sc.glossy("Panel", (0.8, 0.8, 0.85), 0.04, "GGX"),
                 Matrix.Translation((0.5, 2.97, 1.4)) @ Matrix.Rotation(math.radians(90), 4, "X") @
                 Matrix.Diagonal((1.2, 0.9, 1, 1)))
    sc.sphere(scene, "Gold", sc.glossy("Gold", (0.9, 0.7, 0.4), 0.1, "GGX"), (-1.0, 0.9, 0.7), 0.7)
    sc.sphere(scene, "Steel", sc.glossy("Steel", (0.7, 0.7, 0.75), 0.4, "GGX"), (1.2, 0.4, 0.5), 0.5)
    sc.cube(scene, "Block", sc.diffuse("Block", (0.3, 0.45, 0.25)),
            Matrix.Translation((0.3, 1.8, 0.4)) @ Matrix.Diagonal((0.4, 0.4, 0.4, 1)))
    sc.world(scene, (0.8, 0.85, 1.0), 1.2)
    sc.camera(scene, (0.0, -2.9, 1.7), (78.0, 0.0, 0.0), lens=20.0)
    return 4 / 3


def build_window_glass(scene):
    """A 4 × 4 × 2.6 m diffuse room with a 1.2 × 1.0 m window in the left wall (y ∈ [−0.6, 0.6], z ∈ [1.0, 2.0]), a
    1° sun and a sky outside; a table by the window with a glass sphere (r = 0.15 m) on it. The sphere's
    caustic on the table comes from the sun, which no ray can hit."""
    walls = sc.diffuse("Walls", (0.72, 0.7, 0.66))
    deg = math.radians

    def wall_x(name, x, y0, y1, z0, z1):   # a piece of the plane x = const, facing +x
        return sc.rectangle(scene, name, walls, Matrix.Translation((x, 0.5 * (y0 + y1), 0.5 * (z0 + z1))) @
                            Matrix.Rotation(deg(90), 4, "Y") @ Matrix.Diagonal((0.5 * (z1 - z0), 0.5 * (y1 - y0), 1, 1)))

    sc.rectangle(scene, "Floor", sc.diffuse("Floor", (0.5, 0.38, 0.28)), Matrix.Diagonal((2.0, 2.0, 1, 1)))
    sc.rectangle(scene, "Ceiling", walls, Matrix.Translation((0, 0, 2.6)) @ Matrix.Rotation(math.pi, 4, "X") @
                 Matrix.Diagonal((2.0, 2.0, 1, 1)))
    _walls(scene, walls, 2.0, 2.6, names=("Back", "Front", "Right"))
    wall_x("LeftLow", -2.0, -2.0, 2.0, 0.0, 1.0)
    wall_x("LeftHigh", -2.0, -2.0, 2.0, 2.0, 2.6)
    wall_x("LeftFront", -2.0, -2.0, -0.6, 1.0, 2.0)
    wall_x("LeftBack", -2.0, 0.6, 2.0, 1.0, 2.0)
    # The table: a block 1.0 × 0.8 m, 0.75 m high, under the sun patch; the glass sphere on it.
    sc.cube(scene, "Table", sc.diffuse("Table", (0.55, 0.45, 0.35)),
            Matrix.Translation((-0.9, 0.2, 0.375)) @ Matrix.Diagonal((0.5, 0.4, 0.375, 1)))
    sc.sphere(scene, "Glass", sc.glass("Glass"), (-1.0, 0.15, 0.9), 0.15, segments=48, rings=24)
    _sun(scene, (1.0, -0.1, -0.9), 10.0, 1.0)
    sc.world(scene, (0.5, 0.65, 1.0), 1.5)
    sc.camera(scene, (1.7, -1.8, 1.5), (80.0, 0.0, 50.0), lens=18.0)
    return 4 / 3


def build_table_caustic(scene):
    """A closed 4 × 4 × 2.6 m diffuse room lit only by a 0.2 m square area light 1.3 m above a table, a glass sphere
    (r = 0.2 m) on the table off the light's axis: the sphere's caustic on the table top (L S S D), the room lit by
    light that has bounced."""
    walls = sc.diffuse("Walls", (0.7, 0.7, 0.68))
    sc.rectangle(scene, "Floor", sc.diffuse("Floor", (0.45, 0.4, 0.35)), Matrix.Diagonal((2.0, 2.0, 1, 1)))
    sc.rectangle(scene, "Ceiling", walls, Matrix.Translation((0, 0, 2.6)) @ Matrix.Rotation(math.pi, 4, "X") @
                 Matrix.Diagonal((2.0, 2.0, 1, 1)))
    _walls(scene, walls, 2.0, 2.6)
    sc.cube(scene, "Table", sc.diffuse("Table", (0.75, 0.72, 0.65)),
            Matrix.Translation((0.2, 0.5, 0.36)) @ Matrix.Diagonal((0.6, 0.45, 0.36, 1)))
    sc.sphere(scene, "Glass", sc.glass("Glass"), (0.0, 0.45, 0.92), 0.2, segments=48, rings=24)
    sc.area_light(scene, "Lamp", (0.35, 0.55, 2.05), 0.2, 30.0, rotation_deg=(0.0, 8.0, 0.0))
    sc.camera(scene, (-1.6, -1.7, 1.6), (72.0, 0.0, -40.0), lens=22.0)
    sc.world(scene, (0, 0, 0), 0.0)
    return 4 / 3


BUILDERS = {"glossy_atrium": build_glossy_atrium, "window_glass": build_window_glass,
            "table_caustic": build_table_caustic}
