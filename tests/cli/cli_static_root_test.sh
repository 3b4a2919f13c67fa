#!/usr/bin/env bash
# A BVH library from another studio's rig, read with no flags: subject 16's clips written as a
# static root above the hips, 6 channels on every joint, in centimetres (as Bandai Namco
# Research's datasets are), under CMU's names in a folder with no CMU index beside it.
# The unit is found (cm), the hips carry the floor position, the graph keeps frames and paths
# are followed; written BVH keeps the file's hierarchy; a figure of no human size warns. The
# same library written z up is read standing (a crawling clip among it too), and written in place (the hips' travel taken out,
# as game libraries' "in place" exports are) gets its travel back from the planted feet.
# Usage: MOTIONGRAPH=binary MAKE_STATIC_ROOT_BVH=binary cli_static_root_test.sh DATA_DIR
set -euo pipefail
data=$1
bin=${MOTIONGRAPH:?set MOTIONGRAPH to the motiongraph binary}
make=${MAKE_STATIC_ROOT_BVH:?set MAKE_STATIC_ROOT_BVH to the make_static_root_bvh binary}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir "$work/lib" "$work/amc"
clips=("$data"/cmu/16/16_{11,13,15,16,35,37}.amc)
"$make" "$work/lib" "${clips[@]}"
cp "$data/cmu/16/16.asf" "${clips[@]}" "$work/amc/"   # the same clips as CMU gives them
head -3 "$work/lib/16_15.bvh" | grep -q "ROOT joint_Root" || { echo "FAIL: test rig"; exit 1; }

"$bin" info "$work/lib/16_15.bvh" >"$work/info.txt"
grep -q "lengths:  cm (0.01 m)" "$work/info.txt" || { echo "FAIL: unit"; cat "$work/info.txt"; exit 1; }
grep -q "root:     root carries the floor position and facing (above it, folded in: joint_Root)" "$work/info.txt" \
  || { echo "FAIL: trajectory joint"; cat "$work/info.txt"; exit 1; }
"$bin" info --json "$work/lib/16_15.bvh" "$data/cmu/16/16.asf" "$data/cmu/16/16_15.amc" >"$work/info.json"
python3 - "$work/info.json" <<'PY'
import json, sys
bvh, asf, amc = json.load(open(sys.argv[1]))
assert bvh["unit"]["name"] == "cm" and bvh["unit"]["plausible"], bvh["unit"]
assert bvh["static_joints_above_root"] == ["joint_Root"] and bvh["root"] == "root"
# The same capture as the AMC: same height and root travel, in metres.
assert abs(bvh["root_path_m"] - amc["root_path_m"]) < 1e-3, (bvh["root_path_m"], amc["root_path_m"])
assert amc["root_path_m"] > 2.0
for i in range(2):
    assert abs(bvh["height_m"][i] - amc["height_m"][i]) < 1e-3, (bvh["height_m"], amc["height_m"])
PY

# Build with no flags: tags from the index the project ships, and the graph of the same clips
# read from CMU's AMC files (same frame distances, so the same transitions).
"$bin" build "$work/lib" -o "$work/g.mgraph" --report "$work/r.json" --no-cache 2>"$work/build.txt"
grep -q "lengths read in cm: 6 files" "$work/build.txt" || { echo "FAIL: build unit line"; cat "$work/build.txt"; exit 1; }
"$bin" build "$work/amc" -o "$work/amc.mgraph" --report "$work/amc.json" --no-cache -q
python3 - "$work/r.json" "$work/amc.json" <<'PY'
import json, sys
r, amc = (json.load(open(f)) for f in sys.argv[1:3])
assert {"walk", "run"} <= set(r["tags"]), r["tags"]
kept = {t["name"]: t["frames"] for t in r["graph_after"]["tags"]}
kept_amc = {t["name"]: t["frames"] for t in amc["graph_after"]["tags"]}
assert kept.get("walk", 0) > 100 and kept.get("run", 0) > 0, kept
for tag, frames in kept_amc.items():
    assert abs(kept.get(tag, 0) - frames) <= 0.05 * frames, (kept, kept_amc)
assert abs(r["graph_after"]["nodes"] - amc["graph_after"]["nodes"]) <= 0.05 * amc["graph_after"]["nodes"]
PY

# Paths are followed, and the result keeps the rig: the static root, the hips below it.
"$bin" path "$work/g.mgraph" --shape s-curve:20 -o "$work/s.bvh" --report "$work/s.json" >/dev/null
python3 - "$work/s.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
assert r["mean_deviation_m"] < 0.5, r["mean_deviation_m"]
print(f"s-curve:20 on the static-root library: mean deviation {r['mean_deviation_m']:.3f} m, "
      f"max {r['max_deviation_m']:.3f} m")
PY
head -6 "$work/s.bvh" | tr -s ' ' | grep -q "JOINT root" || { echo "FAIL: path output hierarchy"; head "$work/s.bvh"; exit 1; }
head -1 "$work/s.bvh" | grep -q HIERARCHY && sed -n 2p "$work/s.bvh" | grep -q "ROOT joint_Root" \
  || { echo "FAIL: path output root"; head "$work/s.bvh"; exit 1; }

# convert keeps the hierarchy and reads back to the same figure.
"$bin" convert "$work/lib/16_15.bvh" -o "$work/c.bvh" 2>"$work/convert.txt"
grep -q "lengths read in cm" "$work/convert.txt" || { echo "FAIL: convert unit line"; cat "$work/convert.txt"; exit 1; }
"$bin" info --json "$work/c.bvh" "$work/lib/16_15.bvh" >"$work/back.json"
python3 - "$work/back.json" "$work/c.bvh" "$work/lib/16_15.bvh" <<'PY'
import json, re, sys
back, original = json.load(open(sys.argv[1]))
assert back["unit"]["name"] == "m", back["unit"]
for key in ("root_path_m",):
    assert abs(back[key] - original[key]) < 1e-4, key
assert [(j["name"], j["parent"]) for j in back["skeleton"]] == [(j["name"], j["parent"]) for j in original["skeleton"]]
def joints(path):
    return re.findall(r"(?:ROOT|JOINT) (\S+)", open(path).read())
assert joints(sys.argv[2]) == joints(sys.argv[3]), "hierarchy changed"
PY

# The same rig written z up (as 3ds Max and other z-up tools hold it): read standing with no
# flags, an info line saying so, the same graph, and paths followed; --up-axis y reads it lying.
mkdir "$work/zlib"
"$make" --z-up "$work/zlib" "${clips[@]}"
"$bin" info "$work/zlib/16_15.bvh" >"$work/zinfo.txt"
grep "up:       z (the figure stands along z" "$work/zinfo.txt" >/dev/null \
  || { echo "FAIL: z up"; cat "$work/zinfo.txt"; exit 1; }
"$bin" info --json "$work/zlib/16_15.bvh" "$work/lib/16_15.bvh" >"$work/zinfo.json"
"$bin" info --json --up-axis y "$work/zlib/16_15.bvh" >"$work/lying.json"
python3 - "$work/zinfo.json" "$work/lying.json" <<'PY'
import json, sys
(z, y), (lying,) = (json.load(open(f)) for f in sys.argv[1:3])
assert z["up_axis"]["axis"] == "z" and y["up_axis"]["axis"] == "y", (z["up_axis"], y["up_axis"])
assert z["unit"]["name"] == "cm", z["unit"]
for key in ("root_path_m",):
    assert abs(z[key] - y[key]) < 1e-3, (key, z[key], y[key])
for i in range(2):
    assert abs(z["height_m"][i] - y["height_m"][i]) < 1e-3, (z["height_m"], y["height_m"])
# Told y, the figure lies on its back and its walk goes up the wall: metres of "height".
span = lambda h: h[1] - h[0]
assert lying["up_axis"] == {"axis": "y"} and span(lying["height_m"]) > span(z["height_m"]) + 1.0, lying["height_m"]
PY
"$bin" convert "$work/zlib/16_15.bvh" -o "$work/zc.bvh" 2>"$work/zconvert.txt"
grep "zlib/16_15.bvh: read z up (the figure stands along z" "$work/zconvert.txt" >/dev/null \
  || { echo "FAIL: convert up line"; cat "$work/zconvert.txt"; exit 1; }
"$bin" info --json "$work/zc.bvh" "$work/lib/16_15.bvh" >"$work/zc.json"
python3 - "$work/zc.json" <<'PY'
import json, sys
written, y = json.load(open(sys.argv[1]))  # written y up, with the file's hierarchy
assert written["up_axis"]["axis"] == "y" and written["static_joints_above_root"] == ["joint_Root"]
assert abs(written["root_path_m"] - y["root_path_m"]) < 1e-3
assert all(abs(a - b) < 1e-3 for a, b in zip(written["height_m"], y["height_m"])), (written["height_m"], y["height_m"])
PY
"$bin" build "$work/zlib" -o "$work/z.mgraph" --report "$work/zr.json" --no-cache 2>"$work/zbuild.txt"
grep "read z up and turned y up: 6 of 6 files" "$work/zbuild.txt" >/dev/null \
  || { echo "FAIL: build up line"; cat "$work/zbuild.txt"; exit 1; }
# One clip of the z-up library lies along the file's y all through (a crawl): alone, its shape
# says y (its animation against its rest pose); in the library it is read z up like the others,
# with a warning naming it.
mkdir "$work/crawl" "$work/zlib2"
"$make" --z-up --lying "$work/crawl" "$data/cmu/16/16_13.amc"
"$bin" info "$work/crawl/16_13.bvh" | grep "up:       y" >/dev/null \
  || { echo "FAIL: a lying clip alone"; "$bin" info "$work/crawl/16_13.bvh"; exit 1; }
cp "$work"/zlib/*.bvh "$work/zlib2/" && cp "$work/crawl/16_13.bvh" "$work/zlib2/"
"$bin" build "$work/zlib2" -o "$work/z2.mgraph" --no-cache 2>"$work/z2build.txt"
grep "warning: .*zlib2/16_13.bvh: read z up like the library's other files, though its own shape says y" \
  "$work/z2build.txt" >/dev/null && grep "read z up and turned y up: 6 of 6 files" "$work/z2build.txt" >/dev/null \
  || { echo "FAIL: a lying clip in a z-up library"; cat "$work/z2build.txt"; exit 1; }
"$bin" path "$work/z.mgraph" --shape s-curve:20 -o "$work/zs.bvh" --report "$work/zs.json" >/dev/null
python3 - "$work/zr.json" "$work/r.json" "$work/zs.json" <<'PY'
import json, sys
z, y, s = (json.load(open(f)) for f in sys.argv[1:4])
assert z["graph_after"]["nodes"] == y["graph_after"]["nodes"], (z["graph_after"]["nodes"], y["graph_after"]["nodes"])
assert s["mean_deviation_m"] < 0.5 and s["reached_end"], (s["mean_deviation_m"], s["reached_end"])
PY

# The same rig in place: each clip walks or runs on the spot, its planted foot sliding back. With
# no flags the travel comes back from the feet (an info line says so), the graph follows paths,
# and convert writes the clip travelling; --travel root reads it as written.
mkdir "$work/iplib"
"$make" --in-place "$work/iplib" "${clips[@]}"
"$bin" info "$work/iplib/16_15.bvh" >"$work/ipinfo.txt"
grep "travel:   in place as read (planted feet slide" "$work/ipinfo.txt" >/dev/null \
  || { echo "FAIL: in place info"; cat "$work/ipinfo.txt"; exit 1; }
"$bin" info --json "$work/iplib/16_15.bvh" "$work/lib/16_15.bvh" >"$work/ipinfo.json"
"$bin" info --json --travel root "$work/iplib/16_15.bvh" >"$work/asread.json"
python3 - "$work/ipinfo.json" "$work/asread.json" <<'PY'
import json, sys
(ip, capture), (as_read,) = (json.load(open(f)) for f in sys.argv[1:3])
assert ip["travel"]["source"] == "feet" and ip["travel"]["in_place"], ip["travel"]
assert capture["travel"]["source"] == "root" and not capture["travel"]["in_place"], capture["travel"]
assert as_read["travel"] == {"source": "root"} and as_read["root_path_m"] < 0.2, as_read["root_path_m"]
# Back from the feet: within 10 % of the capture's travel.
assert 0.9 * capture["root_path_m"] <= ip["root_path_m"] <= 1.05 * capture["root_path_m"], \
    (ip["root_path_m"], capture["root_path_m"])
PY
"$bin" build "$work/iplib" -o "$work/ip.mgraph" --no-cache 2>"$work/ipbuild.txt"
grep "travel recovered from the planted feet: 6 clips animated in place" "$work/ipbuild.txt" >/dev/null \
  || { echo "FAIL: build travel line"; cat "$work/ipbuild.txt"; exit 1; }
"$bin" path "$work/ip.mgraph" --shape s-curve:20 -o "$work/ips.bvh" --report "$work/ips.json" >/dev/null \
  2>"$work/ips.err"
# Read as written (--travel root) the clips walk on the spot: a path is not followed, and path
# says why beside its summary (the motion is written all the same).
"$bin" build "$work/iplib" -o "$work/iproot.mgraph" --no-cache --travel root -q
"$bin" path "$work/iproot.mgraph" --shape line:10 -o "$work/iproot.bvh" >/dev/null 2>"$work/iproot.err" \
  && grep -Eq "warning: the motion did not reach the path's end: it went [0-9.]+ m of 10.0 m and stops [0-9.]+ m from \
the end; the graph's clips hardly travel \([0-9] % of its clip frames move 0.5 m/s or faster\)" "$work/iproot.err" \
  && [[ -s "$work/iproot.bvh" ]] && ! grep -q "did not reach" "$work/ips.err" \
  || { echo "FAIL: a path the clips cannot follow"; cat "$work/iproot.err"; exit 1; }
"$bin" convert "$work/iplib/16_15.bvh" -o "$work/ipc.bvh" 2>"$work/ipconvert.txt"
grep "iplib/16_15.bvh: travel in place as read" "$work/ipconvert.txt" >/dev/null \
  || { echo "FAIL: convert travel line"; cat "$work/ipconvert.txt"; exit 1; }
"$bin" info --json "$work/ipc.bvh" "$work/iplib/16_15.bvh" >"$work/ipc.json"
python3 - "$work/ips.json" "$work/ipc.json" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
assert s["mean_deviation_m"] < 0.15 and s["reached_end"], (s["mean_deviation_m"], s["reached_end"])
written, recovered = json.load(open(sys.argv[2]))  # written travelling: read as it is, the same path
assert written["travel"]["source"] == "root" and not written["travel"]["in_place"], written["travel"]
assert abs(written["root_path_m"] - recovered["root_path_m"]) < 1e-3, (written["root_path_m"], recovered["root_path_m"])
print(f"s-curve:20 on the in-place library: mean deviation {s['mean_deviation_m']:.3f} m")
PY

# A game's cycles (one walk cycle each of two clips and a run cycle, each made a loop, in a
# Bandai-like rig): the build plays them on past their end so the graph can play them round;
# without that (--no-loops) a cycle of one period holds no transition back to its start.
mkdir -p "$work/loops"
"$make" --loop 32:34 "$work/loops" "$data/cmu/16/16_15.amc"
"$make" --loop 15:36 "$work/loops" "$data/cmu/16/16_16.amc"
"$make" --loop 0:24 "$work/loops" "$data/cmu/16/16_35.amc"
"$bin" build "$work/loops" -o "$work/loops.mgraph" --no-cache --report "$work/loops.json" 2>"$work/loops.txt"
grep "3 clips loop (their end meets their start: 16_15 and 2 more): played on past their end, 33 frames in all" \
  "$work/loops.txt" >/dev/null || { echo "FAIL: loops line"; cat "$work/loops.txt"; exit 1; }
"$bin" build "$work/loops" -o "$work/noloops.mgraph" --no-cache --no-loops --report "$work/noloops.json" 2>/dev/null
"$bin" info --json "$work/loops" >"$work/loops-info.json" 2>/dev/null
"$bin" path "$work/loops.mgraph" --shape s-curve:20 -o "$work/loops.bvh" --report "$work/loops-path.json" >/dev/null 2>&1
"$bin" path "$work/loops.mgraph" --shape s-curve:20 -o "$work/loops-b0.bvh" --bridge-penalty 0 \
  --report "$work/loops-path-b0.json" >/dev/null 2>&1
python3 - "$work/loops.json" "$work/noloops.json" "$work/loops-info.json" "$work/loops-path.json" \
  "$work/loops-path-b0.json" <<'PY'
import json, sys
loops, noloops, info, path, anyway = (json.load(open(p)) for p in sys.argv[1:6])
# The walk and run cycles are joined only by bridges (24 cm RMS apart). A path that asks for no
# motion type keeps to the walking (one bridge into the run for the last metres, measured), and
# its feet slide less than the cycles' own. Priced as any transition, the search wanders into the
# run and back (5 bridges, measured; the clean-up keeps their feet planted all the same).
assert path["bridges"] <= 1 and path["bridges"] < anyway["bridges"], (path["bridges"], anyway["bridges"])
assert path["foot_slide"]["ratio"]["mean_mps"] < 1.0, path["foot_slide"]
assert anyway["foot_slide"]["ratio"]["mean_mps"] < 1.0, anyway["foot_slide"]
kept = lambda r: sum(c["kept_frames"] for c in r["clips"])
# Every clip joins the graph played round; as read, the run cycle joins nothing.
assert all(c["kept_frames"] > 0 for c in loops["clips"]), loops["clips"]
assert [c["kept_frames"] for c in noloops["clips"]][2] == 0, noloops["clips"]
assert kept(loops) > 2 * kept(noloops), (kept(loops), kept(noloops))
assert [l["period_frames"] for l in info["reading"]["loops"]] == [34, 36, 24], info["reading"]["loops"]
assert [c["frames"] for c in info["clips"]] == [34 + 11, 36 + 11, 24 + 11], info["clips"]
assert path["mean_deviation_m"] < 0.15 and path["reached_end"], path["mean_deviation_m"]
print(f"loops: {kept(loops)} frames kept against {kept(noloops)} as read; s-curve:20 {path['mean_deviation_m']:.3f} m")
PY

# An engine's root motion carrying the translation alone: a root that travels without turning
# above the hips, an IK helper hanging off it. The hips take its travel and give the facing, the
# helper is dropped (one warning for the files alike), and steering goes the way asked: north,
# then east (it went 30-50 degrees off, facing the root's fixed axis).
mkdir "$work/engine"
"$make" --translation-root "$work/engine" "${clips[@]}"
"$bin" build "$work/engine" -o "$work/engine.mgraph" --no-cache 2>"$work/engine.err"
[[ $(grep -c "travels without turning" "$work/engine.err") -eq 1 ]] \
  && grep -q "16_11.bvh, .*16_13.bvh and 4 more: their root 'root_motion' travels without turning (an engine's root \
motion), so 'root' below it carries the floor position and facing; dropped ik_foot_l, which hung off it" "$work/engine.err" \
  || { echo "FAIL: a root travelling without turning"; cat "$work/engine.err"; exit 1; }
# Its clips are one rig: one .glb holds two of them (the travelling root written back at the origin).
"$bin" convert "$work/engine/16_11.bvh" "$work/engine/16_13.bvh" -o "$work/engine-set.glb" 2>"$work/engine-set.err" \
  || { echo "FAIL: two clips of an engine rig in one .glb"; cat "$work/engine-set.err"; exit 1; }
printf '{"duration_s": 10, "controls": [{"at_s": 0, "heading": "north", "tag": "walk"}, {"at_s": 4, "heading_deg": 90}]}\n' \
  >"$work/north-east.json"
"$bin" steer "$work/engine.mgraph" --script "$work/north-east.json" -o "$work/engine-steer.json" >/dev/null 2>&1
python3 - "$work/engine-steer.json" <<'PY'
import json, math, sys
d = json.load(open(sys.argv[1]))
hips = [j["name"] for j in d["joints"]].index("root")
at = lambda s: d["positions"][min(len(d["positions"]) - 1, round(s * d["fps"]))][hips]
def bearing(a, b):  # degrees east of north (north: -z) the hips travelled from a to b seconds
    p, q = at(a), at(b)
    return math.degrees(math.atan2(q[0] - p[0], -(q[2] - p[2])))
# Measured: -1.5 and 90.4 degrees (the root's fixed axis taken for the facing: -8.6 and 75.5).
assert abs(bearing(1, 4)) < 6 and abs(bearing(6.5, 10) - 90) < 6, (bearing(1, 4), bearing(6.5, 10))
PY
# A figure no unit makes human-sized: a warning, read as metres.
printf 'HIERARCHY\nROOT a\n{\n OFFSET 0 0 0\n CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation\n JOINT b\n {\n  OFFSET 0 0.05 0\n  CHANNELS 3 Zrotation Xrotation Yrotation\n  End Site\n  {\n   OFFSET 0 0.05 0\n  }\n }\n}\nMOTION\nFrames: 2\nFrame Time: 0.04\n0 0 0 0 0 0 0 0 0\n0 0 0 0 0 0 0 0 0\n' >"$work/tiny.bvh"
"$bin" info "$work/tiny.bvh" >"$work/tiny.txt" 2>"$work/tiny.err"
grep -q "tiny.bvh: no length unit makes the figure human-sized" "$work/tiny.err" || { echo "FAIL: warning"; cat "$work/tiny.err"; exit 1; }
# --scale still decides when given: no line, no warning.
"$bin" info "$work/tiny.bvh" --scale 20 >"$work/tiny.txt" 2>"$work/tiny.err"
[ ! -s "$work/tiny.err" ] || { echo "FAIL: --scale"; cat "$work/tiny.err"; exit 1; }
grep -q "height 0.00 .. 2.00 m" "$work/tiny.txt" || { echo "FAIL: --scale height"; cat "$work/tiny.txt"; exit 1; }
echo "cli_static_root: ok"
