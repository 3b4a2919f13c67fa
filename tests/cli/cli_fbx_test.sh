#!/usr/bin/env bash
# FBX in, as a user meets it: subject 16's clips written as one FBX by FBX's rules alone
# (make_test_fbx: z up, in inches, joints resting in frames of their own under PreRotations and
# every rotation order, an armature turned and scaled, a skinned mesh beside an animated prop),
# an animation stack each named as Blender names them ("Armature|16_15"). `info` lists the
# stacks, `convert --animation` reads one to the AMC's joint positions, `build` reads every stack as
# a clip named FILE:ANIMATION with CMU's tags by the animation's name and its graph follows a path,
# a manifest picks stacks; a stack not there and an FBX whose up axis is x are one error each.
# Usage: MOTIONGRAPH=binary MAKE_TEST_FBX=binary cli_fbx_test.sh DATA_DIR
set -euo pipefail
data=$1
bin=${MOTIONGRAPH:?set MOTIONGRAPH to the motiongraph binary}
make=${MAKE_TEST_FBX:?set MAKE_TEST_FBX to the make_test_fbx binary}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
amcs=("$data"/cmu/16/*.amc)
"$make" --z-up --unit 2.54 "$work/s16.fbx" "${amcs[@]}"
head -1 "$work/s16.fbx" | grep -q "FBX 7.4" || { echo "FAIL: test file"; exit 1; }

"$bin" info "$work/s16.fbx" >"$work/info.txt"
head -1 "$work/info.txt" | grep -q "s16.fbx: FBX, animation '16_01' (1 of ${#amcs[@]}: 16_01, 16_05," \
  && grep -q "lengths:  0.0254 m (the FBX file's: centimetres times its UnitScaleFactor 2.54)" "$work/info.txt" \
  && grep -q "up:       z (the FBX file's, turned y up; --up-axis overrides)" "$work/info.txt" \
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
sed 's/"UpAxis", "int", "Integer", "",2/"UpAxis", "int", "Integer", "",0/' "$work/s16.fbx" >"$work/sideways.fbx"
if "$bin" info "$work/sideways.fbx" 2>"$work/sideways.err" >/dev/null; then echo "FAIL: an x-up FBX was read"; exit 1; fi
[[ $(wc -l <"$work/sideways.err") -eq 1 ]] && grep -q "sideways.fbx: the FBX file's up axis is +x, which is not read (give the axis with --up-axis)" "$work/sideways.err" \
  || { echo "FAIL: x up"; cat "$work/sideways.err"; exit 1; }

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
TOML
"$bin" info --json "$work/fbx.toml" >"$work/fbx-info.json" 2>/dev/null
python3 - "$work/fbx-info.json" <<'PY'
import json, sys
info = json.load(open(sys.argv[1]))
clips = {c["name"]: c for c in info["clips"]}
assert set(clips) == {"s16:16_35", "stroll"}, clips.keys()
assert clips["s16:16_35"]["tags"] == ["jog"], clips["s16:16_35"]
assert "walk" in clips["stroll"]["tags"], clips["stroll"]  # CMU's index, by the animation's name
PY
echo "cli_fbx_test: PASS"
