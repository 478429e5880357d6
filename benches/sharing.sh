#!/usr/bin/env bash
# Runs sharing a machine (issue "Fast on a shared machine"): the 120×4 strip-channel alone,
# two side by side, and the service with 2 workers solving four, each with the default
# thread budget (every core) and with `--threads 1`; then the phases of one run alone
# (elements, LU, solve) with 1 and N threads. Prints Markdown tables of wall times (best of
# REPEAT for the cases of one or two runs; the service case once per REPEAT, best kept).
#
#   bash benches/sharing.sh              # REPEAT=3
#   REPEAT=1 MESH=[240,8] bash benches/sharing.sh
#
# Time it with nothing else running: the point is what the runs do to each other.
set -euo pipefail
cd "$(dirname "$0")/.."
export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$HOME/.cache/contrail-target}"
[[ -n "${BIN:-}" ]] || cargo build --release --locked --quiet --bin contrail
BIN="${BIN:-$CARGO_TARGET_DIR/release/contrail}"
REPEAT="${REPEAT:-3}"
MESH="${MESH:-[120,4]}"
CORES="$(nproc)"
TMP="$(mktemp -d)"
trap 'kill $(jobs -p) 2>/dev/null || true; rm -rf "$TMP"' EXIT
RUN=(run strip-channel --set "body.strip.mesh.elements=$MESH" --quiet)

now() { date +%s.%N; }
# one run; prints its wall time in seconds (the process's, start to exit)
one() { local t0; t0=$(now); "$BIN" "${RUN[@]}" "$@" >"$TMP/out.$BASHPID" 2>&1; awk -v a="$t0" -v b="$(now)" 'BEGIN { printf "%.2f", b - a }'; }
# two runs started together; prints "a b"
two() {
    one "$@" >"$TMP/a" & one "$@" >"$TMP/b" & wait
    echo "$(cat "$TMP/a") $(cat "$TMP/b")"
}
best() { tr ' ' '\n' | sed '/^$/d' | sort -g | head -n 1; }
worst_of_pairs() { awk '{ m = ($1 > $2 ? $1 : $2); if (NR == 1 || m < b) b = m } END { printf "%.2f", b }'; }

# the service: 2 workers, four runs queued at once; wall time until all four completed
# (polled every 0.2 s)
service() {
    local threads_arg=("$@") data="$TMP/svc" port
    rm -rf "$data"; mkdir -p "$data"
    port=$(python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1",0)); print(s.getsockname()[1])')
    "$BIN" serve --port "$port" --data "$data" --workers 2 "${threads_arg[@]}" >"$TMP/serve.log" 2>&1 &
    local pid=$!
    for _ in $(seq 100); do curl -sf "http://127.0.0.1:$port/api/health" >/dev/null 2>&1 && break; sleep 0.1; done
    local t0; t0=$(now)
    for mu in 0.2 0.21 0.22 0.23; do
        "$BIN" submit strip-channel --server "http://127.0.0.1:$port" --set "body.strip.mesh.elements=$MESH" --set "contact.mu=$mu" >/dev/null
    done
    while :; do
        local done_runs
        # (curl and sed only: a poll must not take the CPU the runs are measured on)
        done_runs=$(curl -sf "http://127.0.0.1:$port/api/health" | sed -n 's/.*"completed":\([0-9]*\).*/\1/p')
        [[ "${done_runs:-0}" -ge 4 ]] && break
        sleep 0.2
    done
    awk -v a="$t0" -v b="$(now)" 'BEGIN { printf "%.2f", b - a }'
    kill "$pid"; wait "$pid" 2>/dev/null || true
}

declare -A R
for _ in $(seq "$REPEAT"); do
    R[alone1]+="$(one --threads 1) "
    R[alone]+="$(one) "
    R[two1]+="$(two --threads 1);"
    R[two]+="$(two);"
    R[svc1]+="$(service --threads-per-run 1) "
    R[svc]+="$(service) "
done
pairs() { tr ';' '\n' | sed '/^$/d'; }
base=$(echo "${R[alone1]}" | best)
ratio() { awk -v t="$1" -v b="$base" 'BEGIN { printf "%.2f", t / b }'; }
echo "strip-channel $MESH, $CORES cores, $(date -u +%F), best of $REPEAT"
echo
echo "| case | --threads 1 | default ($CORES threads) | default / one run alone at 1 thread |"
echo "|---|---|---|---|"
a1=$(echo "${R[alone1]}" | best); a=$(echo "${R[alone]}" | best)
echo "| one run alone | $a1 s | $a s | $(ratio "$a") |"
t1=$(echo "${R[two1]}" | pairs | worst_of_pairs); t=$(echo "${R[two]}" | pairs | worst_of_pairs)
echo "| two runs side by side (the slower of the two) | $t1 s | $t s | $(ratio "$t") |"
s1=$(echo "${R[svc1]}" | best); s=$(echo "${R[svc]}" | best)
echo "| service, 2 workers, four runs recorded (until all ended; default: the service's share, cores / workers) | $s1 s | $s s | $(ratio "$s") |"
echo
echo "Phases of one run alone (the run's own account):"
echo
echo "| threads | wall | elements | LU | solve | assemblies on the team |"
echo "|---|---|---|---|---|---|"
for th in 1 "$CORES"; do
    "$BIN" "${RUN[@]}" --threads "$th" >"$TMP/p" 2>&1
    awk -v th="$th" '
        /^wall time/ { wall = $3 }
        /^time spent/ {
            for (i = 1; i <= NF; i++) {
                if ($i == "elements") el = $(i + 1)
                if ($i == "LU") lu = $(i + 1)
                if ($i == "solve") so = $(i + 1)
                if ($i == "shared" && $(i + 1) == "in") team = $(i + 2)
            }
        }
        END { printf "| %s | %s s | %s s | %s s | %s s | %s %% |\n", th, wall, el, lu, so, (team == "" ? "0" : team) }' "$TMP/p"
done
