#!/bin/bash
# The out-of-tree path, as a user of an installed WYSIWYF walks it: install into a temporary
# prefix; build `wysiwyf new component`'s scaffold and docs/writing-a-component.md's project (a
# component and a message type of its own) against the installed package alone; run their tests;
# install the project beside WYSIWYF; describe the component, run a pipeline that includes a
# shipped one plus the component, and echo the user's type from another process.
# Usage: out_of_tree.sh <build dir> <source dir> <domain>
# Works in a temporary folder outside both trees (so any path into them is a leak), removed
# when the test passes and kept, with its logs, when it fails.
set -euo pipefail
build=$(realpath "$1") source=$(realpath "$2") domain=$3
scratch=$(mktemp -d "${TMPDIR:-/tmp}/wysiwyf-sdk.XXXXXX")
echo "working in $scratch"
prefix=$scratch/prefix
step() { echo "== $*"; }
fail() { echo "FAILED: $*"; exit 1; }

step "install into $prefix"
cmake --install "$build" --prefix "$prefix" >"$scratch/install.log"
for f in bin/wysiwyf bin/puma-link-emulator bin/rdt-emulator lib/libwysiwyf_core.so lib/libwysiwyf_msgs.so \
         lib/libwysiwyf_kernel_msgs.so lib/libwysiwyf_msgs_idl.so lib/wysiwyf/wysiwyf_arm_sim.so \
         include/wysiwyf/component.hpp include/wysiwyf/build_info.hpp include/wysiwyf/idl/std_msgs.h \
         include/wysiwyf/libs/arm_model/arm_model.hpp include/wysiwyf/libs/safety_gate/safety_gate.hpp \
         lib/libwysiwyf_arm_model.a lib/libwysiwyf_rtde.a share/wysiwyf/config/robots/ur5e.urdf \
         share/wysiwyf/idl/std_msgs.idl share/wysiwyf/config/pipelines/demo-sim.yaml \
         lib/cmake/wysiwyf/wysiwyfConfig.cmake; do
  [ -e "$prefix/$f" ] || fail "the install lacks $f"
done
# The SDK is installed, the kernel's internal headers (core/internal) are not.
for f in runtime.hpp loader.hpp validator.hpp pipeline_spec.hpp dds.hpp context_access.hpp; do
  [ ! -e "$prefix/include/wysiwyf/$f" ] || fail "the install carries the kernel-internal header $f"
done
for f in component.hpp context.hpp harness.hpp component_description.hpp params.hpp port.hpp; do
  [ -e "$prefix/include/wysiwyf/$f" ] || fail "the install lacks the SDK header $f"
done
# Nothing installed may point back into the source or build tree.
if grep -rlI -e "$source" -e "$build" "$prefix/lib/cmake" "$prefix/include" "$prefix/share/wysiwyf/idl"; then
  fail "installed files name the source or build tree (above)"
fi
for f in "$prefix"/bin/* "$prefix"/lib/*.so "$prefix"/lib/wysiwyf/*.so; do
  if readelf -d "$f" | grep -E "R(UN)?PATH" | grep -q -e "$build" -e "$source"; then
    fail "$f has a run path into the build tree"
  fi
done

# A user's environment: the prefix's tools, no WYSIWYF variables.
unset WYSIWYF_COMPONENT_PATH WYSIWYF_CONFIG_PATH
export PATH=$prefix/bin:$PATH
cmake_user() {
  cmake -S "$1" -B "$1/build" -G Ninja -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_BUILD_TYPE=Release \
    -DCMAKE_EXPORT_COMPILE_COMMANDS=ON >"$1.configure.log" 2>&1 || { cat "$1.configure.log"; fail "configuring $1"; }
  cmake --build "$1/build" >"$1.build.log" 2>&1 || { cat "$1.build.log"; fail "building $1"; }
  # The compiler saw nothing of the source or build tree.
  if grep -e "$source/" -e "$build/" "$1/build/compile_commands.json"; then
    fail "$1 was compiled with the source or build tree on its command line (above)"
  fi
}

step "wysiwyf new component gesture_gain: builds and its test passes as written"
wysiwyf new component gesture_gain --dir "$scratch/scaffold"
cmake_user "$scratch/scaffold"
ctest --test-dir "$scratch/scaffold/build" --output-on-failure || fail "the scaffold's test"
# Configured as its comment says, without a build type, it builds optimised with debug information.
cmake -S "$scratch/scaffold" -B "$scratch/scaffold/build-as-written" -G Ninja -DCMAKE_PREFIX_PATH="$prefix" \
  >"$scratch/scaffold.default.log" 2>&1 || { cat "$scratch/scaffold.default.log"; fail "configuring the scaffold as written"; }
grep -q '^CMAKE_BUILD_TYPE:STRING=RelWithDebInfo$' "$scratch/scaffold/build-as-written/CMakeCache.txt" ||
  fail "the scaffold's default build type is not RelWithDebInfo"

step "docs/writing-a-component.md's project, out of tree"
project=$scratch/contacts
python3 "$source/scripts/extract-doc-code" "$source/docs/writing-a-component.md" "$project" \
  CMakeLists.txt example_msgs.idl contact_summary.cpp test_contact_summary.cpp contacts.yaml
cmake_user "$project"
ctest --test-dir "$project/build" --output-on-failure || fail "the walk-through's tests"

step "a lab's arm tool against the installed arm libraries (arm model, safety gate, joint servo, RTDE)"
cp -r "$source/tests/sdk/arm_sdk" "$scratch/arm_sdk"
cmake_user "$scratch/arm_sdk"
"$scratch/arm_sdk/build/lab_arm" | tee "$scratch/lab_arm.txt"
grep -q "^ok$" "$scratch/lab_arm.txt" || fail "the lab's arm tool"

step "installed beside WYSIWYF, the tools find the component and the type with no variable"
cmake --install "$project/build" --prefix "$prefix" >/dev/null
[ -e "$prefix/lib/wysiwyf/wysiwyf_contact_summary.so" ] || fail "the component was not installed"
[ -e "$prefix/lib/wysiwyf/messages/libexample_msgs.so" ] || fail "the message library was not installed"
wysiwyf components describe contact_summary | tee "$scratch/describe.txt"
grep -q "example::msg::ContactSummary" "$scratch/describe.txt" || fail "describe does not show the user's type"
grep -q "contact_force" "$scratch/describe.txt" || fail "describe does not show the parameters"

step "the commands the shipped pipelines' comments name validate as an installed user types them"
(
  cd "$scratch"
  commands=$(grep -rhoE "^#.*wysiwyf (run|validate) [^ ]+\.yaml( --process [a-z]+)?" "$prefix/share/wysiwyf/config" |
    sed -E 's/^#.*wysiwyf (run|validate) //' | sort -u)
  [ "$(wc -l <<<"$commands")" -ge 8 ] || fail "only $(wc -l <<<"$commands") commands in the shipped comments?"
  while read -r file rest; do
    # shellcheck disable=SC2086  # (--process NAME: two words)
    wysiwyf validate "$file" $rest >"$scratch/comment.log" 2>&1 ||
      { cat "$scratch/comment.log"; fail "a shipped comment's 'wysiwyf run $file $rest' does not validate"; }
  done <<<"$commands"
  echo "ok: $(wc -l <<<"$commands") commands"
)

step "a pipeline including a shipped one plus the user's component, echoed from another process"
cd "$scratch"
wysiwyf validate "$project/contacts.yaml" --set domain="$domain"
wysiwyf topic echo example/contacts --domain "$domain" --transport local --count 2 --timeout 30 \
  >"$scratch/echo.txt" 2>&1 &
echo_pid=$!
wysiwyf record example/contacts -o "$scratch/contacts.mcap" --domain "$domain" --transport local --no-progress \
  >"$scratch/record.txt" 2>&1 &
record_pid=$!
trap 'kill $echo_pid $record_pid 2>/dev/null || true' EXIT
sleep 1
wysiwyf run "$project/contacts.yaml" --set domain="$domain" --no-progress --start-after 1 | tee "$scratch/run.txt"
wait $echo_pid || { cat "$scratch/echo.txt"; fail "topic echo of the user's type"; }
kill -INT $record_pid; wait $record_pid || { cat "$scratch/record.txt"; fail "record of the user's type"; }
cat "$scratch/record.txt"
# The user's IDL, installed beside the message library, is the recorded schema.
grep -q "no IDL defines" "$scratch/record.txt" && fail "the recorder found no IDL for the user's type"
grep -aq "struct ContactSummary" "$scratch/contacts.mcap" || fail "the recording lacks the user's IDL as schema"
cat "$scratch/echo.txt"
grep -q "example::msg::ContactSummary" "$scratch/echo.txt" || fail "echo did not name the type"
grep -q "^contact: 2" "$scratch/echo.txt" || fail "echo did not print the second contact"
grep -q "^peak_force: 0.5" "$scratch/echo.txt" || fail "echo did not print the peak force (0.5 N pushes)"
grep -q "^contacts .*contact_summary .* ok" "$scratch/run.txt" || fail "the run's table lacks the user's component"
rm -rf "$scratch"
echo "out-of-tree path: ok"
