#!/bin/bash
# The runtime package alone, in a clean root: a root that holds only what the `wysiwyf` .deb
# depends on (its Depends, followed recursively through this machine's installed packages: no
# -dev package, no compiler, no CMake, no fastddsgen) and the package itself, unpacked; in it
# (chroot, its own mount namespace with /proc and /dev), the shipped hello-world runs from the
# installed configuration path, and the command line answers.
# Usage: clean_root_install.sh <build dir> <scratch dir> <domain>
set -euo pipefail
build=$(realpath "$1") scratch=$2 domain=$3
[ "$(id -u)" -eq 0 ] || { echo "chroot needs root: skipped"; exit 77; }
rm -rf "$scratch" && mkdir -p "$scratch" && scratch=$(realpath "$scratch")
trap 'rm -rf "$scratch"' EXIT
cpack -G DEB --config "$build/CPackConfig.cmake" -B "$scratch/pkg" >"$scratch/cpack.log" 2>&1 \
  || { cat "$scratch/cpack.log"; exit 1; }
deb=$(ls "$scratch"/pkg/wysiwyf_*.deb)

# What it depends on, and what that depends on, as installed here.
read -r -a wanted < <(dpkg-deb -f "$deb" Depends | sed 's/([^)]*)//g; s/|/,/g' | tr ',' ' ')
mapfile -t closure < <(apt-cache depends --recurse --installed --no-recommends --no-suggests --no-conflicts \
  --no-breaks --no-replaces --no-enhances "${wanted[@]}" bash dash coreutils | grep -v '^[ <]' | sort -u)
for p in "${closure[@]}"; do
  case $p in
    *-dev | cmake | gcc | gcc-[0-9] | gcc-[0-9][0-9] | g++ | g++-[0-9]* | cpp | cpp-[0-9] | cpp-[0-9][0-9] | \
      fastddsgen) echo "the runtime package pulls in $p"; exit 1 ;;
  esac
done
echo "${#closure[@]} packages in the clean root: ${wanted[*]} and theirs"

root=$scratch/root
mkdir -p "$root"/usr/{bin,sbin,lib,lib64} "$root"/{etc,tmp,proc,dev}
for d in bin sbin lib lib64; do [ -L "/$d" ] && ln -s "usr/$d" "$root/$d"; done
for p in "${closure[@]}"; do
  dpkg-query -W -f='${db:Status-Status}' "$p" 2>/dev/null | grep -q installed || continue
  dpkg -L "$p" | while read -r f; do
    [ -d "$f" ] && [ ! -L "$f" ] && continue
    [ -e "$f" ] || [ -L "$f" ] || continue
    cp -a --parents "$f" "$root/" 2>/dev/null || true
  done
done
# What update-alternatives chose (BLAS, LAPACK): links no package lists, to files that are here.
cp -a /etc/alternatives "$root/etc/"
find /usr/lib /usr/bin -lname '/etc/alternatives/*' 2>/dev/null | while read -r link; do
  if [ -e "$root$(readlink -f "$link")" ]; then cp -a --parents "$link" "$root/"; fi
done
dpkg -x "$deb" "$root"
ldconfig -r "$root"
[ ! -e "$root/usr/include/wysiwyf" ] || { echo "headers in the runtime package"; exit 1; }

run() { unshare -m sh -c "mount -t proc proc '$root/proc' && mount --bind /dev '$root/dev' && chroot '$root' $*"; }
help=$(run /usr/bin/wysiwyf --help)
head -3 <<<"$help"
out=$(cd "$root/tmp" && run "sh -c 'cd /tmp && /usr/bin/wysiwyf run admittance-push.yaml --set clock.pace=0 \
  --set domain=$domain --set dds.transport=loopback'" 2>&1) || { echo "$out"; echo "the hello-world failed"; exit 1; }
echo "$out"
grep -q "^stopped: " <<<"$out" || { echo "no run summary"; exit 1; }
! grep -qiE "(warning|error):" <<<"$out" || { echo "the run warned"; exit 1; }
grep -qE "^physics +admittance_sim +6000 .* ok$" <<<"$out" || { echo "the physics did not run its 6 s"; exit 1; }
echo "the hello-world ran in a root with the runtime package and its $((${#closure[@]})) dependencies only"
