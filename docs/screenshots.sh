#!/usr/bin/env bash
# Screenshots of the rerun view of the built-in scenes strip-channel, hertz and slide-3d,
# rendered headless in the viewer's dark and light themes (as in the README):
#   docs/view-strip-channel.png        docs/view-hertz.png         docs/view-slide-3d.png         dark
#   docs/view-strip-channel-light.png  docs/view-hertz-light.png   docs/view-slide-3d-light.png   light
# CONTRAIL_SCREENSHOT_THEMES="dark" (or "light") renders one theme only;
# CONTRAIL_SCREENSHOT_SCENES="slide-3d" (names separated by spaces) only those scenes.
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
#
# The viewer has no command-line switch for its theme: it takes it from its persisted egui
# options (`theme_preference` in app.ron under $XDG_DATA_HOME/rerun). Each screenshot runs the
# viewer with a fresh HOME and XDG directories in a temporary directory holding only that
# setting, so your own viewer settings, blueprints and analytics choice are neither read nor
# written. RUST_LOG=error keeps the start-up notices (Docker, software rasterizer, gRPC port)
# out of the screenshot as toasts; an error toast (a wgpu validation error, seen once while
# the window is resized for the screenshot) makes the script take the screenshot again. The
# Xvfb screen is larger than the window so that the pointer (at the screen's centre) does
# not hover over a view and open a tooltip.
set -euo pipefail
cd "$(dirname "$0")/.."

export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$HOME/.cache/contrail-target}"
VENV="${CONTRAIL_INTEROP_VENV:-$HOME/.cache/contrail-interop-venv}"
SIZE="${CONTRAIL_SCREENSHOT_SIZE:-1366x768}"   # a laptop screen, in logical points
THEMES="${CONTRAIL_SCREENSHOT_THEMES:-dark light}"
RERUN_VERSION="0.36.3"

for theme in $THEMES; do
    case "$theme" in
        dark | light) ;;
        *) echo "unknown theme '$theme' (dark or light)" >&2; exit 2 ;;
    esac
done
if ! "$VENV/bin/rerun" --version 2>/dev/null | grep -q " ${RERUN_VERSION//./\\.} "; then
    python3 -m venv "$VENV"
    "$VENV/bin/pip" install --quiet --disable-pip-version-check "rerun-sdk==$RERUN_VERSION"
fi
if ! command -v xvfb-run >/dev/null; then
    echo "xvfb-run not found: apt-get install -y xvfb mesa-vulkan-drivers libgl1-mesa-dri" >&2
    exit 1
fi

cargo build --release --locked --quiet
TMP="$(mktemp -d)"
trap 'rm -rf "$TMP"' EXIT
# a copy: another build in a shared target directory may replace the binary meanwhile
BIN="$TMP/contrail"
cp "$CARGO_TARGET_DIR/release/contrail" "$BIN"

# A fresh viewer home for `theme` in $TMP/home-THEME: app.ron with only the theme preference
# (and the version, so that the viewer does not reset the preference as it does after an
# upgrade from before 0.24). Sets VIEWER_ENV, the environment the viewer runs in.
viewer_home() {
    local theme="$1" home="$TMP/home-$1" pref
    pref="$(tr '[:lower:]' '[:upper:]' <<<"${theme:0:1}")${theme:1}"
    rm -rf "$home"
    mkdir -p "$home/.local/share/rerun" "$home/.config" "$home/.cache" "$home/run"
    chmod 700 "$home/run"
    printf '{\n    "egui": "(options:(theme_preference:%s))",\n    "rerun.version": "%s",\n}\n' \
        "$pref" "$RERUN_VERSION" >"$home/.local/share/rerun/app.ron"
    VIEWER_ENV=(HOME="$home" XDG_DATA_HOME="$home/.local/share" XDG_CONFIG_HOME="$home/.config"
        XDG_CACHE_HOME="$home/.cache" XDG_RUNTIME_DIR="$home/run" RUST_LOG=error)
}

# Mean luminance of the top bar of the image, dark < 128 < light: the theme was applied.
check_theme() {
    "$VENV/bin/python" - "$1" "$2" <<'PY'
import sys
from PIL import Image, ImageStat
path, theme = sys.argv[1], sys.argv[2]
im = Image.open(path).convert("L")
w, h = im.size
mean = ImageStat.Stat(im.crop((0, 0, w, max(1, h // 60)))).mean[0]
if (mean > 128) != (theme == "light"):
    sys.exit(f"{path}: top bar luminance {mean:.0f} does not look {theme}")
PY
}

shot() {
    local name="$1"; shift
    case " ${CONTRAIL_SCREENSHOT_SCENES:-$name} " in *" $name "*) ;; *) return 0 ;; esac
    echo "== $name: run"
    "$BIN" run "$@" --quiet --rerun-save "$TMP/$name.rrd" >"$TMP/$name.log"
    for theme in $THEMES; do
        local png="docs/view-$name.png"
        [ "$theme" = dark ] || png="docs/view-$name-$theme.png"
        echo "== $name: screenshot ($SIZE, $theme)"
        viewer_home "$theme"
        env "${VIEWER_ENV[@]}" "$VENV/bin/rerun" analytics disable >/dev/null 2>&1 || true
        local log="$TMP/$name.$theme.viewer.log" attempt
        for attempt in 1 2 3; do
            rm -f "$png"
            xvfb-run -a -s "-screen 0 6000x4000x24" env "${VIEWER_ENV[@]}" \
                "$VENV/bin/rerun" --window-size "$SIZE" --screenshot-to "$png" \
                "$TMP/$name.rrd" >"$log" 2>&1 || true
            # a wgpu error while the window is resized for the screenshot shows as a toast
            grep -q "Wgpu validation error" "$log" || break
            echo "   wgpu error toast in attempt $attempt, again" >&2
        done
        if [ ! -s "$png" ]; then
            echo "no $theme screenshot of $name; the viewer said:" >&2
            tail -n 30 "$log" >&2
            exit 1
        fi
        check_theme "$png" "$theme"
        echo "   $png"
    done
}

# 300 nominal increments (adaptive, to v = 12): a recording the viewer loads completely before
# it takes the screenshot (with 1200 it showed whatever increment it had loaded by then)
shot strip-channel strip-channel --set stepping.increments=300
shot hertz hertz
# the 3D view: a block dragged across a slab's facets (friction arrows, crossings in the log)
shot slide-3d slide-3d
