# Shared by scripts/demo, scripts/test and scripts/bench: package check, configure, build.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
BUILD_DIR="${WYSIWYF_BUILD_DIR:-$ROOT/build}"
JOBS="${WYSIWYF_JOBS:-$(nproc)}"

# Installs the packages of scripts/packages.txt that dpkg does not report as installed.
ensure_packages() {
  local wanted missing=()
  mapfile -t wanted < <(grep -v '^\s*#' "$ROOT/scripts/packages.txt" | sed '/^\s*$/d')
  for p in "${wanted[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  if ((${#missing[@]})); then
    echo "wysiwyf: installing missing Debian packages: ${missing[*]}"
    local sudo=""
    [[ $(id -u) -eq 0 ]] || sudo="sudo"
    $sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
  fi
}

# Configures (once) and builds the tree in $BUILD_DIR.
build_tree() {
  local build_type="${1:-RelWithDebInfo}"
  if [[ ! -f "$BUILD_DIR/build.ninja" ]]; then
    cmake -S "$ROOT" -B "$BUILD_DIR" -G Ninja -DCMAKE_BUILD_TYPE="$build_type"
  fi
  cmake --build "$BUILD_DIR" -j "$JOBS"
}
