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
  ensure_npm_packages
}

# The npm packages tests use (the official MCAP reader, Foxglove's decoders), into the build
# tree: npm ci from each tests/*/js/package-lock.json into $BUILD_DIR/npm/<area>, again when the
# lock file changes.
ensure_npm_packages() {
  local lock area dest
  if ! command -v npm >/dev/null; then  # (a machine with Node.js from elsewhere has its own npm)
    echo "wysiwyf: installing Debian's nodejs and npm for the tests' JavaScript clients"
    local sudo=""
    [[ $(id -u) -eq 0 ]] || sudo="sudo"
    $sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends nodejs npm
  fi
  for lock in "$ROOT"/tests/*/js/package-lock.json; do
    [[ -f $lock ]] || continue
    area=$(basename "$(dirname "$(dirname "$lock")")")
    dest="$BUILD_DIR/npm/$area"
    if [[ ! -d $dest/node_modules ]] || ! cmp -s "$lock" "$dest/package-lock.json"; then
      mkdir -p "$dest"
      cp "$(dirname "$lock")/package.json" "$lock" "$dest/"
      (cd "$dest" && npm ci --no-audit --no-fund --loglevel=error)
    fi
  done
}
