#!/usr/bin/env bash
# Usage: bash blender_import_test.sh MOTIONGRAPH_BINARY DATA_DIR GRAPH
#
# Blender reads what a newcomer gets from the README: the bundled graph's figure 8, walked then
# run, written as BVH. check_bvh.py (run inside Blender) checks that Blender finds our frames,
# fps and joints, the same world joint positions as our own forward kinematics, and no pop: no
# joint moves further in one frame than joints move in the source clips the graph was built
# from, read by Blender the same way; and each planted toe (the foot clean-up) within 1 cm of its
# plant on the floor over its contact. The same figure 8 written as glTF (.glb, and .gltf) and as FBX:
# check_scene.py imports each with Blender's glTF or FBX importer and checks its armature, keys,
# frame rate (FBX) and joint positions.
# And glTF and FBX that Blender writes (export_gltf.py, export_fbx.py, from its BVH import of
# data/bvh/16_01.bvh) read in motiongraph to the joint positions of the BVH itself.
# Needs Blender (Debian package blender; the test fails with a message when it is missing, it
# never passes silently).
set -euo pipefail

if [[ $# -ne 3 ]]; then
  echo "usage: bash blender_import_test.sh MOTIONGRAPH_BINARY DATA_DIR GRAPH" >&2
  exit 2
fi
motiongraph=$1
data=$2
graph=$3
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
blender=${BLENDER:-blender}
if ! command -v "$blender" >/dev/null; then
  echo "blender_import_test: FAIL: Blender ('$blender') not found; install it (scripts/install-deps.sh does)" >&2
  exit 1
fi

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# The same synthesis five times: BVH, glTF (.glb and .gltf) and FBX for Blender, JSON world positions
# for the comparison.
for ext in bvh glb gltf fbx json; do
  "$motiongraph" path "$graph" --shape figure8:4 --segment walk:0-25 --segment run:25-51 -o "$tmp/figure8.$ext" >/dev/null
done
sources=()
for amc in "$data"/cmu/16/*.amc; do
  name=$(basename "$amc" .amc)
  "$motiongraph" convert "$amc" --fps 30 -o "$tmp/$name.bvh"
  sources+=("$tmp/$name.bvh")
done

"$blender" --version | head -n 1
# check SCRIPT ARGS...: runs tests/blender/SCRIPT.py inside Blender. Blender prints its own log on
# stdout; the script's lines start with "SCRIPT:" and its last with "SCRIPT: PASS".
check() {
  local script=$1 status
  shift
  set +e
  "$blender" --background --factory-startup --python-exit-code 1 --python "$here/$script.py" -- "$@" \
    >"$tmp/$script.log" 2>&1
  status=$?
  set -e
  grep "^$script:" "$tmp/$script.log" || true
  if [[ $status -ne 0 ]]; then
    echo "blender_import_test: FAIL ($script: Blender exited with $status); its log:" >&2
    tail -n 40 "$tmp/$script.log" >&2
    exit 1
  fi
  grep -q "^$script: PASS" "$tmp/$script.log"
}
check check_bvh "$tmp/figure8.bvh" "$tmp/figure8.json" "${sources[@]}"
check check_scene "$tmp/figure8.glb" "$tmp/figure8.json"
check check_scene "$tmp/figure8.gltf" "$tmp/figure8.json"
check check_scene "$tmp/figure8.fbx" "$tmp/figure8.json"

# And the other way: glTF written by Blender (its armature from a BVH import, bones resting along
# themselves under an armature turned from Blender's z up, keys from frame 1) read by motiongraph
# gives the joint positions motiongraph finds in the BVH itself (in the file's units: --scale 1).
check export_gltf "$data/bvh/16_01.bvh" "$tmp/blender.glb"
"$motiongraph" convert "$tmp/blender.glb" -o "$tmp/blender.json"
"$motiongraph" convert "$data/bvh/16_01.bvh" --scale 1 -o "$tmp/bvh.json"
python3 - "$tmp/blender.json" "$tmp/bvh.json" <<'PY'
import json, sys
ours, bvh = (json.load(open(p)) for p in sys.argv[1:])
names = [j["name"] for j in bvh["joints"]]
index = {n: i for i, n in enumerate(names)}
joints = [j["name"] for j in ours["joints"]]
# Blender makes no bone of an End Site: every other joint is there.
assert sorted(joints) == sorted(n for n in names if not n.endswith("_end")), (joints, names)
assert ours["fps"] == bvh["fps"] and len(ours["positions"]) == len(bvh["positions"]) > 300
worst = max(abs(a - b) for fo, fb in zip(ours["positions"], bvh["positions"])
            for j, p in enumerate(fo) for a, b in zip(p, fb[index[joints[j]]]))
assert worst < 1e-4, worst  # float32 keys, in CMU's units (0.056 m)
print(f"blender_import_test: Blender's glTF of 16_01 read as its BVH is, within {worst:.1e} units")
PY

# FBX written by Blender (export_fbx.py: centimetres under an armature scaled by 100, bones resting
# along themselves, y up or z up) reads to the same joint positions: within float32 with every
# frame's keys, and within Blender's own key reduction (its default) without them.
check export_fbx "$data/bvh/16_01.bvh" "$tmp/every-key.fbx" Z 0
check export_fbx "$data/bvh/16_01.bvh" "$tmp/reduced.fbx" Y 1
# Blender imported the BVH in its own units as metres, so the file's unit makes the figure 25 m
# tall: motiongraph reads it in the unit that makes it human-sized unless --scale gives one (here
# the file's own, 0.01 m per unit, to compare with the BVH in its units).
"$motiongraph" info "$tmp/reduced.fbx" | grep -q "lengths:  mm (0.001 m), figure 2.48 m (chosen by its size: the FBX file's own unit, 0.01 m, made it 24.8 m" \
  || { echo "blender_import_test: FAIL: an FBX of no human size"; "$motiongraph" info "$tmp/reduced.fbx"; exit 1; }
"$motiongraph" convert "$tmp/every-key.fbx" --scale 0.01 -o "$tmp/every-key.json"
"$motiongraph" convert "$tmp/reduced.fbx" --scale 0.01 -o "$tmp/reduced.json"
python3 - "$tmp/every-key.json" "$tmp/reduced.json" "$tmp/bvh.json" <<'PY'
import json, sys
every, reduced, bvh = (json.load(open(p)) for p in sys.argv[1:])
names = [j["name"] for j in bvh["joints"]]
index = {n: i for i, n in enumerate(names)}
for ours, bound in ((every, 1e-4), (reduced, 0.15)):
    joints = [j["name"] for j in ours["joints"]]
    assert sorted(joints) == sorted(n for n in names if not n.endswith("_end")), (joints, names)
    assert ours["fps"] == bvh["fps"] and len(ours["positions"]) == len(bvh["positions"]) > 300
    worst = max(abs(a - b) for fo, fb in zip(ours["positions"], bvh["positions"])
                for j, p in enumerate(fo) for a, b in zip(p, fb[index[joints[j]]]))
    assert worst < bound, (worst, bound)  # in CMU's units (0.056 m)
    print(f"blender_import_test: Blender's FBX of 16_01 read as its BVH is, within {worst:.1e} units")
PY
