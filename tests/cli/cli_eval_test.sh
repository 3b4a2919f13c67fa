#!/usr/bin/env bash
# motiongraph eval as a user runs it on the bundled subject 16: every CSV has its header and
# rows that keep the invariants of what they measure, every PNG is a PNG, the threshold sweep
# at the build's own threshold finds the graph the build wrote, and bad requests (an unknown
# evaluation, no gnuplot) are one line and no output.
# Usage: MOTIONGRAPH=binary cli_eval_test.sh DATA_DIR
set -euo pipefail
data=$1
bin=${MOTIONGRAPH:?set MOTIONGRAPH to the motiongraph binary}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

"$bin" build "$data/cmu/16" -o "$work/g.mgraph" --cache-dir "$work/cache" --threshold-quantile 0.02 -q
"$bin" inspect --json "$work/g.mgraph" >"$work/inspect.json"
"$bin" eval "$work/g.mgraph" --out-dir "$work/eval" --what threshold,consistency,walks,paths -q >"$work/written.txt"
# Foot slide synthesizes a path per threshold and shape: three thresholds of the same range
# (the sweep's first, middle and last quantiles), two shapes.
"$bin" eval "$work/g.mgraph" --out-dir "$work/eval" --what footslide --thresholds 3 --shapes circle:5,figure8:4 -q \
  >>"$work/written.txt"
for name in threshold consistency walks paths footslide; do
  grep -qx "$work/eval/$name.csv" "$work/written.txt" || { echo "FAIL: $name.csv not listed"; exit 1; }
  grep -qx "$work/eval/$name.png" "$work/written.txt" || { echo "FAIL: $name.png not listed"; exit 1; }
done
# At the build's threshold (a 2 % quantile, given), the sweep rebuilds the graph the file holds.
"$bin" eval "$work/g.mgraph" --out-dir "$work/at-build" --what threshold --lowest 0.02 --highest 0.04 \
  --thresholds 2 --no-plots -q >/dev/null
[ ! -e "$work/at-build/threshold.png" ] || { echo "FAIL: --no-plots drew a plot"; exit 1; }

python3 - "$work" <<'PY'
import csv, json, math, struct, sys
work = sys.argv[1]
def rows(name, header):
    with open(f"{work}/{name}") as f:
        r = list(csv.reader(f))
    assert r[0] == header, (name, r[0])
    return [dict(zip(header, row)) for row in r[1:]]

t = rows("eval/threshold.csv", ["quantile", "threshold", "rms_cm", "transitions", "bridges", "nodes",
     "largest_component_nodes", "kept_nodes", "kept_transitions", "kept_clip_frames"])
assert len(t) == 12
for a, b in zip(t, t[1:]):
    assert float(a["quantile"]) < float(b["quantile"]) and float(a["threshold"]) <= float(b["threshold"])
for r in t:
    n, scc, kept = int(r["nodes"]), int(r["largest_component_nodes"]), int(r["kept_nodes"])
    assert 0 <= kept <= scc <= n, r
    assert int(r["kept_transitions"]) <= int(r["transitions"]) + int(r["bridges"]), r
assert any(int(r["kept_nodes"]) > 0 for r in t)

g = json.load(open(f"{work}/inspect.json"))["graph_after"]
at = rows("at-build/threshold.csv", list(t[0].keys()))[0]
assert int(at["kept_nodes"]) == g["nodes"] and int(at["kept_transitions"]) == g["transitions"], (at, g)

c = rows("eval/consistency.csv", ["quantile", "threshold", "rms_cm", "transitions", "frames", "rms_deg",
     "database_frames", "database_rms_deg"])
# Every sweep has the threshold in RMS cm too (the plots' axis), as the build reports it: the
# same D to cm everywhere, rising with D.
scale = {float(r["threshold"]): float(r["rms_cm"]) for r in c}
per_d = float(c[0]["rms_cm"]) ** 2 / float(c[0]["threshold"])  # cm^2 per unit of D
for r in t + c:
    assert float(r["rms_cm"]) == scale[float(r["threshold"])], r
    assert abs(float(r["rms_cm"]) ** 2 / float(r["threshold"]) - per_d) < 1e-4 * per_d, r
assert len(c) == 12
for r in c:
    assert 0 <= float(r["database_rms_deg"]) <= 180 and int(r["database_frames"]) > 0, r
    if int(r["frames"]) > 0:
        assert 0 <= float(r["rms_deg"]) <= 180, r
    else:
        assert r["rms_deg"] == "", r
assert any(int(r["frames"]) > 0 for r in c)

w = rows("eval/walks.csv", ["cost", "walk", "from", "to", "found", "frames", "edges", "transitions",
     "cost_value", "expansions"])
assert len(w) == 400 and {r["cost"] for r in w} == {"constant", "quality", "random", "hybrid"}
for r in w:
    assert r["from"] != r["to"]
    # The pruned graph is strongly connected: every walk is found.
    assert r["found"] == "1", r
    assert int(r["frames"]) > 0 and int(r["edges"]) >= 1 and 0 <= int(r["transitions"]) <= int(r["edges"]), r
    assert float(r["cost_value"]) >= 0, r
    if r["cost"] == "constant":
        assert float(r["cost_value"]) == int(r["edges"]), r
by_walk = {}
for r in w:
    by_walk.setdefault(r["walk"], set()).add((r["from"], r["to"]))
assert all(len(pairs) == 1 for pairs in by_walk.values())   # the same nodes for every cost

p = rows("eval/paths.csv", ["shape", "path_length_m", "arc_covered_m", "mean_deviation_m",
     "max_deviation_m", "reached_end", "frames", "searches", "budget_exhausted", "graph_mean_deviation_m",
     "graph_max_deviation_m", "end_distance_m"])
assert [r["shape"] for r in p] == ["line:20", "circle:5", "figure8:4", "s-curve:100"]
for r in p:
    mean, most = float(r["mean_deviation_m"]), float(r["max_deviation_m"])
    assert math.isfinite(mean) and math.isfinite(most) and 0 <= mean <= most, r
    # Bent onto the path, the motion is closer to it than the graph played it.
    graph_mean, graph_most = float(r["graph_mean_deviation_m"]), float(r["graph_max_deviation_m"])
    assert 0 <= mean < graph_mean <= graph_most, r
    assert float(r["path_length_m"]) > 0 and int(r["frames"]) > 0, r
    # Each reaches its path's end (within half a metre along it), ending near it.
    assert r["reached_end"] == "1" and float(r["path_length_m"]) - 0.5 <= float(r["arc_covered_m"]), r
    assert 0 <= float(r["end_distance_m"]) < 1.0, r

fs = rows("eval/footslide.csv", ["quantile", "threshold", "rms_cm", "shape", "graph", "frames", "transitions",
     "mean_deviation_m", "played_mps", "cleaned_mps", "source_mps", "played_ratio", "cleaned_ratio",
     "step_over_source_p999", "same_frames_steps", "same_frames_source_mps", "played_same_ratio", "cleaned_same_ratio"])
assert len(fs) == 3 * 2, len(fs)
assert all([r["shape"] for r in fs[2 * i:2 * i + 2]] == ["circle:5", "figure8:4"] for i in range(3))
# The threshold sweep's first and last thresholds (the same quantiles).
assert fs[0]["threshold"] == t[0]["threshold"] and fs[-1]["threshold"] == t[-1]["threshold"], (fs, t)
made = [r for r in fs if r["graph"] == "1"]
assert len(made) >= 2 and all(r["played_mps"] == "" for r in fs if r["graph"] == "0")
for r in made:
    played, cleaned, source = float(r["played_mps"]), float(r["cleaned_mps"]), float(r["source_mps"])
    assert source > 0 and played >= 0 and cleaned >= 0 and int(r["frames"]) > 0, r
    assert math.isclose(float(r["played_ratio"]), played / source, rel_tol=1e-9), r
    assert math.isclose(float(r["cleaned_ratio"]), cleaned / source, rel_tol=1e-9), r
    assert 0 < float(r["step_over_source_p999"]) < 10, r
    assert int(r["same_frames_steps"]) > 0 and float(r["same_frames_source_mps"]) > 0, r
    assert 0 <= float(r["cleaned_same_ratio"]) < float(r["played_same_ratio"]), r
# The clean-up takes most of the slide away: below the capture's own on most paths.
cleaned = sorted(float(r["cleaned_ratio"]) for r in made)
played = sorted(float(r["played_ratio"]) for r in made)
assert cleaned[len(cleaned) // 2] < played[len(played) // 2] and cleaned[len(cleaned) // 2] <= 1.0, (cleaned, played)
# On the frames played, the cleaned toes slide less than the capture's did there on every path.
assert all(float(r["cleaned_same_ratio"]) < 1.0 for r in made), [r["cleaned_same_ratio"] for r in made]

for name in ("threshold", "consistency", "walks", "paths", "footslide"):
    with open(f"{work}/eval/{name}.png", "rb") as f:
        head = f.read(24)
    assert head[:8] == b"\x89PNG\r\n\x1a\n" and head[12:16] == b"IHDR", name
    assert struct.unpack(">II", head[16:24]) == (900, 560), name
PY

# Bad requests: one line, exit 1, nothing written.
if "$bin" eval "$work/g.mgraph" --out-dir "$work/bad" --what threshold,fly 2>"$work/err.txt"; then
  echo "FAIL: an unknown evaluation was accepted"; exit 1
fi
grep -q "unknown evaluation 'fly'" "$work/err.txt" && [ "$(wc -l <"$work/err.txt")" -eq 1 ] || { cat "$work/err.txt"; exit 1; }
if env PATH=/nonexistent "$bin" eval "$work/g.mgraph" --out-dir "$work/bad" 2>"$work/err.txt"; then
  echo "FAIL: plotted without gnuplot"; exit 1
fi
grep -q "gnuplot" "$work/err.txt" && [ "$(wc -l <"$work/err.txt")" -eq 1 ] || { cat "$work/err.txt"; exit 1; }
# A bad shape is found before any evaluation runs (the walks' CSV was written before).
if "$bin" eval "$work/g.mgraph" --out-dir "$work/bad" --what walks,paths --shapes line:5,bogus:3 --no-plots \
    2>"$work/err.txt"; then
  echo "FAIL: an unknown shape was accepted"; exit 1
fi
grep -q "^--shapes: unknown shape 'bogus'" "$work/err.txt" && [ "$(wc -l <"$work/err.txt")" -eq 1 ] \
  || { cat "$work/err.txt"; exit 1; }
[ ! -e "$work/bad" ] || { echo "FAIL: a failed eval left output"; exit 1; }
# A library that stands (one pose held 10 s): every CSV, the plots that have points drawn, and
# one warning for each that has none, not gnuplot's own error and a failed run.
python3 - "$data/bvh/131_01.bvh" "$work/static.bvh" <<'PY'
import sys
lines = open(sys.argv[1]).read().split("\n")
at = next(i for i, line in enumerate(lines) if line.startswith("Frame Time"))
open(sys.argv[2], "w").write("\n".join(lines[:at - 1] + ["Frames: 300", lines[at]] + [lines[at + 10]] * 300) + "\n")
PY
"$bin" build "$work/static.bvh" -o "$work/static.mgraph" -q
"$bin" eval "$work/static.mgraph" --out-dir "$work/static" --shapes line:5 -q 2>"$work/static.err" \
  || { echo "FAIL: eval on a library that stands"; cat "$work/static.err"; exit 1; }
for f in threshold.csv consistency.csv walks.csv paths.csv footslide.csv threshold.png walks.png paths.png; do
  [ -s "$work/static/$f" ] || { echo "FAIL: no $f for a library that stands"; exit 1; }
done
[ ! -e "$work/static/consistency.png" ] && [ ! -e "$work/static/footslide.png" ] \
  && grep -q "warning: consistency.png not drawn: no frame around a transition travels" "$work/static.err" \
  && grep -q "warning: footslide.png not drawn: the clips' feet do not slide" "$work/static.err" \
  && ! grep -q "gnuplot failed" "$work/static.err" || { echo "FAIL: plots of no points"; cat "$work/static.err"; exit 1; }
echo "cli_eval: ok"
