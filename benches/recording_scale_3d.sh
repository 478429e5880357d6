#!/usr/bin/env bash
# What a recording costs a 3D model of 1e5 unknowns, by what it keeps of the node positions:
# the built-in hertz-3d as a plate (1 × 1 × 0.25, 56 × 56 × 10 hexahedra: 35 739 nodes,
# 107 217 unknowns; its 3 249 top nodes are the contact slaves) run without a recording,
# with a full one, with `--positions-of surface`, `--positions-every 10`, and both of those
# with `--positions-precision single`. One run at a time; prints per case the wall time and
# its ratio to the run without, and the file and its ratio to the full one.
#
#   bash benches/recording_scale_3d.sh                  # INCREMENTS=200 (hours on 2 cores)
#   INCREMENTS=1 CASES="none full surface surface+single" bash benches/recording_scale_3d.sh
#                                                       # what docs/recording.md quotes
#   KEEP=rec MESH=82,82,4 ELEMENT=q4 SOLVER=general CASES="full every-10+surface" bash benches/recording_scale_3d.sh
#                                                       # 200 increments of a plate of
#                                                       # 82 × 82 × 4 plain hexahedra,
#                                                       # the recordings kept in rec/
#   python3 benches/recording_channels.py rec/full.mcap rec/every-10+surface.mcap
#                                                       # their bytes per channel
#   EXTRA="--set contact.0.search_radius=0.0716" ...    # more settings for every case
#
# Release build. Run it on a machine with nothing else running: the writer thread takes
# its CPU from the solver's second thread.
set -euo pipefail
cd "$(dirname "$0")/.."
export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$HOME/.cache/contrail-target}"
cargo build --release --locked --quiet --bin contrail
BIN="$CARGO_TARGET_DIR/release/contrail"
INCREMENTS="${INCREMENTS:-200}"
TMP="$(mktemp -d)"
trap 'rm -rf "$TMP"' EXIT

MESH="${MESH:-56,56,10}"
THICKNESS="${THICKNESS:-0.25}"
SCENE=(hertz-3d --set "body.block.mesh.elements=[$MESH]" --set "body.block.mesh.size=[1.0,1.0,$THICKNESS]"
  --set "body.block.mesh.origin=[0.0,0.0,-$THICKNESS]" --set "stepping.increments=$INCREMENTS" --quiet)
if [ -n "${ELEMENT:-}" ]; then SCENE+=(--set "body.block.element=\"$ELEMENT\""); fi
if [ -n "${SOLVER:-}" ]; then SCENE+=(--set "solver.linear_solver=\"$SOLVER\""); fi
# shellcheck disable=SC2206
if [ -n "${EXTRA:-}" ]; then SCENE+=($EXTRA); fi
cases=(
  "none|"
  "full|--out REC"
  "surface|--out REC --positions-of surface"
  "every-10|--out REC --positions-every 10"
  "surface+single|--out REC --positions-of surface --positions-precision single"
  "every-10+surface|--out REC --positions-every 10 --positions-of surface"
)
if [ -n "${CASES:-}" ]; then
  picked=()
  for c in "${cases[@]}"; do
    for w in $CASES; do [ "${c%%|*}" = "$w" ] && picked+=("$c"); done
  done
  cases=("${picked[@]}")
fi
echo "$(nproc) cores; load average before: $(cut -d' ' -f1-3 /proc/loadavg); $INCREMENTS increments"
printf '%-18s %9s %7s %12s %7s\n' case wall ratio bytes ratio
base="" full=""
for c in "${cases[@]}"; do
  name="${c%%|*}"
  args="${c#*|}"
  rec="$TMP/$name.mcap"
  start=$(date +%s.%N)
  # shellcheck disable=SC2086
  "$BIN" run "${SCENE[@]}" ${args//REC/$rec} >/dev/null
  wall=$(echo "$(date +%s.%N) - $start" | bc)
  [ -z "$base" ] && base=$wall
  bytes=0
  [ -f "$rec" ] && bytes=$(stat -c %s "$rec")
  if [ -n "${KEEP:-}" ] && [ -f "$rec" ]; then mkdir -p "$KEEP" && cp "$rec" "$KEEP/"; fi
  [ "$name" = full ] && full=$bytes
  ratio_bytes="-"
  [ -n "$full" ] && [ "$bytes" -gt 0 ] && ratio_bytes=$(echo "scale=3; $bytes / $full" | bc)
  printf '%-18s %8.1fs %7.3f %12d %7s\n' "$name" "$wall" "$(echo "$wall / $base" | bc -l)" "$bytes" "$ratio_bytes"
done
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
