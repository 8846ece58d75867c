# cmake -P script: concatenates SQL_DIR/NN-*.sql (in name order) into OUTPUT, naming each
# fragment, and substitutes @STREETGEN_VERSION@.
file(GLOB fragments "${SQL_DIR}/[0-9][0-9]-*.sql")
list(SORT fragments)
set(text "-- Generated from sql/*.sql by cmake/concat_sql.cmake. Do not edit.\n")
foreach(fragment IN LISTS fragments)
  get_filename_component(name ${fragment} NAME)
  file(READ ${fragment} body)
  string(APPEND text "\n-- ---- ${name} ----\n${body}")
endforeach()
string(REPLACE "@STREETGEN_VERSION@" "${VERSION}" text "${text}")
file(WRITE ${OUTPUT}.tmp "${text}")
file(RENAME ${OUTPUT}.tmp ${OUTPUT})
