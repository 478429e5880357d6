#!/usr/bin/env bash
# Runs the benchmark gallery's sweep (sweeps/gallery.toml) and draws its charts into docs/:
# a Pareto chart (error against wall time) and a stability map per scene.
# Usage: bash docs/make-gallery-charts.sh   (the sweep goes to sweeps-out/gallery/; resumable)
# CONTRAIL_BIN=path/to/contrail uses a built binary instead of `cargo run --release`.
set -euo pipefail
cd "$(dirname "$0")/.."
if [ -n "${CONTRAIL_BIN:-}" ]; then bin=("$CONTRAIL_BIN"); else bin=(cargo run --release --quiet --); fi
out=sweeps-out/gallery
# a sweep with failed runs is a result too (exit code 1)
"${bin[@]}" sweep sweeps/gallery.toml --out "$out" --jobs "${JOBS:-2}" --quiet || true
index="$out/index.json"
"${bin[@]}" chart stability "$index" --study contact-patch --x contact.eps_n --y stepping.increments -o docs/gallery-patch-stability
"${bin[@]}" chart stability "$index" --study ironing --x stepping.increments --y body.block.mesh.elements -o docs/gallery-ironing-stability
"${bin[@]}" chart pareto "$index" --study ironing --metric plateau_err -o docs/gallery-ironing-pareto
"${bin[@]}" chart stability "$index" --study capstan --x stepping.increments --y body.belt.mesh.elements -o docs/gallery-capstan-stability
"${bin[@]}" chart pareto "$index" --study capstan --metric analytic_err -o docs/gallery-capstan-pareto
"${bin[@]}" chart stability "$index" --study capstan-polygon --x stepping.increments --y body.belt.mesh.elements -o docs/gallery-capstan-polygon-stability
"${bin[@]}" chart pareto "$index" --study capstan-polygon --metric analytic_err -o docs/gallery-capstan-polygon-pareto
"${bin[@]}" chart stability "$index" --study beam --x stepping.increments --y body.strip.mesh.elements -o docs/gallery-beam-stability
"${bin[@]}" chart pareto "$index" --study beam --metric analytic_err -o docs/gallery-beam-pareto
cp "$out/index.csv" docs/gallery-index.csv
