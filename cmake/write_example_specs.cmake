# cmake -DNETMC=PATH -DOUT=DIR -P write_example_specs.cmake: the job spec of every preset, as the
# program writes it (`netmc sim --preset NAME --print-spec`), one JSON file per preset in DIR.
execute_process(COMMAND ${NETMC} sim --list-presets OUTPUT_VARIABLE names RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "netmc sim --list-presets failed (${status})")
endif()
file(REMOVE_RECURSE ${OUT})
file(MAKE_DIRECTORY ${OUT})
string(REPLACE "\n" ";" names "${names}")
foreach(name IN LISTS names)
  if(name STREQUAL "")
    continue()
  endif()
  execute_process(COMMAND ${NETMC} sim --preset ${name} --print-spec -q OUTPUT_FILE ${OUT}/${name}.json
    RESULT_VARIABLE status)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "netmc sim --preset ${name} --print-spec failed (${status})")
  endif()
endforeach()
