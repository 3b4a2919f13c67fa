"""Run inside Blender: blender --background --factory-startup --python export_fbx.py -- IN.bvh OUT.fbx [UP [SIMPLIFY]]

Blender as another tool's FBX: it imports a BVH (its armature's bones resting along their bones)
and its FBX exporter writes the armature and its animation, baked at the BVH's frame rate, in
centimetres under an armature scaled by 100, with UP (Y, Blender's default, or Z) as the file's up
axis; SIMPLIFY is its key reduction (1, its default, drops keys it finds near their neighbours'
line; 0 keeps every frame's). motiongraph then reads that file (tests/blender/blender_import_test.sh).
Prints "export_fbx: PASS" last when the file was written.
"""
import builtins
import sys

import bpy

# Debian 12's Blender 3.4 BVH importer opens files with mode "rU", which its Python 3.11 no
# longer accepts (as check_bvh.py).
_open = builtins.open
builtins.open = lambda file, mode="r", *args, **kwargs: _open(file, mode.replace("U", ""), *args, **kwargs)


def main(argv):
    source, out = argv[:2]
    up = argv[2] if len(argv) > 2 else "Y"
    simplify = float(argv[3]) if len(argv) > 3 else 1.0
    bpy.ops.wm.read_factory_settings(use_empty=True)
    bpy.ops.import_anim.bvh(filepath=source, global_scale=1.0, update_scene_fps=True, update_scene_duration=True)
    armature = bpy.context.selected_objects[0]
    print(f"export_fbx: {source}: {len(armature.data.bones)} bones, frames {bpy.context.scene.frame_start}-"
          f"{bpy.context.scene.frame_end} at {bpy.context.scene.render.fps} fps, up {up}, simplify {simplify}")
    forward = "-Z" if up == "Y" else "Y"
    bpy.ops.export_scene.fbx(filepath=out, bake_anim=True, add_leaf_bones=False, bake_anim_simplify_factor=simplify, axis_up=up, axis_forward=forward)
    print("export_fbx: PASS")


main(sys.argv[sys.argv.index("--") + 1:])
