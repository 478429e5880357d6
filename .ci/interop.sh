#!/usr/bin/env bash
# Interoperability checks of contrail recordings (called by .ci/run):
#  - Python's `mcap` reader + `jsonschema` read and validate every message of recordings of a
#    completed, a failed and a thinned run, and of LZ4-compressed and uncompressed ones
#    (.ci/interop.py);
#  - the rerun CLI of rerun-sdk==0.36.3 (the crate's version) verifies the .rrd of a run and
#    of a replay (`rerun rrd verify`);
#  - meshio reads the ParaView series (.pvd + .vtu) of `run --out X.pvd` and of
#    `export X.mcap --vtu DIR` and checks names, shapes and values against the run's MCAP and
#    CSV (.ci/vtu_check.py).
# The virtual environment is created on first use and reused (CONTRAIL_INTEROP_VENV).
set -euo pipefail
cd "$(dirname "$0")/.."

export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$HOME/.cache/contrail-target}"
VENV="${CONTRAIL_INTEROP_VENV:-$HOME/.cache/contrail-interop-venv}"
PY_PACKAGES=("mcap==1.6.0" "jsonschema==4.26.0" "rerun-sdk==0.36.3" "meshio==5.3.5")

echo "== interop: python environment ($VENV)"
if ! "$VENV/bin/python" -c "import mcap, jsonschema, meshio" 2>/dev/null \
    || ! "$VENV/bin/rerun" --version 2>/dev/null | grep -q " 0\.36\.3 "; then
    python3 -m venv "$VENV"
    "$VENV/bin/pip" install --quiet --disable-pip-version-check "${PY_PACKAGES[@]}"
fi
"$VENV/bin/rerun" analytics disable >/dev/null 2>&1 || true
"$VENV/bin/rerun" --version

echo "== interop: recordings"
cargo build --locked --quiet
BIN="$CARGO_TARGET_DIR/debug/contrail"
TMP="$(mktemp -d)"
trap 'rm -rf "$TMP"' EXIT
# a run that fails (exit 1) still leaves a complete recording; anything else is an error
record() {
    local rc=0
    "$BIN" run "$@" >"$TMP/run.log" 2>&1 || rc=$?
    if [ "$rc" -gt 1 ]; then
        echo "contrail run $* exited with $rc"; cat "$TMP/run.log"; exit 1
    fi
    return 0
}
record crossing --quiet --out "$TMP/crossing.mcap" --rerun-save "$TMP/crossing.rrd"
record crossing --quiet --compression lz4 --out "$TMP/crossing-lz4.mcap"
record crossing --quiet --compression none --out "$TMP/crossing-none.mcap"
"$BIN" inspect "$TMP/crossing-lz4.mcap" >/dev/null
record strip-channel --quiet --set fix.1.value=-0.55 --set stepping.increments=220 \
    --positions-every 10 --out "$TMP/strip.mcap" --rerun-save "$TMP/strip.rrd"
rc=0
"$BIN" run strip-channel --quiet --set solver.max_iterations=1 --set stepping.max_cutbacks=0 \
    --out "$TMP/failed.mcap" >"$TMP/failed.log" 2>&1 || rc=$?
if [ "$rc" -ne 1 ]; then
    echo "a run meant to fail exited with $rc"; cat "$TMP/failed.log"; exit 1
fi
"$BIN" replay "$TMP/strip.mcap" --rerun-save "$TMP/strip-replay.rrd"
# the Gmsh-meshed built-in scene, with its ParaView series (every increment, and every 2nd)
record half-disc --quiet --out "$TMP/hd.pvd" --out "$TMP/hd.mcap" --out "$TMP/hd.csv"
record half-disc --quiet --vtu-every 2 --out "$TMP/hd2.pvd" --out "$TMP/hd2.csv"
"$BIN" export "$TMP/hd.mcap" --vtu "$TMP/exported" >/dev/null

echo "== interop: mcap + jsonschema"
"$VENV/bin/python" .ci/interop.py --schemas schemas "$TMP/crossing.mcap" "$TMP/strip.mcap" "$TMP/failed.mcap" "$TMP/hd.mcap" \
    "$TMP/crossing-lz4.mcap" "$TMP/crossing-none.mcap"

echo "== interop: meshio reads the VTU series"
"$VENV/bin/python" .ci/vtu_check.py "$TMP/hd.pvd" "$TMP/hd.mcap" "$TMP/hd.csv"
"$VENV/bin/python" .ci/vtu_check.py "$TMP/hd2.pvd" "$TMP/hd.mcap" "$TMP/hd2.csv" --every 2
"$VENV/bin/python" .ci/vtu_check.py "$TMP/exported/hd.pvd" "$TMP/hd.mcap" "$TMP/hd.csv"

echo "== interop: rerun rrd verify"
for f in "$TMP/crossing.rrd" "$TMP/strip.rrd" "$TMP/strip-replay.rrd"; do
    "$VENV/bin/rerun" rrd verify "$f"
done
echo "== interop: contrail serve → contrail submit strip-channel --wait → Python mcap over HTTP range requests"
"$BIN" serve --port 0 --data "$TMP/service" --workers 2 >"$TMP/serve.log" 2>&1 &
SERVE_PID=$!
URL=""
for _ in $(seq 1 50); do
    URL="$(grep -o 'http://[0-9.:]*' "$TMP/serve.log" || true)"
    [ -n "$URL" ] && break
    sleep 0.1
done
[ -n "$URL" ] || { echo "contrail serve did not start"; cat "$TMP/serve.log"; exit 1; }
"$BIN" submit strip-channel --wait --server "$URL" >"$TMP/submit.log" || { cat "$TMP/submit.log"; kill "$SERVE_PID"; exit 1; }
RUN_ID="$(awk '/^run / { print $2; exit }' "$TMP/submit.log")"
INCREMENTS="$(awk '/^ended completed after / { print $4; exit }' "$TMP/submit.log")"
"$VENV/bin/python" .ci/service_mcap.py "$URL" "$RUN_ID" "$INCREMENTS" || { kill "$SERVE_PID"; exit 1; }
kill -INT "$SERVE_PID"
wait "$SERVE_PID" || true
echo "interop: all checks passed"
