#!/usr/bin/env bash
# Install zwidth for the current user on Linux: the application, its menu entry and its icon.
#
#   packaging/install-linux.sh                 copy the standalone build (dist/zwidth, `make package`)
#                                              to ~/.local/lib/zwidth, link ~/.local/bin/zwidth, and
#                                              install the .desktop entry and the icons
#   packaging/install-linux.sh --exec PATH     only the entry and the icons, launching PATH
#                                              (e.g. "$PWD/.venv/bin/zwidth" for a pip install)
#   packaging/install-linux.sh --uninstall     remove all of the above
#
# Options: --app DIR (the one-folder build; default: dist/zwidth next to this script's repository),
#          --prefix DIR (default ~/.local: DIR/lib/zwidth, DIR/bin, DIR/share/applications,
#          DIR/share/icons/hicolor/<size>x<size>/apps).  Nothing here needs root.
set -euo pipefail

HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
ROOT="$(dirname "$HERE")"
PREFIX="$HOME/.local"
APP_SRC="$ROOT/dist/zwidth"
EXEC_CMD=""
UNINSTALL=0
SIZES=(16 32 48 64 128 256 512)

usage() { sed -n '2,14p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'; }

while [[ $# -gt 0 ]]; do
    case "$1" in
        --prefix) PREFIX="$2"; shift 2 ;;
        --app) APP_SRC="$2"; shift 2 ;;
        --exec) EXEC_CMD="$2"; shift 2 ;;
        --uninstall) UNINSTALL=1; shift ;;
        -h|--help) usage; exit 0 ;;
        *) echo "install-linux.sh: unknown option $1" >&2; usage >&2; exit 2 ;;
    esac
done

if [[ "$PREFIX" == "$HOME/.local" ]]; then
    DATA="${XDG_DATA_HOME:-$HOME/.local/share}"
else
    DATA="$PREFIX/share"
fi
APP_DEST="$PREFIX/lib/zwidth"
BIN_LINK="$PREFIX/bin/zwidth"
DESKTOP="$DATA/applications/zwidth.desktop"
ICONS="$DATA/icons/hicolor"

refresh_caches() {
    if command -v update-desktop-database >/dev/null 2>&1; then
        update-desktop-database -q "$DATA/applications" || true
    fi
    if command -v gtk-update-icon-cache >/dev/null 2>&1 && [[ -f "$ICONS/index.theme" ]]; then
        gtk-update-icon-cache -q -t "$ICONS" || true
    fi
}

if [[ $UNINSTALL -eq 1 ]]; then
    rm -f "$DESKTOP"
    for size in "${SIZES[@]}"; do rm -f "$ICONS/${size}x${size}/apps/zwidth.png"; done
    rm -f "$ICONS/scalable/apps/zwidth.svg"
    if [[ -L "$BIN_LINK" && "$(readlink "$BIN_LINK")" == "$APP_DEST/zwidth" ]]; then rm -f "$BIN_LINK"; fi
    if [[ -x "$APP_DEST/zwidth" ]]; then rm -rf "$APP_DEST"; fi
    refresh_caches
    echo "zwidth uninstalled from $PREFIX"
    exit 0
fi

# -- the program ------------------------------------------------------------------------------
if [[ -n "$EXEC_CMD" ]]; then
    if ! EXEC_PATH="$(command -v "$EXEC_CMD")"; then
        echo "install-linux.sh: $EXEC_CMD not found" >&2
        exit 1
    fi
    EXEC_PATH="$(cd "$(dirname "$EXEC_PATH")" && pwd)/$(basename "$EXEC_PATH")"
    ICON_SRC="$ROOT/resources/icons"
else
    if [[ ! -x "$APP_SRC/zwidth" ]]; then
        echo "install-linux.sh: no build in $APP_SRC; run \`make package\` first," \
             "or use --exec PATH to install only the menu entry for an existing zwidth" >&2
        exit 1
    fi
    APP_SRC="$(cd "$APP_SRC" && pwd)"
    if [[ "$APP_SRC" != "$APP_DEST" ]]; then
        mkdir -p "$(dirname "$APP_DEST")"
        rm -rf "$APP_DEST.new"
        cp -a "$APP_SRC" "$APP_DEST.new"
        rm -rf "$APP_DEST"
        mv "$APP_DEST.new" "$APP_DEST"
    fi
    mkdir -p "$(dirname "$BIN_LINK")"
    ln -sfn "$APP_DEST/zwidth" "$BIN_LINK"
    EXEC_PATH="$APP_DEST/zwidth"
    ICON_SRC="$APP_DEST/_internal/resources/icons"
    [[ -d "$ICON_SRC" ]] || ICON_SRC="$ROOT/resources/icons"
fi

# -- icons ----------------------------------------------------------------------------------------
for size in "${SIZES[@]}"; do
    install -D -m 644 "$ICON_SRC/zwidth-$size.png" "$ICONS/${size}x${size}/apps/zwidth.png"
done
if [[ -f "$ICON_SRC/zwidth.svg" ]]; then
    install -D -m 644 "$ICON_SRC/zwidth.svg" "$ICONS/scalable/apps/zwidth.svg"
fi

# -- menu entry: the template with the absolute path of the program -------------------------------
mkdir -p "$(dirname "$DESKTOP")"
escaped="${EXEC_PATH//\\/\\\\\\\\}"
escaped="${escaped//\"/\\\\\"}"
sed -e "s|^Exec=zwidth|Exec=\"${escaped//|/\\|}\"|" -e "s|^TryExec=.*|TryExec=${EXEC_PATH//|/\\|}|" \
    "$HERE/zwidth.desktop" > "$DESKTOP.tmp"
chmod 644 "$DESKTOP.tmp"
mv "$DESKTOP.tmp" "$DESKTOP"
if command -v desktop-file-validate >/dev/null 2>&1; then
    desktop-file-validate "$DESKTOP" || true
fi
refresh_caches

echo "installed: $DESKTOP"
echo "           $ICONS/<size>/apps/zwidth.png"
echo "runs:      $EXEC_PATH"
if [[ -z "$EXEC_CMD" ]] && [[ ":$PATH:" != *":$PREFIX/bin:"* ]]; then
    echo "note: $PREFIX/bin is not on PATH; the menu entry works anyway"
fi
