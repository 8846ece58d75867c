-- Growing networks: example-based (Yu & Steed), blended examples, direction control by a guide
-- curve, and parametric growth (Teng & Bidarra), alone or as the fallback of example growth. One
-- C call grows the whole network; this file reads the example queries (or models), checks the
-- geometry arguments and the params jsonb (unknown keys are rejected), and returns edges shaped
-- for a model's axis table. src/core/growth holds the method.

CREATE FUNCTION streetgen._streetgen_grow_example(example_geoms bytea[], example_classes text[], example_ids bigint[],
    example_sources integer[], region bytea, seeds_x double precision[], seeds_y double precision[], obstacles bytea[],
    epsilon double precision, r double precision, rotation boolean, seed bigint, max_edges integer,
    match_levels boolean, snap double precision, min_angle double precision, candidates integer, existing bytea[],
    parametric boolean, fallback boolean, keep_frame boolean, coherence double precision,
    crop_margin double precision, fill boolean, length double precision, length_deviation double precision,
    min_length double precision, min_degree integer, max_degree integer, angle_deviation double precision,
    road_class text, guide bytea, guide_reach double precision, blend text, blend_angle double precision,
    blend_x double precision[], blend_y double precision[], blend_sigma double precision,
    weights_grid double precision[], weights_values double precision[], direction_grid double precision[],
    direction_values double precision[],
    OUT id bigint, OUT from_node bigint, OUT to_node bigint, OUT road_class text, OUT origin text, OUT geom bytea)
  RETURNS SETOF record
  LANGUAGE c IMMUTABLE PARALLEL SAFE
  COST 1000000 ROWS 1000
  AS 'MODULE_PATHNAME', '_streetgen_grow_example';

-- A control raster (weights for blending, or a direction field) as plain arrays for the C call:
-- grid = [upper-left x, upper-left y, scale x, scale y, width, height, bands] and every band's
-- values as ST_DumpValues gives them (rows from the upper-left one, NULL for nodata): one band's
-- 2-D array as it is, several bands stacked into a 3-D one (no unnest: it tripled the time on a
-- 9-million-cell raster). The
-- raster must share the region's SRID, overlap it, have no skew, and stay below 16 million values
-- (clip it to the region first: ST_Clip). Sampling (bilinear) happens in C++.
CREATE FUNCTION streetgen._control_raster(rast raster, what text, region geometry,
    OUT grid double precision[], OUT vals double precision[])
  LANGUAGE plpgsql STABLE
  SET search_path FROM CURRENT
  AS $$
DECLARE
  m record;
BEGIN
  IF rast IS NULL THEN
    RETURN;
  END IF;
  IF ST_IsEmpty(rast) OR ST_NumBands(rast) = 0 THEN
    RAISE EXCEPTION '% raster is empty', what USING ERRCODE = 'invalid_parameter_value',
      DETAIL = format('It has %s x %s cells and %s band(s).', ST_Width(rast), ST_Height(rast), ST_NumBands(rast));
  END IF;
  IF ST_SRID(rast) <> ST_SRID(region) THEN
    RAISE EXCEPTION '% raster must have the SRID of the region', what USING ERRCODE = 'invalid_parameter_value',
      DETAIL = format('The raster has SRID %s, the region %s.', ST_SRID(rast), ST_SRID(region)),
      HINT = 'ST_Transform the raster to the region''s SRID.';
  END IF;
  m := ST_MetaData(rast);
  IF m.skewx <> 0 OR m.skewy <> 0 THEN
    RAISE EXCEPTION '% raster must not be skewed', what USING ERRCODE = 'invalid_parameter_value',
      DETAIL = format('Its skew is (%s, %s).', m.skewx, m.skewy), HINT = 'ST_Rescale or ST_Transform it onto a north-up grid.';
  END IF;
  IF NOT ST_Intersects(ST_Envelope(rast), region) THEN
    RAISE EXCEPTION '% raster does not overlap the region', what USING ERRCODE = 'invalid_parameter_value',
      DETAIL = format('The raster covers %s, the region %s.', ST_AsText(ST_Envelope(rast)), ST_AsText(ST_Envelope(region)));
  END IF;
  IF m.width::bigint * m.height * m.numbands > 16777216 THEN
    RAISE EXCEPTION '% raster is too large', what USING ERRCODE = 'invalid_parameter_value',
      DETAIL = format('It holds %s x %s cells in %s band(s), more than 16777216 values.', m.width, m.height, m.numbands),
      HINT = 'ST_Clip it to the region or ST_Rescale it to larger cells.';
  END IF;
  grid := ARRAY[m.upperleftx, m.upperlefty, m.scalex, m.scaley, m.width, m.height, m.numbands]::double precision[];
  IF m.numbands = 1 THEN
    vals := ST_DumpValues(rast, 1, true);
  ELSE
    SELECT array_agg(d.valarray ORDER BY d.nband) INTO vals FROM ST_DumpValues(rast, NULL::integer[], true) AS d;
  END IF;
END
$$;

-- The one reader and checker behind grow_example (one or several examples) and grow_parametric
-- (examples NULL). An example is a query returning geom (LineStrings or MultiLineStrings),
-- optionally road_class and id, or the name of a model (its axes). Queries run with the caller's
-- rights.
CREATE FUNCTION streetgen._grow(examples text[], region geometry, seeds geometry, obstacles geometry, params jsonb,
    existing text, guide geometry, direction raster DEFAULT NULL, weights raster DEFAULT NULL,
    OUT id bigint, OUT from_node bigint, OUT to_node bigint, OUT road_class text, OUT origin text,
    OUT geom geometry)
  RETURNS SETOF record
  LANGUAGE plpgsql VOLATILE
  COST 1000000 ROWS 1000
  SET search_path FROM CURRENT
  SET jit = off
  AS $$
DECLARE
  parametric constant boolean := examples IS NULL;
  shared constant text[] := ARRAY['fill', 'guide_reach', 'max_edges', 'min_angle', 'rotation', 'seed', 'snap'];
  known constant text[] := CASE WHEN parametric
    THEN shared || ARRAY['angle_deviation', 'length', 'length_deviation', 'max_degree', 'min_degree', 'min_length',
                         'road_class']
    ELSE shared || ARRAY['blend', 'blend_angle', 'blend_points', 'blend_sigma', 'candidates', 'coherence',
                         'crop_margin', 'epsilon', 'fallback', 'keep_frame', 'match_levels', 'r'] END;
  p jsonb := coalesce(params, '{}'::jsonb);
  geoms bytea[] := '{}';
  classes text[] := '{}';
  ids bigint[] := '{}';
  sources integer[] := '{}';
  srids integer[] := '{}';
  q_geoms bytea[];
  q_classes text[];
  q_ids bigint[];
  q_srids integer[];
  query text;
  k integer;
  xs double precision[];
  ys double precision[];
  bxs double precision[];
  bys double precision[];
  obstacle_geoms bytea[];
  seed_types text[];
  variant integer;
  existing_geoms bytea[];
  existing_srids integer[];
  w record;
  dir record;
BEGIN
  IF NOT parametric AND (cardinality(examples) = 0 OR array_position(examples, NULL) IS NOT NULL) THEN
    RAISE EXCEPTION 'example must not be null' USING ERRCODE = 'null_value_not_allowed';
  END IF;
  IF region IS NULL THEN
    RAISE EXCEPTION 'region must not be null' USING ERRCODE = 'null_value_not_allowed';
  END IF;
  IF seeds IS NULL THEN
    RAISE EXCEPTION 'seeds must not be null' USING ERRCODE = 'null_value_not_allowed';
  END IF;
  PERFORM streetgen._require_params(p, known);
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
  IF p ? 'coherence' AND NOT coalesce((p ->> 'coherence')::double precision BETWEEN 0 AND 1, false) THEN
    RAISE EXCEPTION 'coherence must be a number in [0, 1]' USING ERRCODE = 'invalid_parameter_value',
      DETAIL = format('It is %s.', p -> 'coherence');
  END IF;
  IF p ? 'crop_margin' AND NOT coalesce((p ->> 'crop_margin')::double precision >= 0, false) THEN
    RAISE EXCEPTION 'crop_margin must be a number >= 0' USING ERRCODE = 'invalid_parameter_value',
      DETAIL = format('It is %s.', p -> 'crop_margin');
  END IF;
  IF p ? 'guide_reach' AND NOT coalesce((p ->> 'guide_reach')::double precision > 0, false) THEN
    RAISE EXCEPTION 'guide_reach must be a number > 0' USING ERRCODE = 'invalid_parameter_value',
      DETAIL = format('It is %s.', p -> 'guide_reach'), HINT = 'Leave it out for a guide that acts everywhere.';
  END IF;
  IF p ? 'blend' AND (jsonb_typeof(p -> 'blend') <> 'string' OR p ->> 'blend' NOT IN ('gradient', 'points')) THEN
    RAISE EXCEPTION 'blend must be ''gradient'' or ''points''' USING ERRCODE = 'invalid_parameter_value',
      DETAIL = format('It is %s.', p -> 'blend');
  END IF;
  IF p ? 'blend_sigma' AND NOT coalesce((p ->> 'blend_sigma')::double precision > 0, false) THEN
    RAISE EXCEPTION 'blend_sigma must be a number > 0' USING ERRCODE = 'invalid_parameter_value',
      DETAIL = format('It is %s.', p -> 'blend_sigma');
  END IF;
  IF p ? 'blend_points' THEN
    IF jsonb_typeof(p -> 'blend_points') <> 'array' OR EXISTS (
         SELECT 1 FROM jsonb_array_elements(p -> 'blend_points') AS e
          WHERE jsonb_typeof(e) <> 'array' OR jsonb_array_length(e) <> 2 OR jsonb_typeof(e -> 0) <> 'number'
             OR jsonb_typeof(e -> 1) <> 'number') THEN
      RAISE EXCEPTION 'blend_points must be an array of [x, y] pairs' USING ERRCODE = 'invalid_parameter_value',
        DETAIL = format('It is %s.', p -> 'blend_points'), HINT = 'One point per example, in the region''s SRID.';
    END IF;
    SELECT array_agg((e ->> 0)::double precision ORDER BY n), array_agg((e ->> 1)::double precision ORDER BY n)
      INTO bxs, bys FROM jsonb_array_elements(p -> 'blend_points') WITH ORDINALITY AS t(e, n);
  END IF;
  IF p ->> 'blend' = 'points' AND NOT p ? 'blend_points' THEN
    RAISE EXCEPTION 'blend ''points'' needs blend_points' USING ERRCODE = 'invalid_parameter_value',
      HINT = 'Give one [x, y] per example.';
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
  IF guide IS NOT NULL AND ST_SRID(guide) <> ST_SRID(region) THEN
    RAISE EXCEPTION 'guide must have the SRID of the region' USING ERRCODE = 'invalid_parameter_value',
      DETAIL = format('The guide has SRID %s, the region %s.', ST_SRID(guide), ST_SRID(region));
  END IF;
  IF weights IS NOT NULL AND (parametric OR cardinality(examples) < 2) THEN
    RAISE EXCEPTION 'weights need several examples' USING ERRCODE = 'invalid_parameter_value',
      DETAIL = format('There are %s.', coalesce(cardinality(examples), 0));
  END IF;
  IF weights IS NOT NULL AND ST_NumBands(weights) <> cardinality(examples) THEN
    RAISE EXCEPTION 'weights raster must have one band per example' USING ERRCODE = 'invalid_parameter_value',
      DETAIL = format('It has %s band(s) for %s examples.', ST_NumBands(weights), cardinality(examples)),
      HINT = 'Band k is the weight of example k (ST_AddBand).';
  END IF;
  IF direction IS NOT NULL AND ST_NumBands(direction) > 1 THEN
    RAISE EXCEPTION 'direction raster must have one band' USING ERRCODE = 'invalid_parameter_value',
      DETAIL = format('It has %s.', ST_NumBands(direction)), HINT = 'ST_Band(rast, n) picks one.';
  END IF;
  w := streetgen._control_raster(weights, 'weights', region);
  IF weights IS NOT NULL AND EXISTS (SELECT 1 FROM unnest(w.vals) AS v WHERE v < 0 OR v = 'infinity') THEN
    RAISE EXCEPTION 'weights raster must hold finite weights >= 0' USING ERRCODE = 'invalid_parameter_value',
      DETAIL = format('It holds %s.', (SELECT min(v) FROM unnest(w.vals) AS v WHERE v < 0 OR v = 'infinity')),
      HINT = 'Nodata cells mean no control there.';
  END IF;
  dir := streetgen._control_raster(direction, 'direction', region);
  SELECT array_agg(DISTINCT ST_GeometryType(d.geom)) INTO seed_types
    FROM ST_Dump(seeds) AS d WHERE ST_GeometryType(d.geom) <> 'ST_Point';
  IF seed_types IS NOT NULL THEN
    RAISE EXCEPTION 'seeds must be points' USING ERRCODE = 'invalid_parameter_value',
      DETAIL = format('They hold %s.', array_to_string(seed_types, ', '));
  END IF;
  SELECT array_agg(ST_X(d.geom) ORDER BY d.path), array_agg(ST_Y(d.geom) ORDER BY d.path) INTO xs, ys
    FROM ST_Dump(seeds) AS d;
  SELECT array_agg(ST_AsEWKB(d.geom) ORDER BY d.path) INTO obstacle_geoms FROM ST_Dump(obstacles) AS d;
  FOR k IN 1 .. coalesce(cardinality(examples), 0) LOOP
    query := examples[k];
    -- A model's name stands for its axes.
    IF EXISTS (SELECT 1 FROM streetgen.model m WHERE m.name = query) THEN
      query := format('SELECT id, road_class, geom FROM %I.axis', query);
    END IF;
    -- road_class and id are optional columns of the example query.
    FOR variant IN 1 .. 4 LOOP
      BEGIN
        EXECUTE format('SELECT array_agg(ST_AsEWKB(q.geom)), array_agg(%s), array_agg(%s), array_agg(DISTINCT ST_SRID(q.geom))
                          FROM (%s) AS q',
                       CASE WHEN variant IN (1, 2) THEN 'q.road_class::text' ELSE 'NULL::text' END,
                       CASE WHEN variant IN (1, 3) THEN 'q.id::bigint' ELSE 'NULL::bigint' END, query)
          INTO q_geoms, q_classes, q_ids, q_srids;
        EXIT;
      EXCEPTION WHEN undefined_column THEN
        IF variant = 4 THEN
          RAISE EXCEPTION 'the example query must return a geometry column named geom' USING ERRCODE = 'invalid_parameter_value',
            DETAIL = SQLERRM || CASE WHEN cardinality(examples) > 1 THEN format(' (example %s)', k) ELSE '' END;
        END IF;
      END;
    END LOOP;
    IF q_geoms IS NULL AND cardinality(examples) > 1 THEN
      RAISE EXCEPTION 'example % has no edges', k USING ERRCODE = 'invalid_parameter_value',
        DETAIL = 'The example query returned no LineString.';
    END IF;
    geoms := geoms || coalesce(q_geoms, '{}');
    classes := classes || coalesce(q_classes, '{}');
    ids := ids || coalesce(q_ids, '{}');
    sources := sources || array_fill(k - 1, ARRAY[coalesce(cardinality(q_geoms), 0)]);
    srids := srids || coalesce(q_srids, '{}');
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
  IF (SELECT count(DISTINCT s) FROM unnest(srids) AS s WHERE s IS NOT NULL) > 1 THEN
    RAISE EXCEPTION 'example edges must share one SRID' USING ERRCODE = 'invalid_parameter_value',
      DETAIL = format('The queries return SRIDs %s.',
                      (SELECT string_agg(DISTINCT s::text, ', ') FROM unnest(srids) AS s));
  END IF;
  RETURN QUERY
  SELECT g.id, g.from_node, g.to_node, g.road_class, g.origin, ST_GeomFromEWKB(g.geom)
    FROM streetgen._streetgen_grow_example(
           geoms, classes, ids, sources, ST_AsEWKB(region), coalesce(xs, '{}'), coalesce(ys, '{}'),
           coalesce(obstacle_geoms, '{}'),
           coalesce((p ->> 'epsilon')::double precision, 30), coalesce((p ->> 'r')::double precision, 0),
           coalesce((p ->> 'rotation')::boolean, true), coalesce((p ->> 'seed')::bigint, 0),
           coalesce((p ->> 'max_edges')::integer, 10000), coalesce((p ->> 'match_levels')::boolean, true),
           coalesce((p ->> 'snap')::double precision, CASE WHEN parametric THEN 20 ELSE 0 END),
           coalesce((p ->> 'min_angle')::double precision, CASE WHEN parametric THEN 70 ELSE 20 END),
           coalesce((p ->> 'candidates')::integer, 16), coalesce(existing_geoms, '{}'),
           parametric, coalesce((p ->> 'fallback')::boolean, true), coalesce((p ->> 'keep_frame')::boolean, true),
           coalesce((p ->> 'coherence')::double precision, 1), coalesce((p ->> 'crop_margin')::double precision, -1),
           coalesce((p ->> 'fill')::boolean, NOT parametric),
           coalesce((p ->> 'length')::double precision, 50), coalesce((p ->> 'length_deviation')::double precision, 10),
           coalesce((p ->> 'min_length')::double precision, 20), coalesce((p ->> 'min_degree')::integer, 2),
           coalesce((p ->> 'max_degree')::integer, 4), coalesce((p ->> 'angle_deviation')::double precision, 10),
           coalesce(p ->> 'road_class', 'main'), ST_AsEWKB(guide), coalesce((p ->> 'guide_reach')::double precision, 0),
           coalesce(p ->> 'blend', 'none'), coalesce((p ->> 'blend_angle')::double precision, 0), bxs, bys,
           coalesce((p ->> 'blend_sigma')::double precision, 0), w.grid, w.vals, dir.grid, dir.vals) AS g;
END
$$;

CREATE FUNCTION streetgen.grow_example(examples text[], region geometry, seeds geometry,
    obstacles geometry DEFAULT NULL, params jsonb DEFAULT '{}', existing text DEFAULT NULL, guide geometry DEFAULT NULL,
    direction raster DEFAULT NULL, weights raster DEFAULT NULL,
    OUT id bigint, OUT from_node bigint, OUT to_node bigint, OUT road_class text, OUT origin text,
    OUT geom geometry)
  RETURNS SETOF record
  LANGUAGE sql VOLATILE
  COST 1000000 ROWS 1000
  SET search_path FROM CURRENT
  AS $$
  SELECT * FROM streetgen._grow(coalesce(examples, ARRAY[NULL::text]), region, seeds, obstacles, params, existing, guide,
                                direction, weights)
$$;
COMMENT ON FUNCTION streetgen.grow_example(text[], geometry, geometry, geometry, jsonb, text, geometry, raster, raster) IS
  'Grows a road network inside region from seeds by blending several examples (Yu & Steed): each step draws its example from the selection function at the node, params blend = gradient (first example at the region''s west, last at its east; blend_angle turns it) or points (blend_points: one [x, y] per example, Gaussian fall-off blend_sigma, m); weights: a raster in the region''s SRID whose band k is the weight (>= 0) of example k, sampled bilinearly (where every band is nodata or all weights are 0, blend decides, or without blend every example is alike); direction: as grow_example(text, ...); otherwise as grow_example(text, ...). origin names the example: grow_example:<k>:<id>';

CREATE FUNCTION streetgen.grow_example(example text, region geometry, seeds geometry,
    obstacles geometry DEFAULT NULL, params jsonb DEFAULT '{}', existing text DEFAULT NULL, guide geometry DEFAULT NULL,
    direction raster DEFAULT NULL,
    OUT id bigint, OUT from_node bigint, OUT to_node bigint, OUT road_class text, OUT origin text,
    OUT geom geometry)
  RETURNS SETOF record
  LANGUAGE sql VOLATILE
  COST 1000000 ROWS 1000
  SET search_path FROM CURRENT
  AS $$
  SELECT * FROM streetgen._grow(ARRAY[example], region, seeds, obstacles, params, existing, guide, direction)
$$;
COMMENT ON FUNCTION streetgen.grow_example(text, geometry, geometry, geometry, jsonb, text, geometry, raster) IS
  'Grows a road network inside region from seeds by example (Yu & Steed): node matching of incident edge angles under a rotation within epsilon, neighbourhood matching by weighted line-segment Hausdorff distance within r, copied edges adapted to the region, obstacles, snapping, no crossings and example dead ends. example: a query (columns geom, optionally road_class, id) or a model name. params: epsilon (deg, 30), r (m, 3 x mean example segment), rotation (true), seed (0), max_edges (10000), match_levels (true), snap (m, 0.55 x mean segment), min_angle (deg, 20), candidates (16), fallback (true: a node no example node matches grows parametrically, origin grow_parametric), keep_frame (true: a node matches under the rotation of the match that made it), coherence (1: probability that a node first continues the example node it was copied to), crop_margin (m, mean segment: example dead ends this close to its hull are cut streets and grow on), fill (true: when all fronts died before the region is covered, grow on from a new seed farther than r and than the example''s widest empty space from every edge), guide_reach (m, everywhere). existing: a query of a network to extend (column geom), respected and joined but not returned. guide: a (Multi)LineString whose nearest tangent sets the rotation instead of node matching. direction: a one-band raster in the region''s SRID of azimuths (degrees clockwise from north, undirected) that sets the rotation where it has a value (axial bilinear interpolation), before the guide; where it is nodata the guide or node matching decides. Returns rows for a model''s axis table';

CREATE FUNCTION streetgen.grow_parametric(region geometry, seeds geometry, obstacles geometry DEFAULT NULL,
    params jsonb DEFAULT '{}', existing text DEFAULT NULL, guide geometry DEFAULT NULL, direction raster DEFAULT NULL,
    OUT id bigint, OUT from_node bigint, OUT to_node bigint, OUT road_class text, OUT origin text,
    OUT geom geometry)
  RETURNS SETOF record
  LANGUAGE sql VOLATILE
  COST 1000000 ROWS 1000
  SET search_path FROM CURRENT
  AS $$
  SELECT * FROM streetgen._grow(NULL, region, seeds, obstacles, params, existing, guide, direction)
$$;
COMMENT ON FUNCTION streetgen.grow_parametric(geometry, geometry, geometry, jsonb, text, geometry, raster) IS
  'Grows a road network inside region from seeds by parameters (Teng & Bidarra), e.g. main streets: params length (m, 50), length_deviation (m, 10), min_length (m, 20), min_degree (2), max_degree (4), min_angle (deg, 70), angle_deviation (deg, 10), snap (m, 20), road_class (main), rotation (true; false aligns the lattice with the axes), seed (0), max_edges (10000), fill (false), guide_reach (m). Same local constraints as grow_example (region, obstacles, snapping, no crossing); guide: a (Multi)LineString the streets follow; direction: a raster of azimuths (degrees clockwise from north) they follow where it has a value. origin is grow_parametric';
