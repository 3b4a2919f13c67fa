#!/usr/bin/env bash
# Bad input, as a user meets it: one line "FILE:LINE: what is wrong" on stderr, a non-zero
# exit, no crash, and no output file left behind. Usage: MOTIONGRAPH=binary cli_errors_test.sh DATA_DIR
set -euo pipefail
data=$1
bin=${MOTIONGRAPH:?set MOTIONGRAPH to the motiongraph binary}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0

# expect_error NAME PATTERN FILE [extra args]: convert FILE must fail with one matching line.
expect_error() {
  local name=$1 pattern=$2 input=$3
  shift 3
  local out="$work/out-$name${EXT:-.bvh}"
  set +e
  timeout 20 "$bin" convert "$input" -o "$out" "$@" >"$work/stdout" 2>"$work/stderr"
  local code=$?
  set -e
  local lines
  lines=$(wc -l <"$work/stderr")
  if [[ $code -eq 0 || $code -ge 124 ]]; then
    echo "FAIL $name: exit code $code"; failures=$((failures + 1))
  elif [[ $lines -ne 1 ]]; then
    echo "FAIL $name: expected one line on stderr, got $lines:"; cat "$work/stderr"; failures=$((failures + 1))
  elif ! grep -Eq -- "$pattern" "$work/stderr"; then
    echo "FAIL $name: '$(cat "$work/stderr")' does not match '$pattern'"; failures=$((failures + 1))
  elif compgen -G "$work/out-$name*" >/dev/null || compgen -G "$work/.out-$name*" >/dev/null; then
    echo "FAIL $name: an output file was left behind"; failures=$((failures + 1))
  else
    echo "ok   $name: $(cat "$work/stderr")"
  fi
}

# BVH: a good file, then broken copies of it.
good="$data/bvh/131_01.bvh"
mkdir -p "$work/in"
sed 's/^Frames: 994/Frames: 99999999999999/' "$good" >"$work/in/huge.bvh"
expect_error huge-frames "huge\.bvh:186: 'Frames: 99999999999999' but 994 motion lines follow" "$work/in/huge.bvh"
sed 's/^Frame Time: .0083333/Frame Time: 0/' "$good" >"$work/in/time.bvh"
expect_error frame-time "time\.bvh:187: Frame Time '0' must be a positive number" "$work/in/time.bvh"
sed '300s/ 0.0000 / nan /' "$good" >"$work/in/nan.bvh"
expect_error nan "nan\.bvh:300: value 'nan' is not a finite number" "$work/in/nan.bvh"
head -c 20000 "$good" >"$work/in/cut.bvh"
expect_error truncated "cut\.bvh:[0-9]+: " "$work/in/cut.bvh"
printf 'HIERARCHY\nROOT a\n{\n OFFSET 0 0 0\n CHANNELS 3 Xrotation Yrotation Zrotation\n' >"$work/in/open.bvh"
expect_error unclosed "open\.bvh:2: joint has no closing" "$work/in/open.bvh"
: >"$work/in/empty.bvh"
expect_error empty "empty\.bvh:0: empty file|empty\.bvh: empty file" "$work/in/empty.bvh"
head -c 3000 /dev/urandom >"$work/in/noise.bvh"
expect_error noise "noise\.bvh:[0-9]+: " "$work/in/noise.bvh"
# A binary file (bytes 128..255, then 1..8: no separator among them): the message shows its first
# token escaped and cut short, never raw bytes.
python3 -c "import sys; sys.stdout.buffer.write(bytes(range(128, 256)) + bytes(range(1, 9)))" >"$work/in/binary.bvh"
expect_error binary "binary\.bvh:1: expected 'HIERARCHY', found '(\\\\x[89a-f][0-9a-f]){40}\.\.\.'\$" "$work/in/binary.bvh"
if LC_ALL=C grep -q '[[:cntrl:]]' <(tr -d '\n' <"$work/stderr"); then
  echo "FAIL binary: raw control bytes in the message"; failures=$((failures + 1))
fi

# AMC against the bundled skeleton.
asf="$data/cmu/16/16.asf"
sed '9s/^lowerneck .*/lowerneck 1 2/' "$data/cmu/16/16_35.amc" >"$work/in/count.amc"
expect_error dof-count "count\.amc:9: bone 'lowerneck' has 2 values, its skeleton gives it 3" "$work/in/count.amc" --asf "$asf"
sed '9s/^lowerneck/lowernek/' "$data/cmu/16/16_35.amc" >"$work/in/bone.amc"
expect_error unknown-bone "bone\.amc:9: unknown bone 'lowernek'" "$work/in/bone.amc" --asf "$asf"
sed '34s/^2$/3/' "$data/cmu/16/16_35.amc" >"$work/in/gap.amc"
expect_error frame-gap "gap\.amc:34: frame 3 follows frame 1" "$work/in/gap.amc" --asf "$asf"
cp "$data/cmu/16/16_35.amc" "$work/in/alone.amc"
expect_error no-skeleton "alone\.amc: no skeleton" "$work/in/alone.amc"

# ASF.
sed 's/^:hierarchy/:hierarchy\n  begin\n    root nosuchbone\n  end\n:ignored/' "$asf" >"$work/in/bad.asf"
expect_error unknown-in-hierarchy "bad\.asf:[0-9]+: unknown bone 'nosuchbone'" "$data/cmu/16/16_35.amc" --asf "$work/in/bad.asf"

# Usage errors from the command line itself.
EXT=.txt expect_error wrong-extension "out-wrong-extension\.txt: output must end in \.bvh, \.glb, \.gltf, \.fbx or \.json" "$good"
expect_error bad-scale "--scale must lie between 1e-06 and 1e\+06 metres per unit, not -1" "$good" --scale -1
expect_error huge-scale "--scale must lie between 1e-06 and 1e\+06 metres per unit, not 1e\+300" "$good" --scale 1e300
# Every number option refuses nan and inf (a range check let --fps nan through: nothing resampled).
expect_error fps-nan "--fps: must be a finite number, not nan" "$good" --fps nan
expect_error scale-inf "--scale: must be a finite number, not inf" "$good" --scale inf

# A write that cannot happen leaves nothing behind either.
set +e
"$bin" convert "$good" -o "$work/no-such-dir/out.bvh" 2>"$work/stderr"
code=$?
set -e
if [[ $code -eq 0 ]] || ! grep -q "no-such-dir/out.bvh: cannot write" "$work/stderr"; then
  echo "FAIL unwritable output: $(cat "$work/stderr")"; failures=$((failures + 1))
else
  echo "ok   unwritable: $(cat "$work/stderr")"
fi

# Exit codes: 1 for what the program finds wrong, 2 for a command line it cannot parse; a
# misspelled command is named, with the command it is closest to.
exit_code() {  # name expected-code expected-part command...
  local name=$1 expected=$2 part=$3
  shift 3
  set +e
  "$@" >/dev/null 2>"$work/stderr"
  local code=$?
  set -e
  if [[ $code -ne $expected || $(wc -l <"$work/stderr") -ne 1 ]] || ! grep -qF -- "$part" "$work/stderr"; then
    echo "FAIL $name: exit $code (expected $expected): $(cat "$work/stderr")"; failures=$((failures + 1))
  else
    echo "ok   $name: exit $code: $(cat "$work/stderr")"
  fi
}
exit_code misspelled 2 "unknown command 'biuld': did you mean 'build'? (commands: info, convert, build," \
  "$bin" biuld "$good" -o "$work/x.mgraph"
exit_code unknown-word 2 "unknown command 'frobnicate' (commands: info, convert" "$bin" frobnicate
exit_code missing-output 2 "--output is required" "$bin" build "$good"
exit_code unknown-option 2 "The following argument was not expected: --bogus" "$bin" convert "$good" -o "$work/x.bvh" --bogus
exit_code out-of-range 2 "--fps" "$bin" convert "$good" -o "$work/x.bvh" --fps 0
exit_code smoothing-alone 2 "--root-motion-smoothing requires --root-motion" \
  "$bin" convert "$good" -o "$work/x.bvh" --root-motion-smoothing 2
exit_code missing-input 2 "nonexist.bvh" "$bin" info "$work/nonexist.bvh"
# Values out of their range or that do not go together, found when the settings are checked: 2 too.
exit_code input-fps-zero 2 "--input-fps" "$bin" info "$good" --input-fps 0
exit_code coverage-over-1 2 "coverage" "$bin" build "$good" -o "$work/x.mgraph" --coverage 2
exit_code negative-skeleton 2 "--skeleton" "$bin" walk "$work/x.mgraph" --from 0 --to 1 -o "$work/x.bvh" --skeleton -1
exit_code walk-cost 2 "cost" "$bin" walk "$work/x.mgraph" --from 0 --to 1 -o "$work/x.bvh" --cost cheapest
exit_code walk-seed 2 "--seed: must be 0 or more, not -1" "$bin" walk "$work/x.mgraph" --from 0 --to 1 \
  -o "$work/x.bvh" --cost random --seed -1
exit_code path-budget 2 "the search budget (expansions) must be at least 1, not 0" "$bin" path "$work/x.mgraph" \
  --shape line:5 -o "$work/x.bvh" --max-expansions 0
exit_code start-node 2 "--start-node" "$bin" path "$work/x.mgraph" --shape line:5 -o "$work/x.bvh" --start-node -2
exit_code bad-file 1 "time.bvh:187: Frame Time '0' must be a positive number" "$bin" info "$work/in/time.bvh"
set +e
"$bin" --help >/dev/null 2>&1; help_code=$?
"$bin" --version >/dev/null 2>&1; version_code=$?
set -e
[[ $help_code -eq 0 && $version_code -eq 0 ]] || { echo "FAIL help/version exit $help_code/$version_code"; failures=$((failures + 1)); }

if ((failures)); then echo "$failures failure(s)"; exit 1; fi
echo "all error cases clean"
