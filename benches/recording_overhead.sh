#!/usr/bin/env bash
# What a full MCAP recording costs a run: the seed's benchmark (strip-channel 24×1, μ = 0.2,
# Δv = 0.0025, 4 800 increments) and the 120×4 strip (adaptive steps, the scene's default),
# each without a recording and with `--out X.mcap` (every channel, default options), run
# side by side: N rounds, each round running every case once, in turn, so that a drift of
# the machine's speed hits all cases alike. Release build.
#
#   bash benches/recording_overhead.sh                  # 10 rounds of both models
#   ROUNDS=20 MODELS=24x1 bash benches/recording_overhead.sh   # the seed's benchmark only
#
# Prints per case the best and the median wall time, the spread (min–max), the ratio of the
# recording run to the run without (best against best, median against median), the best
# CPU time (user + system, both threads) and its ratio, and the size of the recording; and
# the load average before and after (other processes on the machine make the wall times of
# the recording runs, which use two threads, worse than those of the runs without). Every
# recording is written to a new file name (replacing an existing file costs ext4 ≈ 4 ms
# more at the rename).
set -euo pipefail
cd "$(dirname "$0")/.."
export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$HOME/.cache/contrail-target}"
cargo build --release --locked --quiet --bin contrail
BIN="$CARGO_TARGET_DIR/release/contrail"
ROUNDS="${ROUNDS:-10}"
MODELS="${MODELS:-24x1 120x4}"
TMP="$(mktemp -d)"
trap 'rm -rf "$TMP"' EXIT

SEED="strip-channel --set stepping.increments=4800 --set stepping.max_cutbacks=0"
MESH="strip-channel --set body.strip.mesh.elements=[120,4]"
cases=()
for m in $MODELS; do
  case "$m" in
    24x1) cases+=("24x1|$SEED" "24x1+mcap|$SEED --out REC") ;;
    120x4) cases+=("120x4|$MESH" "120x4+mcap|$MESH --out REC") ;;
    *) echo "unknown model $m (24x1, 120x4)"; exit 2 ;;
  esac
done

echo "$(nproc) cores; load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
TIMEFORMAT='%3R %3U %3S'
for round in $(seq "$ROUNDS"); do
  for c in "${cases[@]}"; do
    label="${c%%|*}"
    args="${c#*|}"
    rec="$TMP/$label-$round.mcap"
    args="${args//REC/$rec}"
    # `time` of the shell: wall, user and system seconds of the process and its threads
    # shellcheck disable=SC2086
    { time "$BIN" run $args --quiet >"$TMP/out" 2>&1 || { cat "$TMP/out"; exit 1; }; } 2>"$TMP/time"
    echo "$label $(cat "$TMP/time")" >>"$TMP/times"
    if [ -f "$rec" ]; then
      stat -c "%s" "$rec" >"$TMP/$label.size"
      rm -f "$rec"
    fi
  done
done
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"

python3 - "$TMP" "$ROUNDS" <<'EOF'
import statistics, sys, pathlib
tmp, rounds = pathlib.Path(sys.argv[1]), sys.argv[2]
wall, cpu = {}, {}
for line in (tmp / "times").read_text().split("\n"):
    if line:
        label, real, user, system = line.split()
        wall.setdefault(label, []).append(float(real))
        cpu.setdefault(label, []).append(float(user) + float(system))
print(f"{rounds} rounds, cases alternating; wall and CPU times in s")
print("| case | best | median | spread | recording / none (best) | (median) | CPU best | CPU ratio | file |")
print("|---|---|---|---|---|---|---|---|---|")
for label, t in wall.items():
    base = label.split("+")[0]
    rec = "+" in label
    size = tmp / f"{label}.size"
    mb = f"{int(size.read_text()) / 1e6:.2f} MB" if size.exists() else ""
    ratio = f"{min(t) / min(wall[base]):.3f}" if rec else ""
    mratio = f"{statistics.median(t) / statistics.median(wall[base]):.3f}" if rec else ""
    cratio = f"{min(cpu[label]) / min(cpu[base]):.3f}" if rec else ""
    print(f"| {label} | {min(t):.3f} | {statistics.median(t):.3f} | {min(t):.3f}–{max(t):.3f} "
          f"| {ratio} | {mratio} | {min(cpu[label]):.3f} | {cratio} | {mb} |")
EOF
