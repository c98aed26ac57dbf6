# cmake -DOUTPUT=FILE.cpp -DNAMESPACE=ns -DFUNCTION=fn -DINPUTS="a;b" -P embed_files.cmake
# Writes FILE.cpp defining `std::string_view ns::fn(std::string_view name)`, which returns the
# bytes of the input whose file name is `name` (an empty view for any other). Run at build time:
# the generated source lives in the build tree only.
set(body "// Generated at build time by cmake/embed_files.cmake; not in the repository.\n")
string(APPEND body "#include <string_view>\n\nnamespace ${NAMESPACE} {\nnamespace {\n")
set(index 0)
set(cases "")
foreach(input IN LISTS INPUTS)
  file(READ "${input}" hex HEX)
  string(REGEX REPLACE "([0-9a-f][0-9a-f])" "'\\\\x\\1'," hex "${hex}")
  get_filename_component(name "${input}" NAME)
  file(SIZE "${input}" size)
  string(APPEND body "constexpr char file_${index}[] = {${hex} 0};\n")
  string(APPEND cases "  if (name == \"${name}\") return {file_${index}, ${size}};\n")
  math(EXPR index "${index} + 1")
endforeach()
string(APPEND body "}  // namespace\n\nstd::string_view ${FUNCTION}(std::string_view name) {\n${cases}  return {};\n}\n\n}  // namespace ${NAMESPACE}\n")
file(WRITE "${OUTPUT}.tmp" "${body}")
file(RENAME "${OUTPUT}.tmp" "${OUTPUT}")
