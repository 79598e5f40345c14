# The build id covers the SDK and nothing of the kernel's internals: on a copy of the tree's
# headers, editing an internal header (runtime.hpp) leaves the id as it was, editing an SDK
# header (context.hpp) or the kernel IDL changes it; and the id computed here for the unedited
# tree is the one the build compiled into the kernel.
# Usage: cmake -DSOURCE=<source dir> -DBUILD_INFO=<build>/generated/wysiwyf/build_info.hpp
#              -DCOMPILER=<id-version> -DSCRATCH=<empty folder> -P build_id.cmake
include(${SOURCE}/cmake/WysiwyfBuildId.cmake)
file(REMOVE_RECURSE ${SCRATCH})
file(COPY ${SOURCE}/core/include ${SOURCE}/core/internal DESTINATION ${SCRATCH}/core)
file(COPY ${SOURCE}/interfaces/kernel DESTINATION ${SCRATCH}/interfaces)

function(id_now out)
  wysiwyf_build_id(id ${SCRATCH}/core/include/wysiwyf ${SCRATCH}/interfaces/kernel "${COMPILER}")
  set(${out} ${id} PARENT_SCOPE)
endfunction()

id_now(original)
file(STRINGS ${BUILD_INFO} built REGEX "define WYSIWYF_BUILD_ID")
if(NOT built MATCHES "\"${original}\"")
  message(FATAL_ERROR "the build compiled '${built}', the tree's headers hash to ${original}")
endif()

file(APPEND ${SCRATCH}/core/internal/wysiwyf/runtime.hpp "\n// an edit of a kernel-internal header\n")
id_now(after_internal)
if(NOT after_internal STREQUAL original)
  message(FATAL_ERROR "editing core/internal/wysiwyf/runtime.hpp changed the build id (${original} -> ${after_internal})")
endif()

file(APPEND ${SCRATCH}/core/include/wysiwyf/context.hpp "\n// an edit of an SDK header\n")
id_now(after_sdk)
if(after_sdk STREQUAL original)
  message(FATAL_ERROR "editing core/include/wysiwyf/context.hpp left the build id at ${original}")
endif()

file(GLOB idl ${SCRATCH}/interfaces/kernel/*.idl)
list(GET idl 0 first_idl)
file(APPEND ${first_idl} "\n// an edit of the kernel IDL\n")
id_now(after_idl)
if(after_idl STREQUAL after_sdk)
  message(FATAL_ERROR "editing ${first_idl} left the build id at ${after_sdk}")
endif()
file(REMOVE_RECURSE ${SCRATCH})
message(STATUS "build id ${original}: internal edit kept it, SDK and IDL edits changed it")
