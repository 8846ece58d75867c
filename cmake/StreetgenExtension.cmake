# Generates <name>.control and <name>--<version>.sql (the sql/NN-*.sql fragments in name order)
# and installs both into PostgreSQL's extension directory.
function(streetgen_extension)
  cmake_parse_arguments(EXT "" "NAME;VERSION;CONTROL_IN;SQL_DIR" "" ${ARGN})
  set(control "${CMAKE_BINARY_DIR}/${EXT_NAME}.control")
  set(script "${CMAKE_BINARY_DIR}/${EXT_NAME}--${EXT_VERSION}.sql")
  set(STREETGEN_VERSION ${EXT_VERSION})
  configure_file(${EXT_CONTROL_IN} ${control} @ONLY)

  file(GLOB fragments CONFIGURE_DEPENDS "${EXT_SQL_DIR}/[0-9][0-9]-*.sql")
  list(SORT fragments)
  add_custom_command(
    OUTPUT ${script}
    COMMAND ${CMAKE_COMMAND} -DOUTPUT=${script} -DVERSION=${EXT_VERSION} -DSQL_DIR=${EXT_SQL_DIR}
            -P ${CMAKE_SOURCE_DIR}/cmake/concat_sql.cmake
    DEPENDS ${fragments} ${CMAKE_SOURCE_DIR}/cmake/concat_sql.cmake
    COMMENT "Concatenating the SQL API into ${EXT_NAME}--${EXT_VERSION}.sql")
  add_custom_target(${EXT_NAME}_sql ALL DEPENDS ${script})

  install(FILES ${control} ${script} DESTINATION ${PG_SHAREDIR}/extension)
endfunction()
