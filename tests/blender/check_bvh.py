# Run inside Blender: blender --background --python check_bvh.py -- SYNTH.bvh SYNTH.json SOURCE.bvh...
# Imports SYNTH.bvh with Blender's own BVH importer and checks it against SYNTH.json (our world
# joint positions, y up, metres) and against the source clips (see blender_import_test.sh).
import builtins
import json
import sys

import bpy

# Debian 12's Blender 3.4 BVH importer opens files with mode "rU", which its Python 3.11 no
# longer accepts; "r" means the same now.
_open = builtins.open


def _open_without_u(file, mode="r", *args, **kwargs):
    return _open(file, mode.replace("U", ""), *args, **kwargs)


builtins.open = _open_without_u


def fail(message):
    print("check_bvh: FAIL: " + message)
    sys.exit(1)


def import_bvh(path):
    """Imports path into an empty scene; returns (armature, first frame, last frame, fps)."""
    bpy.ops.wm.read_factory_settings(use_empty=True)
    bpy.ops.import_anim.bvh(filepath=path, global_scale=1.0, update_scene_fps=True, update_scene_duration=True)
    armatures = [o for o in bpy.data.objects if o.type == "ARMATURE"]
    if len(armatures) != 1:
        fail(f"{path}: Blender made {len(armatures)} armatures")
    arm = armatures[0]
    first, last = (int(round(v)) for v in arm.animation_data.action.frame_range)
    return arm, first, last, bpy.context.scene.render.fps


def joint_heads(arm, frame):
    """World position of every bone's head (its joint) at frame, in our axes (y up)."""
    bpy.context.scene.frame_set(frame)
    out = {}
    for bone in arm.pose.bones:
        p = arm.matrix_world @ bone.head
        out[bone.name] = (p.x, p.z, -p.y)  # Blender is z up, -y forward: back to x, y up, z
    return out


def steps(arm, first, last):
    """For each frame after the first, the largest distance any joint moved since the last."""
    result = []
    previous = joint_heads(arm, first)
    for f in range(first + 1, last + 1):
        now = joint_heads(arm, f)
        result.append(max(sum((a - b) ** 2 for a, b in zip(now[n], previous[n])) ** 0.5 for n in now))
        previous = now
    return result


args = sys.argv[sys.argv.index("--") + 1:]
synth_bvh, synth_json, sources = args[0], args[1], args[2:]
ours = json.load(open(synth_json))
names = [j["name"] for j in ours["joints"]]
positions = ours["positions"]

arm, first, last, fps = import_bvh(synth_bvh)
frames = last - first + 1
print(f"check_bvh: {synth_bvh}: {frames} frames at {fps} fps, {len(arm.pose.bones)} bones")
if abs(fps - ours["fps"]) > 1e-6:
    fail(f"Blender plays it at {fps} fps, we wrote {ours['fps']}")
if frames != len(positions):
    fail(f"Blender finds {frames} frames, we wrote {len(positions)}")

# Every joint Blender made a bone of sits where our forward kinematics puts it.
worst = 0.0
matched = 0
for f in range(frames):
    heads = joint_heads(arm, first + f)
    for j, name in enumerate(names):
        if name not in heads:
            continue
        matched += 1
        worst = max(worst, max(abs(a - b) for a, b in zip(heads[name], positions[f][j])))
print(f"check_bvh: largest joint difference from our forward kinematics {worst:.2e} m over {matched} joint frames")
if matched < frames * len(arm.pose.bones):
    fail("some of Blender's bones are not joints we wrote")
if worst > 1e-4:
    fail(f"joints differ from ours by up to {worst} m")

# Planted feet stay planted (the foot clean-up, on by default): each contact of a toe that the
# motion carries from its source clips ("contacts" in our JSON) keeps the toe, as Blender places
# it, within 1 cm on the floor of where it was on the contact's first frame. (Its height is the
# capture's: a running toe rises up to 3 cm within its contact as it pushes off.)
contacts = ours.get("contacts")
if contacts is None:
    fail("our JSON has no foot contacts")
toes = [(i, name) for i, name in enumerate(contacts["joints"]) if i % 2 == 1 or len(contacts["joints"]) == 2]
planted = contacts["planted"]
if len(planted) != frames:
    fail(f"{len(planted)} frames of contacts for {frames} frames")
worst_toe, intervals = 0.0, 0
for column, name in toes:
    f = 0
    while f < frames:
        if not planted[f][column]:
            f += 1
            continue
        start = f
        while f < frames and planted[f][column]:
            f += 1
        intervals += 1
        plant = joint_heads(arm, first + start)[name]
        for g in range(start + 1, f):
            here = joint_heads(arm, first + g)[name]
            worst_toe = max(worst_toe, ((here[0] - plant[0]) ** 2 + (here[2] - plant[2]) ** 2) ** 0.5)
print(f"check_bvh: planted toes ({', '.join(n for _, n in toes)}) move at most {worst_toe * 100:.2f} cm on the floor "
      f"over {intervals} contacts")
if intervals < 20:
    fail(f"only {intervals} toe contacts in a 50 m figure 8")
if worst_toe > 0.01:
    fail(f"a planted toe moves {worst_toe:.4f} m within its contact")

# No pops: per frame, no joint moves further than the source clips' joints move (their 99.9th
# percentile, as the CMU captures hold a few single-frame glitches of their own).
synth_steps = steps(arm, first, last)
source_steps = []
for path in sources:
    s_arm, s_first, s_last, _ = import_bvh(path)
    source_steps += steps(s_arm, s_first, s_last)
source_steps.sort()
bound = source_steps[int(0.999 * (len(source_steps) - 1))]
largest = max(synth_steps)
print(f"check_bvh: largest step per frame {largest:.4f} m; the source clips' 99.9th percentile {bound:.4f} m "
      f"over {len(source_steps)} steps")
if largest > 1.05 * bound:
    fail(f"a joint jumps {largest:.4f} m in one frame (frame {first + 1 + synth_steps.index(largest)})")
print("check_bvh: PASS")
