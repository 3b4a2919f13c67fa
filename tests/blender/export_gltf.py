"""Run inside Blender: blender --background --factory-startup --python export_gltf.py -- IN.bvh OUT.glb

Blender as another tool's glTF: it imports a BVH (its armature's bones resting along their bones,
turned from Blender's z up), and its glTF exporter writes the armature and its animation, sampled
at the BVH's frame rate. motiongraph then reads that file (tests/blender/blender_import_test.sh).
Prints "export_gltf: PASS" last when the file was written.
"""
import builtins
import sys

import numpy

numpy.bool = bool  # Debian's numpy 1.24 dropped it; Blender 3.4's glTF add-on still uses it
import bpy

# Debian 12's Blender 3.4 BVH importer opens files with mode "rU", which its Python 3.11 no
# longer accepts (as check_bvh.py).
_open = builtins.open
builtins.open = lambda file, mode="r", *args, **kwargs: _open(file, mode.replace("U", ""), *args, **kwargs)


def main(argv):
    source, out = argv
    bpy.ops.wm.read_factory_settings(use_empty=True)
    bpy.ops.import_anim.bvh(filepath=source, global_scale=1.0, update_scene_fps=True, update_scene_duration=True)
    armature = bpy.context.selected_objects[0]
    print(f"export_gltf: {source}: {len(armature.data.bones)} bones, frames {bpy.context.scene.frame_start}-"
          f"{bpy.context.scene.frame_end} at {bpy.context.scene.render.fps} fps")
    bpy.ops.export_scene.gltf(filepath=out, export_format="GLB", export_animations=True, export_force_sampling=True,
                              export_frame_range=True)
    print("export_gltf: PASS")


main(sys.argv[sys.argv.index("--") + 1:])
