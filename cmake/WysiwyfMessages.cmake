# wysiwyf_add_messages(<name> IDL <files...> TYPES <ns::Type...> [INCLUDE_DIRS <dirs>] [LINK <targets>]
#                      [OUTPUT_DIR <dir>])
# A message library of one's own: fastddsgen compiles the IDL files (which may include ours:
# #include "std_msgs.idl", "geometry_msgs.idl") into the shared library <name>, with
#  - "<name>/messages.hpp": the generated structs, each of TYPES usable on ports
#    (ctx.input<lab::msg::Gesture>(...)); link the target <name> and include it;
#  - the type objects of every type (fastddsgen -typeobject) and an entry point, so the wysiwyf
#    tools load the library from ${CMAKE_BINARY_DIR}/lib/wysiwyf/messages (installed:
#    <libdir>/wysiwyf/messages) and print samples of these types (`wysiwyf topic echo`);
#  - the IDL files beside it (messages/idl/), the schema `wysiwyf record` and `bridge` give.
# OUTPUT_DIR puts the library elsewhere and does not install it (test-only types).
# wysiwyf_fastddsgen(<idl> OUT_DIR <dir> WORK_DIR <dir> [INCLUDE_DIRS <dirs>] SOURCES <var> HEADERS <var>)
# One IDL file through fastddsgen at build time: its struct, TypeSupport and type-object code in
# OUT_DIR; the .cxx files appended to <SOURCES var>, the headers to <HEADERS var>. Shared by
# wysiwyf_add_messages() and this tree's wysiwyf_idl_library().
function(wysiwyf_fastddsgen idl)
  cmake_parse_arguments(ARG "" "OUT_DIR;WORK_DIR;SOURCES;HEADERS" "INCLUDE_DIRS" ${ARGN})
  get_filename_component(base ${idl} NAME_WE)
  get_filename_component(abs ${idl} ABSOLUTE)
  set(include_flags)
  foreach(dir ${ARG_INCLUDE_DIRS})
    list(APPEND include_flags -I ${dir})
  endforeach()
  set(generated ${base}.h ${base}.cxx ${base}PubSubTypes.h ${base}PubSubTypes.cxx ${base}TypeObject.h
                ${base}TypeObject.cxx)
  list(TRANSFORM generated PREPEND ${ARG_OUT_DIR}/ OUTPUT_VARIABLE outs)
  # fastddsgen also writes the code of every IDL the file includes: it runs in a folder of its own
  # and only this file's code is copied out (the included files' code is in their own libraries;
  # rewriting, say, std_msgs.h in the shared folder would relink everything on the next build).
  set(work ${ARG_WORK_DIR}/${base})
  set(work_outs ${work}/${base}.h ${work}/${base}.cxx ${work}/${base}PubSubTypes.h ${work}/${base}PubSubTypes.cxx
                ${work}/typeobject/${base}TypeObject.h ${work}/typeobject/${base}TypeObject.cxx)
  add_custom_command(
    OUTPUT ${outs}
    COMMAND ${CMAKE_COMMAND} -E make_directory ${work}/typeobject ${ARG_OUT_DIR}
    # Two passes: the structs without -typeobject (with it, every constructor registers every
    # type in Fast DDS's factory: a lock and map lookups per message on the tick path), and
    # the type objects alone, registered once by the tools that read types at run time.
    COMMAND ${FASTDDSGEN} -replace -cs -d ${work} ${include_flags} ${abs} > ${work}.fastddsgen.log
    COMMAND ${FASTDDSGEN} -replace -cs -typeobject -d ${work}/typeobject ${include_flags} ${abs} >> ${work}.fastddsgen.log
    COMMAND ${CMAKE_COMMAND} -E copy ${work_outs} ${ARG_OUT_DIR}
    DEPENDS ${abs}
    COMMENT "fastddsgen ${base}.idl"
    VERBATIM)
  list(FILTER outs INCLUDE REGEX "\\.cxx$")
  set(${ARG_SOURCES} ${${ARG_SOURCES}} ${outs} PARENT_SCOPE)
  set(${ARG_HEADERS} ${${ARG_HEADERS}} ${ARG_OUT_DIR}/${base}.h ${ARG_OUT_DIR}/${base}PubSubTypes.h
                     ${ARG_OUT_DIR}/${base}TypeObject.h PARENT_SCOPE)
endfunction()

function(wysiwyf_add_messages name)
  cmake_parse_arguments(ARG "" "OUTPUT_DIR" "IDL;TYPES;INCLUDE_DIRS;LINK" ${ARGN})
  if(NOT ARG_IDL OR NOT ARG_TYPES)
    message(FATAL_ERROR "wysiwyf_add_messages(${name}): expected IDL <files...> and TYPES <ns::Type...> (the "
                        "structs used on ports, with their modules, e.g. TYPES lab::msg::Gesture)")
  endif()
  if(NOT FASTDDSGEN)
    message(FATAL_ERROR "wysiwyf_add_messages(${name}): fastddsgen not found (apt install fastddsgen)")
  endif()
  set(out ${CMAKE_CURRENT_BINARY_DIR}/${name})
  set(sources)
  set(headers)
  set(idl_includes)
  set(registrations)
  set(type_object_includes)
  foreach(idl ${ARG_IDL})
    get_filename_component(base ${idl} NAME_WE)
    wysiwyf_fastddsgen(${idl} OUT_DIR ${out} WORK_DIR ${CMAKE_CURRENT_BINARY_DIR}/fastddsgen/${name}
                       INCLUDE_DIRS ${ARG_INCLUDE_DIRS} ${WYSIWYF_IDL_DIRS} SOURCES sources HEADERS headers)
    string(APPEND idl_includes "#include \"${base}.h\"\n")
    string(APPEND registrations "  register${base}Types();\n")
    string(APPEND type_object_includes "#include \"${base}PubSubTypes.h\"\n#include \"${base}TypeObject.h\"\n")
  endforeach()
  set(traits)
  set(supports)
  foreach(type ${ARG_TYPES})
    string(FIND ${type} "::" last REVERSE)
    if(last LESS 1)
      message(FATAL_ERROR "wysiwyf_add_messages(${name}): TYPES ${type}: expected the struct with its module, "
                          "like lab::msg::Gesture")
    endif()
    string(SUBSTRING ${type} 0 ${last} ns)
    math(EXPR first "${last} + 2")
    string(SUBSTRING ${type} ${first} -1 struct)
    string(APPEND traits "WYSIWYF_MESSAGE(${ns}, ${struct})\n")
    string(APPEND supports "WYSIWYF_MESSAGE_TYPE_SUPPORT(${ns}, ${struct})\n")
  endforeach()
  file(CONFIGURE OUTPUT ${out}/messages.hpp CONTENT
"#pragma once
// Generated by wysiwyf_add_messages(${name}): the types of ${ARG_IDL}, usable on ports.
#include \"wysiwyf/message_traits.hpp\"
${idl_includes}
${traits}")
  file(CONFIGURE OUTPUT ${out}/messages.cpp CONTENT
"// Generated by wysiwyf_add_messages(${name}): the ports' type support, and the entry point the
// wysiwyf tools call after loading this library (it registers every type's type object).
#include \"${name}/messages.hpp\"
#include \"wysiwyf/message_type_support.hpp\"
${type_object_includes}
${supports}
extern \"C\" __attribute__((visibility(\"default\"))) const char* wysiwyf_message_library() {
${registrations}  return \"${name}\";
}
")
  add_library(${name} SHARED ${sources} ${out}/messages.cpp)
  target_include_directories(${name} PUBLIC $<BUILD_INTERFACE:${CMAKE_CURRENT_BINARY_DIR}> $<BUILD_INTERFACE:${out}>
                                            $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}/${name}>)
  target_link_libraries(${name} PUBLIC wysiwyf::core wysiwyf::kernel_msgs wysiwyf::msgs_idl ${ARG_LINK})
  if(NOT ARG_OUTPUT_DIR)
    set(ARG_OUTPUT_DIR ${CMAKE_BINARY_DIR}/lib/wysiwyf/messages)
    install(TARGETS ${name} LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}/wysiwyf/messages)
    install(FILES ${headers} ${out}/messages.hpp DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/${name}/${name}
            COMPONENT dev)  # (what builds against the type; the library and IDL are what runs)
    install(FILES ${ARG_IDL} DESTINATION ${CMAKE_INSTALL_LIBDIR}/wysiwyf/messages/idl)
  endif()
  # The IDL beside the library (messages/idl/): the recorder and the bridge give it as the
  # types' schema (idl_search_dirs()), so Foxglove and MCAP readers decode them too.
  set(idl_copies)
  foreach(idl ${ARG_IDL})
    get_filename_component(abs ${idl} ABSOLUTE)
    list(APPEND idl_copies ${abs})
  endforeach()
  add_custom_command(TARGET ${name} POST_BUILD
    COMMAND ${CMAKE_COMMAND} -E make_directory ${ARG_OUTPUT_DIR}/idl
    COMMAND ${CMAKE_COMMAND} -E copy ${idl_copies} ${ARG_OUTPUT_DIR}/idl
    VERBATIM)
  set_target_properties(${name} PROPERTIES
    LIBRARY_OUTPUT_DIRECTORY ${ARG_OUTPUT_DIR}
    INSTALL_RPATH "$ORIGIN/../..${WYSIWYF_LIBRARY_DIR_RPATH}")
  target_compile_options(${name} PRIVATE -w)  # generated code is not ours to warn about
endfunction()
