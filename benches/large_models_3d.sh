#!/usr/bin/env bash
# Large models in 3D: the built-in `hertz-3d` (rigid sphere on a neo-Hookean block of EAS
# hexahedra, frictionless, penalty) at the meshes given, each with the linear solvers given;
# prints a Markdown table of the cost per Newton iteration and where it went.
#
#   benches/large_models_3d.sh
#   MESHES="16x16x10 32x32x24 plate:56x56x10" SOLVERS="general auto iterative" THREADS=2 \
#     INCREMENTS=4 BIN=path/to/contrail benches/large_models_3d.sh
#
# `plate:NXxNYxNZ` is the block as a 1 × 1 × 0.25 plate. Solvers: `auto` (the default:
# LDLᵀ, the cheaper of minimum degree and nested dissection, earlier factors reused as
# preconditioners while that is cheaper), `general` (the same factorisation for every
# tangent), `iterative` (multigrid-preconditioned Krylov). Unknowns are 3 × nodes (the
# fixed components included). Nothing is recorded.
set -euo pipefail
cd "$(dirname "$0")/.."
BIN=${BIN:-${CARGO_TARGET_DIR:-target}/release/contrail}
read -r -a meshes <<<"${MESHES:-16x16x10 32x32x24 plate:56x56x10}"
read -r -a solvers <<<"${SOLVERS:-general auto iterative}"
THREADS=${THREADS:-2}
INCREMENTS=${INCREMENTS:-4}
[[ -x "$BIN" ]] || { echo "no binary at $BIN: cargo build --release --locked --bin contrail" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

printf '| mesh | 3 × nodes | solver | Newton iterations | wall [s] | per iteration [s] | elements / LU / solve per iteration [s] | factorisations | ordering, flops per factorisation | lagged solves (CG iterations) | peak RSS [MB] |\n'
printf '|---|---:|---|---:|---:|---:|---|---:|---|---|---:|\n'
for m in "${meshes[@]}"; do
  shape=()
  dims=${m#plate:}
  if [[ "$m" == plate:* ]]; then
    shape=(--set 'body.block.mesh.size=[1.0,1.0,0.25]' --set 'body.block.mesh.origin=[0.0,0.0,-0.25]')
  fi
  IFS=x read -r nx ny nz <<<"$dims"
  for s in "${solvers[@]}"; do
    out="$tmp/run.out"
    /usr/bin/time -f "rss_kb %M" "$BIN" run hertz-3d --threads "$THREADS" \
      --set "body.block.mesh.elements=[$nx,$ny,$nz]" "${shape[@]}" \
      --set "stepping.increments=$INCREMENTS" --set "solver.linear_solver=\"$s\"" >"$out" 2>&1 || {
      echo "run $m $s failed:" >&2
      cat "$out" >&2
      exit 1
    }
    ord=$(grep -oE '(nested dissection|minimum degree) ordering \([0-9.e+]+' "$out" | sed 's/ ordering (/, /' || true)
    grep -q multigrid "$out" && ord=multigrid
    lag=$(grep -oE '[0-9]+ solve\(s\) by conjugate gradients[^(]*\([0-9]+' "$out" | sed -E 's/^([0-9]+) .*\(([0-9]+)$/\1 (\2)/' || true)
    awk -v m="$m" -v s="$s" -v nodes="$(( (nx + 1) * (ny + 1) * (nz + 1) ))" -v ord="${ord:-–}" -v lag="${lag:-–}" '
      /^newton/      { it = $2 }
      /^wall time/   { wall = $3 }
      /^time spent/  { el = $4; lu = $14; so = $19; for (i = 1; i <= NF; i++) if ($i ~ /^factorisations/) f = $(i - 1) }
      /^rss_kb/      { rss = $2 }
      END {
        printf "| %s | %d | %s | %d | %.1f | %.2f | %.2f / %.2f / %.2f | %s | %s | %s | %.0f |\n",
          m, 3 * nodes, s, it, wall, wall / it, el / it, lu / it, so / it, f, ord, lag, rss / 1024 }' "$out"
  done
done
