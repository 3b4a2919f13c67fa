#!/usr/bin/env bash
# The CLI as a user runs it on the bundled data: info and convert work, --help on every
# subcommand, outputs are complete files. Usage: MOTIONGRAPH=binary cli_convert_test.sh DATA_DIR
set -euo pipefail
data=$1
bin=${MOTIONGRAPH:?set MOTIONGRAPH to the motiongraph binary}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

for sub in "" info convert; do
  "$bin" $sub --help | grep "Usage" >/dev/null || { echo "FAIL: no usage for '$sub --help'"; exit 1; }
done

# info on every bundled file at once (the .asf given with the AMCs).
"$bin" info "$data"/cmu/16/16.asf "$data"/cmu/16/*.amc "$data"/bvh/*.bvh >"$work/info.txt"
[[ $(grep -c "frames at" "$work/info.txt") -eq 20 ]] || { echo "FAIL: info did not report 20 clips"; cat "$work/info.txt"; exit 1; }
"$bin" info --json "$data"/cmu/16/16_35.amc >"$work/info.json"
python3 - "$work/info.json" <<'PY'
import json, sys
info = json.load(open(sys.argv[1]))[0]
assert info["frames"] == 162 and info["fps"] == 120 and info["joints"] == 31 and info["dofs"] == 62, info
x0, x1 = info["floor_extent_m"]["x"]; z0, z1 = info["floor_extent_m"]["z"]
assert 0.5 < max(x1 - x0, z1 - z0) < 20, info["floor_extent_m"]   # a 1.3 s jog, in metres
PY

# A capture glitch within a clip: 131_01 with its right shoulder turned 100 degrees for the
# file's frames 301..310. info says where the glitches lie and that a library cuts the clip
# there; a library reads it as two clips, 10 frames dropped; convert writes the file whole, and
# says so; --keep-rest-frames keeps the library's clip whole.
mkdir -p "$work/glitch"
python3 - "$data/bvh/131_01.bvh" "$work/glitch/glitched.bvh" <<'PY'
import sys
lines = open(sys.argv[1]).read().split("\n")
column, target = 0, None
for line in lines:
    words = line.split()
    if words[:1] in (["ROOT"], ["JOINT"]):
        joint = words[1]
    if words[:1] == ["CHANNELS"]:
        if joint == "RightShoulder":
            target = column + int(words[1]) - 1   # its last channel, Xrotation
        column += int(words[1])
    if words[:1] == ["MOTION"]:
        break
assert target is not None
first = next(i for i, line in enumerate(lines) if line.startswith("Frame Time")) + 1
for f in range(300, 310):   # the file's frames 301..310
    values = lines[first + f].split()
    values[target] = str(float(values[target]) + 100.0)
    lines[first + f] = " ".join(values)
open(sys.argv[2], "w").write("\n".join(lines))
PY
"$bin" info "$work/glitch/glitched.bvh" | grep -E "glitches: 2 glitches at 2\.50-2\.58 s \(the largest .*\) within it .*: a library cuts it there into 2 parts, 10 frames dropped" >/dev/null \
  || { echo "FAIL: info's glitches line"; "$bin" info "$work/glitch/glitched.bvh"; exit 1; }
"$bin" info --json --mirror off "$work/glitch" >"$work/glitch.json" 2>"$work/glitch.err"
grep -E "info: clips cut at capture glitches within them .*: glitched \(glitched.bvh\): 2 glitches at .* cut into glitched, glitched_part2, 10 frames dropped" "$work/glitch.err" >/dev/null \
  || { echo "FAIL: the library's glitch line"; cat "$work/glitch.err"; exit 1; }
"$bin" info --keep-rest-frames --json --mirror off "$work/glitch" >"$work/glitch-kept.json" 2>/dev/null
"$bin" convert "$work/glitch/glitched.bvh" -o "$work/glitch-whole.bvh" 2>"$work/glitch-convert.err"
grep -E "warning: .*glitched.bvh: 2 glitches at .*; converted whole" "$work/glitch-convert.err" >/dev/null \
  || { echo "FAIL: convert's glitch warning"; cat "$work/glitch-convert.err"; exit 1; }
python3 - "$work/glitch.json" "$work/glitch-kept.json" "$work/glitch-whole.bvh" "$data/bvh/131_01.bvh" <<'PY'
import json, sys
lib, kept = json.load(open(sys.argv[1])), json.load(open(sys.argv[2]))
frames = lambda path: int(next(l for l in open(path) if l.startswith("Frames:")).split()[1])
n = frames(sys.argv[4])
assert frames(sys.argv[3]) == n   # convert writes it whole
split, = lib["reading"]["glitch_splits"]
assert split["clip"] == "glitched" and split["dropped_frames"] == 10, split
assert [g["frame"] for g in split["glitches"]] == [300, 310], split["glitches"]
assert [(p["clip"], p["first_frame"], p["last_frame"]) for p in split["parts"]] \
    == [("glitched", 1, 300), ("glitched_part2", 311, n)], split["parts"]
assert [c["name"] for c in lib["clips"]] == ["glitched", "glitched_part2"], lib["clips"]
for clip, (first, last) in zip(lib["clips"], [(1, 300), (311, n)]):   # as long as their frames (within a frame at 30 fps)
    assert abs(clip["duration_s"] - (last - first) / 120) < 0.04, (clip, first, last)
assert kept["reading"]["glitch_splits"] == [] and [c["name"] for c in kept["clips"]] == ["glitched"], kept
PY

# info names the feet it found and how often each is planted; a rig whose feet it cannot find
# by name (16_01 with its feet renamed) says so, and --feet names them: the same shares as the
# original file's.
"$bin" info "$data/cmu/16/16_35.amc" | grep "feet:     lfoot > ltoes, rfoot > rtoes (found by name; planted" >/dev/null \
  || { echo "FAIL: info's feet line"; "$bin" info "$data/cmu/16/16_35.amc"; exit 1; }
sed 's/lfoot/lpes/; s/rfoot/rpes/' "$data/bvh/16_01.bvh" >"$work/pes.bvh"
"$bin" info "$work/pes.bvh" | grep "feet:     not found: no left ankle joint found" >/dev/null \
  || { echo "FAIL: info on feet it cannot find"; "$bin" info "$work/pes.bvh"; exit 1; }
"$bin" info --json "$data/bvh/16_01.bvh" >"$work/feet.json"
"$bin" info --json "$work/pes.bvh" >"$work/pes.json"
"$bin" info --json --feet lpes,,rpes, "$work/pes.bvh" >"$work/named.json"
python3 - "$work/feet.json" "$work/pes.json" "$work/named.json" <<'PY'
import json, sys
found, missing, named = (json.load(open(p))[0]["feet"] for p in sys.argv[1:4])
assert found["source"] == "found by name" and found["left"]["ankle"] == "lfoot" and found["right"]["toe"] == "rtoes", found
assert missing["source"] is None and "no left ankle joint" in missing["missing"], missing
assert named["source"] == "--feet" and named["left"]["ankle"] == "lpes" and named["left"]["toe"] == "ltoes", named
for side in ("left", "right"):
    assert 0.3 < found[side]["planted_share"] < 1.0, found   # a jump: standing before and after
    assert named[side]["planted_share"] == found[side]["planted_share"], (named, found)
PY

# A Frame Time 4x too long (amc2bvh's 30 fps on CMU's 120 fps frames): the jump's flight falls at
# g / 16, and info says which rate the file more likely has; read at that rate, nothing is said.
"$bin" info "$data/bvh/16_01.bvh" \
  | grep -E "warning:  its flights fall at 0\.[56][0-9] m/s\^2, not 9\.81: it plays about [34]\.[0-9]x slower than it was captured; its frame rate as read, 30 fps, is likely about [34]\.[0-9] times that \(--input-fps" >/dev/null \
  || { echo "FAIL: info on a clock 4x slow"; "$bin" info "$data/bvh/16_01.bvh"; exit 1; }
"$bin" build --no-cache "$data/bvh/16_01.bvh" -o "$work/clock.mgraph" --report "$work/clock.json" 2>"$work/clock.err" >/dev/null
python3 -c '
import json, sys
clips = json.load(open(sys.argv[1]))["clips"]   # the report says it of the clip too
assert len(clips) == 1 and len(clips[0]["doubts"]) == 1 and clips[0]["doubts"][0].startswith("its flights fall at"), clips' "$work/clock.json"
grep -E "warning: 16_01: its flights fall at .* its frame rate as read, 30 fps, is likely about [34]\.[0-9] times that" \
  "$work/clock.err" >/dev/null || { echo "FAIL: build on a clock 4x slow"; cat "$work/clock.err"; exit 1; }
if "$bin" info --input-fps 120 "$data/bvh/16_01.bvh" | grep -q "flights fall"; then
  echo "FAIL: info at the right rate still doubts the clock"; exit 1
fi
"$bin" info --json "$data/bvh/16_01.bvh" | python3 -c '
import json, sys
clip = json.load(sys.stdin)[0]
doubts, fall = clip["doubts"], clip["flight_fall"]
assert len(doubts) == 1 and doubts[0].startswith("its flights fall at"), doubts
assert fall["flights"] == 1 and fall["highest_rise_m"] > 0.1 and 3.6 < fall["slowdown"] < 4.4, fall
assert abs(fall["fall_mps2"] * fall["slowdown"] ** 2 - 9.81) < 1e-6, fall'
"$bin" info --json "$data/cmu/16/16_15.amc" | python3 -c '
import json, sys
clip = json.load(sys.stdin)[0]
fall, walk = clip["flight_fall"], clip["walk_pace"]   # a walk: no flight, its strides measured
assert fall["flights"] == 0 and fall["fall_mps2"] is None and fall["slowdown"] is None, fall
assert walk["strides"] >= 3 and 1.1 < walk["stride_m"] < 1.5 and 0.9 < walk["stride_s"] < 1.4, walk
assert 0.8 < walk["slowdown"] < 1.25 and abs(walk["walk_ratio"] / walk["slowdown"] - 2.1) < 1e-9, walk
h = walk["figure_m"]   # the walk ratio: (stride / h) * duration * sqrt(g / h), the median of the strides
assert 1.4 < h < 1.8 and abs(walk["walk_ratio"] / (walk["stride_m"] / h * walk["stride_s"] * (9.81 / h) ** 0.5) - 1) < 0.1, walk
assert clip["doubts"] == [], clip["doubts"]'
"$bin" info --json "$data/bvh/16_01.bvh" | python3 -c '
import json, sys
walk = json.load(sys.stdin)[0]["walk_pace"]   # a jump: no walk
assert walk["strides"] == 0 and walk["walk_ratio"] is None and walk["slowdown"] is None, walk'
# A walk without flights read 4x slow (its 120 fps frames at 30): its strides take 4x a walk's.
"$bin" info --input-fps 30 "$data/cmu/16/16_15.amc" \
  | grep -E "warning:  its walking strides of 1\.[0-9]{2} m take [45]\.[0-9]{2} s, where people's of that length take about 1\.[0-9]{2} s: it plays about [345]\.[0-9]x slower than it was captured; its frame rate as read, 30 fps, is likely about [345]\.[0-9] times that \(--input-fps" >/dev/null \
  || { echo "FAIL: info on a walk read 4x slow"; "$bin" info --input-fps 30 "$data/cmu/16/16_15.amc"; exit 1; }
# convert says it too, and writes the clip as read.
"$bin" convert "$data/bvh/16_01.bvh" -o "$work/slow.bvh" 2>"$work/slow-convert.err"
grep -E "warning: .*16_01\.bvh: its flights fall at 0\.[56][0-9] m/s\^2, not 9\.81: it plays about [34]\.[0-9]x slower" \
  "$work/slow-convert.err" >/dev/null && test -s "$work/slow.bvh" \
  || { echo "FAIL: convert on a clock 4x slow"; cat "$work/slow-convert.err"; exit 1; }
"$bin" convert --input-fps 120 "$data/bvh/16_01.bvh" -o "$work/right.bvh" 2>"$work/right-convert.err"
if grep -q "flights fall" "$work/right-convert.err"; then echo "FAIL: convert at the right rate doubts the clock"; exit 1; fi
# A library read 4x slow: the clips whose clock is all that is wrong, said in one line.
"$bin" info --input-fps 30 "$data/cmu/16" 2>"$work/slow-library.err" >/dev/null
test "$(grep -c "plays\? about" "$work/slow-library.err")" = 1 \
  && grep -E "warning: 16_01, 16_05, 16_13, 16_15: their flights or walking strides say they play about [34]\.[0-9]x slower than they were captured \([34]\.[0-9]-[345]\.[0-9]x\); their frame rate as read, 30 fps, is likely about [34]\.[0-9] times that" \
    "$work/slow-library.err" >/dev/null \
  || { echo "FAIL: a library read 4x slow"; cat "$work/slow-library.err"; exit 1; }

# A library's options on plain files: said, not silently ignored.
"$bin" info --fps 60 "$data/bvh/16_01.bvh" 2>&1 >/dev/null | grep "apply to folders and manifests" >/dev/null \
  || { echo "FAIL: info --fps on a file"; exit 1; }

# convert: AMC -> BVH and JSON, resampled; BVH -> BVH with a scale.
"$bin" convert "$data/cmu/16/16_35.amc" -o "$work/jog.bvh" --fps 30
"$bin" convert "$data/cmu/16/16_35.amc" -o "$work/jog.json" --fps 30
"$bin" convert "$data/bvh/111_36.bvh" -o "$work/carry.bvh" --scale 0.056444
# Several outputs from one read: the same files as one output each, and each message once.
"$bin" convert "$data/bvh/111_36.bvh" --scale 0.056444 -o "$work/carry2.bvh" -o "$work/carry2.json" 2>"$work/two.err"
"$bin" convert "$data/bvh/111_36.bvh" --scale 0.056444 -o "$work/carry1.json" 2>/dev/null
cmp -s "$work/carry.bvh" "$work/carry2.bvh" || { echo "FAIL: the BVH of a two-output convert differs"; exit 1; }
cmp -s "$work/carry1.json" "$work/carry2.json" || { echo "FAIL: the JSON of a two-output convert differs"; exit 1; }
# Upper-case extensions (files from systems that keep them) are the same outputs.
"$bin" convert "$data/bvh/111_36.bvh" --scale 0.056444 -o "$work/CARRY.BVH" -o "$work/CARRY.JSON" -o "$work/Carry.GlB" 2>/dev/null
cmp -s "$work/carry.bvh" "$work/CARRY.BVH" || { echo "FAIL: .BVH is not written as .bvh"; exit 1; }
cmp -s "$work/carry1.json" "$work/CARRY.JSON" || { echo "FAIL: .JSON is not written as .json (with contacts)"; exit 1; }
[[ $(head -c 4 "$work/Carry.GlB") == glTF ]] || { echo "FAIL: .GlB is not binary glTF"; exit 1; }
[[ $(grep -c "dropped 1 leading" "$work/two.err") -eq 1 ]] || { echo "FAIL: the dropped-frame message is not said once"; cat "$work/two.err"; exit 1; }
grep -q "^Frames: 41$" "$work/jog.bvh" || { echo "FAIL: 162 frames at 120 fps should give 41 at 30 fps"; exit 1; }
grep -q "^Frame Time: 0.0333333333$" "$work/jog.bvh" || { echo "FAIL: frame time"; exit 1; }
grep -q "^Frames: 1465$" "$work/carry.bvh" || { echo "FAIL: the T-pose frame should be dropped"; exit 1; }
python3 - "$work/jog.json" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
assert d["fps"] == 30 and len(d["positions"]) == 41
assert len(d["joints"]) == 38 and d["joints"][0] == {"name": "root", "parent": -1}
assert all(len(frame) == 38 and all(len(p) == 3 for p in frame) for frame in d["positions"])
names = [j["name"] for j in d["joints"]]
head, toes = names.index("head"), names.index("ltoes")
assert 1.3 < d["positions"][0][head][1] - d["positions"][0][toes][1] < 1.9   # metres
PY
# The JSON carries the feet's contacts: planted toes move slowly, free ones fast.
python3 - "$work/jog.json" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
c = d["contacts"]
assert c["joints"] == ["lfoot", "ltoes", "rfoot", "rtoes"], c["joints"]
assert len(c["planted"]) == len(d["positions"]) and all(len(f) == 4 and set(f) <= {0, 1} for f in c["planted"])
names = [j["name"] for j in d["joints"]]
for k, toe in ((1, names.index("ltoes")), (3, names.index("rtoes"))):
    speed = lambda f: ((d["positions"][f + 1][toe][0] - d["positions"][f][toe][0]) ** 2 +
                       (d["positions"][f + 1][toe][2] - d["positions"][f][toe][2]) ** 2) ** 0.5 * d["fps"]
    planted = [speed(f) for f in range(len(d["positions"]) - 1) if c["planted"][f][k]]
    free = [speed(f) for f in range(len(d["positions"]) - 1) if not c["planted"][f][k]]
    assert planted and free, (k, len(planted), len(free))
    assert sum(planted) / len(planted) < 0.25 * sum(free) / len(free), (k, planted, free)
PY
# --feet names them; a joint the rig lacks is one clear line and no output.
"$bin" convert "$data/cmu/16/16_35.amc" -o "$work/shins.json" --feet ltibia,,rtibia,
python3 -c "import json,sys; j=json.load(open(sys.argv[1]))['contacts']['joints']; assert j == ['ltibia', 'ltoes', 'rtibia', 'rtoes'], j" "$work/shins.json"
if "$bin" convert "$data/cmu/16/16_35.amc" -o "$work/nofoot.json" --feet LeftAnkle,,, 2>"$work/nofoot.err"; then
  echo "FAIL: a missing foot joint was accepted"; exit 1
fi
[[ $(wc -l <"$work/nofoot.err") -eq 1 && ! -e "$work/nofoot.json" ]] && grep -q "LeftAnkle" "$work/nofoot.err" \
  || { echo "FAIL: missing foot joint: $(cat "$work/nofoot.err")"; exit 1; }
# --root-motion: a joint on the floor above the hips, every other joint where it was (the contacts
# naming the same feet); read back from BVH, the new joint is the root; a bad smoothing is one line.
"$bin" convert "$data/cmu/16/16_35.amc" --fps 30 --root-motion -o "$work/jog-rm.json" -o "$work/jog-rm.bvh"
python3 - "$work/jog.json" "$work/jog-rm.json" <<'PY'
import json, sys
plain, moved = (json.load(open(p)) for p in sys.argv[1:])
assert moved["joints"][0] == {"name": "root_motion", "parent": -1}, moved["joints"][:2]
assert moved["joints"][1]["parent"] == 0 and moved["contacts"]["joints"] == plain["contacts"]["joints"]
assert moved["contacts"]["planted"] == plain["contacts"]["planted"]
for f, (a, b) in enumerate(zip(plain["positions"], moved["positions"])):
    assert b[0][1] == moved["positions"][0][0][1] and abs(b[0][1]) < 0.05, (f, b[0])  # on the floor
    assert max(abs(x - y) for p, q in zip(a, b[1:]) for x, y in zip(p, q)) < 2e-6, f
PY
grep -q "^ROOT root_motion" "$work/jog-rm.bvh" || { echo "FAIL: the root-motion joint is not the BVH's root"; exit 1; }
# A library of that export beside a plain file (roots root_motion and root): read from the plain
# file's root down, the root-motion joint composed into it, and said so.
mkdir "$work/mixed"
cp "$work/jog-rm.bvh" "$work/mixed/"
"$bin" convert "$data/cmu/16/16_15.amc" --fps 30 -o "$work/mixed/walk.bvh"
"$bin" info "$work/mixed" >"$work/mixed.txt" 2>"$work/mixed.err" \
  && grep -q "^  skeleton: 2 read from 'root' down" "$work/mixed.txt" \
  && grep -q "jog-rm.bvh: read from 'root' down, the root of the library's other rigs: the motion of 'root_motion' above" \
    "$work/mixed.err" || { echo "FAIL: a root-motion export beside a plain file"; cat "$work/mixed.txt" "$work/mixed.err"; exit 1; }
if "$bin" convert "$data/cmu/16/16_35.amc" --root-motion --root-motion-smoothing -1 -o "$work/bad-rm.json" 2>"$work/rm.err"; then
  echo "FAIL: a negative smoothing was accepted"; exit 1
fi
[[ ! -e "$work/bad-rm.json" ]] || { echo "FAIL: output written despite a bad smoothing"; exit 1; }
# Several clips of one rig: one .glb, an animation each named as its file (a name repeated made
# unique), each as long as its clip; any other output, or a clip of another rig, is one line and
# no file.
mkdir "$work/again"
cp "$data/cmu/16/16_15.amc" "$work/again/"
"$bin" convert "$data/cmu/16/16_15.amc" "$data/cmu/16/16_35.amc" "$work/again/16_15.amc" --asf "$data/cmu/16/16.asf" \
  --fps 30 -o "$work/set.glb"
python3 - "$work/set.glb" "$work/jog.json" <<'PY'
import json, sys
data = open(sys.argv[1], "rb").read()
gltf = json.loads(data[20:20 + int.from_bytes(data[12:16], "little")])
assert [a["name"] for a in gltf["animations"]] == ["16_15", "16_35", "16_15_2"], gltf["animations"]
keys = [gltf["accessors"][a["samplers"][0]["input"]]["count"] for a in gltf["animations"]]
assert keys[1] == len(json.load(open(sys.argv[2]))["positions"]) == 41 and keys[0] == keys[2] > keys[1], keys
PY
if "$bin" convert "$data/cmu/16/16_15.amc" "$data/cmu/16/16_35.amc" -o "$work/set.glb" -o "$work/set.bvh" 2>"$work/set.err"; then
  echo "FAIL: several clips into a BVH were accepted"; exit 1
fi
[[ $(wc -l <"$work/set.err") -eq 1 && ! -e "$work/set.bvh" ]] && grep -q "set.bvh: the inputs are 2 clips, and several clips go into a .glb, .gltf or .fbx only" "$work/set.err" \
  || { echo "FAIL: several clips into a BVH"; cat "$work/set.err"; exit 1; }
if "$bin" convert "$data/cmu/16/16_15.amc" "$data/cmu/16/16_35.amc" --feet LeftAnkle,,, -o "$work/feet.glb" 2>"$work/feet.err"; then
  echo "FAIL: feet that are not there were accepted"; exit 1
fi
# One line says what is wrong (beside the info that 16_15's first frames were dropped).
[[ $(grep -vc "^motiongraph: info: " "$work/feet.err") -eq 1 && ! -e "$work/feet.glb" ]] \
  && grep -q "16_15.amc: .*LeftAnkle" "$work/feet.err" \
  || { echo "FAIL: --feet with several clips"; cat "$work/feet.err"; exit 1; }
if "$bin" convert "$data/cmu/16/16_15.amc" "$data/bvh/16_01.bvh" -o "$work/mixed.glb" 2>"$work/mixed.err"; then
  echo "FAIL: clips of two rigs went into one file"; exit 1
fi
# (beside the info lines, and the warning that 16_01.bvh's clock looks 4x slow)
[[ $(grep -v "info:" "$work/mixed.err" | grep -vc "warning: .*16_01.bvh: its flights fall") -eq 1 && ! -e "$work/mixed.glb" ]] \
  && grep -q "16_01.bvh: its rig is not .*16_15.amc's (joint 0 is 'root' there, 'hip' here): one .glb holds one skeleton (a library read as one" "$work/mixed.err" \
  || { echo "FAIL: clips of two rigs"; cat "$work/mixed.err"; exit 1; }
# A library (a folder): every clip as build reads it, an animation each; BVH of three converters
# (other names, another rest pose) in one folder are read on one rig, each clip played on the
# first's skeleton (--skeleton picks another); only a .glb, and a skeleton the library has.
"$bin" convert "$data/cmu/16" -o "$work/s16.glb" 2>/dev/null
mkdir "$work/rigs"
cp "$data/bvh/16_01.bvh" "$data/bvh/111_36.bvh" "$data/bvh/131_01.bvh" "$work/rigs/"
"$bin" convert "$work/rigs" --skeleton 2 -o "$work/rigs.glb" 2>"$work/rigs.err"
grep -q "3 clips of 3 skeletons played on .*16_01.bvh's (--skeleton 2)" "$work/rigs.err" || { echo "FAIL: rigs"; cat "$work/rigs.err"; exit 1; }
"$bin" convert "$work/rigs" -o "$work/rigs0.glb" 2>/dev/null
python3 - "$work/s16.glb" "$work/rigs.glb" "$work/rigs0.glb" "$data/cmu/16" <<'PY'
import json, os, sys
def gltf(path):
    data = open(path, "rb").read()
    return json.loads(data[20:20 + int.from_bytes(data[12:16], "little")])
s16, rigs, rigs0 = (gltf(p) for p in sys.argv[1:4])
clips = sorted(f[:-4] for f in os.listdir(sys.argv[4]) if f.endswith(".amc"))
assert [a["name"] for a in s16["animations"]] == clips, [a["name"] for a in s16["animations"]]
assert [a["name"] for a in rigs["animations"]] == ["111_36", "131_01", "16_01"], rigs["animations"]
# The library's joint names (its first file's, 111_36), on 16_01's bones with --skeleton 2.
node = lambda g, name: next(n for n in g["nodes"] if n["name"] == name)
assert node(rigs, "LeftUpLeg") and node(rigs0, "LeftUpLeg") and "lfemur" not in {n["name"] for n in rigs["nodes"]}
assert node(rigs, "LeftLeg")["translation"] != node(rigs0, "LeftLeg")["translation"]
PY
for bad in "-o $work/lib.bvh" "--skeleton 3 -o $work/lib.glb"; do
  if "$bin" convert "$work/rigs" $bad 2>"$work/lib.err"; then echo "FAIL: accepted $bad"; exit 1; fi
  [[ $(grep -vc "info:\|warning:" "$work/lib.err") -eq 1 && ! -e "$work/lib.bvh" && ! -e "$work/lib.glb" ]] \
    || { echo "FAIL: $bad"; cat "$work/lib.err"; exit 1; }
done
grep -q "skeleton 3: the library has 3 skeleton(s)" "$work/lib.err" || { echo "FAIL: --skeleton 3"; cat "$work/lib.err"; exit 1; }
"$bin" convert "$work/rigs" -o "$work/lib.bvh" 2>"$work/lib.err" || true
grep -q "lib.bvh: the library holds 3 clips, and several clips go into a .glb, .gltf or .fbx only" "$work/lib.err" \
  || { echo "FAIL: a library of 3 clips into a BVH"; cat "$work/lib.err"; exit 1; }
# A library of one clip (a folder of one file, a manifest's frame range) goes into any format.
mkdir "$work/one" && cp "$data/bvh/131_01.bvh" "$work/one/"
printf '[[clip]]\nfile = "%s"\nfirst_frame = 41\nlast_frame = 240\n' "$data/cmu/16/16_15.amc" >"$work/range.toml"
"$bin" convert "$work/one" -o "$work/one.bvh" -o "$work/one.json" 2>/dev/null \
  && "$bin" convert "$work/range.toml" -o "$work/range.json" -o "$work/range.glb" 2>/dev/null \
  && "$bin" convert "$work/one/131_01.bvh" --fps 30 -o "$work/one-file.json" 2>/dev/null \
  || { echo "FAIL: a library of one clip into a BVH or JSON"; exit 1; }
python3 - "$work" <<'PY'
import json, sys
work = sys.argv[1]
one, one_file, ranged = (json.load(open(f"{work}/{n}.json")) for n in ("one", "one-file", "range"))
# The folder's one clip is the file's, as build reads it at 30 fps; the range 200 frames at 120 fps.
assert len(one["positions"]) == len(one_file["positions"]) and one["contacts"]["joints"], len(one["positions"])
assert len(ranged["positions"]) == 50 and ranged["fps"] == 30, (len(ranged["positions"]), ranged["fps"])
# Its .glb's animation is named as the clip, as a library's are (not as the output file).
data = open(f"{work}/range.glb", "rb").read()
gltf = json.loads(data[20:20 + int.from_bytes(data[12:16], "little")])
assert [a["name"] for a in gltf["animations"]] == ["16_15"], gltf["animations"]
PY
"$bin" info "$work/one.bvh" | grep -q "at 30 fps" || { echo "FAIL: the one clip's BVH"; exit 1; }
# An output is none of the files a folder gives, though no argument names it: refused, unchanged.
cp "$work/rigs.glb" "$work/one/"
cp "$work/one/rigs.glb" "$work/rigs-before.glb"
if "$bin" convert "$work/one" -o "$work/one/rigs.glb" 2>"$work/over.err"; then echo "FAIL: wrote over a clip read"; exit 1; fi
grep -q "one/rigs.glb: is also an input ('.*one/rigs.glb', a clip file of a folder given)" "$work/over.err" \
  && cmp -s "$work/one/rigs.glb" "$work/rigs-before.glb" || { echo "FAIL: over a clip read"; cat "$work/over.err"; exit 1; }
# glTF in: an animation of a set reads back to its clip's joints; a library of glTF files reads
# every animation, named FILE:ANIMATION, tagged by CMU's index when named as CMU's clips are.
"$bin" convert "$work/set.glb" --animation 16_35 -o "$work/set-jog.json"
"$bin" info "$work/set.glb" | head -1 | grep -q "glTF, animation '16_15' (1 of 3: 16_15, 16_35, 16_15_2;" \
  || { echo "FAIL: info on a glTF set"; "$bin" info "$work/set.glb"; exit 1; }
python3 - "$work/jog.json" "$work/set-jog.json" <<'PY'
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:])
index = {j["name"]: i for i, j in enumerate(b["joints"])}
assert a["fps"] == b["fps"] and len(a["positions"]) == len(b["positions"]) == 41
worst = max(abs(x - y) for fa, fb in zip(a["positions"], b["positions"])
            for j, p in enumerate(fa) for x, y in zip(p, fb[index[a["joints"][j]["name"]]]))
assert worst < 2e-5, worst
PY
if "$bin" convert "$work/set.glb" --animation swim -o "$work/swim.json" 2>"$work/swim.err"; then echo "FAIL: no such animation"; exit 1; fi
[[ $(wc -l <"$work/swim.err") -eq 1 && ! -e "$work/swim.json" ]] && grep -q "set.glb: no animation 'swim' (the file has 16_15, 16_35, 16_15_2)" "$work/swim.err" \
  || { echo "FAIL: --animation swim"; cat "$work/swim.err"; exit 1; }
# A manifest names an animation of a glTF file, with its own tags.
cat >"$work/glb.toml" <<'TOML'
fps = 30
[[clip]]
file = "s16.glb"
animation = "16_35"
tags = ["jog"]
[[clip]]
file = "s16.glb"
animation = "16_15"
name = "stroll"
TOML
"$bin" info --json "$work/glb.toml" >"$work/glb-info.json" 2>/dev/null
python3 - "$work/glb-info.json" <<'PY'
import json, sys
info = json.load(open(sys.argv[1]))
clips = {c["name"]: c for c in info["clips"]}
assert set(clips) == {"s16:16_35", "stroll"}, clips.keys()
assert clips["s16:16_35"]["tags"] == ["jog"] and clips["s16:16_35"]["frames"] == 41, clips["s16:16_35"]
assert "walk" in clips["stroll"]["tags"], clips["stroll"]  # CMU's index, by the animation's name
PY
# An animation the file has not: the manifest's line that asks for it is blamed.
sed 's/animation = "16_15"/animation = "swim"/' "$work/glb.toml" >"$work/swim.toml"
if "$bin" info "$work/swim.toml" >/dev/null 2>"$work/swim.err"; then echo "FAIL: manifest animation swim"; exit 1; fi
[[ $(wc -l <"$work/swim.err") -eq 1 ]] \
  && grep -q "swim.toml:8: clip .*s16.glb: no animation 'swim' (the file has 16_01, " "$work/swim.err" \
  || { echo "FAIL: manifest animation swim"; cat "$work/swim.err"; exit 1; }
# A folder of a character's model alone (glTF without animation) holds no clip.
mkdir "$work/model"
printf '{"asset": {"version": "2.0"}, "nodes": [{"name": "Body"}], "scenes": [{"nodes": [0]}]}\n' >"$work/model/character.gltf"
if "$bin" info "$work/model" 2>"$work/model.err" >/dev/null; then echo "FAIL: a folder without clips was a library"; exit 1; fi
grep -q "model: the folder holds no clip (its glTF and FBX files have no animation)" "$work/model.err" \
  || { echo "FAIL: a folder of a model"; cat "$work/model.err"; exit 1; }
"$bin" build "$work/s16.glb" -o "$work/glb.mgraph" --no-cache -q
"$bin" inspect --clips "$work/glb.mgraph" >"$work/glb.clips"
grep -q "^s16:16_15 .* walk" "$work/glb.clips" && [[ $(grep -c "^s16:16_" "$work/glb.clips") -eq 15 ]] \
  || { echo "FAIL: a glTF library's clips"; cat "$work/glb.clips"; exit 1; }
# The converted BVH reads back.
"$bin" info "$work/jog.bvh" | grep "41 frames at 30 fps" >/dev/null || { echo "FAIL: written BVH does not read back"; exit 1; }
# An output that is the input is refused, the input untouched.
cp "$work/jog.bvh" "$work/jog-in.bvh"
if "$bin" convert "$work/jog-in.bvh" -o "$work/jog-in.bvh" --output-scale 100 2>"$work/same.err"; then
  echo "FAIL: converted a file over itself"; exit 1
fi
grep -q "jog-in.bvh: is also an input" "$work/same.err" && cmp -s "$work/jog.bvh" "$work/jog-in.bvh" \
  || { echo "FAIL: output over the input"; cat "$work/same.err"; exit 1; }
# 16_15 opens on two frames a capture glitch cuts off: convert and info say so, and
# --keep-rest-frames keeps them (471 frames in the file).
"$bin" convert "$data/cmu/16/16_15.amc" -o "$work/g15.json" 2>"$work/g15.err"
"$bin" convert "$data/cmu/16/16_15.amc" --keep-rest-frames -o "$work/k15.json" 2>"$work/k15.err"
grep -q "info: .*16_15.amc: the first 2 frames dropped, cut off by a capture glitch: a joint jumping 0.2 m or more at 20 m/s or faster between two calm frames" \
  "$work/g15.err" && ! grep -q "glitch" "$work/k15.err" \
  && "$bin" info "$data/cmu/16/16_15.amc" | grep -q "^  motion:   469 frames at 120 fps, 3.90 s (the first 2 frames dropped, cut" \
  && "$bin" info "$data/cmu/16/16_15.amc" --keep-rest-frames | grep -q "^  motion:   471 frames at 120 fps, 3.92 s$" \
  || { echo "FAIL: 16_15's glitched first frames"; cat "$work/g15.err"; "$bin" info "$data/cmu/16/16_15.amc"; exit 1; }
python3 - "$work/g15.json" "$work/k15.json" <<'PY'
import json, sys
dropped, kept = (json.load(open(p))["positions"] for p in sys.argv[1:3])
assert len(kept) == len(dropped) + 2 and kept[2:] == dropped, (len(kept), len(dropped))
PY
ls -A "$work" | grep -q "tmp-" && { echo "FAIL: temporary files left"; exit 1; }
# --mirror: a walk turning left written as its mirror image turns right, each joint where its
# partner's mirror image is (within the subject's own left-right differences), and mirrored
# again it is the walk as read (to the BVH's precision); a library's clips are each followed by
# theirs.
"$bin" convert "$data/cmu/16/16_17.amc" -o "$work/left.json" 2>/dev/null
"$bin" convert "$data/cmu/16/16_17.amc" --mirror -o "$work/right.bvh" -o "$work/right.json" 2>/dev/null
"$bin" convert "$work/right.bvh" --mirror -o "$work/left-again.json" 2>/dev/null
python3 - "$work/left.json" "$work/right.json" "$work/left-again.json" <<'PY'
import json, math, sys
left, right, again = (json.load(open(p)) for p in sys.argv[1:4])
names = [j["name"] for j in left["joints"]]
partner = lambda n: ("r" + n[1:]) if n[0] == "l" and "r" + n[1:] in names else \
                    ("l" + n[1:]) if n[0] == "r" and "l" + n[1:] in names else n
at = {n: i for i, n in enumerate(names)}
# The mirror's plane: across the hips in the first frame's rest, x here (CMU's left is +x).
worst = max(math.dist((-a[at[n]][0], a[at[n]][1], a[at[n]][2]), b[at[partner(n)]])
            for a, b in zip(left["positions"], right["positions"]) for n in names)
assert worst < 0.06, worst
def turn(pos):   # the root's heading of travel, first second against last, radians (left +)
    r = [f[0] for f in pos]
    a = (r[30][0] - r[0][0], r[30][2] - r[0][2]); b = (r[-1][0] - r[-31][0], r[-1][2] - r[-31][2])
    return math.atan2(a[1] * b[0] - a[0] * b[1], a[0] * b[0] + a[1] * b[1])
assert turn(left["positions"]) > 1.0 and abs(turn(right["positions"]) + turn(left["positions"])) < 0.01, \
    (turn(left["positions"]), turn(right["positions"]))
twice = max(abs(x - y) for fa, fb in zip(left["positions"], again["positions"])
            for ja, jb in zip(fa, fb) for x, y in zip(ja, jb))
assert twice < 1e-4, twice
PY
mkdir "$work/mirror-lib" && cp "$data/bvh/131_01.bvh" "$work/mirror-lib/"
"$bin" convert "$work/mirror-lib" --mirror -o "$work/mirror-lib.glb" -o "$work/mirror-lib.bvh" 2>/dev/null
"$bin" convert "$work/mirror-lib.bvh" --mirror -o "$work/mirror-lib-twice.json" 2>/dev/null
"$bin" convert "$work/mirror-lib" -o "$work/mirror-lib-plain.json" 2>/dev/null
python3 - "$work/mirror-lib-plain.json" "$work/mirror-lib-twice.json" <<'PY'
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
worst = max(abs(x - y) for fa, fb in zip(a["positions"], b["positions"])
            for ja, jb in zip(fa, fb) for x, y in zip(ja, jb))
assert len(a["positions"]) == len(b["positions"]) and worst < 1e-4, worst
PY
python3 - "$work/mirror-lib.glb" <<'PY'
import json, sys
data = open(sys.argv[1], "rb").read()
gltf = json.loads(data[20:20 + int.from_bytes(data[12:16], "little")])
assert [a["name"] for a in gltf["animations"]] == ["131_01_mirrored"], gltf["animations"]
PY
# Several clips mirrored into one file: their animations named so. A rig whose rest pose is not its
# own mirror image (an arm held 30 units higher) stops convert --mirror, a file or a library, and
# writes nothing; build keeps its clips as they are, with a warning.
"$bin" convert --mirror "$data/cmu/16/16_15.amc" "$data/cmu/16/16_17.amc" -o "$work/mirror-set.glb" 2>/dev/null
python3 - "$work/mirror-set.glb" <<'PY'
import json, sys
data = open(sys.argv[1], "rb").read()
gltf = json.loads(data[20:20 + int.from_bytes(data[12:16], "little")])
assert [a["name"] for a in gltf["animations"]] == ["16_15_mirrored", "16_17_mirrored"], gltf["animations"]
PY
mkdir "$work/lopsided"
python3 - "$data/bvh/131_01.bvh" "$work/lopsided/raised.bvh" <<'PY'
import sys
lines = open(sys.argv[1]).read().split("\n")
at = next(i for i, l in enumerate(lines) if l.split()[:2] == ["JOINT", "LeftShoulder"])
o = next(i for i in range(at, len(lines)) if lines[i].split()[:1] == ["OFFSET"])
x, y, z = (float(v) for v in lines[o].split()[1:4])
lines[o] = lines[o][:len(lines[o]) - len(lines[o].lstrip())] + f"OFFSET {x} {y + 30} {z}"
open(sys.argv[2], "w").write("\n".join(lines))
PY
for input in "$work/lopsided" "$work/lopsided/raised.bvh"; do
  if "$bin" convert --mirror "$input" -o "$work/raised.glb" 2>"$work/raised.err"; then
    echo "FAIL: convert --mirror of a lopsided rig ($input)"; exit 1
  fi
  grep -q "raised.bvh: cannot be mirrored: its rest pose is not its own mirror image: its LeftShoulder and \
RightShoulder stand" "$work/raised.err" && [[ ! -e "$work/raised.glb" ]] \
    || { echo "FAIL: convert --mirror of a lopsided rig ($input)"; cat "$work/raised.err"; exit 1; }
done
"$bin" info --mirror on "$work/lopsided" 2>&1 >/dev/null | grep -q "warning: .*raised.bvh: its clip is not mirrored: \
its rest pose is not its own mirror image" || { echo "FAIL: info --mirror on of a lopsided rig"; exit 1; }
"$bin" info --mirror on "$work/lopsided" 2>/dev/null | grep -q "^  turning:  .*, and its rig cannot be mirrored" \
  || { echo "FAIL: info's turning line, a rig that cannot be mirrored"; exit 1; }
# The same rig in a second file (another take: its last value changed): one warning for both.
python3 -c 'import sys; t = open(sys.argv[1]).read().rstrip(); open(sys.argv[2], "w").write(t + "1\n")' \
  "$work/lopsided/raised.bvh" "$work/lopsided/raised2.bvh"
"$bin" info --mirror on "$work/lopsided" 2>"$work/lopsided.err" >/dev/null
[[ $(grep -c "not mirrored" "$work/lopsided.err") -eq 1 ]] \
  && grep -q "raised.bvh, .*raised2.bvh: their 2 clips are not mirrored: of each rig, its rest" "$work/lopsided.err" \
  || { echo "FAIL: one warning for a rig in two files"; cat "$work/lopsided.err"; exit 1; }
if "$bin" info --mirror sometimes "$data/bvh/131_01.bvh" >/dev/null 2>&1; then
  echo "FAIL: info --mirror sometimes on a file"; exit 1
fi
# Several outputs, one of which cannot be made (a root 1e41 units east all along: past glTF's
# floats): none is written, not the ones before it.
python3 - "$data/bvh/131_01.bvh" "$work/far.bvh" <<'PY'
import sys
lines = open(sys.argv[1]).read().split("\n")
for at in range(lines.index("MOTION") + 3, len(lines)):
    values = lines[at].split()
    if values:
        values[0] = "1e41"
        lines[at] = " ".join(values)
open(sys.argv[2], "w").write("\n".join(lines))
PY
if "$bin" convert "$work/far.bvh" -o "$work/far-out.bvh" -o "$work/far-out.json" \
    -o "$work/far-out.gltf" 2>"$work/far.err"; then
  echo "FAIL: convert of a root past glTF's floats succeeded"; exit 1
fi
grep -q "far-out.gltf: .*past what glTF's single-precision numbers hold" "$work/far.err" \
  && [[ ! -e "$work/far-out.bvh" && ! -e "$work/far-out.json" && ! -e "$work/far-out.gltf" ]] \
  || { echo "FAIL: a failed output left the others written"; cat "$work/far.err"; ls "$work"; exit 1; }
"$bin" convert "$work/far.bvh" -o "$work/far-out.bvh" -o "$work/far-out.json" 2>/dev/null \
  && [[ -s "$work/far-out.bvh" && -s "$work/far-out.json" ]] \
  || { echo "FAIL: convert of a far root to BVH, JSON"; exit 1; }
echo "cli convert ok"
