#!/usr/bin/env bash
# Runs the four model sweeps of docs/models.md — each one scene built as several models —
# and draws their charts (error against wall time) into docs/:
#   sweeps/models.toml           Hertz point contact: axisymmetric, 3D quarter, revolved
#   sweeps/models-disc.toml      a disc barrelling between plates: axisymmetric, revolved, Gmsh quarter
#   sweeps/models-cylinder.toml  a long cylinder in a block: plane strain, plane stress, 3D slice, free ends
#   sweeps/models-plate.toml     a thin plate over an edge: plane stress, half the plate in 3D
# One run at a time (--jobs 1), so that the wall times compare; run it with the machine
# otherwise idle. Usage: bash docs/make-models-charts.sh   (the sweeps go to sweeps-out/; resumable)
# CONTRAIL_BIN=path/to/contrail uses a built binary instead of `cargo run --release`.
set -euo pipefail
cd "$(dirname "$0")/.."
if [ -n "${CONTRAIL_BIN:-}" ]; then bin=("$CONTRAIL_BIN"); else bin=(cargo run --release --quiet --); fi
for plan in models:hertz:analytic_err models-disc:disc:analytic_err models-cylinder:cylinder:analytic_err models-plate:plate:peak_err; do
    IFS=: read -r name chart metric <<<"$plan"
    # a sweep with failed runs is a result too (exit code 1)
    "${bin[@]}" sweep "sweeps/$name.toml" --out "sweeps-out/$name" --jobs 1 --quiet || true
    "${bin[@]}" chart pareto "sweeps-out/$name/index.json" --metric "$metric" -o "docs/models-$chart-pareto"
done
