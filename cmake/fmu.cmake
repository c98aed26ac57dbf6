# FMUs built here from C (the example of examples/fmu_axis, the test FMUs of tests/fmu): a shared
# object that exports the fmi2 functions, zipped at build time with its modelDescription.xml.
enable_language(C)

# netmc_fmu_binary(<target> SOURCES <file>... [DEFINITIONS <definition>...]): a C11 shared object
# exporting only what its sources mark visible, built warning-free with the project's checks
# spelled out for C; it includes server/fmu/fmi2_api.h from the source root.
function(netmc_fmu_binary name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEFINITIONS" ${ARGN})
  add_library(${name} MODULE ${ARG_SOURCES})
  target_include_directories(${name} PRIVATE ${PROJECT_SOURCE_DIR})
  target_compile_definitions(${name} PRIVATE ${ARG_DEFINITIONS})
  target_link_libraries(${name} PRIVATE m)
  set_target_properties(${name} PROPERTIES C_STANDARD 11 C_STANDARD_REQUIRED ON C_EXTENSIONS OFF
    C_VISIBILITY_PRESET hidden)
  target_compile_options(${name} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wconversion
    $<$<BOOL:${NETMC_WERROR}>:-Werror>)
endfunction()

# netmc_fmu_archive(<fmu file> IDENTIFIER <model identifier> [XML <modelDescription.xml> | NO_XML]
#   [SYMLINK_XML] [BINARY <target> | BINARY_FILE <file>] [COMMENT <text>])
# zips, at build time, the XML as modelDescription.xml (SYMLINK_XML: a symbolic link to it) and
# the binary as binaries/linux64/<identifier>.so into <fmu file>, staged beside it.
function(netmc_fmu_archive fmu)
  cmake_parse_arguments(ARG "NO_XML;SYMLINK_XML" "IDENTIFIER;XML;BINARY;BINARY_FILE;COMMENT" "" ${ARGN})
  get_filename_component(base ${fmu} NAME_WLE)
  get_filename_component(directory ${fmu} DIRECTORY)
  set(stage ${directory}/${base}.stage)
  set(commands COMMAND ${CMAKE_COMMAND} -E rm -rf ${stage}
               COMMAND ${CMAKE_COMMAND} -E make_directory ${stage}/binaries/linux64)
  set(entries)
  set(depends ${ARG_XML})
  if(ARG_SYMLINK_XML)
    list(APPEND commands COMMAND ${CMAKE_COMMAND} -E copy ${ARG_XML} ${stage}/real.xml
                         COMMAND ${CMAKE_COMMAND} -E create_symlink real.xml ${stage}/modelDescription.xml)
    list(APPEND entries modelDescription.xml real.xml)
  elseif(NOT ARG_NO_XML)
    list(APPEND commands COMMAND ${CMAKE_COMMAND} -E copy ${ARG_XML} ${stage}/modelDescription.xml)
    list(APPEND entries modelDescription.xml)
  endif()
  set(binary)
  if(ARG_BINARY)
    set(binary $<TARGET_FILE:${ARG_BINARY}>)
    list(APPEND depends ${ARG_BINARY})
  elseif(ARG_BINARY_FILE)
    set(binary ${ARG_BINARY_FILE})
    list(APPEND depends ${ARG_BINARY_FILE})
  endif()
  if(binary)
    list(APPEND commands COMMAND ${CMAKE_COMMAND} -E copy ${binary}
                                 ${stage}/binaries/linux64/${ARG_IDENTIFIER}.so)
  endif()
  list(APPEND entries binaries)
  if(NOT ARG_COMMENT)
    set(ARG_COMMENT "Zipping FMU ${base}.fmu")
  endif()
  add_custom_command(OUTPUT ${fmu}
    ${commands}
    COMMAND ${CMAKE_COMMAND} -E chdir ${stage} ${CMAKE_COMMAND} -E tar cf ${fmu} --format=zip ${entries}
    DEPENDS ${depends}
    COMMENT "${ARG_COMMENT}"
    VERBATIM)
endfunction()
