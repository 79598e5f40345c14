#!/bin/bash
# The two .debs CPack makes from the install: `wysiwyf` holds the apps, the libraries, the
# components, the configuration and the manual with its copyright file, and depends on no -dev
# package and no toolchain; `wysiwyf-dev` holds the headers and the CMake package, and depends on
# `wysiwyf` of this very version and on the toolchain.
# Usage: debian_package.sh <build dir> <scratch dir>
set -euo pipefail
build=$(realpath "$1") scratch=$2
rm -rf "$scratch" && mkdir -p "$scratch" && scratch=$(realpath "$scratch")
cpack -G DEB --config "$build/CPackConfig.cmake" -B "$scratch" >"$scratch/cpack.log" 2>&1 \
  || { cat "$scratch/cpack.log"; exit 1; }
runtime=$(ls "$scratch"/wysiwyf_*.deb) dev=$(ls "$scratch"/wysiwyf-dev_*.deb)
dpkg-deb -I "$runtime"
dpkg-deb -I "$dev"
dpkg-deb -c "$runtime" >"$scratch/runtime.txt"
dpkg-deb -c "$dev" >"$scratch/dev.txt"
has() { grep -q " $2\$" "$scratch/$1.txt" || { echo "the $1 package lacks $2"; exit 1; }; }
for f in ./usr/bin/wysiwyf ./usr/bin/puma-link-emulator ./usr/bin/rdt-emulator ./usr/bin/ur-emulator \
         ./usr/lib/libwysiwyf_core.so ./usr/lib/wysiwyf/wysiwyf_arm_sim.so \
         ./usr/share/wysiwyf/config/pipelines/demo-sim.yaml ./usr/share/doc/wysiwyf/copyright \
         ./usr/share/doc/wysiwyf/README.md ./usr/share/doc/wysiwyf/command-line.md; do
  has runtime "$f"
done
for f in ./usr/lib/cmake/wysiwyf/wysiwyfConfig.cmake ./usr/lib/cmake/wysiwyf/WysiwyfComponent.cmake \
         ./usr/include/wysiwyf/component.hpp ./usr/share/doc/wysiwyf-dev/copyright; do
  has dev "$f"
done
! grep -q " ./usr/include/\| ./usr/lib/cmake/" "$scratch/runtime.txt" || { echo "SDK files in the runtime package"; exit 1; }
! grep -q " ./usr/bin/\| ./usr/lib/wysiwyf/" "$scratch/dev.txt" || { echo "programs or components in the dev package"; exit 1; }
depends=$(dpkg-deb -f "$runtime" Depends)
! grep -qE "(-dev|cmake|g\+\+|fastddsgen)\b" <<<"$depends" || { echo "wysiwyf depends on the toolchain: $depends"; exit 1; }
grep -q "libfastrtps2.9" <<<"$depends" || { echo "wysiwyf does not depend on Fast DDS: $depends"; exit 1; }
dev_depends=$(dpkg-deb -f "$dev" Depends)
version=$(dpkg-deb -f "$runtime" Version)
grep -q "wysiwyf (= $version)" <<<"$dev_depends" || { echo "wysiwyf-dev does not pin wysiwyf $version: $dev_depends"; exit 1; }
grep -q "cmake" <<<"$dev_depends" && grep -q "fastddsgen" <<<"$dev_depends" || { echo "wysiwyf-dev lacks the toolchain"; exit 1; }
echo "$(basename "$runtime"): $(wc -l <"$scratch/runtime.txt") entries; $(basename "$dev"): $(wc -l <"$scratch/dev.txt"), ok"
rm -f "$runtime" "$dev"  # the test needs only their lists
