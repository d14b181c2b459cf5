#!/usr/bin/env bash
# Installs every Debian 12 package listed in scripts/packages.txt that is not
# installed yet. Idempotent: a second run installs nothing and takes seconds.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
mapfile -t wanted < <(grep -vE '^\s*(#|$)' "$here/packages.txt")

install_debian_packages() {
  local missing=() pkg status
  for pkg in "${wanted[@]}"; do
    status=$(dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null || true)
    [[ "$status" == "install ok installed" ]] || missing+=("$pkg")
  done
  # Debian's own nodejs package comes without npm (a separate package); other builds bundle it.
  command -v npm >/dev/null || missing+=(npm)
  if ((${#missing[@]} == 0)); then
    echo "setup: all ${#wanted[@]} packages present"
    return
  fi
  local sudo_cmd=()
  if ((EUID != 0)); then
    command -v sudo >/dev/null || { echo "setup: run as root or install sudo" >&2; exit 1; }
    sudo_cmd=(sudo)
  fi
  echo "setup: installing ${#missing[@]} missing packages: ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  "${sudo_cmd[@]}" apt-get update -qq
  "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
}

# The JavaScript consumers of the glTF export, pinned by tests/consumers/package-lock.json;
# npm ci installs exactly the lock, skipped while node_modules holds that
# lock's install.
install_npm_packages() {
  local dir="$here/../tests/consumers"
  [[ -f "$dir/package-lock.json" ]] || return 0
  cmp -s "$dir/package-lock.json" "$dir/node_modules/.installed-lock.json" 2>/dev/null && return 0
  echo "setup: npm ci in tests/consumers"
  (cd "$dir" && npm ci --no-audit --no-fund --loglevel=error)
  cp "$dir/package-lock.json" "$dir/node_modules/.installed-lock.json"
}

install_debian_packages
install_npm_packages
