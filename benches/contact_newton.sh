#!/usr/bin/env bash
# The contact Newton across penalties (issue "One contact Newton, by the book"): the built-in
# ironing with ε_N = ε_T from 1e1·E to 1e6·E and μ = 0.1, 0.3 on MESH (default the scene's
# 36×12) at INCREMENTS (default the scene's 120); one line per run
# with its outcome, Newton iterations (all, and per converged increment), cut-backs and end
# forces. ACTIVE_SET=penalty gives the seed's decisions for comparison.
#
#   bash benches/contact_newton.sh
#   MESH=[72,24] INCREMENTS=240 bash benches/contact_newton.sh
set -euo pipefail
cd "$(dirname "$0")/.."
export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$HOME/.cache/contrail-target}"
[[ -n "${BIN:-}" ]] || cargo build --release --locked --quiet --bin contrail
BIN="${BIN:-$CARGO_TARGET_DIR/release/contrail}"
MESH="${MESH:-}"
INCREMENTS="${INCREMENTS:-}"
ACTIVE_SET="${ACTIVE_SET:-augmented}"
extra=(--set "solver.active_set=$ACTIVE_SET" --threads 1 --quiet)
[[ -n "$MESH" ]] && extra+=(--set "body.block.mesh.elements=$MESH")
[[ -n "$INCREMENTS" ]] && extra+=(--set "stepping.increments=$INCREMENTS")
line() {
    local out
    out=$("$BIN" run "$@" 2>&1 || true)
    printf '%s | %s | %s | %s\n' "$*" \
        "$(grep -E '^ended' <<<"$out" | awk '{print $2}')" \
        "$(grep -E '^newton' <<<"$out" | sed 's/newton *//; s/ (as `contrail inspect` counts)//')" \
        "$(grep -E '^last point' <<<"$out" | sed 's/last point *//')"
}
for mu in 0.1 0.3; do
    for eps in 1e1 1e2 1e3 1e4 1e5 1e6; do
        line ironing --set "contact.mu=$mu" --set "contact.eps_n=$eps" --set "contact.eps_t=$eps" "${extra[@]}"
    done
done
