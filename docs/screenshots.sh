#!/usr/bin/env bash
# Screenshots of the rerun view of the built-in scenes strip-channel and hertz, rendered
# headless: docs/view-strip-channel.png and docs/view-hertz.png (as in the README).
#
# Needs: Xvfb and a software Vulkan/GL driver (Debian/Ubuntu:
#   apt-get install -y xvfb mesa-vulkan-drivers libgl1-mesa-dri)
# and the rerun viewer of the crate's version, installed on first use into the same Python
# virtual environment as the interoperability checks (CONTRAIL_INTEROP_VENV, default
# ~/.cache/contrail-interop-venv).
#
# The viewer's `--screenshot-to` loads the .rrd with contrail's default blueprint, waits until
# the views settle, saves the window and quits. rerun 0.36.3 then panics while shutting down
# ("Failed to take store hub from the Viewer", exit code 101/102) after the PNG is written;
# the script accepts that when the PNG exists.
set -euo pipefail
cd "$(dirname "$0")/.."

export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$HOME/.cache/contrail-target}"
VENV="${CONTRAIL_INTEROP_VENV:-$HOME/.cache/contrail-interop-venv}"
SIZE="${CONTRAIL_SCREENSHOT_SIZE:-1366x768}"   # a laptop screen, in logical points

if ! "$VENV/bin/rerun" --version 2>/dev/null | grep -q " 0\.36\.3 "; then
    python3 -m venv "$VENV"
    "$VENV/bin/pip" install --quiet --disable-pip-version-check "rerun-sdk==0.36.3"
fi
"$VENV/bin/rerun" analytics disable >/dev/null 2>&1 || true
if ! command -v xvfb-run >/dev/null; then
    echo "xvfb-run not found: apt-get install -y xvfb mesa-vulkan-drivers libgl1-mesa-dri" >&2
    exit 1
fi

cargo build --locked --quiet
BIN="$CARGO_TARGET_DIR/debug/contrail"
TMP="$(mktemp -d)"
trap 'rm -rf "$TMP"' EXIT
export XDG_RUNTIME_DIR="$TMP/xdg"
mkdir -p "$XDG_RUNTIME_DIR" && chmod 700 "$XDG_RUNTIME_DIR"

shot() {
    local name="$1"; shift
    echo "== $name: run"
    "$BIN" run "$@" --quiet --rerun-save "$TMP/$name.rrd" >"$TMP/$name.log"
    echo "== $name: screenshot ($SIZE)"
    rm -f "docs/view-$name.png"
    xvfb-run -a -s "-screen 0 2000x1200x24" \
        "$VENV/bin/rerun" --window-size "$SIZE" --screenshot-to "docs/view-$name.png" \
        "$TMP/$name.rrd" >"$TMP/$name.viewer.log" 2>&1 || true
    if [ ! -s "docs/view-$name.png" ]; then
        echo "no screenshot of $name; the viewer said:" >&2
        tail -n 30 "$TMP/$name.viewer.log" >&2
        exit 1
    fi
    echo "   docs/view-$name.png"
}

# 300 nominal increments (adaptive, to v = 12): a recording the viewer loads completely before
# it takes the screenshot (with 1200 it showed whatever increment it had loaded by then)
shot strip-channel strip-channel --set stepping.increments=300
shot hertz hertz
