-- Growing networks from examples (Yu & Steed): one C call grows the whole network; this file
-- reads the example query, checks the geometry arguments and the params jsonb (unknown keys are
-- rejected), and returns edges shaped for a model's axis table. src/core/growth holds the method.

CREATE FUNCTION streetgen._streetgen_grow_example(example_geoms bytea[], example_classes text[], example_ids bigint[],
    region bytea, seeds_x double precision[], seeds_y double precision[], obstacles bytea[],
    epsilon double precision, r double precision, rotation boolean, seed bigint, max_edges integer,
    match_levels boolean, snap double precision, min_angle double precision, candidates integer, existing bytea[],
    OUT id bigint, OUT from_node bigint, OUT to_node bigint, OUT road_class text, OUT origin text, OUT geom bytea)
  RETURNS SETOF record
  LANGUAGE c IMMUTABLE PARALLEL SAFE
  COST 1000000 ROWS 1000
  AS 'MODULE_PATHNAME', '_streetgen_grow_example';

-- The example is a query returning a geometry column geom (LineStrings or MultiLineStrings),
-- optionally road_class (levels: matched separately) and id (kept in origin). It runs with the
-- caller's rights. A model's axes are 'SELECT id, geom, road_class FROM <model>.axis'.
CREATE FUNCTION streetgen.grow_example(example text, region geometry, seeds geometry,
    obstacles geometry DEFAULT NULL, params jsonb DEFAULT '{}', existing text DEFAULT NULL,
    OUT id bigint, OUT from_node bigint, OUT to_node bigint, OUT road_class text, OUT origin text,
    OUT geom geometry)
  RETURNS SETOF record
  LANGUAGE plpgsql VOLATILE
  COST 1000000 ROWS 1000
  SET search_path FROM CURRENT
  SET jit = off
  AS $$
DECLARE
  known constant text[] := ARRAY['candidates', 'epsilon', 'match_levels', 'max_edges', 'min_angle', 'r', 'rotation',
                                 'seed', 'snap'];
  p jsonb := coalesce(params, '{}'::jsonb);
  unknown text[];
  geoms bytea[];
  classes text[];
  ids bigint[];
  srids integer[];
  xs double precision[];
  ys double precision[];
  obstacle_geoms bytea[];
  seed_types text[];
  variant integer;
  existing_geoms bytea[];
  existing_srids integer[];
BEGIN
  IF example IS NULL THEN
    RAISE EXCEPTION 'example must not be null' USING ERRCODE = 'null_value_not_allowed';
  END IF;
  IF region IS NULL THEN
    RAISE EXCEPTION 'region must not be null' USING ERRCODE = 'null_value_not_allowed';
  END IF;
  IF seeds IS NULL THEN
    RAISE EXCEPTION 'seeds must not be null' USING ERRCODE = 'null_value_not_allowed';
  END IF;
  IF jsonb_typeof(p) <> 'object' THEN
    RAISE EXCEPTION 'params must be a json object' USING ERRCODE = 'invalid_parameter_value',
      DETAIL = format('It is a json %s.', jsonb_typeof(p));
  END IF;
  SELECT array_agg(k ORDER BY k) INTO unknown FROM jsonb_object_keys(p) AS k WHERE k <> ALL (known);
  IF unknown IS NOT NULL THEN
    RAISE EXCEPTION 'unknown params key: %', array_to_string(unknown, ', ') USING ERRCODE = 'invalid_parameter_value',
      DETAIL = format('Known keys: %s.', array_to_string(known, ', '));
  END IF;
  IF p ? 'r' AND NOT coalesce((p ->> 'r')::double precision > 0, false) THEN
    RAISE EXCEPTION 'r must be a number > 0' USING ERRCODE = 'invalid_parameter_value',
      DETAIL = format('It is %s.', p -> 'r'), HINT = 'Leave r out for 3 x the mean example segment length.';
  END IF;
  IF p ? 'snap' AND NOT coalesce((p ->> 'snap')::double precision > 0, false) THEN
    RAISE EXCEPTION 'snap must be a number > 0' USING ERRCODE = 'invalid_parameter_value',
      DETAIL = format('It is %s.', p -> 'snap');
  END IF;
  IF NOT coalesce((p ->> 'epsilon')::double precision > 0, NOT p ? 'epsilon') THEN
    RAISE EXCEPTION 'epsilon must be a number > 0 (degrees)' USING ERRCODE = 'invalid_parameter_value',
      DETAIL = format('It is %s.', p -> 'epsilon');
  END IF;
  PERFORM streetgen._require_metric_srid(ST_SRID(region), 'region SRID');
  IF ST_SRID(seeds) <> ST_SRID(region) THEN
    RAISE EXCEPTION 'seeds must have the SRID of the region' USING ERRCODE = 'invalid_parameter_value',
      DETAIL = format('The seeds have SRID %s, the region %s.', ST_SRID(seeds), ST_SRID(region));
  END IF;
  IF obstacles IS NOT NULL AND ST_SRID(obstacles) <> ST_SRID(region) THEN
    RAISE EXCEPTION 'obstacles must have the SRID of the region' USING ERRCODE = 'invalid_parameter_value',
      DETAIL = format('The obstacles have SRID %s, the region %s.', ST_SRID(obstacles), ST_SRID(region));
  END IF;
  SELECT array_agg(DISTINCT ST_GeometryType(d.geom)) INTO seed_types
    FROM ST_Dump(seeds) AS d WHERE ST_GeometryType(d.geom) <> 'ST_Point';
  IF seed_types IS NOT NULL THEN
    RAISE EXCEPTION 'seeds must be points' USING ERRCODE = 'invalid_parameter_value',
      DETAIL = format('They hold %s.', array_to_string(seed_types, ', '));
  END IF;
  SELECT array_agg(ST_X(d.geom) ORDER BY d.path), array_agg(ST_Y(d.geom) ORDER BY d.path) INTO xs, ys
    FROM ST_Dump(seeds) AS d;
  SELECT array_agg(ST_AsEWKB(d.geom) ORDER BY d.path) INTO obstacle_geoms FROM ST_Dump(obstacles) AS d;
  -- road_class and id are optional columns of the example query.
  FOR variant IN 1 .. 4 LOOP
    BEGIN
      EXECUTE format('SELECT array_agg(ST_AsEWKB(q.geom)), array_agg(%s), array_agg(%s), array_agg(DISTINCT ST_SRID(q.geom))
                        FROM (%s) AS q',
                     CASE WHEN variant IN (1, 2) THEN 'q.road_class::text' ELSE 'NULL::text' END,
                     CASE WHEN variant IN (1, 3) THEN 'q.id::bigint' ELSE 'NULL::bigint' END, example)
        INTO geoms, classes, ids, srids;
      EXIT;
    EXCEPTION WHEN undefined_column THEN
      IF variant = 4 THEN
        RAISE EXCEPTION 'the example query must return a geometry column named geom' USING ERRCODE = 'invalid_parameter_value',
          DETAIL = SQLERRM;
      END IF;
    END;
  END LOOP;
  IF existing IS NOT NULL THEN
    BEGIN
      EXECUTE format('SELECT array_agg(ST_AsEWKB(q.geom)), array_agg(DISTINCT ST_SRID(q.geom)) FROM (%s) AS q', existing)
        INTO existing_geoms, existing_srids;
    EXCEPTION WHEN undefined_column THEN
      RAISE EXCEPTION 'the existing query must return a geometry column named geom' USING ERRCODE = 'invalid_parameter_value',
        DETAIL = SQLERRM;
    END;
    existing_srids := array_remove(existing_srids, NULL);
    IF cardinality(existing_srids) > 1 OR existing_srids[1] <> ST_SRID(region) THEN
      RAISE EXCEPTION 'the existing network must have the SRID of the region' USING ERRCODE = 'invalid_parameter_value',
        DETAIL = format('The query returns SRIDs %s, the region has %s.', array_to_string(existing_srids, ', '),
                        ST_SRID(region));
    END IF;
  END IF;
  IF cardinality(array_remove(srids, NULL)) > 1 THEN
    RAISE EXCEPTION 'example edges must share one SRID' USING ERRCODE = 'invalid_parameter_value',
      DETAIL = format('The query returns SRIDs %s.', array_to_string(srids, ', '));
  END IF;
  RETURN QUERY
  SELECT g.id, g.from_node, g.to_node, g.road_class, g.origin, ST_GeomFromEWKB(g.geom)
    FROM streetgen._streetgen_grow_example(
           coalesce(geoms, '{}'), classes, ids, ST_AsEWKB(region), coalesce(xs, '{}'), coalesce(ys, '{}'),
           coalesce(obstacle_geoms, '{}'),
           coalesce((p ->> 'epsilon')::double precision, 30), coalesce((p ->> 'r')::double precision, 0),
           coalesce((p ->> 'rotation')::boolean, true), coalesce((p ->> 'seed')::bigint, 0),
           coalesce((p ->> 'max_edges')::integer, 10000), coalesce((p ->> 'match_levels')::boolean, true),
           coalesce((p ->> 'snap')::double precision, 0), coalesce((p ->> 'min_angle')::double precision, 20),
           coalesce((p ->> 'candidates')::integer, 16), coalesce(existing_geoms, '{}')) AS g;
END
$$;
COMMENT ON FUNCTION streetgen.grow_example(text, geometry, geometry, geometry, jsonb, text) IS
  'Grows a road network inside region from seeds by example (Yu & Steed): node matching of incident edge angles under a rotation within epsilon, neighbourhood matching by weighted line-segment Hausdorff distance within r, copied edges adapted to the region, obstacles, snapping, no crossings and example dead ends; params: epsilon (deg, 30), r (m, 3 x mean example segment), rotation (true), seed (0), max_edges (10000), match_levels (true), snap (m, 0.45 x mean segment), min_angle (deg, 20), candidates (16). existing: a query of a network to extend (column geom), respected and joined but not returned; seeds on its nodes grow it. Returns rows for a model''s axis table';
