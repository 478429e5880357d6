#!/usr/bin/env bash
# Phases of one run against its thread budget (issue "Fast on a shared machine"): the run's
# own account of its wall time, element kernels, LU and solve with 1, 2, 4, … threads up to
# the cores of the machine, for the 120×4 and 240×8 strip-channel and a 20 000-element
# `punch-large` (400×50); then K runs started together (K = the cores), each with the default
# budget against `--threads 1` (the slowest of the K). Prints Markdown tables.
#
#   bash benches/phases.sh                       # builds the release binary
#   BIN=path/to/contrail CASES="strip:[120,4]" REPEAT=1 bash benches/phases.sh
#
# Each figure is the least of REPEAT runs (default 3; each phase's least on its own: noise
# only ever adds).
#
# Time it with nothing else running.
set -euo pipefail
cd "$(dirname "$0")/.."
export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$HOME/.cache/contrail-target}"
[[ -n "${BIN:-}" ]] || cargo build --release --locked --quiet --bin contrail
BIN="${BIN:-$CARGO_TARGET_DIR/release/contrail}"
CORES="$(nproc)"
REPEAT="${REPEAT:-3}"
CASES="${CASES:-strip:[120,4] strip:[240,8] punch:[400,50]}"
TMP="$(mktemp -d)"
trap 'rm -rf "$TMP"' EXIT

args() { # the run of a case "strip:[NX,NY]" or "punch:[NX,NY]"
    local kind=${1%%:*} mesh=${1#*:}
    case $kind in
        strip) echo "strip-channel --set body.strip.mesh.elements=$mesh --quiet" ;;
        punch) echo "scenes/punch-large.toml --set body.block.mesh.elements=$mesh --quiet" ;;
        *) echo "unknown case $1" >&2; exit 2 ;;
    esac
}
# "wall elements LU solve" of a run's summary
phases() {
    awk '/^wall time/ { w = $3 }
         /^time spent/ { for (i = 1; i <= NF; i++) { if ($i == "elements") e = $(i + 1); if ($i == "LU") l = $(i + 1); if ($i == "solve") s = $(i + 1) } }
         END { printf "%s %s %s %s", w, e, l, s }' "$1"
}
budgets=(1)
for ((n = 2; n <= CORES; n *= 2)); do budgets+=("$n"); done
[[ " ${budgets[*]} " == *" $CORES "* ]] || budgets+=("$CORES")

echo "$(date -u +%F), $CORES cores ($(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'))"
echo
echo "| case | threads | wall | elements | LU | solve |"
echo "|---|---|---|---|---|---|"
for c in $CASES; do
    read -r -a a <<<"$(args "$c")"
    for th in "${budgets[@]}"; do
        for ((r = 0; r < REPEAT; r++)); do
            "$BIN" run "${a[@]}" --threads "$th" >"$TMP/p" 2>&1
            phases "$TMP/p"
            echo
        done | awk -v c="$c" -v th="$th" '
            { for (i = 1; i <= 4; i++) if (NR == 1 || $i < m[i]) m[i] = $i }
            END { printf "| %s | %s | %s s | %s s | %s s | %s s |\n", c, th, m[1], m[2], m[3], m[4] }'
    done
done
echo
echo "| case | $CORES runs together, default budget (slowest) | $CORES runs together, --threads 1 (slowest) |"
echo "|---|---|---|"
for c in ${TOGETHER:-strip:[120,4]}; do
    read -r -a a <<<"$(args "$c")"
    row="| $c |"
    for th in default 1; do
        extra=(); [[ $th == 1 ]] && extra=(--threads 1)
        best=""
        for ((r = 0; r < REPEAT; r++)); do
            t0=$(date +%s.%N)
            for ((k = 0; k < CORES; k++)); do "$BIN" run "${a[@]}" "${extra[@]}" >/dev/null 2>&1 & done
            wait
            t=$(awk -v a="$t0" -v b="$(date +%s.%N)" 'BEGIN { printf "%.2f", b - a }')
            best=$(awk -v a="${best:-$t}" -v b="$t" 'BEGIN { print (b < a ? b : a) }')
        done
        row+=" $best s |"
    done
    echo "$row"
done
