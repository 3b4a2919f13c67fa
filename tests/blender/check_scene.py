# Run inside Blender: blender --background --python check_scene.py -- SYNTH.glb|SYNTH.gltf|SYNTH.fbx SYNTH.json
# Imports SYNTH.glb (or .gltf) with Blender's own glTF importer, or SYNTH.fbx with its FBX importer, and
# checks it against SYNTH.json (our world joint positions, y up, metres): one armature with a bone
# per joint, one key per frame, every bone's head where our forward kinematics puts its joint in
# every frame; the stick figure deformed by that armature, its bones on their joints at the
# first, middle and last frame; in FBX the frame rate the file gives.
import json
import sys

# Debian 12's Blender 3.4 glTF importer still uses numpy.bool, which Debian 12's numpy (1.24) no
# longer has; it meant the builtin bool.
import numpy

if "bool" not in vars(numpy):
    numpy.bool = bool

import bpy


def fail(message):
    print("check_scene: FAIL: " + message)
    sys.exit(1)


args = sys.argv[sys.argv.index("--") + 1:]
synth, synth_json = args
fbx = synth.lower().endswith(".fbx")
ours = json.load(open(synth_json))
names = [j["name"] for j in ours["joints"]]
positions = ours["positions"]

bpy.ops.wm.read_factory_settings(use_empty=True)
if abs(ours["fps"] - round(ours["fps"])) > 1e-9:
    fail(f"the test needs a whole frame rate, not {ours['fps']}")
if fbx:
    # The file's frame rate becomes the scene's; its centimetres Blender's metres.
    bpy.context.scene.render.fps = 7
    bpy.ops.import_scene.fbx(filepath=synth)
    fps = bpy.context.scene.render.fps / bpy.context.scene.render.fps_base
    if abs(fps - ours["fps"]) > 1e-6:
        fail(f"Blender plays it at {fps} fps, we wrote {ours['fps']}")
else:
    # glTF keys are seconds; Blender's importer puts them at seconds * the scene's frame rate.
    bpy.context.scene.render.fps = int(round(ours["fps"]))
    bpy.context.scene.render.fps_base = 1.0
    bpy.ops.import_scene.gltf(filepath=synth)
armatures = [o for o in bpy.data.objects if o.type == "ARMATURE"]
if len(armatures) != 1:
    fail(f"{synth}: Blender made {len(armatures)} armatures")
arm = armatures[0]
first, last = (int(round(v)) for v in arm.animation_data.action.frame_range)
frames = last - first + 1
print(f"check_scene: {synth}: {frames} frames from frame {first}, {len(arm.pose.bones)} bones")
# Blender's glTF importer keys the first frame at 0, its FBX importer at 1 (its anim_offset).
if first != (1 if fbx else 0) or frames != len(positions):
    fail(f"Blender keys frames {first}..{last}, we wrote {len(positions)} frames")
missing = [name for name in names if name not in arm.pose.bones]
if missing:
    fail(f"joints without a bone: {', '.join(missing)}")
meshes = [o for o in bpy.data.objects if o.type == "MESH"]
if len(meshes) != 1 or not any(m.type == "ARMATURE" and m.object == arm for m in meshes[0].modifiers):
    fail("the stick figure is not one mesh deformed by the armature")
figure = meshes[0]
# Each bone of the figure runs from a joint to a child: a joint with a child 1 mm away or more is
# the apex of a bone, so some vertex of the deformed figure lies on it.
parents = {j["name"]: j["parent"] for j in ours["joints"]}
apexes = sorted({n for n, p in parents.items() if p is not None and p >= 0} | {names[p] for p in parents.values() if p is not None and p >= 0})

worst = 0.0
worst_apex = 0.0
for f in range(frames):
    bpy.context.scene.frame_set(first + f)
    for j, name in enumerate(names):
        p = arm.matrix_world @ arm.pose.bones[name].head
        here = (p.x, p.z, -p.y)  # Blender is z up, -y forward: back to x, y up, z
        worst = max(worst, max(abs(a - b) for a, b in zip(here, positions[f][j])))
    if f in (0, frames // 2, frames - 1):  # the skinned figure, deformed, on the joints
        mesh = figure.evaluated_get(bpy.context.evaluated_depsgraph_get()).to_mesh()
        points = [figure.matrix_world @ v.co for v in mesh.vertices]
        points = [(p.x, p.z, -p.y) for p in points]
        for name in apexes:
            joint = positions[f][names.index(name)]
            nearest = min(sum((a - b) ** 2 for a, b in zip(p, joint)) for p in points) ** 0.5
            worst_apex = max(worst_apex, nearest)
        figure.evaluated_get(bpy.context.evaluated_depsgraph_get()).to_mesh_clear()
print(f"check_scene: largest joint difference from our forward kinematics {worst:.2e} m over "
      f"{frames * len(names)} joint frames; the deformed figure's bones on their joints within {worst_apex:.2e} m")
if worst > 1e-5:
    fail(f"joints differ from ours by up to {worst} m")
if worst_apex > 1e-4:
    fail(f"the deformed figure's bones miss their joints by up to {worst_apex} m")
print("check_scene: PASS")
