#!/usr/bin/env bash
# Usage: MOTIONGRAPH=... MOTIONGRAPH_TEST_GRAPH=... bash cli_serve_test.sh
# `motiongraph serve` as a user runs it: prints its address once listening, serves the
# front-end and the API, stops with exit 0 on SIGINT and on SIGTERM; bad input is one line.
set -euo pipefail
mg=${MOTIONGRAPH:?set MOTIONGRAPH to the motiongraph binary}
graph=${MOTIONGRAPH_TEST_GRAPH:?set MOTIONGRAPH_TEST_GRAPH (the CTest fixture subject16_graph)}
tmp=$(mktemp -d)
pid=
cleanup() {
  if [[ -n $pid ]] && kill -0 "$pid" 2>/dev/null; then kill -KILL "$pid"; fi
  rm -rf "$tmp"
}
trap cleanup EXIT
fail() { echo "cli_serve: FAIL: $*" >&2; exit 1; }

# start_serve HOST: starts the studio on HOST and a free port, in the background; sets pid and
# port once it prints its address.
start_serve() {
  local host=$1
  : >"$tmp/out"
  : >"$tmp/err"
  "$mg" serve "$graph" --host "$host" --port 0 >"$tmp/out" 2>"$tmp/err" &
  pid=$!
  port=
  for _ in $(seq 100); do
    port=$(sed -n "s|^studio: http://$host:\([0-9]*\)/\$|\1|p" "$tmp/out")
    [[ -n $port ]] && return 0
    sleep 0.1
  done
  fail "no 'studio: http://$host:PORT/' line on stdout"
}

# serve_and_stop SIGNAL: starts the studio, checks it answers, stops it with SIGNAL.
serve_and_stop() {
  local signal=$1
  # The files exist before the server starts: the background job opens them only once it runs,
  # and reading a file not yet there would end this script (set -e).
  : >"$tmp/out"
  : >"$tmp/err"
  "$mg" serve "$graph" --port 0 >"$tmp/out" 2>"$tmp/err" &
  pid=$!
  local url=
  for _ in $(seq 100); do
    url=$(sed -n 's|^studio: \(http://127.0.0.1:[0-9]*/\)$|\1|p' "$tmp/out")
    [[ -n $url ]] && break
    kill -0 "$pid" 2>/dev/null || fail "serve exited early: $(cat "$tmp/err")"
    sleep 0.1
  done
  [[ -n $url ]] || fail "no 'studio: http://127.0.0.1:PORT/' line on stdout"
  # Into files, not `| grep -q`: grep ending at its match while curl still writes a later chunk
  # fails curl, hence the pipe (pipefail).
  curl -sf -m 30 "${url}api/summary" -o "$tmp/summary" && grep -q '"frames"' "$tmp/summary" || fail "GET /api/summary"
  curl -sf -m 30 "$url" -o "$tmp/page" && grep -q 'importmap' "$tmp/page" || fail "GET / is not the studio page"
  [[ $(curl -s -m 30 -o /dev/null -w '%{http_code}' "${url}api/clips/999/frames") == 404 ]] || fail "a bad clip is not 404"
  kill "-$signal" "$pid"
  local status=0
  wait "$pid" || status=$?
  pid=
  [[ $status -eq 0 ]] || fail "serve exited with $status on SIG$signal: $(cat "$tmp/err")"
  echo "serve: answered at $url, exit 0 on SIG$signal"
}
serve_and_stop INT
serve_and_stop TERM

# A client that stays connected (half a request sent, as a stalled client or an open tab's idle
# connection keeps one) does not hold the stop for long: the studio waits 2 s for the clients
# still connected, then ends (exit 0) saying so; it waited on the socket's own timeout, 10 s.
start_serve 127.0.0.1
exec 3<>"/dev/tcp/127.0.0.1/$port"
printf 'GET /api/summary HTTP/1.1\r\nHost: studio\r\n' >&3
sleep 0.5
started=$(date +%s%N)
kill -INT "$pid"
status=0
wait "$pid" || status=$?
pid=
took_ms=$(( ($(date +%s%N) - started) / 1000000 ))
exec 3>&-
[[ $status -eq 0 ]] || fail "serve exited with $status with a client connected: $(cat "$tmp/err")"
grep -q "stopped without waiting for the clients still connected" "$tmp/err" \
  || fail "no line saying it did not wait: $(cat "$tmp/err")"
(( took_ms < 6000 )) || fail "the stop took ${took_ms} ms with a client connected"
echo "serve: a client connected, stopped after ${took_ms} ms, exit 0"

# Every interface (what HOST=0.0.0.0 scripts/demo.sh does): the address printed is not one a
# browser opens, so a second line says what to open and that anyone reaching it can use it. The
# test talks to it on loopback only.
start_serve 0.0.0.0
grep -q "listening on every network interface: open http://.*:$port/ from another machine" "$tmp/out" \
  || fail "no line saying what to open: $(cat "$tmp/out")"
curl -sf -m 30 "http://127.0.0.1:$port/api/summary" -o "$tmp/summary" && grep -q '"frames"' "$tmp/summary" \
  || fail "GET /api/summary on every interface"
# The machine's name, which the line says to open, is answered; a name a page of another site
# could rebind to this machine is not, and the refusal says how to allow one.
# status_for HOST PATH: the status of GET PATH addressed to HOST (the body in $tmp/answer).
status_for() {
  curl -s -m 30 -o "$tmp/answer" -w '%{http_code}' -H "Host: $1:$port" "http://127.0.0.1:$port$2"
}
name=$(hostname)
[[ $(status_for "$name" /api/summary) == 200 ]] || fail "the machine's name $name is refused on every interface"
[[ $(status_for evil.example /) == 403 ]] || fail "a request addressed to evil.example is answered"
grep -q -- "--allow-host evil.example" "$tmp/answer" \
  || fail "the refusal does not say how to allow: $(cat "$tmp/answer")"
kill -INT "$pid"
wait "$pid" || fail "serve --host 0.0.0.0 did not stop cleanly"
pid=
echo "serve: every interface, said so, exit 0; its name answered, another refused"

# --allow-host: the names given are answered (and the name given to --host, where it resolves
# on this machine); a URL is refused as one line.
: >"$tmp/out"
"$mg" serve "$graph" --port 0 --allow-host studio.test --allow-host .lan --max-sessions 1 >"$tmp/out" 2>"$tmp/err" &
pid=$!
port=
for _ in $(seq 100); do
  port=$(sed -n 's|^studio: http://127.0.0.1:\([0-9]*\)/$|\1|p' "$tmp/out")
  [[ -n $port ]] && break
  sleep 0.1
done
[[ -n $port ]] || fail "serve --allow-host did not start: $(cat "$tmp/err")"
for host in studio.test box.lan; do
  [[ $(status_for "$host" /api/summary) == 200 ]] || fail "--allow-host: $host is refused"
done
# --max-sessions 1: a second session while the first is in use is refused as busy.
session_status() {
  curl -s -m 30 -o "$tmp/answer" -w '%{http_code}' -H 'Content-Type: application/json' -d '{}' \
    "http://127.0.0.1:$port/api/steer/sessions"
}
[[ $(session_status) == 200 ]] || fail "--max-sessions 1: the first session is refused: $(cat "$tmp/answer")"
[[ $(session_status) == 503 ]] && grep -q -- "--max-sessions" "$tmp/answer" \
  || fail "--max-sessions 1: a second session is not refused as busy: $(cat "$tmp/answer")"
kill -INT "$pid"
wait "$pid" || fail "serve --allow-host did not stop cleanly"
pid=
if getent hosts "$name" >/dev/null; then
  start_serve "$name"
  curl -sf -m 30 "http://$name:$port/api/summary" -o "$tmp/summary" || fail "serve --host $name: refused under its name"
  kill -INT "$pid"
  wait "$pid" || fail "serve --host $name did not stop cleanly"
  pid=
else
  echo "serve: $name does not resolve here: the name given to --host not tried"
fi
status=0
timeout 60 "$mg" serve "$graph" --allow-host http://studio.test/ --port 0 >/dev/null 2>"$tmp/err" || status=$?
[[ $status -ne 0 && $(wc -l <"$tmp/err") -eq 1 ]] && grep -q "not a URL" "$tmp/err" \
  || fail "--allow-host with a URL: exit $status, $(cat "$tmp/err")"
status=0
timeout 60 "$mg" serve "$graph" --max-sessions 0 --port 0 >/dev/null 2>"$tmp/err" || status=$?
[[ $status -ne 0 && $(wc -l <"$tmp/err") -eq 1 ]] || fail "--max-sessions 0: exit $status, $(cat "$tmp/err")"
echo "serve: --allow-host answered, a URL refused; --max-sessions held"

# Bad input: one line, exit 1 (under a timeout: a server that starts anyway fails, not hangs).
status=0
timeout 60 "$mg" serve "$graph" --web-root "$tmp" --port 0 >/dev/null 2>"$tmp/err" || status=$?
[[ $status -eq 1 && $(wc -l <"$tmp/err") -eq 1 ]] || fail "a web root without index.html: exit $status, $(cat "$tmp/err")"
grep -q "index.html" "$tmp/err" || fail "the error does not say what is missing: $(cat "$tmp/err")"
echo '<script type="importmap"></script>' >"$tmp/index.html"
status=0
timeout 60 "$mg" serve "$graph" --web-root "$tmp" --port 0 >/dev/null 2>"$tmp/err" || status=$?
[[ $status -eq 1 ]] && grep -q "npm ci" "$tmp/err" || fail "a web root without three.js: exit $status, $(cat "$tmp/err")"
echo "not json" >"$tmp/bad.mgraph"
status=0
timeout 60 "$mg" serve "$tmp/bad.mgraph" --port 0 >/dev/null 2>"$tmp/err" || status=$?
[[ $status -eq 1 && $(wc -l <"$tmp/err") -eq 1 ]] || fail "a bad graph file: exit $status, $(cat "$tmp/err")"
echo "cli_serve: ok"
