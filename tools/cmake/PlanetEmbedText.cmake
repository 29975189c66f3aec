# Text files embedded in the binary (built-in presets, the plot script): no runtime file lookup.
#
# planet_embed_text(OUTPUT <header> NAMESPACE <ns> FILES <file ...> [STRUCT <name>])
# generates <header> with
#   namespace <ns> { struct EmbeddedPresetData { const char* name; const char* text; };
#                    inline constexpr EmbeddedPresetData kEmbedded[] = {{"earth", R"..."}, ...}; }
# where name is the file name without extension and STRUCT renames the struct (default
# EmbeddedPresetData). Regenerated when any file changes.

set(PLANET_EMBED_SCRIPT ${CMAKE_CURRENT_LIST_DIR}/PlanetEmbedTextScript.cmake)

function(planet_embed_text)
  cmake_parse_arguments(ARG "" "OUTPUT;NAMESPACE;STRUCT" "FILES" ${ARGN})
  if(NOT ARG_STRUCT)
    set(ARG_STRUCT EmbeddedPresetData)
  endif()
  set(absFiles)
  foreach(f ${ARG_FILES})
    get_filename_component(abs ${f} ABSOLUTE)
    list(APPEND absFiles ${abs})
  endforeach()
  string(REPLACE ";" "|" fileArg "${absFiles}")
  add_custom_command(
    OUTPUT ${ARG_OUTPUT}
    COMMAND ${CMAKE_COMMAND} -DOUTPUT=${ARG_OUTPUT} -DNAMESPACE=${ARG_NAMESPACE} -DSTRUCT=${ARG_STRUCT} "-DFILES=${fileArg}"
            -P ${PLANET_EMBED_SCRIPT}
    DEPENDS ${absFiles} ${PLANET_EMBED_SCRIPT}
    COMMENT "embedding ${ARG_FILES}"
    VERBATIM)
endfunction()
