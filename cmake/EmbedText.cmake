# cmake -DINPUT=<text file> -DOUTPUT=<cpp> -DSYMBOL=<name> -DNAMESPACE=<ns> -P EmbedText.cmake
# Writes a C++ source defining `std::string_view NAMESPACE::SYMBOL()` holding the file's text,
# so shipped tables are part of the library and the tool runs from any directory.
file(READ "${INPUT}" text)
file(WRITE "${OUTPUT}.tmp"
  "// Generated from ${INPUT} by cmake/EmbedText.cmake; do not edit.\n"
  "#include <string_view>\n"
  "namespace ${NAMESPACE} {\n"
  "std::string_view ${SYMBOL}() {\n"
  "  static constexpr char text[] = R\"embedded(${text})embedded\";\n"
  "  return {text, sizeof(text) - 1};\n"
  "}\n"
  "}  // namespace ${NAMESPACE}\n")
file(COPY_FILE "${OUTPUT}.tmp" "${OUTPUT}" ONLY_IF_DIFFERENT)
file(REMOVE "${OUTPUT}.tmp")
