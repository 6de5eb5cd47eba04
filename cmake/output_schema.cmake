# The output schema (src/core/output_schema.json, docs/outputs.md): the one list of the columns of
# every CSV file shpb writes. From it, at configure time, the header output_schema.hpp the C++
# writers take their column names from (build/generated/), and its copy beside the report package
# (build/share/shpb/, installed to share/shpb/) that the report reads its names from.
set(SHPB_OUTPUT_SCHEMA ${PROJECT_SOURCE_DIR}/src/core/output_schema.json)
set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${SHPB_OUTPUT_SCHEMA})
file(READ ${SHPB_OUTPUT_SCHEMA} schema)
string(JSON file_count LENGTH "${schema}" files)
math(EXPR last_file "${file_count} - 1")
set(namespaces "")
foreach(f RANGE ${last_file})
  string(JSON id GET "${schema}" files ${f} id)
  string(JSON name GET "${schema}" files ${f} file)
  string(JSON command GET "${schema}" files ${f} command)
  string(APPEND namespaces "\n// ${name} (${command})\nnamespace ${id} {\ninline constexpr char kFile[] = \"${name}\";\n")
  string(JSON column_count LENGTH "${schema}" files ${f} columns)
  math(EXPR last_column "${column_count} - 1")
  foreach(c RANGE ${last_column})
    string(JSON column GET "${schema}" files ${f} columns ${c} name)
    # A name in angle brackets stands for one column per gauge or interface: no constant. A
    # quantile's point ("p2.5") is an underscore in the constant's name (stress_3wave_p2_5_Pa).
    string(REPLACE "." "_" constant "${column}")
    if(constant MATCHES "^[A-Za-z_][A-Za-z0-9_]*$")
      string(APPEND namespaces "inline constexpr char ${constant}[] = \"${column}\";\n")
    endif()
  endforeach()
  string(APPEND namespaces "}  // namespace ${id}\n")
endforeach()
file(CONFIGURE OUTPUT ${PROJECT_BINARY_DIR}/generated/output_schema.hpp CONTENT
"// Generated from src/core/output_schema.json by cmake/output_schema.cmake: edit the schema.
// The column names of the CSV files shpb writes, one namespace per file (docs/outputs.md).
#pragma once

namespace shpb::schema {
@namespaces@
}  // namespace shpb::schema
" @ONLY)
configure_file(${SHPB_OUTPUT_SCHEMA} ${PROJECT_BINARY_DIR}/share/shpb/output_schema.json COPYONLY)
install(FILES ${SHPB_OUTPUT_SCHEMA} DESTINATION ${CMAKE_INSTALL_DATADIR}/shpb)
