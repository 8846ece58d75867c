CREATE FUNCTION streetgen._streetgen_version(OUT extension text, OUT geos text, OUT cgal text)
  RETURNS record
  LANGUAGE c IMMUTABLE STRICT PARALLEL SAFE
  AS 'MODULE_PATHNAME', '_streetgen_version';

CREATE FUNCTION streetgen.version(OUT extension text, OUT geos text, OUT cgal text, OUT postgis text,
                                  OUT postgresql text)
  RETURNS record
  LANGUAGE sql STABLE PARALLEL SAFE
  SET search_path FROM CURRENT
  AS $$
    SELECT v.extension, v.geos, v.cgal, postgis_lib_version(), current_setting('server_version')
      FROM streetgen._streetgen_version() AS v
  $$;
COMMENT ON FUNCTION streetgen.version() IS
  'Versions of the streetgen module, and of the GEOS, CGAL, PostGIS and PostgreSQL it runs with';
