#!/usr/bin/env bash
# Usage: bash run_three_test.sh MOTIONGRAPH_BINARY DATA_DIR
#
# Checks that three.js's BVHLoader and GLTFLoader (npm package "three", in Node) read the BVH
# and glTF files `motiongraph convert` and `motiongraph path` write and find the same world joint
# positions as our own forward kinematics (`motiongraph convert ... -o X.json`), to 1e-5 m; each
# glTF file must also pass the Khronos glTF validator (npm "gltf-validator") with no issue.
# Needs tests/js/node_modules, installed by `npm ci` in tests/js
# (scripts/install-deps.sh does that).
set -euo pipefail

if [[ $# -ne 2 ]]; then
  echo "usage: bash run_three_test.sh MOTIONGRAPH_BINARY DATA_DIR" >&2
  exit 2
fi
motiongraph=$1
data=$2
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
tolerance=1e-5  # metres (0.01 mm)

node=${NODE:-node}
if ! command -v "$node" >/dev/null; then
  echo "run_three_test: FAIL: Node.js ('$node') not found; install Node.js 18 or newer" >&2
  exit 1
fi
if [[ ! -f $here/node_modules/three/package.json ]]; then
  echo "run_three_test: FAIL: three.js is not installed in $here/node_modules;" \
       "run 'npm ci' in $here (scripts/install-deps.sh does)" >&2
  exit 1
fi
if [[ ! -x $motiongraph ]]; then
  echo "run_three_test: FAIL: motiongraph binary '$motiongraph' not found or not executable" >&2
  exit 1
fi

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

three_version=$("$node" -p "require('$here/node_modules/three/package.json').version")
echo "three.js $three_version, $("$node" --version)"

# check NAME INPUT [convert options...]
check() {
  local name=$1 input=$2
  shift 2
  echo "== $name: $input $*"
  # (set -e is off inside a function called with ||, hence the explicit returns)
  "$motiongraph" convert "$input" "$@" -o "$tmp/$name.bvh" || return 1
  "$motiongraph" convert "$input" "$@" -o "$tmp/$name.json" -o "$tmp/$name.glb" || return 1
  "$node" "$here/bvh_world_positions.mjs" "$tmp/$name.bvh" "$tmp/$name.three.json" || return 1
  "$node" "$here/compare_positions.mjs" "$tmp/$name.json" "$tmp/$name.three.json" "$tolerance" || return 1
  "$node" "$here/gltf_world_positions.mjs" "$tmp/$name.glb" "$tmp/$name.gltf.json" || return 1
  "$node" "$here/compare_positions.mjs" "$tmp/$name.json" "$tmp/$name.gltf.json" "$tolerance" || return 1
}

# Synthesized motion: a walk-then-run figure 8 on the subject-16 graph, written once as BVH
# and once as JSON (path synthesis is deterministic), read back by three.js.
check_synthesized() {
  echo "== synthesized: figure8:4, walk then run"
  "$motiongraph" build "$data/cmu/16" -o "$tmp/s16.mgraph" --no-cache -q || return 1
  local out
  for out in bvh json glb gltf; do
    "$motiongraph" path "$tmp/s16.mgraph" --shape figure8:4 --segment walk:0-25 --segment run:25-51 \
      -o "$tmp/figure8.$out" >/dev/null || return 1
  done
  "$node" "$here/bvh_world_positions.mjs" "$tmp/figure8.bvh" "$tmp/figure8.three.json" || return 1
  "$node" "$here/compare_positions.mjs" "$tmp/figure8.json" "$tmp/figure8.three.json" "$tolerance" || return 1
  "$node" "$here/gltf_world_positions.mjs" "$tmp/figure8.glb" "$tmp/figure8.gltf.json" || return 1
  "$node" "$here/compare_positions.mjs" "$tmp/figure8.json" "$tmp/figure8.gltf.json" "$tolerance" || return 1
  # The same as .gltf (JSON, its buffer a base64 data URI): the validator and three.js alike.
  "$node" "$here/gltf_world_positions.mjs" "$tmp/figure8.gltf" "$tmp/figure8.text.json" || return 1
  "$node" "$here/compare_positions.mjs" "$tmp/figure8.json" "$tmp/figure8.text.json" "$tolerance" || return 1
}

# An animation set: two clips of one rig in one .glb, and a library (a folder), each animation
# where its clip's JSON puts the joints.
check_set() {
  echo "== animation set: 16_15 and 16_35 with root motion"
  "$motiongraph" convert "$data/cmu/16/16_15.amc" "$data/cmu/16/16_35.amc" --root-motion -o "$tmp/set.glb" \
    -o "$tmp/set.gltf" || return 1
  local clip
  for clip in 16_15 16_35; do
    "$motiongraph" convert "$data/cmu/16/$clip.amc" --root-motion -o "$tmp/set-$clip.json" || return 1
    "$node" "$here/gltf_world_positions.mjs" "$tmp/set.glb" "$tmp/set-$clip.gltf.json" "$clip" || return 1
    "$node" "$here/compare_positions.mjs" "$tmp/set-$clip.json" "$tmp/set-$clip.gltf.json" "$tolerance" || return 1
    "$node" "$here/gltf_world_positions.mjs" "$tmp/set.gltf" "$tmp/set-$clip.text.json" "$clip" || return 1
    "$node" "$here/compare_positions.mjs" "$tmp/set-$clip.json" "$tmp/set-$clip.text.json" "$tolerance" || return 1
  done
  echo "== animation set: the subject-16 library, as build reads it (30 fps)"
  "$motiongraph" convert "$data/cmu/16" -o "$tmp/library.glb" 2>/dev/null || return 1
  "$motiongraph" convert "$data/cmu/16/16_35.amc" --fps 30 -o "$tmp/library-16_35.json" || return 1
  "$node" "$here/gltf_world_positions.mjs" "$tmp/library.glb" "$tmp/library-16_35.gltf.json" 16_35 || return 1
  "$node" "$here/compare_positions.mjs" "$tmp/library-16_35.json" "$tmp/library-16_35.gltf.json" "$tolerance" || return 1
}

failed=0
check_set || failed=1
check_synthesized || failed=1
check 16_15 "$data/cmu/16/16_15.amc" || failed=1
check 16_01 "$data/cmu/16/16_01.amc" || failed=1
check 131_01 "$data/bvh/131_01.bvh" --scale 0.056444 || failed=1
# A root-motion joint above the hips: the hips become a joint with position channels in BVH.
check 16_35_root_motion "$data/cmu/16/16_35.amc" --root-motion || failed=1

if [[ $failed -ne 0 ]]; then
  echo "run_three_test: FAIL" >&2
  exit 1
fi
echo "run_three_test: all clips match"
