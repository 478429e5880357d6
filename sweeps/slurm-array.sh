#!/bin/bash
# Run a sweep plan as a Slurm array job: task I of N runs `--shard I/N` of the plan into its
# own folder, with one run per core of its node; a dependent job merges the shards' indexes.
# No coordination between tasks: the split is deterministic (round robin over the plan's
# run order), and a task that is requeued or resubmitted skips the runs it has finished.
#
#   sbatch --array=1-16 sweeps/slurm-array.sh sweeps/strip-speed-accuracy.toml sweeps-out/strip
#   # when all tasks are done (or: sbatch --dependency=afterok:JOBID --wrap "...merge..."):
#   contrail sweep merge sweeps-out/strip/shard-* --out sweeps-out/strip
#   contrail chart pareto sweeps-out/strip/index.json
#
# Build once before submitting (cargo build --release); CONTRAIL overrides the binary.
#SBATCH --job-name=contrail-sweep
#SBATCH --cpus-per-task=8
#SBATCH --time=04:00:00
#SBATCH --output=slurm-%A_%a.out
set -euo pipefail
PLAN=${1:?usage: sbatch --array=1-N sweeps/slurm-array.sh PLAN.toml OUTDIR}
OUT=${2:?usage: sbatch --array=1-N sweeps/slurm-array.sh PLAN.toml OUTDIR}
CONTRAIL=${CONTRAIL:-target/release/contrail}
: "${SLURM_ARRAY_TASK_ID:?run this script with sbatch --array=1-N}"
N=${SLURM_ARRAY_TASK_COUNT:-1}
I=$(( SLURM_ARRAY_TASK_ID - ${SLURM_ARRAY_TASK_MIN:-1} + 1 ))
exec "$CONTRAIL" sweep "$PLAN" --out "$OUT/shard-$I" --shard "$I/$N" --jobs "${SLURM_CPUS_PER_TASK:-1}" --positions-every 10
