#!/usr/bin/env bash
# Large models (issue 8, item 4): the `punch-large` scene (a wide rigid cylinder pressed into
# a thin Neo-Hookean block, most top nodes in contact) at about 1e3, 1e4, 1e5 and 1e6 DOFs
# with the release binary; prints a Markdown table and the fitted exponents of the cost
# per Newton iteration against the number of DOFs.
#
#   benches/large_models.sh                 # 1e3 … 1e6 DOFs (the 1e6 run takes minutes, ~GBs)
#   QUICK=1 benches/large_models.sh         # 1e3 … 1e5
#   SIZES="100x4 316x15:2" benches/large_models.sh  # own meshes (NXxNY elements; `:K`: only
#                                                   # the first K of the INCREMENTS increments)
#   INCREMENTS=8 (default)  BIN=path/to/contrail  SCENE=scenes/punch-large.toml
#   PUNCH_DEPTH=0.05 (the scene's punch travel, scaled for the `:K` runs)
#
# Memory is the peak resident set of the whole process (`/usr/bin/time -f %M`), divided by
# the DOFs; time per iteration is the wall time of the solve (`wall time`, which includes
# the setup of the assembler and the symbolic factorisation) over the Newton iterations
# (failed attempts included); ΣLU is the time of all LU factorisations (symbolic ones
# included). Nothing is recorded (no --out).
set -euo pipefail
cd "$(dirname "$0")/.."
BIN=${BIN:-${CARGO_TARGET_DIR:-target}/release/contrail}
SCENE=${SCENE:-scenes/punch-large.toml}
INCREMENTS=${INCREMENTS:-8}
PUNCH_DEPTH=${PUNCH_DEPTH:-0.05} # the scene's `move = { y = -0.05 }` (for the `:K` runs)
if [[ -n "${SIZES:-}" ]]; then
  read -r -a sizes <<<"$SIZES"
elif [[ "${QUICK:-0}" == 1 ]]; then
  sizes=(100x4 316x15 1000x50)
else
  # the 1e6-DOF run does the first 2 of the 8 increments only (minutes, not an hour)
  sizes=(100x4 316x15 1000x50 3160x158:2)
fi
[[ -x "$BIN" ]] || { echo "no binary at $BIN: cargo build --release --locked --bin contrail" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

rows=()
for s in "${sizes[@]}"; do
  mesh=${s%%:*}
  nx=${mesh%x*}
  ny=${mesh#*x}
  steps=(--set "stepping.increments=$INCREMENTS")
  if [[ "$s" == *:* ]]; then
    k=${s#*:}
    # the scene's ramps reach their final values at `stepping.end`, so the first K of N
    # increments are K increments of a punch moved K/N of the way (not a shorter `end`,
    # which would squeeze the whole motion into K increments)
    steps=(--set "stepping.increments=$k" --set "rigid.punch.move.y=$(awk -v k="$k" -v n="$INCREMENTS" -v d="$PUNCH_DEPTH" 'BEGIN { print -d * k / n }')")
  fi
  out="$tmp/$mesh.out"
  /usr/bin/time -f "rss_kb %M" "$BIN" run "$SCENE" --quiet \
    --set "body.block.mesh.elements=[$nx,$ny]" "${steps[@]}" >"$out" 2>&1 || {
    echo "run $s failed:" >&2
    cat "$out" >&2
    exit 1
  }
  rows+=("$(awk -v nx="$nx" -v ny="$ny" '
    /^newton/      { it = $2; for (i = 1; i <= NF; i++) if ($i == "cut-backs" || $i == "cut-back") cb = $(i - 1) }
    /^reached/     { inc = $(NF - 1) }
    /^in contact/  { act = $3 }
    /^wall time/   { wall = $3 }
    /^time spent/  { el = $4; co = $9; lu = $14; so = $19 }
    /^rss_kb/      { rss = $2 }
    END { printf "%d %d %s %s %s %s %s %s %s %s %s %s\n", nx, ny, 2 * (nx + 1) * (ny + 1), act, inc, it, wall, el, co, lu, so, rss; if (cb + 0 > 0) printf "" }
  ' "$out") $(awk '/^newton/ { for (i = 1; i <= NF; i++) if ($i ~ /^cut-back/) print $(i - 1) }' "$out")")
done

printf '| mesh | DOFs | contact points active | increments | Newton iterations (cut-backs) | wall time [s] | per iteration [ms] | elements / contact / LU / solve per iteration [ms] | total / ΣLU | peak RSS [MB] | bytes / DOF |\n'
printf '|---|---:|---:|---:|---:|---:|---:|---|---:|---:|---:|\n'
for r in "${rows[@]}"; do
  awk '{ n = $3; it = $6; w = $7
    printf "| %dx%d | %d | %d | %d | %d (%d) | %.2f | %.2f | %.2f / %.3f / %.2f / %.2f | %.2f | %.0f | %.0f |\n",
      $1, $2, n, $4, $5, it, $13, w, 1e3 * w / it, 1e3 * $8 / it, 1e3 * $9 / it, 1e3 * $10 / it, 1e3 * $11 / it,
      w / $10, $12 / 1024, $12 * 1024 / n }' <<<"$r"
done
echo
echo "Exponent p of the cost per iteration, t ~ n^p (wall time per Newton iteration):"
printf '%s\n' "${rows[@]}" | awk '
  { n[NR] = $3; t[NR] = $7 / $6; lu[NR] = $10 / $6; el[NR] = $8 / $6 }
  END {
    for (i = 2; i <= NR; i++)
      printf "  %d -> %d DOFs: p = %.2f (LU alone %.2f, elements alone %.2f)\n", n[i - 1], n[i],
        log(t[i] / t[i - 1]) / log(n[i] / n[i - 1]), log(lu[i] / lu[i - 1]) / log(n[i] / n[i - 1]),
        log(el[i] / el[i - 1]) / log(n[i] / n[i - 1])
    if (NR > 2) {
      # least-squares slope of log t against log n over all sizes
      for (i = 1; i <= NR; i++) { x = log(n[i]); y = log(t[i]); sx += x; sy += y; sxx += x * x; sxy += x * y }
      printf "  full range %d -> %d DOFs: p = %.2f (least squares), %.2f (end points)\n", n[1], n[NR],
        (NR * sxy - sx * sy) / (NR * sxx - sx * sx), log(t[NR] / t[1]) / log(n[NR] / n[1])
    }
  }'
