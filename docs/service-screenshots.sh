#!/usr/bin/env bash
# Remake the screenshots of docs/service.md: a service with a few runs (completed, failed,
# one running), pictured by headless Chromium (Debian's `chromium`).
# usage: bash docs/service-screenshots.sh   (from the repository; needs chromium)
set -euo pipefail
cd "$(dirname "$0")/.."
export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$HOME/.cache/contrail-target}"
cargo build --locked --quiet
BIN="$CARGO_TARGET_DIR/debug/contrail"
TMP="$(mktemp -d)"
"$BIN" serve --port 0 --data "$TMP/data" --workers 2 >"$TMP/serve.log" 2>&1 &
PID=$!
trap 'kill -INT $PID 2>/dev/null; wait $PID 2>/dev/null; rm -rf "$TMP"' EXIT
sleep 1
URL="$(grep -o 'http://[0-9.:]*' "$TMP/serve.log")"
s() { "$BIN" submit "$@" --server "$URL" 2>/dev/null | awk '/^run / { print $2; exit }'; }
OK="$(s strip-channel --wait)"
s strip-channel --set solver.max_iterations=1 --set stepping.max_cutbacks=0 --wait >/dev/null || true
A="$(s block-slide --set contact.mu=0.2 --wait)"
B="$(s block-slide --set contact.mu=0.4 --wait)"
s crossing --wait >/dev/null
FAIL="$(s strip-channel --set contact.transfer='"straightforward"' --wait || true)"
s strip-channel --set stepping.increments=200000 >/dev/null
sleep 2
shot() {
    chromium --headless --no-sandbox --disable-gpu --disable-quic --no-first-run --disable-background-networking \
        --disable-component-update --disable-sync --hide-scrollbars --user-data-dir="$TMP/chrome-$1" \
        --window-size=1400,"$3" --virtual-time-budget=8000 --screenshot="docs/service-$1.png" "$URL/?live=0$2" 2>/dev/null
}
shot runs "#/" 560
shot run "#/runs/$OK" 1000
shot failed "#/runs/$FAIL" 1000
shot compare "#/compare/$A/$B" 1000
echo "written docs/service-{runs,run,failed,compare}.png"
