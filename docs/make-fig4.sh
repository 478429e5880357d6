#!/usr/bin/env bash
# Reproduces docs/fig4.png (the seed's Fig. 4): load–displacement curves of the strip drawn
# into the channel, continuous vs straightforward transfer, frictionless and μ = 0.1, 0.2, 0.3.
# Usage: bash docs/make-fig4.sh   (writes the CSVs to recordings/fig4/)
set -euo pipefail
cd "$(dirname "$0")/.."
out=recordings/fig4
mkdir -p "$out"
# CONTRAIL_BIN=path/to/contrail uses a built binary instead of `cargo run --release`
if [ -n "${CONTRAIL_BIN:-}" ]; then bin=("$CONTRAIL_BIN"); else bin=(cargo run --release --quiet --); fi
args=()
for mu in 0 0.1 0.2 0.3; do
  for scheme in continuous straightforward; do
    f="$out/$scheme-$mu.csv"
    # a straightforward run that stops early is part of the result (exit code 1)
    # the seed's settings: v = 11 in fixed steps dv = 0.0025, no cut-backs
    "${bin[@]}" run strip-channel --quiet --set fix.1.value=-11.0 --set stepping.increments=4400 \
      --set stepping.max_cutbacks=0 --set contact.mu=$mu --set contact.transfer=$scheme --out "$f" || true
    label="$scheme"
    [ "$mu" = 0 ] && label="$label, frictionless" || label="$label, μ = $mu"
    [ "$mu" = 0 ] && [ "$scheme" = straightforward ] && continue  # identical to continuous (see README)
    args+=("$f=$label")
  done
done
"${bin[@]}" plot "${args[@]}" --out docs/fig4.png --x-label "v (prescribed displacement of the centre)" \
  --y-label "force on the centre section (half model)" --title "Strip drawn into a channel over a sharp corner (seed Fig. 4)"
"${bin[@]}" plot "${args[@]}" --out docs/fig4.svg --x-label "v (prescribed displacement of the centre)" \
  --y-label "force on the centre section (half model)" --title "Strip drawn into a channel over a sharp corner (seed Fig. 4)"
