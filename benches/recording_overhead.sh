#!/usr/bin/env bash
# What a full MCAP recording costs a run: the seed's benchmark (strip-channel 24×1, μ = 0.2,
# Δv = 0.0025, 4 800 increments) and the 120×4 strip (adaptive steps, the scene's default),
# each without a recording and with `--out X.mcap` (every channel, default options), run
# side by side: N rounds, each round running every case once, in turn, so that a drift of
# the machine's speed hits all cases alike. Release build.
#
#   bash benches/recording_overhead.sh          # 10 rounds (ROUNDS=20 for more)
#
# Prints per case the best and the median wall time, the spread (min–max), and the ratio of
# the recording run to the run without (best against best, median against median), and the
# size of the recording. Every recording is written to a new file name (replacing an
# existing file costs ext4 ≈ 4 ms more at the rename).
set -euo pipefail
cd "$(dirname "$0")/.."
export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$HOME/.cache/contrail-target}"
cargo build --release --locked --quiet --bin contrail
BIN="$CARGO_TARGET_DIR/release/contrail"
ROUNDS="${ROUNDS:-10}"
TMP="$(mktemp -d)"
trap 'rm -rf "$TMP"' EXIT

SEED="strip-channel --set stepping.increments=4800 --set stepping.max_cutbacks=0"
MESH="strip-channel --set body.strip.mesh.elements=[120,4]"
cases=(
  "24x1|$SEED"
  "24x1+mcap|$SEED --out REC"
  "120x4|$MESH"
  "120x4+mcap|$MESH --out REC"
)

now_ns() { date +%s%N; }

for round in $(seq "$ROUNDS"); do
  for c in "${cases[@]}"; do
    label="${c%%|*}"
    args="${c#*|}"
    rec="$TMP/$label-$round.mcap"
    args="${args//REC/$rec}"
    start=$(now_ns)
    # shellcheck disable=SC2086
    "$BIN" run $args --quiet >"$TMP/out" 2>&1
    end=$(now_ns)
    echo "$label $(( (end - start) / 1000 ))" >>"$TMP/times"
    if [ -f "$rec" ]; then
      stat -c "%s" "$rec" >"$TMP/$label.size"
      rm -f "$rec"
    fi
  done
done

python3 - "$TMP" "$ROUNDS" <<'EOF'
import statistics, sys, pathlib
tmp, rounds = pathlib.Path(sys.argv[1]), sys.argv[2]
times = {}
for line in (tmp / "times").read_text().split("\n"):
    if line:
        label, us = line.split()
        times.setdefault(label, []).append(int(us) / 1e6)
print(f"{rounds} rounds, cases alternating; wall times in s")
print("| case | best | median | spread | recording / none (best) | (median) | file |")
print("|---|---|---|---|---|---|---|")
for label, t in times.items():
    base = times.get(label.split("+")[0], t)
    size = tmp / f"{label}.size"
    mb = f"{int(size.read_text()) / 1e6:.2f} MB" if size.exists() else ""
    ratio = f"{min(t) / min(base):.3f}" if "+" in label else ""
    mratio = f"{statistics.median(t) / statistics.median(base):.3f}" if "+" in label else ""
    print(f"| {label} | {min(t):.3f} | {statistics.median(t):.3f} | {min(t):.3f}–{max(t):.3f} | {ratio} | {mratio} | {mb} |")
EOF
