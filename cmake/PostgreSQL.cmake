# Finds the PostgreSQL server development files through pg_config (PG_CONFIG overrides).
find_program(PG_CONFIG NAMES pg_config
             PATHS /usr/lib/postgresql/15/bin
             DOC "pg_config of the PostgreSQL server to build against")
if(NOT PG_CONFIG)
  message(FATAL_ERROR "pg_config not found: install postgresql-server-dev-15 (scripts/install-deps.sh)")
endif()

function(_pg_config_value var flag)
  execute_process(COMMAND ${PG_CONFIG} ${flag} OUTPUT_VARIABLE out OUTPUT_STRIP_TRAILING_WHITESPACE
                  RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${PG_CONFIG} ${flag} failed")
  endif()
  set(${var} "${out}" PARENT_SCOPE)
endfunction()

_pg_config_value(PG_INCLUDEDIR_SERVER --includedir-server)
_pg_config_value(PG_PKGLIBDIR --pkglibdir)
_pg_config_value(PG_SHAREDIR --sharedir)
_pg_config_value(PG_BINDIR --bindir)
_pg_config_value(PG_PGXS --pgxs)
_pg_config_value(PG_VERSION_STRING --version)
get_filename_component(PG_PGXS_DIR "${PG_PGXS}" DIRECTORY)   # .../lib/pgxs/src/makefiles
get_filename_component(PG_PGXS_DIR "${PG_PGXS_DIR}" DIRECTORY) # .../lib/pgxs/src
set(PG_ISOLATION_REGRESS "${PG_PGXS_DIR}/test/isolation/pg_isolation_regress")
message(STATUS "PostgreSQL: ${PG_VERSION_STRING} (${PG_CONFIG})")
