#!/usr/bin/env bash
# Whole-run timings of the strip-channel benchmark (issue 8's figures), release build.
#
#   bash benches/runs.sh            # prints a Markdown table (best of 3 wall times per case)
#   REPEAT=1 bash benches/runs.sh   # one run per case
#
# Each case is run by the release binary; the table gives the best wall time, the CPU
# time of that run (user + sys, all threads: zstd compresses on a thread of its own), the
# increments and Newton iterations, and the run's own split of its time (from the summary
# that `contrail run` prints: elements, contact, LU factorisations, substitutions,
# recording). Wall times on a shared 2-core machine are noisy: compare within one table.
set -euo pipefail
cd "$(dirname "$0")/.."
export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$HOME/.cache/contrail-target}"
cargo build --release --locked --quiet --bin contrail
BIN="$CARGO_TARGET_DIR/release/contrail"
REPEAT="${REPEAT:-3}"
TMP="$(mktemp -d)"
trap 'rm -rf "$TMP"' EXIT

SEED=(--set stepping.increments=4800 --set stepping.max_cutbacks=0)
cases=(
  "24×1, μ = 0.2, Δv = 0.0025 fixed, no recording|strip-channel ${SEED[*]}"
  "24×1, μ = 0.2, Δv = 0.0025 fixed, MCAP|strip-channel ${SEED[*]} --out REC.mcap"
  "24×1, same, without the predictor|strip-channel ${SEED[*]} --set stepping.predictor=last"
  "24×1, same, without predictor and line search|strip-channel ${SEED[*]} --set stepping.predictor=last --set solver.line_search=false"
  "120×4, μ = 0.2, adaptive (default), no recording|strip-channel --set body.strip.mesh.elements=[120,4]"
  "120×4, μ = 0.2, adaptive (default), MCAP|strip-channel --set body.strip.mesh.elements=[120,4] --out REC.mcap"
  "120×4, no recording, one thread (--threads 1)|strip-channel --set body.strip.mesh.elements=[120,4] --threads 1"
  "120×4, μ = 0.2, Δv = 0.0025 fixed (the seed's settings), one thread|strip-channel --set body.strip.mesh.elements=[120,4] ${SEED[*]} --threads 1"
)
echo "| case | outcome | wall (best of $REPEAT) | CPU | increments | Newton its | assemblies (with tangent) | µs / iteration | elements | contact | LU | solve | recording |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|"
for c in "${cases[@]}"; do
  label="${c%%|*}"
  args="${c#*|}"
  args="${args//REC.mcap/$TMP/rec.mcap}"
  best=""
  for _ in $(seq "$REPEAT"); do
    rc=0
    /usr/bin/time -f "%e %U %S" -o "$TMP/time" "$BIN" run $args --quiet >"$TMP/out" 2>&1 || rc=$?
    read -r wall user sys < <(tail -n1 "$TMP/time")
    if [ -z "$best" ] || awk "BEGIN{exit !($wall < $best)}"; then
      best="$wall"
      cpu=$(awk "BEGIN{printf \"%.2f\", $user + $sys}")
      cp "$TMP/out" "$TMP/best"
      outcome=$([ "$rc" -eq 0 ] && echo completed || echo "failed ($rc)")
    fi
  done
  incs=$(sed -n 's/^reached .* in \([0-9]*\) increments.*/\1/p' "$TMP/best")
  its=$(sed -n 's/^newton *\([0-9]*\) iterations.*/\1/p' "$TMP/best")
  split=$(sed -n 's/^time spent *//p' "$TMP/best")
  asm=$(echo "$split" | sed -n 's/.*, \([0-9]*\) assemblies (\([0-9]*\) with the tangent.*/\1 (\2)/p')
  part() { echo "$split" | sed -n "s/.*$1 \([0-9.]*\) s.*/\1/p"; }
  per=$(awk "BEGIN{ if (\"$its\" > 0) printf \"%.0f\", 1e6 * $best / $its; else print \"–\" }")
  echo "| $label | $outcome | $best s | $cpu s | $incs | $its | $asm | $per | $(part elements) s | $(part contact) s | $(part LU) s | $(part solve) s | $(part recording) s |"
done
