# Build-time GLSL -> SPIR-V, embedded in the binary as generated C++ headers.
#
# planet_add_shaders(TARGET <name> SOURCES <file.comp|.vert|.frag ...>
#                    [VARIANTS <file>:<suffix>:<MACRO>[+<MACRO>...] ...])
# creates an INTERFACE library <name> whose include directory holds spv/<file>.h
# with `const uint32_t kSpv_<file_with_underscores>[]`. Each VARIANTS entry compiles
# <file> once more with each MACRO defined, as spv/<stem>_<suffix>.<ext>.h with
# kSpv_<stem>_<suffix>_<ext>[] (a shader whose text differs by an #ifdef only). glslangValidator
# writes a depfile for every shader so that editing an #included file rebuilds it.

find_program(GLSLANG_VALIDATOR glslangValidator REQUIRED)

function(planet_add_shaders)
  cmake_parse_arguments(ARG "" "TARGET" "SOURCES;VARIANTS" ${ARGN})
  set(genDir ${CMAKE_CURRENT_BINARY_DIR}/generated)
  set(headers)
  # One glslang run: <src> compiled as spv/<fileName>.h, with the extra arguments ARGN.
  macro(planet_compile_shader src fileName)
    get_filename_component(srcAbs ${src} ABSOLUTE)
    string(MAKE_C_IDENTIFIER "kSpv_${fileName}" varName)
    set(out ${genDir}/spv/${fileName}.h)
    add_custom_command(
      OUTPUT ${out}
      COMMAND ${CMAKE_COMMAND} -E make_directory ${genDir}/spv
      COMMAND ${GLSLANG_VALIDATOR} -V --target-env vulkan1.2 --quiet
              -I${CMAKE_CURRENT_SOURCE_DIR} ${ARGN}
              --vn ${varName} --depfile ${out}.d -o ${out} ${srcAbs}
      DEPENDS ${srcAbs}
      DEPFILE ${out}.d
      COMMENT "glslang ${fileName}"
      VERBATIM)
    list(APPEND headers ${out})
  endmacro()
  foreach(src ${ARG_SOURCES})
    get_filename_component(fileName ${src} NAME)
    planet_compile_shader(${src} ${fileName})
  endforeach()
  foreach(variant ${ARG_VARIANTS})
    string(REPLACE ":" ";" parts ${variant})
    list(LENGTH parts partCount)
    if(NOT partCount EQUAL 3)
      message(FATAL_ERROR "planet_add_shaders: variant '${variant}' is not <file>:<suffix>:<MACRO>[+<MACRO>...]")
    endif()
    list(GET parts 0 src)
    list(GET parts 1 suffix)
    list(GET parts 2 macroNames)
    get_filename_component(stem ${src} NAME_WE)
    get_filename_component(ext ${src} LAST_EXT)
    # Several macros joined by '+': each defined.
    string(REPLACE "+" ";" macroList ${macroNames})
    list(TRANSFORM macroList PREPEND "-D")
    planet_compile_shader(${src} ${stem}_${suffix}${ext} ${macroList})
  endforeach()
  add_custom_target(${ARG_TARGET}_compile DEPENDS ${headers})
  add_library(${ARG_TARGET} INTERFACE)
  add_dependencies(${ARG_TARGET} ${ARG_TARGET}_compile)
  target_include_directories(${ARG_TARGET} INTERFACE ${genDir})
endfunction()
