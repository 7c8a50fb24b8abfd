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
