#!/usr/bin/env bash
# Builds the libFuzzer targets (fuzz/) with clang and ASan+UBSan in build-fuzz/, makes seed
# corpora from the bundled data and runs each target for a while, one after the other.
#
# usage: scripts/fuzz.sh [SECONDS_PER_TARGET]     (default 30; works from any directory)
# (MOTIONGRAPH_FUZZ_BUILD=DIR builds and keeps corpora in DIR instead of build-fuzz/)
#
#   build-fuzz/corpus-<target>/       seeds + what the fuzzer found; kept between runs
#   build-fuzz/artifacts/             crash-*, leak-*, timeout-*, oom-* inputs, named
#                                     <target>-<kind>-<sha1>
#   build-fuzz/logs/fuzz_*.log        the full output of each run
#
# Exits non-zero if a target reports a crash, sanitizer error, leak, timeout or OOM (or the
# build fails). Reproduce a finding with: build-fuzz/fuzz/fuzz_<target> <artifact>
# (for fuzz_amc also set MOTIONGRAPH_FUZZ_ASF=data/cmu/16/16.asf).
set -euo pipefail

seconds="${1:-30}"
if ! [[ "$seconds" =~ ^[1-9][0-9]*$ ]]; then
  echo "usage: $0 [SECONDS_PER_TARGET]   (a positive whole number, default 30)" >&2
  exit 2
fi

cd "$(dirname "${BASH_SOURCE[0]}")/.."
root="$PWD"
build="${MOTIONGRAPH_FUZZ_BUILD:-$root/build-fuzz}"  # the build folder, overridable
max_len=65536

# --- build ---------------------------------------------------------------------------------
CC=clang CXX=clang++ cmake -S . -B "$build" -G Ninja \
  -DMOTIONGRAPH_FUZZ=ON -DMOTIONGRAPH_SANITIZE=address,undefined \
  -DMOTIONGRAPH_TESTS=OFF -DMOTIONGRAPH_BENCHMARKS=OFF -DCMAKE_BUILD_TYPE=RelWithDebInfo
targets=(asf amc bvh gltf manifest floor_path control_script graph_file)
cmake --build "$build" --target "${targets[@]/#/fuzz_}"

# --- seed corpora --------------------------------------------------------------------------
# Each bundled file as it is (libFuzzer reads only its first max_len bytes), plus for large
# files byte prefixes of 4 KB and 16 KB (mostly invalid: cut mid-line / frame count wrong)
# and a short valid file of the first 3 frames, so that the fuzzer has small seeds that reach
# past the parser into the builders.
add_seed() {  # add_seed CORPUS FILE
  local corpus="$1" file="$2" base size
  base="$(basename "$file")"
  size="$(wc -c <"$file")"
  cp "$file" "$corpus/$base"
  if ((size > 4096)); then head -c 4096 "$file" >"$corpus/$base.4k"; fi
  if ((size > 16384)); then head -c 16384 "$file" >"$corpus/$base.16k"; fi
}

corpus_asf="$build/corpus-asf" corpus_amc="$build/corpus-amc" corpus_bvh="$build/corpus-bvh"
artifacts="$build/artifacts" logs="$build/logs"
for target in "${targets[@]}"; do mkdir -p "$build/corpus-$target"; done
mkdir -p "$artifacts" "$logs"

for f in data/cmu/*/*.asf; do add_seed "$corpus_asf" "$f"; done
for f in data/cmu/16/*.amc; do
  add_seed "$corpus_amc" "$f"
  # The header and frames 1-3: stop at the line that is just the 4th frame number.
  awk '/^[ \t]*[0-9]+[ \t\r]*$/ { if (++frames > 3) exit } { print }' "$f" \
    >"$corpus_amc/$(basename "$f").3frames"
done
for f in data/bvh/*.bvh; do
  add_seed "$corpus_bvh" "$f"
  # The hierarchy and the first 3 motion lines, with 'Frames:' set to match.
  awk 'motion && /^[ \t]*Frames:/ { print "Frames: 3"; next }
       motion && /^[ \t]*Frame Time:/ { print; data = 1; next }
       data { if (++n > 3) exit }
       /^[ \t]*MOTION/ { motion = 1 }
       { print }' "$f" >"$corpus_bvh/$(basename "$f").3frames"
done

# Manifests, floor paths and control scripts: small files of each kind, written here.
awk '/^```toml/ { n++; on = 1; next } /^```/ { on = 0 } on { print > (dir "/example-" n ".toml") }' \
  dir="$build/corpus-manifest" docs/manifest.md
printf '{"points": [[0, 0], [0, -20]]}\n' >"$build/corpus-floor_path/line.json"
printf '{"points": [[0, 0], [3, -4], [3, -4], [6, 0]],\n "segments": [{"from_m": 0, "to_m": 5, "tag": "walk"},\n  {"from_m": 4, "to_m": 10, "tag": "run"}]}\n' \
  >"$build/corpus-floor_path/segments.json"
printf '{"duration_s": 12,\n "controls": [{"at_s": 0, "heading": "north", "tag": "walk"},\n  {"at_s": 4, "heading_deg": 90}, {"at_s": 8, "tag": "run"}, {"at_s": 9, "tag": "any"}]}\n' \
  >"$build/corpus-control_script/script.json"
printf '{"controls": [{"at_s": 0, "heading": "west"}]}\n' >"$build/corpus-control_script/short.json"

# A small graph file (two clips), written by the target itself; and its first 16 KB.
MOTIONGRAPH_FUZZ_GRAPH_SEED="$build/corpus-graph_file/two-clips.mgraph" \
  MOTIONGRAPH_FUZZ_CLIPS="$root/data/cmu/16/16_35.amc,$root/data/cmu/16/16_39.amc" "$build/fuzz/fuzz_graph_file"
head -c 16384 "$build/corpus-graph_file/two-clips.mgraph" >"$build/corpus-graph_file/two-clips.16k"
# glTF files of the first frames of two clips, and the two as one animation set.
MOTIONGRAPH_FUZZ_GLTF_SEED="$build/corpus-gltf" \
  MOTIONGRAPH_FUZZ_CLIPS="$root/data/cmu/16/16_35.amc,$root/data/cmu/16/16_39.amc" "$build/fuzz/fuzz_gltf"

# --- run -----------------------------------------------------------------------------------
export MOTIONGRAPH_FUZZ_ASF="$root/data/cmu/16/16.asf"  # fuzz_amc's skeleton
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"

failed=()
summary=()
for target in "${targets[@]}"; do
  log="$logs/fuzz_$target.log"
  corpus="$build/corpus-$target"
  echo "=== fuzz_$target: ${seconds}s, corpus $(find "$corpus" -type f | wc -l) files, log $log"
  rc=0
  len=$max_len
  [[ $target == graph_file ]] && len=262144  # the two-clip graph seed is 121 KB
  "$build/fuzz/fuzz_$target" -max_total_time="$seconds" -max_len="$len" -timeout=10 \
    -rss_limit_mb=2048 -print_final_stats=1 -artifact_prefix="$artifacts/$target-" \
    "$corpus" >"$log" 2>&1 || rc=$?
  # Last status line ("#N DONE cov: .. ft: .. corp: .. exec/s: ..") and the final stats.
  status="$(grep -E '^#[0-9]+' "$log" | tail -n 1 || true)"
  execs="$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")"
  rate="$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log")"
  rss="$(sed -n 's/^stat::peak_rss_mb: *//p' "$log")"
  cov="$(grep -oE 'cov: [0-9]+ ft: [0-9]+' <<<"$status" || true)"
  line="fuzz_$target: ${execs:-?} runs, ${rate:-?} exec/s, ${cov:-no coverage line}, peak RSS ${rss:-?} MB"
  if ((rc != 0)); then
    line+=" -- FAILED (exit $rc)"
    failed+=("fuzz_$target")
    echo "--- fuzz_$target failed (exit $rc); end of $log:"
    tail -n 60 "$log"
    grep -E "Test unit written to|artifact_prefix" "$log" || true
  fi
  echo "$line"
  summary+=("$line")
done

echo
echo "=== summary (${seconds}s per target)"
printf '%s\n' "${summary[@]}"
if ((${#failed[@]})); then
  echo "FAILED: ${failed[*]}; inputs in $artifacts, logs in $logs"
  exit 1
fi
echo "no crashes, leaks or timeouts"
