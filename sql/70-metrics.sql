-- Network metrics (OSMnx definitions, Connected Node Ratio, block shapes) and the comparison of
-- two networks. One C call builds the graph once and computes everything; src/core/metrics holds
-- the definitions (network_stats.hpp, compare_networks.hpp).

CREATE TYPE streetgen.network_metrics AS (
  node_count bigint,
  edge_count bigint,
  duplicate_edges bigint,
  collapsed_edges bigint,
  component_count bigint,
  largest_component_share double precision,
  total_length double precision,
  area double precision,
  node_density double precision,
  intersection_count bigint,
  intersection_density double precision,
  street_density double precision,
  mean_degree double precision,
  dead_end_share double precision,
  degree2_share double precision,
  degree3_share double precision,
  degree4_share double precision,
  degree5plus_share double precision,
  connected_node_ratio double precision,
  mean_segment_length double precision,
  circuity double precision,
  orientation_entropy double precision,
  orientation_order double precision,
  block_count bigint,
  block_area_p25 double precision,
  block_area_median double precision,
  block_area_p75 double precision,
  block_area_mean double precision,
  block_compactness_p25 double precision,
  block_compactness_median double precision,
  block_compactness_p75 double precision,
  block_aspect_ratio_p25 double precision,
  block_aspect_ratio_median double precision,
  block_aspect_ratio_p75 double precision,
  degrees integer[],
  segment_lengths double precision[],
  orientation_histogram double precision[],
  block_areas double precision[],
  block_compactness double precision[],
  block_aspect_ratios double precision[]
);
COMMENT ON TYPE streetgen.network_metrics IS
  'Statistics of a street network (see streetgen.network_stats): counts, lengths in m, areas in m², densities per km², shares in [0, 1], orientation in 36 bins of 10° centred on 0° (north), raw distributions as arrays';

CREATE FUNCTION streetgen._streetgen_network_stats(geoms bytea[], node_tolerance double precision, win bytea,
                                                   split_at_crossings boolean, simplify boolean, blocks boolean,
                                                   layers integer[])
  RETURNS streetgen.network_metrics
  LANGUAGE c IMMUTABLE PARALLEL SAFE
  COST 100000
  AS 'MODULE_PATHNAME', '_streetgen_network_stats';

CREATE FUNCTION streetgen._streetgen_compare_networks(a streetgen.network_metrics, b streetgen.network_metrics,
    OUT metric text, OUT kind text, OUT a double precision, OUT b double precision,
    OUT relative_difference double precision, OUT ks double precision, OUT wasserstein double precision,
    OUT score double precision)
  RETURNS SETOF record
  LANGUAGE c IMMUTABLE PARALLEL SAFE
  COST 1000 ROWS 50
  AS 'MODULE_PATHNAME', '_streetgen_compare_networks';

-- Checks shared by the overloads: a metric SRID for the edges and the window.
CREATE FUNCTION streetgen._network_stats(geoms bytea[], srid integer, node_tolerance double precision,
    window_polygon geometry, split_at_crossings boolean, simplify boolean, blocks boolean, layers integer[] DEFAULT NULL)
  RETURNS streetgen.network_metrics
  LANGUAGE plpgsql STABLE PARALLEL SAFE
  SET search_path FROM CURRENT
  AS $$
BEGIN
  IF node_tolerance IS NULL THEN
    RAISE EXCEPTION 'node_tolerance must not be null' USING ERRCODE = 'null_value_not_allowed';
  END IF;
  IF srid IS NOT NULL THEN
    PERFORM streetgen._require_metric_srid(srid, 'edges SRID');
  END IF;
  IF window_polygon IS NOT NULL THEN
    PERFORM streetgen._require_metric_srid(ST_SRID(window_polygon), 'window SRID');
  END IF;
  RETURN streetgen._streetgen_network_stats(coalesce(geoms, '{}'), node_tolerance, ST_AsEWKB(window_polygon),
                                            coalesce(split_at_crossings, false), coalesce(simplify, false),
                                            coalesce(blocks, true), coalesce(layers, '{}'));
END
$$;

-- A geometry collection (or MultiLineString, or one LineString) of edges.
CREATE FUNCTION streetgen.network_stats(edges geometry, node_tolerance double precision DEFAULT 0,
    window_polygon geometry DEFAULT NULL, split_at_crossings boolean DEFAULT false,
    simplify boolean DEFAULT false, blocks boolean DEFAULT true)
  RETURNS streetgen.network_metrics
  LANGUAGE sql STABLE PARALLEL SAFE
  SET search_path FROM CURRENT
  AS $$
  SELECT streetgen._network_stats((SELECT array_agg(ST_AsEWKB(d.geom)) FROM ST_Dump(edges) AS d), ST_SRID(edges),
                                  node_tolerance, window_polygon, split_at_crossings, simplify, blocks)
$$;
COMMENT ON FUNCTION streetgen.network_stats(geometry, double precision, geometry, boolean, boolean, boolean) IS
  'Network statistics (OSMnx definitions, CNR, dead ends, orientation entropy and order, blocks) of the LineStrings in a geometry; ends closer than node_tolerance (m) merge; with window_polygon, nodes and blocks inside it count, with their full degree';

-- The edges a query returns (a column named geom: LineStrings or MultiLineStrings). The query
-- runs with the caller's rights; NULL geometries are skipped, like an aggregate skips NULLs.
CREATE FUNCTION streetgen.network_stats(edges text, node_tolerance double precision DEFAULT 0,
    window_polygon geometry DEFAULT NULL, split_at_crossings boolean DEFAULT false,
    simplify boolean DEFAULT false, blocks boolean DEFAULT true)
  RETURNS streetgen.network_metrics
  LANGUAGE plpgsql VOLATILE
  SET search_path FROM CURRENT
  SET jit = off
  AS $$
DECLARE
  geoms bytea[];
  srids integer[];
BEGIN
  IF edges IS NULL THEN
    RAISE EXCEPTION 'edges must not be null' USING ERRCODE = 'null_value_not_allowed';
  END IF;
  BEGIN
    EXECUTE format('SELECT array_agg(ST_AsEWKB(q.geom)), array_agg(DISTINCT ST_SRID(q.geom)) FROM (%s) AS q', edges)
      INTO geoms, srids;
  EXCEPTION WHEN undefined_column OR undefined_function THEN
    RAISE EXCEPTION 'the edges query must return a geometry column named geom'
      USING ERRCODE = 'invalid_parameter_value', DETAIL = SQLERRM;
  END;
  srids := array_remove(srids, NULL);
  IF cardinality(srids) > 1 THEN
    RAISE EXCEPTION 'edges must share one SRID' USING ERRCODE = 'invalid_parameter_value',
      DETAIL = format('The query returns SRIDs %s.', array_to_string(srids, ', '));
  END IF;
  RETURN streetgen._network_stats(geoms, srids[1], node_tolerance, window_polygon, split_at_crossings, simplify, blocks);
END
$$;
COMMENT ON FUNCTION streetgen.network_stats(text, double precision, geometry, boolean, boolean, boolean) IS
  'Network statistics of the edges a query returns (column geom); see network_stats(geometry, ...)';

-- A model's axes, through the surface engine's topology (split where axes of one layer cross;
-- bridges and tunnels meet the rest only at their ends) with the model's snap tolerance unless
-- one is given.
CREATE FUNCTION streetgen.model_network_stats(model text, node_tolerance double precision DEFAULT NULL,
    window_polygon geometry DEFAULT NULL, simplify boolean DEFAULT false, blocks boolean DEFAULT true)
  RETURNS streetgen.network_metrics
  LANGUAGE plpgsql STABLE
  SET search_path FROM CURRENT
  SET jit = off
  AS $$
DECLARE
  srid integer := streetgen.model_srid(model);
  tolerance double precision := node_tolerance;
  geoms bytea[];
  layers integer[];
BEGIN
  IF tolerance IS NULL THEN
    EXECUTE format('SELECT s.snap_tolerance FROM %I.settings s', model) INTO tolerance;
  END IF;
  EXECUTE format('SELECT array_agg(ST_AsEWKB(a.geom) ORDER BY a.id), array_agg(a.layer::integer ORDER BY a.id)
                    FROM %I.axis a', model) INTO geoms, layers;
  RETURN streetgen._network_stats(geoms, srid, coalesce(tolerance, 0), window_polygon, true, simplify, blocks, layers);
END
$$;
COMMENT ON FUNCTION streetgen.model_network_stats(text, double precision, geometry, boolean, boolean) IS
  'Network statistics of a model''s axes, split where they cross (the surface engine''s topology), nodes merged within the model''s snap tolerance unless node_tolerance is given';

CREATE FUNCTION streetgen.compare_networks(reference streetgen.network_metrics, candidate streetgen.network_metrics,
    OUT metric text, OUT kind text, OUT reference_value double precision, OUT candidate_value double precision,
    OUT relative_difference double precision, OUT ks double precision, OUT wasserstein double precision,
    OUT score double precision)
  RETURNS SETOF record
  LANGUAGE plpgsql IMMUTABLE PARALLEL SAFE
  COST 1000 ROWS 50
  SET search_path FROM CURRENT
  AS $$
BEGIN
  IF reference IS NULL OR candidate IS NULL THEN
    RAISE EXCEPTION 'reference and candidate must not be null' USING ERRCODE = 'null_value_not_allowed';
  END IF;
  RETURN QUERY SELECT * FROM streetgen._streetgen_compare_networks(reference, candidate);
END
$$;
COMMENT ON FUNCTION streetgen.compare_networks(streetgen.network_metrics, streetgen.network_metrics) IS
  'How far candidate is from reference: per metric (candidate - reference) / |reference|; Kolmogorov-Smirnov (Kuiper for orientation) and Wasserstein distances of the degree, segment length, block and orientation distributions; realism_score = 1 - median of min(1, |relative difference|) over the eight headline metrics';
