-- Road rasters (StreetGAN, Hartmann et al. 2017): a network drawn into a binary PostGIS raster,
-- and a raster traced back into a street graph. A road raster has one band, 1 = road,
-- 0 = background, in the network's CRS (metres). rasterise_network is PostGIS alone (GEOS buffer,
-- GDAL burn by pixel centre); raster_to_network is one C call (src/core/raster).

-- The edges a query returns (column geom, LineStrings or MultiLineStrings; a model's axes are
-- 'SELECT geom FROM <model>.axis'), drawn road_width_px pixels wide with round ends: a pixel is
-- road when its centre is within half the road width of an edge (the paper: 3 m pixels, roads
-- 15 px wide). Without an extent, the edges' bounding box grown by half the road width. The grid
-- is aligned on multiples of pixel_size, so rasters of one CRS and pixel size line up.
CREATE FUNCTION streetgen.rasterise_network(edges text, pixel_size double precision DEFAULT 3,
    road_width_px integer DEFAULT 15, extent geometry DEFAULT NULL)
  RETURNS raster
  LANGUAGE plpgsql VOLATILE
  COST 100000
  SET search_path FROM CURRENT
  SET jit = off
  AS $$
DECLARE
  geoms geometry[];
  lines geometry;
  srids integer[];
  kinds text[];
  box geometry;
  x0 double precision;
  y1 double precision;
  w bigint;
  h bigint;
  srid integer;
BEGIN
  IF edges IS NULL THEN
    RAISE EXCEPTION 'edges must not be null' USING ERRCODE = 'null_value_not_allowed';
  END IF;
  IF NOT coalesce(pixel_size > 0 AND pixel_size < 'infinity', false) THEN
    RAISE EXCEPTION 'pixel_size must be a number > 0 (metres)' USING ERRCODE = 'invalid_parameter_value',
      DETAIL = format('It is %s.', coalesce(pixel_size::text, 'null'));
  END IF;
  IF NOT coalesce(road_width_px >= 1, false) THEN
    RAISE EXCEPTION 'road_width_px must be an integer >= 1' USING ERRCODE = 'invalid_parameter_value',
      DETAIL = format('It is %s.', coalesce(road_width_px::text, 'null'));
  END IF;
  BEGIN
    EXECUTE format('SELECT array_agg(q.geom), array_agg(DISTINCT ST_SRID(q.geom)), array_agg(DISTINCT ST_GeometryType(q.geom))
                      FROM (%s) AS q WHERE q.geom IS NOT NULL', edges)
      INTO geoms, srids, kinds;
  EXCEPTION WHEN undefined_column OR undefined_function THEN
    RAISE EXCEPTION 'the edges query must return a geometry column named geom'
      USING ERRCODE = 'invalid_parameter_value', DETAIL = SQLERRM;
  END;
  IF cardinality(srids) > 1 THEN
    RAISE EXCEPTION 'edges must share one SRID' USING ERRCODE = 'invalid_parameter_value',
      DETAIL = format('The query returns SRIDs %s.', array_to_string(srids, ', '));
  END IF;
  IF EXISTS (SELECT 1 FROM unnest(kinds) k WHERE k NOT IN ('ST_LineString', 'ST_MultiLineString')) THEN
    RAISE EXCEPTION 'edges must be LineStrings or MultiLineStrings' USING ERRCODE = 'invalid_parameter_value',
      DETAIL = format('The query returns %s.', array_to_string(kinds, ', '));
  END IF;
  lines := ST_Collect(geoms);
  IF extent IS NOT NULL AND srids IS NOT NULL AND ST_SRID(extent) <> srids[1] THEN
    RAISE EXCEPTION 'extent must have the SRID of the edges' USING ERRCODE = 'invalid_parameter_value',
      DETAIL = format('The extent has SRID %s, the edges %s.', ST_SRID(extent), srids[1]);
  END IF;
  IF extent IS NULL AND lines IS NULL THEN
    RAISE EXCEPTION 'edges are empty and no extent is given' USING ERRCODE = 'invalid_parameter_value',
      HINT = 'Give an extent for an empty (all background) raster.';
  END IF;
  IF extent IS NOT NULL AND ST_IsEmpty(extent) THEN
    RAISE EXCEPTION 'extent must not be empty' USING ERRCODE = 'invalid_parameter_value';
  END IF;
  srid := coalesce(ST_SRID(extent), srids[1]);
  PERFORM streetgen._require_metric_srid(srid, 'edges SRID');
  box := coalesce(extent, ST_Expand(ST_Envelope(lines), road_width_px * pixel_size / 2));
  x0 := floor(ST_XMin(box) / pixel_size) * pixel_size;
  y1 := ceil(ST_YMax(box) / pixel_size) * pixel_size;
  w := greatest(1, ceil((ST_XMax(box) - x0) / pixel_size));
  h := greatest(1, ceil((y1 - ST_YMin(box)) / pixel_size));
  IF w > 65535 OR h > 65535 THEN
    RAISE EXCEPTION 'the raster would be % x % pixels, more than PostGIS''s 65535 a side', w, h
      USING ERRCODE = 'invalid_parameter_value', HINT = 'Use a larger pixel_size or a smaller extent.';
  END IF;
  RETURN ST_SetValues(ST_AddBand(ST_MakeEmptyRaster(w::integer, h::integer, x0, y1, pixel_size, -pixel_size, 0, 0, srid),
                                 '8BUI'::text, 0, NULL),
                      1, ARRAY[ROW(ST_Buffer(coalesce(lines, ST_SetSRID('LINESTRING EMPTY'::geometry, srid)),
                                             road_width_px * pixel_size / 2), 1)]::geomval[]);
END
$$;
COMMENT ON FUNCTION streetgen.rasterise_network(text, double precision, integer, geometry) IS
  'Draws the edges a query returns (column geom) into a one-band 8BUI raster, 1 = road, 0 = background: pixels whose centre is within road_width_px * pixel_size / 2 of an edge; pixel_size in metres (3), road_width_px (15), extent (default: the edges'' bounding box grown by half the road width)';

CREATE FUNCTION streetgen._streetgen_raster_to_network(rast_wkb bytea, threshold double precision, erode integer,
    dilate integer, min_block_area double precision, min_dead_end_length double precision, smooth_iterations integer,
    simplify_tolerance double precision, max_gap double precision, gap_angle double precision,
    OUT id bigint, OUT from_node bigint, OUT to_node bigint, OUT geom bytea)
  RETURNS SETOF record
  LANGUAGE c IMMUTABLE PARALLEL SAFE
  COST 100000 ROWS 1000
  AS 'MODULE_PATHNAME', '_streetgen_raster_to_network';

-- The band, pixel type and emptiness checks live in C++ (core/raster/wkb_raster.cpp), on the
-- same bytes the tracer reads; this wrapper checks the params jsonb (unknown keys and non-numbers
-- are refused here, ranges in C++).
CREATE FUNCTION streetgen.raster_to_network(rast raster, params jsonb DEFAULT '{}',
    OUT id bigint, OUT from_node bigint, OUT to_node bigint, OUT geom geometry)
  RETURNS SETOF record
  LANGUAGE plpgsql IMMUTABLE PARALLEL SAFE
  COST 100000 ROWS 1000
  SET search_path FROM CURRENT
  SET jit = off
  AS $$
DECLARE
  known constant text[] := ARRAY['dilate', 'erode', 'gap_angle', 'max_gap', 'min_block_area', 'min_dead_end_length',
                                 'simplify_tolerance', 'smooth_iterations', 'threshold'];
  integers constant text[] := ARRAY['dilate', 'erode', 'smooth_iterations'];
  p jsonb := coalesce(params, '{}'::jsonb);
  k text;
BEGIN
  IF rast IS NULL THEN
    RAISE EXCEPTION 'rast must not be null' USING ERRCODE = 'null_value_not_allowed';
  END IF;
  PERFORM streetgen._require_params(p, known);
  FOR k IN SELECT o FROM jsonb_object_keys(p) AS o ORDER BY o LOOP
    IF jsonb_typeof(p -> k) <> 'number' OR (k = ANY (integers) AND (p ->> k)::numeric % 1 <> 0) THEN
      RAISE EXCEPTION 'params.% must be %', k, CASE WHEN k = ANY (integers) THEN 'an integer' ELSE 'a number' END
        USING ERRCODE = 'invalid_parameter_value', DETAIL = format('It is %s.', p -> k);
    END IF;
    IF k = ANY (integers) AND abs((p ->> k)::numeric) > 100 THEN
      RAISE EXCEPTION 'params.% must be between 0 and 100', k USING ERRCODE = 'invalid_parameter_value',
        DETAIL = format('It is %s.', p -> k);
    END IF;
  END LOOP;
  RETURN QUERY
  SELECT r.id, r.from_node, r.to_node, ST_GeomFromEWKB(r.geom)
    FROM streetgen._streetgen_raster_to_network(
           ST_AsBinary(rast), coalesce((p ->> 'threshold')::double precision, 0.5),
           coalesce((p ->> 'erode')::integer, 1), coalesce((p ->> 'dilate')::integer, 5),
           coalesce((p ->> 'min_block_area')::double precision, 100),
           coalesce((p ->> 'min_dead_end_length')::double precision, 25),
           coalesce((p ->> 'smooth_iterations')::integer, 5),
           coalesce((p ->> 'simplify_tolerance')::double precision, 3),
           coalesce((p ->> 'max_gap')::double precision, 60),
           coalesce((p ->> 'gap_angle')::double precision, 30)) AS r;
END
$$;
COMMENT ON FUNCTION streetgen.raster_to_network(raster, jsonb) IS
  'Traces a one-band road raster (8BUI, 32BF, 64BF or 1BB; road = value > threshold, nodata is background) into street edges in its CRS (StreetGAN post-processing): erosion and dilation with a 3 x 3 cross, Zhang-Suen thinning, a graph of the 8-connected skeleton, faces below min_block_area lose their longest edge, each dead end is joined to the nearest road ahead within max_gap and gap_angle of its direction (without crossing an edge), dead ends shorter than min_dead_end_length are pruned, chains smoothed and simplified (Douglas-Peucker). params: threshold (0.5), erode (1), dilate (5), min_block_area (m², 100), max_gap (m, 60; 0: no gap closing), gap_angle (degrees, 30), min_dead_end_length (m, 25), smooth_iterations (5), simplify_tolerance (m, 3). Returns rows for a model''s axis table';
