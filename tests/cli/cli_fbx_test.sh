#!/usr/bin/env bash
# FBX in, as a user meets it: subject 16's clips written as one FBX by FBX's rules alone
# (make_test_fbx: z up, in inches, joints resting in frames of their own under PreRotations and
# every rotation order, an armature turned and scaled, a skinned mesh beside an animated prop),
# an animation stack each named as Blender names them ("Armature|16_15"). `info` lists the
# stacks, `convert --animation` reads one to the AMC's joint positions, `build` reads every stack as
# a clip named FILE:ANIMATION with CMU's tags by the animation's name and its graph follows a path,
# a manifest picks stacks (and overrides a file's up axis); clips written as FBX (one, and a set
# with a root-motion joint) read back to their joints, a library written as FBX builds its graph;
# a file standing along -x reads standing; a stack not there is one error.
# Usage: MOTIONGRAPH=binary MAKE_TEST_FBX=binary cli_fbx_test.sh DATA_DIR
set -euo pipefail
data=$1
bin=${MOTIONGRAPH:?set MOTIONGRAPH to the motiongraph binary}
make=${MAKE_TEST_FBX:?set MAKE_TEST_FBX to the make_test_fbx binary}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
amcs=("$data"/cmu/16/*.amc)
"$make" --up +z --unit 2.54 "$work/s16.fbx" "${amcs[@]}"
head -1 "$work/s16.fbx" | grep -q "FBX 7.4" || { echo "FAIL: test file"; exit 1; }

"$bin" info "$work/s16.fbx" >"$work/info.txt"
head -1 "$work/info.txt" | grep -q "s16.fbx: FBX, animation '16_01' (1 of ${#amcs[@]}: 16_01, 16_05," \
  && grep -q "lengths:  0.0254 m (the FBX file's: centimetres times its UnitScaleFactor 2.54)" "$work/info.txt" \
  && grep -q "up:       +z (the FBX file's, turned y up; --up-axis takes the file as y or z up)" "$work/info.txt" \
  || { echo "FAIL: info on an FBX file"; cat "$work/info.txt"; exit 1; }

"$bin" convert "$work/s16.fbx" --animation 16_35 -o "$work/fbx.json"
"$bin" convert "$data/cmu/16/16_35.amc" --fps 30 -o "$work/amc.json"
python3 - "$work/amc.json" "$work/fbx.json" <<'PY'
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:])
index = {j["name"]: i for i, j in enumerate(b["joints"])}
assert a["fps"] == b["fps"] == 30 and len(a["positions"]) == len(b["positions"]) > 30
assert "Prop" not in index and "Body" not in index, index
worst = max(abs(x - y) for fa, fb in zip(a["positions"], b["positions"])
            for j, p in enumerate(fa) for x, y in zip(p, fb[index[a["joints"][j]["name"]]]))
assert worst < 1e-4, worst  # 9 digits of ASCII keys, in inches
print(f"cli_fbx_test: 16_35 read from FBX within {worst:.1e} m of its AMC")
PY

if "$bin" convert "$work/s16.fbx" --animation swim -o "$work/swim.json" 2>"$work/swim.err"; then echo "FAIL: no such animation"; exit 1; fi
[[ $(wc -l <"$work/swim.err") -eq 1 && ! -e "$work/swim.json" ]] && grep -q "s16.fbx: no animation 'swim' (the file has 16_01, " "$work/swim.err" \
  || { echo "FAIL: --animation swim"; cat "$work/swim.err"; exit 1; }
# A file that stands along -x reads standing: the same heights, the same figure turned about y.
"$make" --up -x "$work/sideways.fbx" "$data/cmu/16/16_35.amc"
"$bin" convert "$work/sideways.fbx" -o "$work/sideways.json"
python3 - "$work/amc.json" "$work/sideways.json" <<'PY'
import json, math, sys
a, b = (json.load(open(p)) for p in sys.argv[1:])
index = {j["name"]: i for i, j in enumerate(b["joints"])}
worst = 0.0
for fa, fb in zip(a["positions"], b["positions"]):
    for j, p in enumerate(fa):
        q = fb[index[a["joints"][j]["name"]]]
        worst = max(worst, abs(p[1] - q[1]),  # height, and distance from the root over the floor
                    abs(math.dist((p[0], p[2]), (fa[0][0], fa[0][2])) - math.dist((q[0], q[2]), (fb[0][0], fb[0][2]))))
assert worst < 1e-4, worst
PY

# A library of the file's stacks: named FILE:ANIMATION, CMU's tags by the animation's name.
"$bin" build "$work/s16.fbx" -o "$work/fbx.mgraph" --no-cache -q
"$bin" inspect --clips "$work/fbx.mgraph" >"$work/fbx.clips"
grep -q "^s16:16_15 .* walk" "$work/fbx.clips" && [[ $(grep -c "^s16:16_" "$work/fbx.clips") -eq ${#amcs[@]} ]] \
  || { echo "FAIL: an FBX library's clips"; cat "$work/fbx.clips"; exit 1; }
"$bin" path "$work/fbx.mgraph" --shape line:8 -o "$work/line.json" --report "$work/line-report.json" >/dev/null
python3 - "$work/line-report.json" <<'PY'
import json, sys
report = json.load(open(sys.argv[1]))
assert report["reached_end"] and report["mean_deviation_m"] < 0.15, (report["reached_end"], report["mean_deviation_m"])
PY

# A manifest names stacks of an FBX file, with their own tags.
cat >"$work/fbx.toml" <<'TOML'
fps = 30
[[clip]]
file = "s16.fbx"
animation = "16_35"
tags = ["jog"]
[[clip]]
file = "s16.fbx"
animation = "16_15"
name = "stroll"
[[clip]]
file = "s16.fbx"
animation = "16_15"
name = "taken_y_up"
up_axis = "y"
TOML
"$bin" info --json "$work/fbx.toml" >"$work/fbx-info.json" 2>/dev/null
python3 - "$work/fbx-info.json" <<'PY'
import json, sys
info = json.load(open(sys.argv[1]))
clips = {c["name"]: c for c in info["clips"]}
assert set(clips) == {"s16:16_35", "stroll", "taken_y_up"}, clips.keys()
# The clip's up_axis overrides the file's +z: the figure lies on its side, its walk no longer
# over the floor alone.
assert abs(clips["taken_y_up"]["root_path_m"] - clips["stroll"]["root_path_m"]) > 0.2, clips
assert clips["s16:16_35"]["tags"] == ["jog"], clips["s16:16_35"]
assert "walk" in clips["stroll"]["tags"], clips["stroll"]  # CMU's index, by the animation's name
PY

# FBX out: a clip written as FBX (centimetres, y up) reads back to its joints; several clips make
# one file, a stack each named as its file; a root-motion joint goes in too.
mkdir "$work/out"
"$bin" convert "$data/cmu/16/16_35.amc" --fps 30 -o "$work/out/jog.fbx" -o "$work/out/jog.json"
"$bin" info "$work/out/jog.fbx" >"$work/out-info.txt"
grep -q "jog.fbx: FBX, animation 'jog' (1 of 1: jog" "$work/out-info.txt" \
  && grep -q "lengths:  0.01 m (the FBX file's: centimetres times its UnitScaleFactor 1)" "$work/out-info.txt" \
  && grep -q "up:       +y (the FBX file's" "$work/out-info.txt" \
  || { echo "FAIL: info on an FBX file written"; cat "$work/out-info.txt"; exit 1; }
"$bin" convert "$work/out/jog.fbx" -o "$work/out/jog-back.json"
"$bin" convert "$data/cmu/16/16_15.amc" "$data/cmu/16/16_35.amc" --fps 30 --root-motion -o "$work/out/set.fbx"
"$bin" convert "$work/out/set.fbx" --animation 16_15 -o "$work/out/set-walk.json"
"$bin" convert "$data/cmu/16/16_15.amc" --fps 30 --root-motion -o "$work/out/walk.json"
python3 - "$work/out" <<'PY'
import json, sys
out = sys.argv[1]
def worst(a, b):
    a, b = (json.load(open(f"{out}/{n}.json")) for n in (a, b))
    index = {j["name"]: i for i, j in enumerate(b["joints"])}
    assert a["fps"] == b["fps"] == 30 and len(a["positions"]) == len(b["positions"]) > 30
    assert sorted(index) == sorted(j["name"] for j in a["joints"]), (index, a["joints"])
    return max(abs(x - y) for fa, fb in zip(a["positions"], b["positions"])
               for j, p in enumerate(fa) for x, y in zip(p, fb[index[a["joints"][j]["name"]]]))
for a, b in (("jog", "jog-back"), ("walk", "set-walk")):
    w = worst(a, b)
    assert w < 2e-5, (a, b, w)  # float32 keys in centimetres
    print(f"cli_fbx_test: {a} written as FBX reads back within {w:.1e} m")
PY
"$bin" info "$work/out/set.fbx" | head -1 | grep -q "set.fbx: FBX, animation '16_15' (1 of 2: 16_15, 16_35" \
  || { echo "FAIL: an animation set as FBX"; "$bin" info "$work/out/set.fbx"; exit 1; }
# The library written as one FBX (a stack a clip) builds the graph the library builds.
"$bin" convert "$data/cmu/16" -o "$work/out/library.fbx" 2>/dev/null
"$bin" build "$work/out/library.fbx" -o "$work/out/library.mgraph" --no-cache -q --report "$work/out/fbx-report.json"
"$bin" build "$data/cmu/16" -o "$work/out/amc.mgraph" --no-cache -q --report "$work/out/amc-report.json"
python3 - "$work/out/amc-report.json" "$work/out/fbx-report.json" <<'PY'
import json, sys
amc, fbx = (json.load(open(p)) for p in sys.argv[1:])
assert len(fbx["clips"]) == len(amc["clips"]) == 15 and fbx["frames"] == amc["frames"], (len(fbx["clips"]), fbx["frames"])
for key in ("transitions", "transitions_kept"):
    assert abs(fbx["counts"][key] - amc["counts"][key]) <= 1, (key, fbx["counts"][key], amc["counts"][key])
a, b = amc["graph_after"]["nodes"], fbx["graph_after"]["nodes"]
assert abs(a - b) <= 0.01 * a, (a, b)
print(f"cli_fbx_test: the library as FBX builds {fbx['counts']['transitions_kept']} transitions, {b} nodes "
      f"({amc['counts']['transitions_kept']}, {a} from its AMC files)")
PY
echo "cli_fbx_test: PASS"
