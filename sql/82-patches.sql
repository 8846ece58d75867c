-- Growing networks II: example patches (Nishida et al. 2016) with semantic tags (Teng & Bidarra
-- 2017), and growth from them. extract_patches reads an example query (or model) into patch rows
-- that a table can hold; grow_patches grows a network from such rows. One C call each; this file
-- reads the queries and checks the params jsonb (unknown keys are rejected).

CREATE FUNCTION streetgen._streetgen_extract_patches(example_geoms bytea[], example_classes text[],
    example_ids bigint[], example_roundabouts boolean[], short_edge double precision,
    cluster_distance double precision, detect_circles boolean, circle_min_diameter double precision,
    circle_max_diameter double precision, circle_compactness double precision, crop_margin double precision,
    levels boolean,
    OUT patch_id bigint, OUT edge_index integer, OUT role text, OUT road_class text, OUT tags text[],
    OUT edge_tags text[], OUT start_tags text[], OUT end_tags text[], OUT example_id bigint, OUT geom bytea)
  RETURNS SETOF record
  LANGUAGE c IMMUTABLE PARALLEL SAFE
  COST 1000000 ROWS 1000
  AS 'MODULE_PATHNAME', '_streetgen_extract_patches';

CREATE FUNCTION streetgen._streetgen_grow_patches(patch_ids bigint[], roles text[], classes text[], geoms bytea[],
    max_uses integer[], region bytea, seeds_x double precision[], seeds_y double precision[], obstacles bytea[],
    seed bigint, max_edges integer, snap double precision, min_angle double precision, scale double precision,
    max_distance double precision, angle_window double precision, tries integer, default_max_uses integer,
    rotation double precision, fallback boolean, clearance double precision, arterials boolean[], levels boolean,
    water bytea[], dem_grid double precision[], dem_values double precision[], max_slope double precision,
    bridge_distance double precision, bridge_turn double precision,
    guide bytea, guide_reach double precision, patch_ids_b bigint[], roles_b text[], classes_b text[], geoms_b bytea[],
    max_uses_b integer[], arterials_b boolean[], t double precision, blend text, blend_angle double precision,
    blend_x double precision[], blend_y double precision[], blend_sigma double precision, prune_dangling boolean,
    direction_grid double precision[], direction_values double precision[], connect_dangling boolean,
    fallback_curvature boolean, arterial_fallback double precision, fallback_local_seeds boolean,
    initials boolean[], bridge_fronts boolean, cell_init text, max_turn double precision, cell_spacing double precision,
    promote_arterials boolean, terminal_room double precision, roundabouts boolean[],
    OUT id bigint, OUT from_node bigint, OUT to_node bigint, OUT road_class text, OUT origin text, OUT geom bytea)
  RETURNS SETOF record
  LANGUAGE c IMMUTABLE PARALLEL SAFE
  COST 1000000 ROWS 1000
  AS 'MODULE_PATHNAME', '_streetgen_grow_patches';

-- Reads `query` into one jsonb per row (its columns but geom) and the geometry, so optional
-- columns need no variant of the query.
CREATE FUNCTION streetgen._rows_with_geom(query text, what text)
  RETURNS TABLE (j jsonb, geom geometry, n bigint)
  LANGUAGE plpgsql VOLATILE
  SET search_path FROM CURRENT
  AS $$
BEGIN
  RETURN QUERY EXECUTE format('SELECT to_jsonb(q) - ''geom'', q.geom::geometry, row_number() OVER () FROM (%s) AS q', query);
EXCEPTION WHEN undefined_column THEN
  RAISE EXCEPTION 'the % query must return a geometry column named geom', what USING ERRCODE = 'invalid_parameter_value',
    DETAIL = SQLERRM;
END
$$;

CREATE FUNCTION streetgen.extract_patches(example text, params jsonb DEFAULT '{}',
    OUT patch_id bigint, OUT edge_index integer, OUT role text, OUT road_class text, OUT tags text[],
    OUT edge_tags text[], OUT start_tags text[], OUT end_tags text[], OUT max_uses integer, OUT example_id bigint,
    OUT geom geometry)
  RETURNS SETOF record
  LANGUAGE plpgsql VOLATILE
  COST 1000000 ROWS 1000
  SET search_path FROM CURRENT
  SET jit = off
  AS $$
DECLARE
  p jsonb := coalesce(params, '{}'::jsonb);
  query text := example;
  geoms bytea[];
  classes text[];
  ids bigint[];
  rounds boolean[];
  srids integer[];
  k text;
BEGIN
  IF example IS NULL THEN
    RAISE EXCEPTION 'example must not be null' USING ERRCODE = 'null_value_not_allowed';
  END IF;
  PERFORM streetgen._require_params(p, ARRAY['circle_compactness', 'circle_max_diameter', 'circle_min_diameter',
                                             'cluster_distance', 'crop_margin', 'detect_circles', 'levels',
                                             'short_edge']);
  FOREACH k IN ARRAY ARRAY['short_edge', 'cluster_distance', 'circle_min_diameter', 'circle_max_diameter',
                           'circle_compactness', 'crop_margin'] LOOP
    IF p ? k AND (jsonb_typeof(p -> k) <> 'number' OR (p ->> k)::double precision < 0) THEN
      RAISE EXCEPTION '% must be a number >= 0', k USING ERRCODE = 'invalid_parameter_value',
        DETAIL = format('It is %s.', p -> k);
    END IF;
  END LOOP;
  FOREACH k IN ARRAY ARRAY['detect_circles', 'levels'] LOOP
    IF p ? k AND jsonb_typeof(p -> k) <> 'boolean' THEN
      RAISE EXCEPTION '% must be true or false', k USING ERRCODE = 'invalid_parameter_value',
        DETAIL = format('It is %s.', p -> k);
    END IF;
  END LOOP;
  IF EXISTS (SELECT 1 FROM streetgen.model m WHERE m.name = query) THEN
    query := format('SELECT id, road_class, geom FROM %I.axis', query);
  END IF;
  -- road_class, else the example files' type, else an OSM highway column; id; roundabout.
  SELECT array_agg(ST_AsEWKB(r.geom) ORDER BY r.n),
         array_agg(coalesce(r.j ->> 'road_class', r.j ->> 'type', r.j ->> 'highway') ORDER BY r.n),
         array_agg(CASE WHEN r.j ->> 'id' ~ '^-?[0-9]{1,18}$' THEN (r.j ->> 'id')::bigint END ORDER BY r.n),
         array_agg(coalesce(lower(r.j ->> 'roundabout') IN ('true', 't', 'yes', '1'), false) ORDER BY r.n),
         array_agg(DISTINCT ST_SRID(r.geom))
    INTO geoms, classes, ids, rounds, srids
    FROM streetgen._rows_with_geom(query, 'example') AS r WHERE r.geom IS NOT NULL;
  IF geoms IS NULL THEN
    RAISE EXCEPTION 'example has no edges' USING ERRCODE = 'invalid_parameter_value',
      DETAIL = 'The example query returned no geometry.', HINT = 'Pass a query (or model) whose rows hold the example''s road edges.';
  END IF;
  IF cardinality(srids) > 1 THEN
    RAISE EXCEPTION 'example edges must share one SRID' USING ERRCODE = 'invalid_parameter_value',
      DETAIL = format('The query returns SRIDs %s.', array_to_string(srids, ', '));
  END IF;
  RETURN QUERY
  SELECT x.patch_id, x.edge_index, x.role, x.road_class, x.tags, x.edge_tags, x.start_tags, x.end_tags, NULL::integer,
         x.example_id, ST_GeomFromEWKB(x.geom)
    FROM streetgen._streetgen_extract_patches(
           geoms, classes, ids, rounds, coalesce((p ->> 'short_edge')::double precision, 0),
           coalesce((p ->> 'cluster_distance')::double precision, 0), coalesce((p ->> 'detect_circles')::boolean, true),
           coalesce((p ->> 'circle_min_diameter')::double precision, 8),
           coalesce((p ->> 'circle_max_diameter')::double precision, 100),
           coalesce((p ->> 'circle_compactness')::double precision, 0.85),
           coalesce((p ->> 'crop_margin')::double precision, 0), coalesce((p ->> 'levels')::boolean, true)) AS x;
END
$$;
COMMENT ON FUNCTION streetgen.extract_patches(text, jsonb) IS
  'Decomposes an example road network into patches (Nishida et al. 2016): roundabouts (the example''s roundabout column, or small compact faces found by polygonize) and clusters of 3 or more junctions closer than cluster_distance are detected first, then each structure and every other junction is grown by its streets shorter than short_edge. One row per patch edge: role inner, connector (shared with the neighbouring patch, oriented outwards) or dead_end (towards the dead end); a street with no junction at either end (in no patch) is a patch of its own after the others, role and tag isolated (grow_patches never places it, but counts its dead ends in the example''s dead-end share); semantic tags (Teng & Bidarra) per patch (roundabout, cluster, loop, cul-de-sac, curved, straight, terminal, initial, main, local, isolated), per edge (main, local, connector, dead-end, snappable, curved, straight, roundabout) and per end vertex (intersection, connectable, dead-end); max_uses NULL (set it to limit a patch''s uses in grow_patches). Levels (when the example has main and local streets): arterial patches (tag arterial) from the graph of the main streets alone, then local patches around the junctions where a local street meets. example: a query (geom, optionally road_class or type, id, roundabout) or a model name. params: short_edge (m, 0.4 x the median street length), cluster_distance (m, short_edge), detect_circles (true), circle_min_diameter (m, 8), circle_max_diameter (m, 100), circle_compactness (0.85), levels (true), crop_margin (m, 0 = off: a dead end this close to the example''s convex hull is a street the crop cut, a connector tagged cut)';

-- A patch query's rows as the arrays of the C call (what names the parameter in errors): rows of
-- extract_patches (all columns there) are read directly, others through jsonb. patch_id, role and
-- geom; optionally road_class, max_uses, edge_index (order), tags (arterial: the first phase;
-- initial; roundabout).
CREATE FUNCTION streetgen._patch_arrays(patches text, what text,
    OUT pids bigint[], OUT roles text[], OUT classes text[], OUT geoms bytea[], OUT uses integer[],
    OUT arterials boolean[], OUT srids integer[], OUT initials boolean[], OUT roundabouts boolean[])
  LANGUAGE plpgsql VOLATILE
  SET search_path FROM CURRENT
  AS $$
DECLARE
  complete boolean;
BEGIN
  BEGIN
    EXECUTE format('SELECT array_agg(q.patch_id::bigint ORDER BY q.patch_id, q.edge_index),
                           array_agg(q.role::text ORDER BY q.patch_id, q.edge_index),
                           array_agg(q.road_class::text ORDER BY q.patch_id, q.edge_index),
                           array_agg(ST_AsEWKB(q.geom::geometry) ORDER BY q.patch_id, q.edge_index),
                           array_agg(q.max_uses::integer ORDER BY q.patch_id, q.edge_index),
                           array_agg(coalesce(''arterial'' = ANY (q.tags::text[]), false) ORDER BY q.patch_id, q.edge_index),
                           array_agg(DISTINCT ST_SRID(q.geom::geometry)) FILTER (WHERE q.geom IS NOT NULL),
                           array_agg(coalesce(''initial'' = ANY (q.tags::text[]), false) ORDER BY q.patch_id, q.edge_index),
                           array_agg(coalesce(''roundabout'' = ANY (q.tags::text[]), false) ORDER BY q.patch_id, q.edge_index)
                      FROM (%s) AS q', patches)
      INTO pids, roles, classes, geoms, uses, arterials, srids, initials, roundabouts;
  EXCEPTION WHEN undefined_column THEN
    SELECT array_agg((r.j ->> 'patch_id')::bigint ORDER BY (r.j ->> 'patch_id')::bigint, (r.j ->> 'edge_index')::integer, r.n),
           array_agg(r.j ->> 'role' ORDER BY (r.j ->> 'patch_id')::bigint, (r.j ->> 'edge_index')::integer, r.n),
           array_agg(r.j ->> 'road_class' ORDER BY (r.j ->> 'patch_id')::bigint, (r.j ->> 'edge_index')::integer, r.n),
           array_agg(ST_AsEWKB(r.geom) ORDER BY (r.j ->> 'patch_id')::bigint, (r.j ->> 'edge_index')::integer, r.n),
           array_agg((r.j ->> 'max_uses')::integer ORDER BY (r.j ->> 'patch_id')::bigint, (r.j ->> 'edge_index')::integer, r.n),
           array_agg(coalesce(jsonb_typeof(r.j -> 'tags') = 'array' AND (r.j -> 'tags') ? 'arterial', false)
                     ORDER BY (r.j ->> 'patch_id')::bigint, (r.j ->> 'edge_index')::integer, r.n),
           array_agg(DISTINCT ST_SRID(r.geom)) FILTER (WHERE r.geom IS NOT NULL),
           bool_and(r.j ? 'patch_id' AND r.j ? 'role'),
           array_agg(coalesce(jsonb_typeof(r.j -> 'tags') = 'array' AND (r.j -> 'tags') ? 'initial', false)
                     ORDER BY (r.j ->> 'patch_id')::bigint, (r.j ->> 'edge_index')::integer, r.n),
           array_agg(coalesce(jsonb_typeof(r.j -> 'tags') = 'array' AND (r.j -> 'tags') ? 'roundabout', false)
                     ORDER BY (r.j ->> 'patch_id')::bigint, (r.j ->> 'edge_index')::integer, r.n)
      INTO pids, roles, classes, geoms, uses, arterials, srids, complete, initials, roundabouts
      FROM streetgen._rows_with_geom(patches, what) AS r;
    IF NOT complete THEN
      RAISE EXCEPTION 'the % query must return the columns patch_id, role and geom', what
        USING ERRCODE = 'invalid_parameter_value', HINT = 'Use the rows of streetgen.extract_patches.';
    END IF;
  END;
  IF pids IS NULL THEN
    RAISE EXCEPTION '% has no rows', what USING ERRCODE = 'invalid_parameter_value',
      DETAIL = 'The patch query returned no patch edge.',
      HINT = 'Fill the patch table with streetgen.extract_patches(example).';
  END IF;
  IF cardinality(srids) > 1 THEN
    RAISE EXCEPTION '% edges must share one SRID', CASE WHEN what = 'patches' THEN 'patch' ELSE what || ' patch' END
      USING ERRCODE = 'invalid_parameter_value',
      DETAIL = format('The query returns SRIDs %s.', array_to_string(srids, ', '));
  END IF;
END
$$;

CREATE FUNCTION streetgen.grow_patches(patches text, region geometry, seeds geometry, obstacles geometry DEFAULT NULL,
    params jsonb DEFAULT '{}', water geometry DEFAULT NULL, dem raster DEFAULT NULL, guide geometry DEFAULT NULL,
    direction raster DEFAULT NULL,
    OUT id bigint, OUT from_node bigint, OUT to_node bigint, OUT road_class text, OUT origin text,
    OUT geom geometry)
  RETURNS SETOF record
  LANGUAGE plpgsql VOLATILE
  COST 1000000 ROWS 1000
  SET search_path FROM CURRENT
  SET jit = off
  AS $$
DECLARE
  p jsonb := coalesce(params, '{}'::jsonb);
  xs double precision[];
  ys double precision[];
  obstacle_geoms bytea[];
  seed_types text[];
  water_geoms bytea[];
  dem_r record;
  dir_r record;
  k text;
  lib record;
  lib_b record;
  bxs double precision[];
  bys double precision[];
BEGIN
  IF patches IS NULL THEN
    RAISE EXCEPTION 'patches must not be null' USING ERRCODE = 'null_value_not_allowed';
  END IF;
  IF region IS NULL THEN
    RAISE EXCEPTION 'region must not be null' USING ERRCODE = 'null_value_not_allowed';
  END IF;
  IF seeds IS NULL THEN
    RAISE EXCEPTION 'seeds must not be null' USING ERRCODE = 'null_value_not_allowed';
  END IF;
  PERFORM streetgen._require_params(p, ARRAY['angle_window', 'arterial_fallback', 'blend', 'blend_angle', 'blend_points',
                                             'blend_sigma', 'bridge_distance', 'bridge_fronts', 'bridge_turn', 'cell_init',
                                             'cell_spacing', 'clearance', 'connect_dangling', 'fallback', 'fallback_curvature',
                                             'fallback_local_seeds', 'guide_reach', 'interpolate', 'levels', 'max_distance',
                                             'max_edges', 'max_slope', 'max_turn',
                                             'max_uses', 'min_angle', 'promote_arterials', 'prune_dangling', 'rotation',
                                             'scale', 'seed',
                                             'snap', 't', 'terminal_room', 'tries']);
  -- Operations (Nishida et al. 2016, section 5): warping (guide, guide_reach), interpolation
  -- (interpolate, t) and blending (blend, blend_angle, blend_points, blend_sigma).
  IF p ? 'guide_reach' AND NOT coalesce(jsonb_typeof(p -> 'guide_reach') = 'number'
                                        AND (p ->> 'guide_reach')::double precision > 0, false) THEN
    RAISE EXCEPTION 'guide_reach must be a number > 0' USING ERRCODE = 'invalid_parameter_value',
      DETAIL = format('It is %s.', p -> 'guide_reach'), HINT = 'Leave it out for a guide that acts everywhere.';
  END IF;
  IF p ? 'guide_reach' AND guide IS NULL THEN
    RAISE EXCEPTION 'guide_reach needs a guide' USING ERRCODE = 'invalid_parameter_value',
      HINT = 'Pass a (Multi)LineString as the guide argument.';
  END IF;
  IF p ? 'interpolate' AND NOT coalesce(jsonb_typeof(p -> 'interpolate') = 'string' AND p ->> 'interpolate' <> '', false) THEN
    RAISE EXCEPTION 'interpolate must be the query of a second patch library' USING ERRCODE = 'invalid_parameter_value',
      DETAIL = format('It is %s.', p -> 'interpolate'), HINT = 'Rows of streetgen.extract_patches of a second example.';
  END IF;
  IF p ? 't' AND NOT coalesce(jsonb_typeof(p -> 't') = 'number' AND (p ->> 't')::double precision BETWEEN 0 AND 1, false) THEN
    RAISE EXCEPTION 't must be a number in [0, 1]' USING ERRCODE = 'invalid_parameter_value',
      DETAIL = format('It is %s.', p -> 't'), HINT = '0 is the patches'' style, 1 the interpolate library''s.';
  END IF;
  IF p ? 'blend' AND NOT coalesce(jsonb_typeof(p -> 'blend') = 'string' AND p ->> 'blend' IN ('gradient', 'points'), false) THEN
    RAISE EXCEPTION 'blend must be ''gradient'' or ''points''' USING ERRCODE = 'invalid_parameter_value',
      DETAIL = format('It is %s.', p -> 'blend');
  END IF;
  IF p ? 'blend_angle' AND jsonb_typeof(p -> 'blend_angle') <> 'number' THEN
    RAISE EXCEPTION 'blend_angle must be a number (degrees)' USING ERRCODE = 'invalid_parameter_value',
      DETAIL = format('It is %s.', p -> 'blend_angle');
  END IF;
  IF p ? 'blend_sigma' AND NOT coalesce(jsonb_typeof(p -> 'blend_sigma') = 'number'
                                        AND (p ->> 'blend_sigma')::double precision > 0, false) THEN
    RAISE EXCEPTION 'blend_sigma must be a number > 0' USING ERRCODE = 'invalid_parameter_value',
      DETAIL = format('It is %s.', p -> 'blend_sigma');
  END IF;
  IF p ? 'blend_points' THEN
    IF jsonb_typeof(p -> 'blend_points') <> 'array' OR jsonb_array_length(p -> 'blend_points') <> 2 OR EXISTS (
         SELECT 1 FROM jsonb_array_elements(p -> 'blend_points') AS e
          WHERE jsonb_typeof(e) <> 'array' OR jsonb_array_length(e) <> 2 OR jsonb_typeof(e -> 0) <> 'number'
             OR jsonb_typeof(e -> 1) <> 'number') THEN
      RAISE EXCEPTION 'blend_points must be an array of two [x, y] pairs' USING ERRCODE = 'invalid_parameter_value',
        DETAIL = format('It is %s.', p -> 'blend_points'),
        HINT = 'The seed of the patches'' style, then the interpolate library''s, in the region''s SRID.';
    END IF;
    SELECT array_agg((e ->> 0)::double precision ORDER BY n), array_agg((e ->> 1)::double precision ORDER BY n)
      INTO bxs, bys FROM jsonb_array_elements(p -> 'blend_points') WITH ORDINALITY AS q(e, n);
  END IF;
  IF p ->> 'blend' = 'points' AND NOT p ? 'blend_points' THEN
    RAISE EXCEPTION 'blend ''points'' needs blend_points' USING ERRCODE = 'invalid_parameter_value',
      HINT = 'Give the two styles'' seeds as [[x, y], [x, y]].';
  END IF;
  IF (p ? 'blend' OR p ? 't') AND NOT p ? 'interpolate' THEN
    RAISE EXCEPTION '% needs interpolate', CASE WHEN p ? 'blend' THEN 'blend' ELSE 't' END
      USING ERRCODE = 'invalid_parameter_value', HINT = 'Set params interpolate to a second patch library''s query.';
  END IF;
  IF p ? 'blend' AND p ? 't' THEN
    RAISE EXCEPTION 'blend and t exclude each other' USING ERRCODE = 'invalid_parameter_value',
      DETAIL = 'Blending sets the weight t at every point.';
  END IF;
  IF guide IS NOT NULL THEN
    IF ST_SRID(guide) <> ST_SRID(region) THEN
      RAISE EXCEPTION 'guide must have the SRID of the region' USING ERRCODE = 'invalid_parameter_value',
        DETAIL = format('The guide has SRID %s, the region %s.', ST_SRID(guide), ST_SRID(region));
    END IF;
    IF ST_GeometryType(guide) NOT IN ('ST_LineString', 'ST_MultiLineString') THEN
      RAISE EXCEPTION 'guide must be a LineString or MultiLineString' USING ERRCODE = 'invalid_parameter_value',
        DETAIL = format('It is a %s.', ST_GeometryType(guide));
    END IF;
  END IF;
  IF p ? 'arterial_fallback' AND NOT coalesce(jsonb_typeof(p -> 'arterial_fallback') = 'number'
                                              AND (p ->> 'arterial_fallback')::double precision >= 0, false) THEN
    RAISE EXCEPTION 'arterial_fallback must be a number >= 0' USING ERRCODE = 'invalid_parameter_value',
      DETAIL = format('It is %s.', p -> 'arterial_fallback'),
      HINT = 'A share of the example''s main-street length per area (1: as much); 0 turns the arterial fallback off.';
  END IF;
  IF p ? 'cell_init' AND NOT coalesce(jsonb_typeof(p -> 'cell_init') = 'string' AND p ->> 'cell_init' IN ('seeds', 'initial'), false) THEN
    RAISE EXCEPTION 'cell_init must be ''seeds'' or ''initial''' USING ERRCODE = 'invalid_parameter_value',
      DETAIL = format('It is %s.', p -> 'cell_init'),
      HINT = 'seeds: the example''s local junctions along the arterials; initial: patches tagged initial along the main streets.';
  END IF;
  IF p ? 'cell_spacing' AND NOT coalesce(jsonb_typeof(p -> 'cell_spacing') = 'number'
                                         AND (p ->> 'cell_spacing')::double precision > 0, false) THEN
    RAISE EXCEPTION 'cell_spacing must be a number > 0' USING ERRCODE = 'invalid_parameter_value',
      DETAIL = format('It is %s.', p -> 'cell_spacing'), HINT = '1 spaces the seed points as the example''s local junctions along its main streets.';
  END IF;
  IF p ? 'terminal_room' AND NOT coalesce(jsonb_typeof(p -> 'terminal_room') = 'number'
                                          AND (p ->> 'terminal_room')::double precision >= 0, false) THEN
    RAISE EXCEPTION 'terminal_room must be a number >= 0 (mean streets)' USING ERRCODE = 'invalid_parameter_value',
      DETAIL = format('It is %s.', p -> 'terminal_room'), HINT = '0 lets terminal patches end a street anywhere.';
  END IF;
  IF p ? 'max_turn' AND NOT coalesce(jsonb_typeof(p -> 'max_turn') = 'number'
                                     AND (p ->> 'max_turn')::double precision BETWEEN 0 AND 180, false) THEN
    RAISE EXCEPTION 'max_turn must be a number in [0, 180] (degrees)' USING ERRCODE = 'invalid_parameter_value',
      DETAIL = format('It is %s.', p -> 'max_turn'), HINT = '180 turns bridging and initial patches freely, as Teng & Bidarra.';
  END IF;
  FOREACH k IN ARRAY ARRAY['levels', 'prune_dangling', 'connect_dangling', 'fallback_curvature', 'fallback_local_seeds',
                           'bridge_fronts', 'promote_arterials'] LOOP
    IF p ? k AND jsonb_typeof(p -> k) <> 'boolean' THEN
      RAISE EXCEPTION '% must be true or false', k USING ERRCODE = 'invalid_parameter_value',
        DETAIL = format('It is %s.', p -> k);
    END IF;
  END LOOP;
  FOREACH k IN ARRAY ARRAY['scale', 'snap', 'max_distance', 'angle_window', 'clearance', 'max_slope'] LOOP
    IF p ? k AND NOT coalesce(jsonb_typeof(p -> k) = 'number' AND (p ->> k)::double precision > 0, false) THEN
      RAISE EXCEPTION '% must be a number > 0', k USING ERRCODE = 'invalid_parameter_value',
        DETAIL = format('It is %s.', p -> k);
    END IF;
  END LOOP;
  IF p ? 'bridge_distance' AND NOT coalesce(jsonb_typeof(p -> 'bridge_distance') = 'number'
                                            AND (p ->> 'bridge_distance')::double precision >= 0, false) THEN
    RAISE EXCEPTION 'bridge_distance must be a number >= 0' USING ERRCODE = 'invalid_parameter_value',
      DETAIL = format('It is %s.', p -> 'bridge_distance'), HINT = '0 turns bridges off.';
  END IF;
  IF p ? 'bridge_turn' AND NOT coalesce(jsonb_typeof(p -> 'bridge_turn') = 'number'
                                        AND (p ->> 'bridge_turn')::double precision >= 0
                                        AND (p ->> 'bridge_turn')::double precision < 90, false) THEN
    RAISE EXCEPTION 'bridge_turn must be a number in [0, 90) (degrees)' USING ERRCODE = 'invalid_parameter_value',
      DETAIL = format('It is %s.', p -> 'bridge_turn');
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
  IF water IS NOT NULL AND ST_SRID(water) <> ST_SRID(region) THEN
    RAISE EXCEPTION 'water must have the SRID of the region' USING ERRCODE = 'invalid_parameter_value',
      DETAIL = format('The water has SRID %s, the region %s.', ST_SRID(water), ST_SRID(region)),
      HINT = 'ST_Transform the water to the region''s SRID.';
  END IF;
  IF dem IS NOT NULL AND NOT ST_IsEmpty(dem) AND ST_NumBands(dem) > 1 THEN
    RAISE EXCEPTION 'dem raster must have one band' USING ERRCODE = 'invalid_parameter_value',
      DETAIL = format('It has %s.', ST_NumBands(dem)), HINT = 'ST_Band(rast, n) picks the band of heights.';
  END IF;
  -- SRID, skew, overlap with the region and size are checked there; NULL cells are unknown terrain.
  dem_r := streetgen._control_raster(dem, 'dem', region);
  IF direction IS NOT NULL AND NOT ST_IsEmpty(direction) AND ST_NumBands(direction) > 1 THEN
    RAISE EXCEPTION 'direction raster must have one band' USING ERRCODE = 'invalid_parameter_value',
      DETAIL = format('It has %s.', ST_NumBands(direction)), HINT = 'ST_Band(rast, n) picks one.';
  END IF;
  dir_r := streetgen._control_raster(direction, 'direction', region);
  SELECT array_agg(DISTINCT ST_GeometryType(d.geom)) INTO seed_types
    FROM ST_Dump(seeds) AS d WHERE ST_GeometryType(d.geom) <> 'ST_Point';
  IF seed_types IS NOT NULL THEN
    RAISE EXCEPTION 'seeds must be points' USING ERRCODE = 'invalid_parameter_value',
      DETAIL = format('They hold %s.', array_to_string(seed_types, ', '));
  END IF;
  SELECT array_agg(ST_X(d.geom) ORDER BY d.path), array_agg(ST_Y(d.geom) ORDER BY d.path) INTO xs, ys
    FROM ST_Dump(seeds) AS d;
  SELECT array_agg(ST_AsEWKB(d.geom) ORDER BY d.path) INTO obstacle_geoms FROM ST_Dump(obstacles) AS d;
  SELECT array_agg(ST_AsEWKB(d.geom) ORDER BY d.path) INTO water_geoms FROM ST_Dump(water) AS d;
  SELECT * INTO lib FROM streetgen._patch_arrays(patches, 'patches');
  IF p ? 'interpolate' THEN
    SELECT * INTO lib_b FROM streetgen._patch_arrays(p ->> 'interpolate', 'interpolate');
    IF lib_b.srids <> lib.srids THEN
      RAISE EXCEPTION 'interpolate patches must have the SRID of the patches' USING ERRCODE = 'invalid_parameter_value',
        DETAIL = format('The interpolate patches have SRID %s, the patches %s.', lib_b.srids[1], lib.srids[1]);
    END IF;
  ELSE
    SELECT NULL::bigint[] AS pids, NULL::text[] AS roles, NULL::text[] AS classes, NULL::bytea[] AS geoms,
           NULL::integer[] AS uses, NULL::boolean[] AS arterials INTO lib_b;
  END IF;
  RETURN QUERY
  SELECT g.id, g.from_node, g.to_node, g.road_class, g.origin, ST_GeomFromEWKB(g.geom)
    FROM streetgen._streetgen_grow_patches(
           lib.pids, lib.roles, lib.classes, lib.geoms, lib.uses, ST_AsEWKB(region), coalesce(xs, '{}'), coalesce(ys, '{}'),
           coalesce(obstacle_geoms, '{}'), coalesce((p ->> 'seed')::bigint, 0),
           coalesce((p ->> 'max_edges')::integer, 10000), coalesce((p ->> 'snap')::double precision, 0),
           coalesce((p ->> 'min_angle')::double precision, 20), coalesce((p ->> 'scale')::double precision, 0.1),
           coalesce((p ->> 'max_distance')::double precision, 0), coalesce((p ->> 'angle_window')::double precision, 30),
           coalesce((p ->> 'tries')::integer, 24), coalesce((p ->> 'max_uses')::integer, 0),
           coalesce((p ->> 'rotation')::double precision, 0), coalesce((p ->> 'fallback')::boolean, true),
           coalesce((p ->> 'clearance')::double precision, 0), lib.arterials, coalesce((p ->> 'levels')::boolean, true),
           coalesce(water_geoms, '{}'), dem_r.grid, dem_r.vals, coalesce((p ->> 'max_slope')::double precision, 12),
           coalesce((p ->> 'bridge_distance')::double precision, 300),
           coalesce((p ->> 'bridge_turn')::double precision, 30),
           ST_AsEWKB(guide), coalesce((p ->> 'guide_reach')::double precision, 0),
           lib_b.pids, lib_b.roles, lib_b.classes, lib_b.geoms, lib_b.uses, lib_b.arterials,
           coalesce((p ->> 't')::double precision, 0), coalesce(p ->> 'blend', 'none'),
           coalesce((p ->> 'blend_angle')::double precision, 0), bxs, bys,
           coalesce((p ->> 'blend_sigma')::double precision, 0), coalesce((p ->> 'prune_dangling')::boolean, false),
           dir_r.grid, dir_r.vals, coalesce((p ->> 'connect_dangling')::boolean, true),
           coalesce((p ->> 'fallback_curvature')::boolean, false), coalesce((p ->> 'arterial_fallback')::double precision, 0),
           coalesce((p ->> 'fallback_local_seeds')::boolean, false), lib.initials,
           coalesce((p ->> 'bridge_fronts')::boolean, false), coalesce(p ->> 'cell_init', 'seeds'),
           coalesce((p ->> 'max_turn')::double precision, 5),
           coalesce((p ->> 'cell_spacing')::double precision, 1),
           coalesce((p ->> 'promote_arterials')::boolean, true),
           coalesce((p ->> 'terminal_room')::double precision, 0), lib.roundabouts) AS g;
END
$$;
COMMENT ON FUNCTION streetgen.grow_patches(text, geometry, geometry, geometry, jsonb, geometry, raster, geometry, raster) IS
  'Grows a road network inside region from seeds with example patches (Nishida et al. 2016): fronts are processed breadth first; at each, a patch is drawn with probability proportional to exp(-d / scale), d the smallest Hausdorff distance between one of its connectors (inner end on the front) and the front''s streets, among the patches that pass the legality checks (inside region, outside obstacles, no crossing, min_angle, degree); its vertices within snap of nodes are merged, its connectors become new fronts. Where no patch is legal, growth I''s parametric rule with the patch streets'' length statistics (origin grow_parametric); with fallback_curvature (false) each such street bends as a circular arc by the curvature of a patch street drawn at random (the arc with that street''s length and chord) times its own length, up to 90 degrees, in segments of at most 15 degrees whose chord keeps the straight street''s direction, when the arc''s inner points keep a snap distance from the network (else straight). patches: a query with patch_id, role, geom (optionally road_class, max_uses, edge_index): the rows of extract_patches. params: seed (0), max_edges (10000), snap (m, 0.45 x the mean segment), min_angle (deg, 20), scale (m, 0.1), max_distance (m, a quarter of the mean street), angle_window (deg, 30), tries (24), max_uses (0: unlimited, for patches without their own), rotation (deg, 0), fallback (true), clearance (m, 4 % of the mean street: new patch streets keep this far from streets they do not meet), levels (true: patches tagged arterial grow first, without the fallback unless arterial_fallback; then local streets from the example''s local junctions along the arterial streets, with those junctions'' patches, local streets only). origin: grow_patches:<patch_id> or grow_parametric; the example-based share is count(*) FILTER (WHERE origin LIKE ''grow_patches:%'') / count(*). water: (Multi)Polygons in the region''s SRID that no street crosses (patches with an edge over it are illegal, open connectors and statistical streets stop at its edge) except an arterial (main road class) that meets it: it goes on across, turned up to bridge_turn for a shorter crossing, to a far bank within bridge_distance with room for a street; that edge has origin bridge (insert layer 1 for it: CASE origin WHEN ''bridge'' THEN 1 ELSE 0 END). Seeds must not lie in water; water over the whole region is an error. Unlike obstacles (nothing crosses them). dem: a one-band raster of heights (m) in the region''s SRID overlapping it, NULL cells unknown: no new street is steeper than max_slope (patch edges steeper make the patch illegal, open connectors are cut where they get steeper); a statistical street that would be bends towards the contour (in 5 degree steps) to the first direction under max_slope, else is discarded. params also: max_slope (percent, 12), bridge_distance (m, 300; 0: no bridges), bridge_turn (deg, 30). Operations (Nishida et al. 2016, section 5): guide, a (Multi)LineString in the region''s SRID, warps the growth: each patch (and the statistical fallback''s lattice) is turned so that the patches'' dominant street direction follows the tangent of the nearest guide point (params guide_reach, m: only this close to the guide; everywhere without it); direction, a one-band raster in the region''s SRID of azimuths (degrees clockwise from north, undirected), warps the same way where it has a value, before the guide (as grow_example''s direction). params interpolate: the query of a second patch library (another style, rows of extract_patches), with t (0..1, 0): a front takes its patch from the second library with probability t (else the first; the other when none of the drawn one is legal) and the statistical fallback interpolates the two styles'' street length and curvature statistics and junction mixes with weight t; such edges have origin grow_patches:<patch_id>:b. blend (with interpolate, instead of t) makes t vary over the region: gradient (blend_angle, deg: 0 runs from the first style in the west to the second in the east) or points (blend_points [[x, y], [x, y]]: each style''s seed; t = w2 / (w1 + w2) with Gaussian fall-off w = exp(-d^2 / (2 blend_sigma^2)), blend_sigma m, a quarter of the region''s extent diagonal). connect_dangling (true): after growth, a street ending where the example does not end one joins the closest node ahead of it (within angle_window and half a mean street), else the first street straight on (split there), when legal, nearest gaps first, while the network has more dead ends than the example''s own share (a patch dead_end edge ending within a quarter mean street of its library''s hull is a street the example''s crop cut, not one of its dead ends), both counted as the realism metrics count them: the library''s street ends (its isolated streets'' too) farther than 50 m from its hull, a node''s degree its streets, against the network''s farther than 50 m from the region''s boundary; joins have origin grow_parametric. With connect_dangling, after those joins a T-junction whose lone street has a T ahead (within angle_window and a mean street) whose own lone street leaves on the far side is joined to it (two crossings), nearest first, and then an arterial T (three main streets) with no T facing it goes on straight to the first street within a mean street (split there), while the network''s share of 4-way junctions is below the example''s. prune_dangling (false): the dangling-edge post-process: after growth every dead end is cut back to its junction except the example''s own (the end of a patch''s dead_end edge, not the crop''s), ends where a step on is illegal (the region''s edge, obstacles, water, too steep), bridges and the existing network; an example without dead ends of its own (its library''s street ends all junctions or the crop''s) is pruned so whatever prune_dangling says. The local growth stops once its streets are as long as the example''s street length per area of its hull x the region''s area (the open connectors then queued cut back to their junctions); a growth that the joins after it take more than 3 % past that length is grown once more with that length lowered by the overshoot, and the one of the two nearer it kept (a second growth''s cost; reported at DEBUG1). arterial_fallback (0: off): with levels, the arterial phase''s statistical fallback (Nishida et al.''s procedural growth for arterials): once the arterial queue is empty, each arterial front still a dead end (and each arterial street the example''s crop cut) goes on straight with the arterial level''s street length statistics, the arterial patches taking over again at its new end, while the grown main streets are shorter than arterial_fallback x the example''s main-street length per area of its hull x the region''s area; not in a city of cul-de-sacs. fallback_local_seeds (false): the arterial streets the fallback made are cut into fragments of the local level''s mean street length and the local phase starts at every cut (where no local patch is legal there, the local fallback grows from it), not only at their ends. Teng & Bidarra (2017): bridge_fronts (false): breadth-first bridging (their Algorithm 2): at a front of one street (local phase, or one level), before the draw above, the other open fronts in line of sight are paired with the library''s pairs of patch junctions (connector inner ends; pair distances computed once per call) whose distance is within snap of the fronts'' distance; the best rated (1 - |d_patch - d_graph| / d_graph) that passes every legality check (the seam rule too) is placed turned so its two junctions land on the two fronts (at each front a connector of the patch must fit its street as in the depth-first draw: within angle_window and, by the Hausdorff distance, max_distance; it doubles the street and is left out). cell_init (''seeds''): how the local phase starts (with levels): seeds, from the example''s local junctions along the arterial patches; initial, Teng & Bidarra''s patches on main streets: patches tagged initial (the tags column) at seed points spaced along the grown main streets at the example''s spacing of local junctions along its main streets, (cell_spacing, 1: times that spacing), sides alternating, each turned so its main street lies along the grown one (its main streets left out), local growth going on from their connectors. max_turn (deg, 5): both turn a patch at most this far from the library''s frame (an initial patch mod 180; 180: freely, as Teng & Bidarra). How many fronts were bridged and initial patches placed is reported at DEBUG1 (grow_patches: teng-bidarra). promote_arterials (true): with levels, last of all, an arterial street (main road class) that ends farther than 50 m inside the region at a node where only local streets go on is continued by the cheapest route of local streets (metres, plus a local mean street for each turn sharper than 30 degrees, at most two such turns and none over 100) to a main street ahead of or beside its end, or straight on to within 50 m of the region''s boundary, no longer than the example''s widest space between its main streets: those streets take the arterial''s road_class (cheapest routes first, while the main streets stay within the example''s main-street length per area of its hull x the region''s area); one that still ends so, within a local mean street of a junction of three or more main streets, is a patch''s stub past that junction and takes the local streets'' commonest class. No geometry changes; false leaves the classes as the patches gave them (reported at DEBUG1: grow_patches: arterials run on). terminal_room (mean streets, 0: off): Teng & Bidarra''s rule of use for terminal patches (one connector, extract_patches'' tag terminal: they add no front, so the street they end cannot go on): at a dead-end front such a patch is drawn only where little room is left ahead, a street or node of the growth within terminal_room mean streets ahead (within angle_window of its heading) or the region''s edge, an obstacle or water on the straight line that long; fronts on a junction (local seeds on main streets) are not ruled (the candidates refused are reported at DEBUG1). Roundabouts: with levels, the local phase places no patch whose main streets double none there, except a patch tagged roundabout (the tags column) while the growth has no roundabout yet, so that a roundabout the example has on its main streets comes with them in the local phase when the arterial phase placed none';
