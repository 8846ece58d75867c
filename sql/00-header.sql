-- streetgen SQL API, version @STREETGEN_VERSION@.
\echo Use "CREATE EXTENSION streetgen CASCADE" to load this file. \quit

-- Every function below is declared with SET search_path FROM CURRENT, which captures this path:
-- pg_catalog first, pg_temp last (so temporary objects can never shadow ours), and PostGIS's
-- schema wherever PostGIS was installed (the PostgreSQL 15 stand-in for @extschema:postgis@).
SELECT pg_catalog.set_config('search_path',
  pg_catalog.format('pg_catalog, streetgen, %I, pg_temp',
    (SELECT n.nspname FROM pg_catalog.pg_extension e
       JOIN pg_catalog.pg_namespace n ON n.oid = e.extnamespace
      WHERE e.extname = 'postgis')),
  true);

-- The functions that run queries also SET jit = off: their cost is in geometry functions, which
-- JIT does not speed up, while compiling the plans took 300 ms of a 20 ms refresh.

COMMENT ON SCHEMA streetgen IS
  'streetgen: street surfaces from road axes, network growth and network metrics';
GRANT USAGE ON SCHEMA streetgen TO PUBLIC;
