#!/bin/bash
# The .deb CPack makes from the install: it builds, and its file list holds the apps, the
# libraries, the components and the CMake package config under /usr.
# Usage: debian_package.sh <build dir> <scratch dir>
set -euo pipefail
build=$(realpath "$1") scratch=$2
rm -rf "$scratch" && mkdir -p "$scratch" && scratch=$(realpath "$scratch")
cpack -G DEB --config "$build/CPackConfig.cmake" -B "$scratch" >"$scratch/cpack.log" 2>&1 \
  || { cat "$scratch/cpack.log"; exit 1; }
deb=$(ls "$scratch"/wysiwyf_*.deb)
dpkg-deb -I "$deb"
dpkg-deb -c "$deb" >"$scratch/files.txt"
for f in ./usr/bin/wysiwyf ./usr/bin/puma-link-emulator ./usr/bin/rdt-emulator ./usr/lib/libwysiwyf_core.so \
         ./usr/lib/wysiwyf/wysiwyf_arm_sim.so ./usr/lib/cmake/wysiwyf/wysiwyfConfig.cmake \
         ./usr/lib/cmake/wysiwyf/WysiwyfComponent.cmake ./usr/include/wysiwyf/component.hpp \
         ./usr/share/wysiwyf/config/pipelines/demo-sim.yaml; do
  grep -q " $f\$" "$scratch/files.txt" || { echo "the package lacks $f"; exit 1; }
done
echo "$(basename "$deb"): $(wc -l <"$scratch/files.txt") entries, ok"
rm -f "$deb"  # 100 MB: the test needs only its file list
