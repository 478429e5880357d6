#!/usr/bin/env bash
# `contrail serve --backend slurm` against a real one-node Slurm (Debian's slurm-wlm and munge,
# started here; see docs/service.md). Called by .ci/run. Where Slurm cannot be installed or
# started (no root, no apt, daemons that do not come up), it says so and exits 0: it is a
# check of the Slurm paths, not a requirement of the machine. Once Slurm runs, any failure
# of contrail's is an error (exit 1).
#
# Exercised: sbatch of each queued run (batch script in the shared data folder), squeue
# polling, live progress and the outcome read from the job's progress file, cancel with
# `scancel --signal=INT --full` (the run ends interrupted with a finalised recording), and a
# restart of the service that follows a job submitted before it stopped. Not exercised:
# several nodes, a shared filesystem other than the local disk, accounting (sacct).
set -euo pipefail
cd "$(dirname "$0")/.."

skip() { echo "== slurm: skipped: $*"; exit 0; }

export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$HOME/.cache/contrail-target}"
[ "$(id -u)" = 0 ] || skip "not root (slurmctld, slurmd and munged are started here as root)"
if ! command -v slurmctld >/dev/null || ! command -v munged >/dev/null; then
    command -v apt-get >/dev/null || skip "no apt-get to install slurm-wlm and munge"
    echo "== slurm: installing slurm-wlm and munge"
    timeout 600 apt-get install -y -qq slurm-wlm munge >/tmp/contrail-slurm-apt.log 2>&1 \
        || { apt-get update -qq >/dev/null 2>&1 && timeout 600 apt-get install -y -qq slurm-wlm munge >/tmp/contrail-slurm-apt.log 2>&1; } \
        || skip "apt-get install slurm-wlm munge failed ($(tail -n 1 /tmp/contrail-slurm-apt.log))"
fi

HOST="$(hostname)"
CPUS="$(nproc)"
MEM_MB="$(awk '/MemTotal/ { print int($2 / 1024 * 0.8) }' /proc/meminfo)"
SERVE_PID=
MUNGED_STARTED=
cleanup() {
    for p in /run/slurmd.pid /run/slurmctld.pid; do
        [ -f "$p" ] && kill "$(cat "$p")" 2>/dev/null || true
    done
    [ -n "${SERVE_PID:-}" ] && kill -INT "$SERVE_PID" 2>/dev/null || true
    if [ -n "${MUNGED_STARTED:-}" ] && [ -f /run/munge/munged.pid ]; then
        kill "$(cat /run/munge/munged.pid)" 2>/dev/null || true
    fi
    [ -n "${TMP:-}" ] && rm -rf "$TMP"
}
trap cleanup EXIT

echo "== slurm: starting munged, slurmctld, slurmd (one node: $HOST, $CPUS CPUs)"
mkdir -p /etc/munge /run/munge /var/lib/munge /var/log/munge
if [ ! -s /etc/munge/munge.key ]; then
    (mungekey --create 2>/dev/null || dd if=/dev/urandom of=/etc/munge/munge.key bs=1 count=1024 2>/dev/null)
fi
chown -R munge:munge /etc/munge /run/munge /var/lib/munge /var/log/munge 2>/dev/null || true
chmod 400 /etc/munge/munge.key
if ! pgrep -x munged >/dev/null; then
    su -s /bin/sh munge -c munged || skip "munged did not start"
    MUNGED_STARTED=1
fi
for _ in $(seq 1 50); do
    munge -n 2>/dev/null | unmunge >/dev/null 2>&1 && break
    sleep 0.1
done
munge -n 2>/dev/null | unmunge >/dev/null 2>&1 || skip "munge does not authenticate (munge -n | unmunge fails)"
mkdir -p /etc/slurm /var/spool/slurmd /var/spool/slurmctld /var/log/slurm
cat >/etc/slurm/slurm.conf <<EOF
ClusterName=contrail-ci
SlurmctldHost=$HOST
AuthType=auth/munge
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
SlurmctldPidFile=/run/slurmctld.pid
SlurmdPidFile=/run/slurmd.pid
SlurmdSpoolDir=/var/spool/slurmd
StateSaveLocation=/var/spool/slurmctld
SlurmctldLogFile=/var/log/slurm/slurmctld.log
SlurmdLogFile=/var/log/slurm/slurmd.log
SlurmUser=root
MinJobAge=60
NodeName=$HOST CPUs=$CPUS RealMemory=$MEM_MB State=UNKNOWN
PartitionName=debug Nodes=$HOST Default=YES MaxTime=INFINITE State=UP
EOF
slurmctld || skip "slurmctld did not start ($(tail -n 2 /var/log/slurm/slurmctld.log 2>/dev/null))"
slurmd || skip "slurmd did not start ($(tail -n 2 /var/log/slurm/slurmd.log 2>/dev/null))"
for _ in $(seq 1 30); do
    sinfo -h -o %T 2>/dev/null | grep -qE "idle|mixed" && break
    sleep 1
done
sinfo -h -o %T 2>/dev/null | grep -qE "idle|mixed" || skip "the Slurm node did not become idle ($(sinfo 2>&1 | tail -n 1))"
echo "Slurm is up: $(sinfo -h -o '%P %D %T %C')"

echo "== slurm: contrail serve --backend slurm"
cargo build --locked --quiet
BIN="$CARGO_TARGET_DIR/debug/contrail"
TMP="$(mktemp -d)"
serve() {
    "$BIN" serve --port 0 --data "$TMP/data" --backend slurm >"$TMP/serve.log" 2>&1 &
    SERVE_PID=$!
    for _ in $(seq 1 50); do
        URL="$(grep -o 'http://[0-9.:]*' "$TMP/serve.log" || true)"
        [ -n "$URL" ] && return 0
        sleep 0.1
    done
    echo "the service did not start"; cat "$TMP/serve.log"; exit 1
}
fail() { echo "FAILED: $*"; cat "$TMP/serve.log"; ls -la "$TMP/data/runs" || true; cat "$TMP"/data/runs/*.slurm.out 2>/dev/null || true; exit 1; }
field() { curl -s "$URL/api/runs/$1" | python3 -c "import json,sys; print(json.load(sys.stdin)$2)"; }
serve

# 1. a run submitted as a job, followed to its outcome
out="$("$BIN" submit strip-channel --wait --server "$URL")" || fail "submit strip-channel --wait: $out"
ID="$(echo "$out" | awk '/^run / { print $2; exit }')"
[ "$(field "$ID" "['backend']")" = slurm ] || fail "run $ID was not solved on Slurm"
JOB="$(field "$ID" "['job']")"
[ -n "$JOB" ] && [ "$JOB" != None ] || fail "run $ID has no Slurm job id"
[ "$(field "$ID" "['figures']['increments']")" -gt 0 ] || fail "no increments"
[ -s "$TMP/data/runs/$ID.mcap" ] || fail "no recording"
"$BIN" inspect "$TMP/data/runs/$ID.mcap" >/dev/null || fail "the job's recording does not read"
echo "run $ID: Slurm job $JOB, $(field "$ID" "['status']"), $(field "$ID" "['figures']['increments']") increments"

# 2. cancel a running job: SIGINT through scancel, a finalised recording that ends interrupted
LONG="$("$BIN" submit strip-channel --set stepping.increments=400000 --server "$URL" | awk '/^run / { print $2; exit }')"
for _ in $(seq 1 200); do
    inc="$(curl -s "$URL/api/runs/$LONG" | python3 -c "import json,sys; p=json.load(sys.stdin).get('progress') or {}; print(p.get('increment', 0))")"
    [ "$inc" -gt 20 ] && break
    sleep 0.2
done
[ "$inc" -gt 20 ] || fail "no live progress from the job of $LONG"
curl -s -X POST "$URL/api/runs/$LONG/cancel" >/dev/null
for _ in $(seq 1 150); do
    st="$(field "$LONG" "['status']")"
    [ "$st" != running ] && break
    sleep 0.2
done
[ "$st" = interrupted ] || fail "cancelled run $LONG ended $st"
"$BIN" inspect "$TMP/data/runs/$LONG.mcap" | grep -qi interrupted || fail "the cancelled run's recording does not end interrupted"
echo "run $LONG: live progress seen (increment $inc), cancelled through scancel: interrupted, recording finalised"

# 3. a job submitted before the service stopped is followed after its restart
NEXT="$("$BIN" submit block-slide --set contact.mu=0.25 --server "$URL" | awk '/^run / { print $2; exit }')"
for _ in $(seq 1 100); do
    j="$(field "$NEXT" "['job']")"
    [ "$j" != None ] && break
    sleep 0.1
done
kill -9 "$SERVE_PID"; wait "$SERVE_PID" 2>/dev/null || true
serve
for _ in $(seq 1 150); do
    st="$(field "$NEXT" "['status']")"
    [ "$st" = completed ] && break
    sleep 0.2
done
[ "$st" = completed ] || fail "run $NEXT (job $j) after the restart: $st"
echo "run $NEXT: job $j followed again after a kill -9 and restart of the service: completed"
echo "== slurm: 3 passed, 0 failed"
