CREATE FUNCTION streetgen._streetgen_roadway_borders(axis bytea, roadway_width double precision,
                                                     OUT side text, OUT border bytea)
  RETURNS SETOF record
  LANGUAGE c IMMUTABLE PARALLEL SAFE
  COST 100 ROWS 2
  AS 'MODULE_PATHNAME', '_streetgen_roadway_borders';

CREATE FUNCTION streetgen.roadway_borders(axis geometry, roadway_width double precision,
                                          OUT side text, OUT geom geometry)
  RETURNS SETOF record
  LANGUAGE plpgsql STABLE PARALLEL SAFE
  COST 100 ROWS 2
  SET search_path FROM CURRENT
  AS $$
BEGIN
  IF axis IS NULL THEN
    RAISE EXCEPTION 'axis must not be null' USING ERRCODE = 'null_value_not_allowed';
  END IF;
  PERFORM streetgen._require_metric_srid(ST_SRID(axis), 'axis SRID');
  RETURN QUERY
    SELECT b.side, ST_GeomFromEWKB(b.border)
      FROM streetgen._streetgen_roadway_borders(ST_AsEWKB(axis), roadway_width) AS b;
END
$$;
COMMENT ON FUNCTION streetgen.roadway_borders(geometry, double precision) IS
  'Left and right roadway borders of an axis: offset curves at half the width (metres), in the axis direction';
