#!/usr/bin/env bash
# Runs the methods sweep (sweeps/methods.toml: transfer x smoothing x enforcement x mesh x
# step x eps on strip-channel, ironing and the belt over a polygon) and draws its charts into
# docs/: Pareto charts (error against wall time, front marked) and stability maps (one panel
# per method). The table behind them is docs/methods-index.csv; docs/methods.md reads them.
# Usage: bash docs/make-methods-charts.sh   (the sweep goes to sweeps-out/methods/; resumable)
# CONTRAIL_BIN=path/to/contrail uses a built binary instead of `cargo run --release`.
set -euo pipefail
cd "$(dirname "$0")/.."
if [ -n "${CONTRAIL_BIN:-}" ]; then bin=("$CONTRAIL_BIN"); else bin=(cargo run --release --quiet --); fi
out=sweeps-out/methods
# a sweep with failed runs is a result too (exit code 1)
"${bin[@]}" sweep sweeps/methods.toml --out "$out" --jobs "${JOBS:-2}" --quiet || true
index="$out/index.json"
chart() { "${bin[@]}" chart "$@"; }
chart pareto "$index" --study strip --metric peak_err -o docs/methods-strip-pareto
chart pareto "$index" --study strip --metric spike_rel -o docs/methods-strip-spikes-pareto
chart stability "$index" --study strip --x stepping.increments --y body.strip.mesh.elements --panel family -o docs/methods-strip-stability
chart pareto "$index" --study strip-eps --metric peak_err -o docs/methods-strip-eps-pareto
chart pareto "$index" --study ironing --metric plateau_err -o docs/methods-ironing-pareto
chart stability "$index" --study ironing --x stepping.increments --y body.block.mesh.elements --panel family -o docs/methods-ironing-stability
chart pareto "$index" --study capstan-polygon --metric analytic_err -o docs/methods-capstan-polygon-pareto
chart stability "$index" --study capstan-polygon --x stepping.increments --y body.belt.mesh.elements --panel family -o docs/methods-capstan-polygon-stability
chart pareto "$index" --study capstan-fillet --metric analytic_err -o docs/methods-capstan-fillet-pareto
chart stability "$index" --study capstan-fillet --x rigid.drum.fillet --y body.belt.mesh.elements --panel family -o docs/methods-capstan-fillet-stability
cp "$out/index.csv" docs/methods-index.csv
