#!/usr/bin/env bash
# Side by side with CalculiX in 3D (issue "Side by side with CalculiX in 3D"): the built-in
# `hertz-3d` scene (rigid sphere R = 1 pressed 0.005 into a neo-Hookean block, quarter model,
# 4 increments) in contrail and in CalculiX 2.20 (Debian `calculix-ccx`) at equal meshes,
# wall time, peak RSS and result in one markdown table. The CalculiX deck is written by
# benches/calculix/hertz_3d_inp.py (same nodes; C3D8I; the sphere a prescribed faceted cap;
# the same penalty per unit area); both runs are read with the measures of
# tests/hertz_sphere_3d.rs (benches/calculix/hertz_ref.py). See docs/calculix-3d.md.
#
#   BIN=path/to/contrail bash benches/calculix_hertz_3d.sh
#   MESHES="8x8x6 16x16x12 24x24x18" REPEATS=3 BIN=... bash benches/calculix_hertz_3d.sh
#
# MESHES (default "8x8x6 16x16x12"): block meshes NXxNYxNZ. THREADS (default "1 N", N the
# cores this process may use): contrail's --threads and CalculiX's OMP_NUM_THREADS (its
# matrix set-up, element loop and SPOOLES solver; CCX_NPROC_* are left unset). REPEATS
# (default 1): timed runs per row, the fastest reported. CCX (default `ccx`). CCX_TOL
# (default "tight default"): CalculiX's Newton criteria, one set of rows each: `tight` (an
# increment ends when the displacement correction is below 1e-8, converged as contrail's)
# and `default` (CalculiX's own criteria); see hertz_3d_inp.py.
# WORK: scratch folder (default a fresh temporary one, kept). Timings need /usr/bin/time
# (GNU time, `time -v`). Each timed contrail run writes no recording; its result comes from
# one more run with `--out RUN.jsonl`, not timed. Every CalculiX run is read. The load
# average (1 min) before and after each timed run is in the table: other work on the
# machine slows both codes. Exits non-zero if a run fails or a number cannot be read.
set -euo pipefail
cd "$(dirname "$0")/.."
here=$PWD
if [[ -z "${BIN:-}" ]]; then
    export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$HOME/.cache/contrail-target}"
    cargo build --release --locked --quiet --bin contrail
    BIN="$CARGO_TARGET_DIR/release/contrail"
fi
CCX="${CCX:-ccx}"
MESHES="${MESHES:-8x8x6 16x16x12}"
cores=$(nproc)
THREADS="${THREADS:-1 $cores}"
REPEATS="${REPEATS:-1}"
CCX_TOL="${CCX_TOL:-tight default}"
WORK="${WORK:-$(mktemp -d -t contrail-ccx.XXXXXX)}"
mkdir -p "$WORK"
WORK=$(cd "$WORK" && pwd)
die() {
    echo "calculix_hertz_3d: $*" >&2
    exit 1
}
[[ -x /usr/bin/time ]] || die "needs GNU time at /usr/bin/time"
command -v "$CCX" >/dev/null || die "no CalculiX ($CCX) on PATH: apt-get install calculix-ccx"
[[ -x "$BIN" ]] || die "no contrail binary at $BIN"
py="$here/benches/calculix"

load1() { cut -d' ' -f1 /proc/loadavg; }
# wall seconds and peak RSS (MB) from a `time -v` report
wall_of() {
    awk -F': ' '/Elapsed \(wall clock\)/ {n = split($2, p, ":"); s = 0; for (i = 1; i <= n; i++) s = s * 60 + p[i]; printf "%.2f", s}' "$1"
}
rss_of() { awk -F': ' '/Maximum resident set size/ {printf "%.0f", $2 / 1024}' "$1"; }
cpu_of() { awk -F': ' '/(User|System) time \(seconds\)/ {s += $2; n++} END {if (n == 2) printf "%.2f", s}' "$1"; }
# the value of key K in a `key=value` line
field() { tr ' ' '\n' <<<"$1" | awk -F= -v k="$2" '$1 == k {print $2}'; }
pct() { awk -v x="$1" 'BEGIN {printf "%+.2f %%", 100 * x}'; }

# timed KIND (contrail|ccx) THREADS DIR -- command...: runs the command in DIR REPEATS times
# (CalculiX with OMP_NUM_THREADS=THREADS), its output in DIR/tTHREADS.log, checks and reads
# each run, keeps the fastest run's time report; sets $wall, $cpu (user + system of that run),
# $rss, $loads and, for CalculiX,
# $result (read_ccx.py's line)
timed() {
    local kind=$1 t=$2 dir=$3
    shift 4
    local best="" r w before after log="$dir/t$t"
    loads=""
    for ((r = 1; r <= REPEATS; r++)); do
        before=$(load1)
        {
            echo "$(date -u +%FT%TZ) $dir $kind threads=$t start: $(uptime)"
            # what else runs: the busiest processes over 0.3 s
            top -bn2 -d0.3 -o %CPU 2>/dev/null | awk '/^top -/ {n++} n == 2 && /^ *[0-9]/ {print "    busy: " $9 " % " $12; if (++k == 3) exit}' || true
        } >>"$WORK/uptime.log"
        local envs=()
        [[ $kind == ccx ]] && envs=(env "OMP_NUM_THREADS=$t")
        if ! (cd "$dir" && "${envs[@]}" /usr/bin/time -v -o "$log.time.$r" "$@" >"$log.log" 2>&1); then
            die "$kind failed ($*) in $dir, see $log.log"
        fi
        after=$(load1)
        echo "$(date -u +%FT%TZ) $dir $kind threads=$t end:   $(uptime)" >>"$WORK/uptime.log"
        loads+="${loads:+, }$before→$after"
        if [[ $kind == ccx ]]; then
            cp "$log.log" "$dir/job.log"
            result=$(python3 "$py/read_ccx.py" "$dir/job" 2>>"$dir/read.txt") || die "cannot read the CalculiX run in $dir"
        else
            grep -q '^ended *completed' "$log.log" || die "contrail did not complete, see $log.log"
        fi
        w=$(wall_of "$log.time.$r")
        [[ -n "$w" ]] || die "no wall time in $log.time.$r"
        if [[ -z "$best" ]] || awk -v a="$w" -v b="$best" 'BEGIN {exit !(a < b)}'; then
            best=$w
            cp "$log.time.$r" "$log.time"
        fi
    done
    wall=$best
    rss=$(rss_of "$log.time")
    [[ -n "$rss" ]] || die "no peak RSS in $log.time"
    cpu=$(cpu_of "$log.time")
    [[ -n "$cpu" ]] || die "no CPU time in $log.time"
}

rows=()
# row CODE THREADS RESULT-LINE: one line of the table (fails if a number is missing)
row() {
    local k v
    declare -A m
    for k in unknowns iterations F F_err a a_err p0 p0_err; do
        v=$(field "$3" "$k")
        [[ -n "$v" ]] || die "no $k for $1 on $mesh in: $3"
        m[$k]=$v
    done
    rows+=("| $mesh | ${m[unknowns]} | $1 | $2 | $wall | $cpu | $rss | ${m[iterations]} | ${m[F]} | $(pct "${m[F_err]}") | ${m[a]} | $(pct "${m[a_err]}") | ${m[p0]} | $(pct "${m[p0_err]}") | $loads |")
}
date_utc=$(date -u +%F)
echo "work folder: $WORK" >&2
for mesh in $MESHES; do
    IFS=x read -r nx ny nz <<<"$mesh"
    [[ "$nx" =~ ^[0-9]+$ && "$ny" =~ ^[0-9]+$ && "$nz" =~ ^[0-9]+$ ]] || die "mesh '$mesh' is not NXxNYxNZ"
    set_mesh=(--set "body.block.mesh.elements=[$nx,$ny,$nz]")
    d="$WORK/$mesh"
    mkdir -p "$d/contrail"
    # contrail: the result (recorded, not timed), then the timed runs (no recording)
    "$BIN" run hertz-3d "${set_mesh[@]}" --threads 1 --quiet --out "$d/contrail/run.jsonl" >"$d/contrail/result.log" 2>&1 ||
        die "contrail failed on $mesh, see $d/contrail/result.log"
    c_line=$(python3 "$py/read_contrail.py" "$d/contrail/run.jsonl" "$nx" "$ny" "$nz" 2>>"$d/contrail/read.txt") ||
        die "cannot read the contrail run of $mesh"
    for t in $THREADS; do
        timed contrail "$t" "$d/contrail" -- "$BIN" run hertz-3d "${set_mesh[@]}" --threads "$t" --quiet
        row contrail "$t" "$c_line"
    done
    # CalculiX: per Newton criteria, the deck, then the timed runs (each one read)
    for tol in $CCX_TOL; do
        mkdir -p "$d/ccx-$tol"
        python3 "$py/hertz_3d_inp.py" --elements "$nx" "$ny" "$nz" --tol "$tol" --out "$d/ccx-$tol/job.inp" 2>>"$d/ccx-$tol/inp.txt" ||
            die "cannot write the CalculiX deck of $mesh"
        for t in $THREADS; do
            timed ccx "$t" "$d/ccx-$tol" -- "$CCX" -i job
            row "CalculiX 2.20 ($tol)" "$t" "$result"
        done
    done
done

echo
echo "hertz-3d, contrail against CalculiX 2.20, $date_utc, $(nproc) cores ($(uname -m)), REPEATS=$REPEATS (fastest shown)"
echo
echo "| mesh | unknowns | code | threads | wall [s] | CPU [s] | peak RSS [MB] | Newton its | F | F vs Hertz(d) | a | a vs Hertz(F) | p0 | p0 vs Hertz(F) | load 1 min (before→after) |"
echo "|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|"
printf '%s\n' "${rows[@]}"
echo
echo "Hertz for d = 0.005: F = $(python3 -c "import sys; sys.path.insert(0, '$py'); import hertz_ref as h; print(f'{h.hertz_force():.6f}')"); a and p0 against Hertz for each run's own F (as tests/hertz_sphere_3d.rs)."
echo "wall, CPU (user + system) and peak RSS of the fastest of the REPEATS runs, from /usr/bin/time -v."
echo "CalculiX (tight): an increment ends when its displacement correction is below 1e-8; (default): CalculiX's own criteria."
echo "Load averages and what ran: $WORK/uptime.log"
