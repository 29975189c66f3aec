# Build-time GLSL -> SPIR-V, embedded in the binary as generated C++ headers.
#
# planet_add_shaders(TARGET <name> SOURCES <file.comp|.vert|.frag ...>)
# creates an INTERFACE library <name> whose include directory holds spv/<file>.h
# with `const uint32_t kSpv_<file_with_underscores>[]`. glslangValidator writes a
# depfile for every shader so that editing an #included file rebuilds it.

find_program(GLSLANG_VALIDATOR glslangValidator REQUIRED)

function(planet_add_shaders)
  cmake_parse_arguments(ARG "" "TARGET" "SOURCES" ${ARGN})
  set(genDir ${CMAKE_CURRENT_BINARY_DIR}/generated)
  set(headers)
  foreach(src ${ARG_SOURCES})
    get_filename_component(srcAbs ${src} ABSOLUTE)
    get_filename_component(fileName ${src} NAME)
    string(MAKE_C_IDENTIFIER "kSpv_${fileName}" varName)
    set(out ${genDir}/spv/${fileName}.h)
    add_custom_command(
      OUTPUT ${out}
      COMMAND ${CMAKE_COMMAND} -E make_directory ${genDir}/spv
      COMMAND ${GLSLANG_VALIDATOR} -V --target-env vulkan1.2 --quiet
              -I${CMAKE_CURRENT_SOURCE_DIR}
              --vn ${varName} --depfile ${out}.d -o ${out} ${srcAbs}
      DEPENDS ${srcAbs}
      DEPFILE ${out}.d
      COMMENT "glslang ${fileName}"
      VERBATIM)
    list(APPEND headers ${out})
  endforeach()
  add_custom_target(${ARG_TARGET}_compile DEPENDS ${headers})
  add_library(${ARG_TARGET} INTERFACE)
  add_dependencies(${ARG_TARGET} ${ARG_TARGET}_compile)
  target_include_directories(${ARG_TARGET} INTERFACE ${genDir})
endfunction()
