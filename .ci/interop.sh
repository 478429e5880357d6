#!/usr/bin/env bash
# Interoperability checks of contrail recordings (called by .ci/run):
#  - Python's `mcap` reader + `jsonschema` read and validate every message of recordings of a
#    completed, a failed and a thinned run, of LZ4-compressed and uncompressed ones, of the
#    checked-in format-2 recording and of its conversion to format 3 (.ci/interop.py); the
#    Foxglove channels also against the JSON Schemas published in the npm package
#    `@foxglove/schemas` (installed into $CONTRAIL_INTEROP_NPM);
#  - the Python snippet of docs/recording.md reads the arrays of a recording into numpy;
#  - the rerun CLI of rerun-sdk==0.36.3 (the crate's version) verifies the .rrd of a run and
#    of a replay (`rerun rrd verify`);
#  - meshio reads the ParaView series (.pvd + .vtu) of `run --out X.pvd` and of
#    `export X.mcap --vtu DIR` and checks names, shapes and values against the run's MCAP and
#    CSV (.ci/vtu_check.py), and the hexahedra of a 3D run against its MCAP (.ci/vtu_check_3d.py);
#  - ParaView itself (Debian's `paraview`, its pvpython) opens the series of a Gmsh hexahedral
#    model with a contact surface and of the 3D Hertz run, and what it read is checked against
#    their MCAP (.ci/paraview_read.py, .ci/paraview_check.py); with CI=true a ParaView that
#    cannot be installed fails the check, elsewhere it is skipped with the reason.
# The virtual environment is created on first use and reused (CONTRAIL_INTEROP_VENV).
set -euo pipefail
cd "$(dirname "$0")/.."

export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$HOME/.cache/contrail-target}"
VENV="${CONTRAIL_INTEROP_VENV:-$HOME/.cache/contrail-interop-venv}"
PY_PACKAGES=("mcap==1.6.0" "jsonschema==4.26.0" "rerun-sdk==0.36.3" "meshio==5.3.5")
NPM_DIR="${CONTRAIL_INTEROP_NPM:-$HOME/.cache/contrail-interop-npm}"
FOXGLOVE_SCHEMAS="@foxglove/schemas@2.1.0"

echo "== interop: python environment ($VENV)"
if ! "$VENV/bin/python" -c "import mcap, jsonschema, meshio" 2>/dev/null \
    || ! "$VENV/bin/rerun" --version 2>/dev/null | grep -q " 0\.36\.3 "; then
    python3 -m venv "$VENV"
    "$VENV/bin/pip" install --quiet --disable-pip-version-check "${PY_PACKAGES[@]}"
fi
"$VENV/bin/rerun" analytics disable >/dev/null 2>&1 || true
"$VENV/bin/rerun" --version

echo "== interop: $FOXGLOVE_SCHEMAS ($NPM_DIR)"
if ! command -v npm >/dev/null; then
    apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq nodejs npm >/dev/null
fi
if [ ! -f "$NPM_DIR/node_modules/@foxglove/schemas/package.json" ] \
    || ! grep -q '"version": "2.1.0"' "$NPM_DIR/node_modules/@foxglove/schemas/package.json"; then
    mkdir -p "$NPM_DIR"
    npm install --prefix "$NPM_DIR" --no-save --no-audit --no-fund --loglevel=error "$FOXGLOVE_SCHEMAS"
fi

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
# a format-2 recording and the same run converted to format 3
"$BIN" convert recordings/golden/format2/strip-channel.mcap "$TMP/converted.mcap" >/dev/null
# every increment with a Foxglove scene, and every contact point written
record strip-channel --quiet --set stepping.increments=60 --set fix.1.value=-0.3 --scene-every 1 \
    --all-points --out "$TMP/scenes.mcap"
# a two-pass pair: its /interface channel
record contact-patch --quiet --out "$TMP/patch.mcap"
# a 3D solid: its recording, rerun stream and ParaView series of hexahedra
record cantilever-3d --quiet --out "$TMP/c3.mcap" --out "$TMP/c3.pvd" --rerun-save "$TMP/c3.rrd"
"$BIN" inspect "$TMP/c3.mcap" >/dev/null
# 3D contact (a rigid sphere): /surface_contact, its rerun view live and replayed
record hertz-3d --quiet --out "$TMP/h3.mcap" --out "$TMP/h3.pvd" --rerun-save "$TMP/h3.rrd"
"$BIN" export "$TMP/h3.mcap" --vtu "$TMP/h3-exported" >/dev/null
"$BIN" inspect "$TMP/h3.mcap" >"$TMP/h3.inspect"
grep -q "^3D contact" "$TMP/h3.inspect"
"$BIN" replay "$TMP/h3.mcap" --rerun-save "$TMP/h3-replay.rrd"
# a Gmsh hexahedral model with a contact surface (rigid plates on a physical surface), and a
# rigid cylinder: their Foxglove scenes and ParaView series
record tests/data/disc-3d.toml --quiet --set 'body.disc.mesh.file="disc-quarter-4.msh"' \
    --out "$TMP/d3.mcap" --out "$TMP/d3.pvd"
record tests/data/cylinder-slice-3d.toml --quiet --out "$TMP/cy3.mcap"

echo "== interop: the published Foxglove schemas"
# the package ships its JSON Schemas as a module (dist/jsonschema): written out as files
FOXGLOVE_DIR="$TMP/foxglove"
mkdir -p "$FOXGLOVE_DIR"
NODE_PATH="$NPM_DIR/node_modules" node -e '
const s = require("@foxglove/schemas/jsonschema");
const fs = require("fs");
for (const n of ["Log", "SceneUpdate"]) {
    fs.writeFileSync(process.argv[1] + "/foxglove." + n + ".json", JSON.stringify(s[n]));
}' "$FOXGLOVE_DIR"
ls "$FOXGLOVE_DIR"

echo "== interop: mcap + jsonschema"
"$VENV/bin/python" .ci/interop.py --schemas schemas --foxglove "$FOXGLOVE_DIR" \
    "$TMP/crossing.mcap" "$TMP/strip.mcap" "$TMP/failed.mcap" "$TMP/hd.mcap" \
    "$TMP/crossing-lz4.mcap" "$TMP/crossing-none.mcap" "$TMP/scenes.mcap" \
    "$TMP/patch.mcap" "$TMP/c3.mcap" "$TMP/h3.mcap" "$TMP/d3.mcap" "$TMP/cy3.mcap" \
    recordings/golden/format2/strip-channel.mcap "$TMP/converted.mcap"

echo "== interop: the numpy snippet of docs/recording.md"
# the python block after the marker line, run as it is on a recording
awk '/<!-- snippet: read-arrays -->/ { on = 1; next } on && /^```python/ { inside = 1; next } inside && /^```/ { exit } inside' \
    docs/recording.md >"$TMP/snippet.py"
test -s "$TMP/snippet.py"
"$VENV/bin/python" .ci/snippet_check.py "$TMP/snippet.py" "$TMP/strip.mcap" "$TMP/scenes.mcap"

echo "== interop: meshio reads the VTU series"
"$VENV/bin/python" .ci/vtu_check.py "$TMP/hd.pvd" "$TMP/hd.mcap" "$TMP/hd.csv"
"$VENV/bin/python" .ci/vtu_check.py "$TMP/hd2.pvd" "$TMP/hd.mcap" "$TMP/hd2.csv" --every 2
"$VENV/bin/python" .ci/vtu_check.py "$TMP/exported/hd.pvd" "$TMP/hd.mcap" "$TMP/hd.csv"
"$VENV/bin/python" .ci/vtu_check_3d.py "$TMP/c3.pvd" "$TMP/c3.mcap"
"$VENV/bin/python" .ci/vtu_check_3d.py "$TMP/h3.pvd" "$TMP/h3.mcap"
"$VENV/bin/python" .ci/vtu_check_3d.py "$TMP/h3-exported/h3.pvd" "$TMP/h3.mcap"
"$VENV/bin/python" .ci/vtu_check_3d.py "$TMP/d3.pvd" "$TMP/d3.mcap"

echo "== interop: ParaView (pvpython) opens the 3D series"
if ! command -v pvpython >/dev/null && command -v apt-get >/dev/null; then
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq paraview >"$TMP/paraview-apt.log" 2>&1 \
        || { apt-get update -qq >/dev/null 2>&1 \
            && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq paraview >"$TMP/paraview-apt.log" 2>&1; } || true
fi
if command -v pvpython >/dev/null; then
    for run in d3 h3; do
        pvpython .ci/paraview_read.py "$TMP/$run.pvd" "$TMP/$run-paraview.json"
        "$VENV/bin/python" .ci/paraview_check.py "$TMP/$run-paraview.json" "$TMP/$run.mcap"
    done
elif [ "${CI:-}" = "true" ]; then
    echo "ParaView could not be installed: $(tail -n 1 "$TMP/paraview-apt.log" 2>/dev/null)"; exit 1
else
    echo "skipped: no pvpython (apt-get install paraview)"
fi

echo "== interop: rerun rrd verify"
for f in "$TMP/crossing.rrd" "$TMP/strip.rrd" "$TMP/strip-replay.rrd" "$TMP/c3.rrd" "$TMP/h3.rrd" "$TMP/h3-replay.rrd"; do
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
