#!/usr/bin/env bash
# Check the system libraries that Qt (PySide6 wheels) loads at run time, on Debian/Ubuntu.
#
# All present: exit 0 silently.  Something missing: as root, install it with apt-get;
# otherwise print the apt-get line to stderr and exit 1.
set -euo pipefail

# "soname package [alternative package ...]": the first package apt knows is used.
REQUIRED=(
    "libEGL.so.1 libegl1"
    "libGL.so.1 libgl1"
    "libxkbcommon.so.0 libxkbcommon0"
    "libfontconfig.so.1 libfontconfig1"
    "libdbus-1.so.3 libdbus-1-3"
    "libglib-2.0.so.0 libglib2.0-0t64 libglib2.0-0"
)
# The X11 client libraries of Qt's xcb platform plugin, checked when a display is present
# (DISPLAY or WAYLAND_DISPLAY set): without them the GUI aborts at start on an X11 desktop.
# The same list as app/display_check.py (XCB_LIBRARIES).
XCB_REQUIRED=(
    "libxcb.so.1 libxcb1"
    "libX11-xcb.so.1 libx11-xcb1"
    "libxcb-cursor.so.0 libxcb-cursor0"
    "libxcb-icccm.so.4 libxcb-icccm4"
    "libxcb-image.so.0 libxcb-image0"
    "libxcb-keysyms.so.1 libxcb-keysyms1"
    "libxcb-randr.so.0 libxcb-randr0"
    "libxcb-render.so.0 libxcb-render0"
    "libxcb-render-util.so.0 libxcb-render-util0"
    "libxcb-shape.so.0 libxcb-shape0"
    "libxcb-shm.so.0 libxcb-shm0"
    "libxcb-sync.so.1 libxcb-sync1"
    "libxcb-util.so.1 libxcb-util1"
    "libxcb-xfixes.so.0 libxcb-xfixes0"
    "libxcb-xkb.so.1 libxcb-xkb1"
    "libxkbcommon-x11.so.0 libxkbcommon-x11-0"
)
if [[ -n "${DISPLAY:-}" || -n "${WAYLAND_DISPLAY:-}" ]]; then
    REQUIRED+=("${XCB_REQUIRED[@]}")
fi
FONT_PACKAGE=fonts-dejavu-core

ldconfig_bin=$(PATH="$PATH:/sbin:/usr/sbin" command -v ldconfig || true)
if [[ -z "$ldconfig_bin" ]]; then
    echo "system-deps.sh: ldconfig not found; cannot check the libraries Qt needs" >&2
    exit 1
fi
cache=$("$ldconfig_bin" -p)

# Pick the package name this system's apt knows (e.g. libglib2.0-0t64 on Debian 13 / Ubuntu 24.04).
pick_package() {
    local candidate
    if command -v apt-cache >/dev/null 2>&1; then
        for candidate in "$@"; do
            if [[ -n "$(apt-cache policy "$candidate" 2>/dev/null | grep -E '^  Candidate: [^(]')" ]]; then
                echo "$candidate"
                return
            fi
        done
    fi
    echo "${@: -1}"
}

missing=()  # one entry per missing item: its candidate packages, space-separated
for entry in "${REQUIRED[@]}"; do
    read -r soname packages <<<"$entry"
    if ! grep -qF -- "$soname " <<<"$cache"; then
        missing+=("$packages")
    fi
done

have_font=0
if command -v fc-list >/dev/null 2>&1 && [[ -n "$(fc-list 2>/dev/null | head -n 1)" ]]; then
    have_font=1
elif [[ -d /usr/share/fonts ]] && [[ -n "$(find /usr/share/fonts -type f -print -quit 2>/dev/null)" ]]; then
    have_font=1
fi
if [[ $have_font -eq 0 ]]; then
    missing+=("$FONT_PACKAGE")
fi

if [[ ${#missing[@]} -eq 0 ]]; then
    exit 0
fi

resolve_packages() {
    local item
    packages=()
    for item in "${missing[@]}"; do
        # shellcheck disable=SC2086
        packages+=("$(pick_package $item)")
    done
}

if [[ "$(id -u)" -eq 0 ]]; then
    apt-get update
    resolve_packages
    echo "Installing system libraries for Qt: ${packages[*]}" >&2
    DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends "${packages[@]}"
    exit 0
fi

resolve_packages
echo "Missing system libraries for Qt. Run: sudo apt-get install -y ${packages[*]}" >&2
exit 1
