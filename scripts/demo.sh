#!/usr/bin/env bash
# The main job on the bundled data: installs what is missing, builds, then reads every bundled
# clip, prints its summary, converts it to BVH in metres and to JSON world positions (30 fps),
# builds the motion graph of subject 16 with its report and distance picture, and evaluates it
# (CSV files and PNG plots in out/eval), all in out/, then starts the web studio on the graph
# and prints its address.
# Usage: scripts/demo.sh   (from anywhere; PORT=... and HOST=... for the studio's address,
#        loopback 127.0.0.1:8080 by default)
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

# Only what the demo needs: no test or benchmark programs (scripts/test.sh builds those).
scripts/install-deps.sh --demo
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DMOTIONGRAPH_TESTS=OFF -DMOTIONGRAPH_BENCHMARKS=OFF >/dev/null
cmake --build build -j "$(nproc)" --target motiongraph
bin=build/motiongraph
mkdir -p out/bvh out/json

echo "== the bundled clips"
"$bin" info data/cmu/16/16.asf data/cmu/16/*.amc data/bvh/*.bvh | tee out/summary.txt

echo "== converting to out/bvh (metres) and out/json (world positions), 30 fps"
for amc in data/cmu/16/*.amc; do
  name=$(basename "$amc" .amc)
  "$bin" convert "$amc" --fps 30 -o "out/bvh/$name.bvh" -o "out/json/$name.json"
done
# BVH has no unit: each file's is found from its figure's size (the CMU conversions are in the
# ASF's unit, the Daz-style ones (07_*) in cm). 16_01.bvh says 30 fps but holds the 120 fps capture (see data/README.md).
convert_bvh() {
  local file=$1
  shift
  local name
  name=$(basename "$file" .bvh)
  "$bin" convert "$file" --fps 30 "$@" -o "out/bvh/${name}_bvh.bvh" -o "out/json/${name}_bvh.json"
}
convert_bvh data/bvh/16_01.bvh --input-fps 120
convert_bvh data/bvh/131_01.bvh
convert_bvh data/bvh/111_36.bvh
convert_bvh data/bvh/07_01.bvh
convert_bvh data/bvh/07_12.bvh

echo "== the motion graph of subject 16 (distance stage cached in out/cache)"
"$bin" build data/cmu/16 -o out/subject16.mgraph --cache-dir out/cache \
  --report out/subject16-report.json --matrix-png out/subject16-distance.png
"$bin" inspect out/subject16.mgraph | tee out/subject16-graph.txt

echo "== new motion: walking then running a figure 8 (4 m loops), a walk, a steered run"
"$bin" path out/subject16.mgraph --shape figure8:4 --segment walk:0-25 --segment run:25-51 \
  -o out/figure8-walk-run.bvh --report out/figure8-walk-run.json
# The same motion (path synthesis is deterministic) as binary glTF, for game engines and viewers.
"$bin" path out/subject16.mgraph --shape figure8:4 --segment walk:0-25 --segment run:25-51 \
  -o out/figure8-walk-run.glb >/dev/null
cat >out/steer-demo.json <<'JSON'
{"duration_s": 16, "controls": [{"at_s": 0, "heading": "north", "tag": "walk"},
  {"at_s": 4, "heading": "east"}, {"at_s": 8, "heading": "south"}, {"at_s": 11, "tag": "run"}]}
JSON
"$bin" steer out/subject16.mgraph --script out/steer-demo.json -o out/steer-demo.bvh --report out/steer-demo-report.json
"$bin" walk out/subject16.mgraph --from 0 --to 40 --cost quality --min-frames 300 -o out/walk-demo.bvh

echo "== evaluating the graph of subject 16 (CSV and PNG plots in out/eval)"
"$bin" eval out/subject16.mgraph --out-dir out/eval

echo "== done: $(ls out/bvh | wc -l) BVH files in out/bvh (open them in Blender: File > Import > BVH),"
echo "   JSON world positions in out/json, summary in out/summary.txt,"
echo "   the graph in out/subject16.mgraph with its report and distance picture (out/subject16-*),"
echo "   synthesized motion: out/figure8-walk-run.bvh (and .glb, glTF for game engines: File > Import >"
echo "   glTF 2.0 in Blender, or drop it on any glTF viewer), out/steer-demo.bvh, out/walk-demo.bvh,"
echo "   the graph's evaluation in out/eval (threshold, consistency, walks, paths: .csv and .png)"

echo "== the studio: open the address below in a browser (Ctrl-C stops it; PORT=... and HOST=... to change it)"
exec "$bin" serve out/subject16.mgraph --host "${HOST:-127.0.0.1}" --port "${PORT:-8080}"
