# The build id: a hash of everything a component library shares with the kernel, namely the SDK
# headers (core/include/wysiwyf), the kernel IDL and the compiler. The kernel's internal headers
# (core/internal) are not part of it: editing them must not invalidate users' components.
# core/CMakeLists.txt calls it; tests/kernel/build_id.cmake checks it (`cmake -P`).
function(wysiwyf_build_id out_var sdk_dir idl_dir compiler_text)
  file(GLOB_RECURSE headers ${sdk_dir}/*.hpp)
  file(GLOB idl ${idl_dir}/*.idl)
  list(SORT headers)
  list(SORT idl)
  set(text "${compiler_text}")
  foreach(f ${headers} ${idl})
    file(READ ${f} content)
    string(APPEND text "${content}")
  endforeach()
  string(SHA1 hash "${text}")
  string(SUBSTRING ${hash} 0 16 id)
  set(${out_var} ${id} PARENT_SCOPE)
endfunction()
