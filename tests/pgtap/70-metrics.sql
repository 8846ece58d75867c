-- Network metrics: network_stats in its three forms, compare_networks, and every bad input of
-- the metrics issue (empty set, single edge, disconnected components, zero-area hull, duplicate
-- edges, geographic SRID), each with a defined result or an error with its SQLSTATE.
BEGIN;
SELECT * FROM no_plan();

-- A 3 x 3 grid of 100 m blocks in UTM 31N, one edge per block side.
CREATE TEMP TABLE grid AS
SELECT row_number() OVER () AS id, ST_SetSRID(g, 32631) AS geom
  FROM generate_series(0, 3) i, generate_series(0, 2) j,
       LATERAL (VALUES (ST_MakeLine(ST_MakePoint(j * 100, i * 100), ST_MakePoint((j + 1) * 100, i * 100))),
                       (ST_MakeLine(ST_MakePoint(i * 100, j * 100), ST_MakePoint(i * 100, (j + 1) * 100)))) AS v(g);

SELECT results_eq(
  $$SELECT node_count, edge_count, intersection_count, block_count, component_count
      FROM streetgen.network_stats('SELECT geom FROM grid')$$,
  $$VALUES (16::bigint, 24::bigint, 16::bigint, 9::bigint, 1::bigint)$$,
  'grid: 16 nodes, 24 edges, 9 blocks, one component');
SELECT ok((SELECT abs(mean_degree - 3) < 1e-12 AND abs(area - 90000) < 1e-6 AND abs(street_density - 2.4 / 0.09) < 1e-9
                  AND abs(orientation_order - 1) < 1e-12 AND abs(circuity - 1) < 1e-12 AND connected_node_ratio = 1
                  AND abs(block_compactness_median - pi() / 4) < 1e-9
             FROM streetgen.network_stats('SELECT geom FROM grid')),
          'grid: mean degree 3, hull area, density, order 1, circuity 1, CNR 1, square blocks');
SELECT is((SELECT array_length(degrees, 1) FROM streetgen.network_stats('SELECT geom FROM grid')), 16,
          'raw degrees: one per node');
SELECT is((SELECT array_length(orientation_histogram, 1) FROM streetgen.network_stats('SELECT geom FROM grid')), 36,
          '36 orientation bins');
SELECT is((SELECT s FROM streetgen.network_stats((SELECT ST_Collect(geom) FROM grid)) s),
          (SELECT s FROM streetgen.network_stats('SELECT geom FROM grid') s),
          'a geometry collection gives what the query gives');
SELECT is((SELECT s.node_count FROM streetgen.network_stats((SELECT ST_Multi(ST_Collect(geom)) FROM grid)) s), 16::bigint,
          'and so does a MultiLineString');

-- Window: the crop shrunk so that only the four inner nodes count, with their full degree 4.
SELECT results_eq(
  $$SELECT node_count, dead_end_share, degree4_share, block_count, area
      FROM streetgen.network_stats('SELECT geom FROM grid', 0, ST_MakeEnvelope(50, 50, 250, 250, 32631))$$,
  $$VALUES (4::bigint, 0::float8, 1::float8, 1::bigint, 40000::float8)$$,
  'window: inner nodes keep their degree, one block inside, the window is the area');

-- compare_networks: a network against itself, and against the grid with one street removed.
SELECT is((SELECT score FROM streetgen.compare_networks(streetgen.network_stats('SELECT geom FROM grid'),
                                                       streetgen.network_stats('SELECT geom FROM grid'))
            WHERE metric = 'realism_score'), 1::float8, 'a network is perfectly like itself');
SELECT ok((SELECT relative_difference < 0 FROM streetgen.compare_networks(
             streetgen.network_stats('SELECT geom FROM grid'),
             streetgen.network_stats('SELECT geom FROM grid WHERE id <> 8'))
            WHERE metric = 'block_count'), 'removing an inner street merges two blocks');
SELECT is((SELECT count(*) FROM streetgen.compare_networks(streetgen.network_stats('SELECT geom FROM grid'),
                                                          streetgen.network_stats('SELECT geom FROM grid WHERE id <> 8'))
            WHERE kind = 'distribution' AND ks IS NOT NULL AND wasserstein IS NOT NULL), 6::bigint,
          'six distributions compared (degree, segment length, block area, compactness, aspect ratio, orientation)');

-- Bad input: defined results.
SELECT results_eq(
  $$SELECT node_count, edge_count, total_length, mean_degree, street_density, block_count
      FROM streetgen.network_stats('SELECT geom FROM grid WHERE false')$$,
  $$VALUES (0::bigint, 0::bigint, 0::float8, NULL::float8, NULL::float8, 0::bigint)$$,
  'empty set: zero counts, undefined ratios are NULL');
SELECT results_eq(
  $$SELECT node_count, edge_count, area, street_density, dead_end_share
      FROM streetgen.network_stats('LINESTRING(0 0, 100 0)'::geometry)$$,
  $$VALUES (2::bigint, 1::bigint, 0::float8, NULL::float8, 1::float8)$$,
  'single edge: two dead ends, zero-area hull, density NULL');
SELECT results_eq(
  $$SELECT area, street_density, node_count FROM streetgen.network_stats('MULTILINESTRING((0 0, 100 0), (100 0, 300 0))'::geometry)$$,
  $$VALUES (0::float8, NULL::float8, 3::bigint)$$,
  'collinear edges: zero-area hull, density NULL');
SELECT results_eq(
  $$SELECT component_count, largest_component_share FROM streetgen.network_stats(
      'MULTILINESTRING((0 0, 100 0), (100 0, 100 100), (500 0, 600 0))'::geometry)$$,
  $$VALUES (2::bigint, 0.6::float8)$$,
  'disconnected components are counted');
SELECT results_eq(
  $$SELECT edge_count, duplicate_edges, node_count FROM streetgen.network_stats(
      'MULTILINESTRING((0 0, 100 0), (100 0, 0 0), (0 0, 100 0), (0 0, 50 20, 100 0))'::geometry)$$,
  $$VALUES (2::bigint, 2::bigint, 2::bigint)$$,
  'duplicate edges (either direction) are dropped and counted; a parallel edge with its own course is kept');
SELECT results_eq(
  $$SELECT node_count, collapsed_edges FROM streetgen.network_stats(
      'MULTILINESTRING((0 0, 100 0), (100.3 0, 200 0), (100 0, 100.2 0.1))'::geometry, 0.5)$$,
  $$VALUES (3::bigint, 1::bigint)$$,
  'node tolerance: near ends merge, an edge inside a merged node collapses');
SELECT is((SELECT node_count FROM streetgen.network_stats((SELECT ST_Collect(geom) FROM grid WHERE false))), 0::bigint,
          'a NULL geometry (ST_Collect of no rows) is the empty set');
SELECT is((SELECT node_count FROM streetgen.network_stats('SELECT geom FROM grid WHERE geom IS NULL OR id < 3
                                                          UNION ALL SELECT NULL::geometry')), 3::bigint,
          'NULL geometries are skipped');
SELECT results_eq(
  $$SELECT node_count, edge_count FROM streetgen.network_stats(
      'MULTILINESTRING((-50 0, 50 0), (0 -50, 0 50))'::geometry, split_at_crossings => true)$$,
  $$VALUES (5::bigint, 4::bigint)$$,
  'split_at_crossings: crossing lines meet in a node');
SELECT results_eq(
  $$SELECT node_count, edge_count FROM streetgen.network_stats(
      'MULTILINESTRING((0 0, 10 0), (10 0, 20 0), (20 0, 30 0), (20 0, 20 10))'::geometry, simplify => true)$$,
  $$VALUES (4::bigint, 3::bigint)$$,
  'simplify: a degree-2 node disappears');

-- Bad input: clear errors.
SELECT throws_ok($$SELECT streetgen.network_stats(ST_SetSRID('LINESTRING(2 48, 2.1 48.1)'::geometry, 4326))$$,
                 '22023', NULL, 'geographic SRID: 22023');
SELECT throws_ok($$SELECT streetgen.network_stats('SELECT ST_SetSRID(''LINESTRING(2 48, 2.1 48.1)''::geometry, 4326) AS geom')$$,
                 '22023', NULL, 'geographic SRID through a query: 22023');
SELECT throws_ok($$SELECT streetgen.network_stats('SELECT geom FROM grid UNION ALL SELECT ''SRID=32632;LINESTRING(0 0, 1 1)''::geometry')$$,
                 '22023', 'edges must share one SRID', 'mixed SRIDs: 22023');
SELECT throws_ok($$SELECT streetgen.network_stats('SELECT ST_Buffer(geom, 1) AS geom FROM grid')$$,
                 '22023', 'edges must be LineStrings or MultiLineStrings', 'polygons as edges: 22023');
SELECT throws_ok($$SELECT streetgen.network_stats('SELECT id FROM grid')$$,
                 '22023', 'the edges query must return a geometry column named geom', 'no geom column: 22023');
SELECT throws_ok($$SELECT streetgen.network_stats('SELECT geom FROM grid', -1)$$,
                 '22023', 'node_tolerance must be a finite number >= 0', 'negative tolerance: 22023');
SELECT throws_ok($$SELECT streetgen.network_stats('SELECT geom FROM grid', 'NaN')$$,
                 '22023', 'node_tolerance must be a finite number >= 0', 'NaN tolerance: 22023');
SELECT throws_ok($$SELECT streetgen.network_stats('SELECT geom FROM grid', NULL)$$,
                 '22004', NULL, 'NULL tolerance: 22004');
SELECT throws_ok($$SELECT streetgen.network_stats(NULL::text)$$, '22004', NULL, 'NULL query: 22004');
SELECT throws_ok($$SELECT streetgen.network_stats('SELECT geom FROM grid', 0, ST_MakeEnvelope(0, 0, 1, 1, 32632))$$,
                 '22023', 'window must have the SRID of the edges', 'window in another SRID: 22023');
SELECT throws_ok($$SELECT streetgen.network_stats('SELECT geom FROM grid', 0, 'SRID=32631;LINESTRING(0 0, 1 1)'::geometry)$$,
                 '22023', 'window must be a non-empty Polygon or MultiPolygon', 'a line as window: 22023');
SELECT throws_ok($$SELECT streetgen.network_stats('SELECT geom FROM grid', 0, 'SRID=32631;POLYGON((0 0, 1 0, 2 0, 0 0))'::geometry)$$,
                 '22023', 'window must have a positive area', 'a zero-area window: 22023');
SELECT throws_ok($$SELECT streetgen.network_stats('LINESTRING(0 0, 1 1)'::geometry, 0, ST_SetSRID('POLYGON((0 0, 1 0, 1 1, 0 0))'::geometry, 4326))$$,
                 '22023', NULL, 'a geographic window: 22023');
SELECT throws_ok($$SELECT streetgen.compare_networks(NULL, streetgen.network_stats('SELECT geom FROM grid'))$$,
                 '22004', NULL, 'compare_networks with a NULL side: 22004');

-- A model: its axes go through the surface engine's topology (crossings split) with its snap tolerance.
SELECT streetgen.create_model('metrics_m', 32631);
INSERT INTO metrics_m.axis (geom, roadway_width, speed_kmh)
VALUES (ST_GeomFromText('LINESTRING(-60 0, 60 0)', 32631), 8, 50),
       (ST_GeomFromText('LINESTRING(0 -60, 0 60)', 32631), 8, 50),
       (ST_GeomFromText('LINESTRING(60.3 0, 120 0)', 32631), 8, 50);
SELECT results_eq(
  $$SELECT node_count, edge_count, degree4_share FROM streetgen.model_network_stats('metrics_m')$$,
  $$VALUES (6::bigint, 5::bigint, 1::float8 / 6)$$,
  'model: crossing axes split, ends within the snap tolerance (0.5 m) merged');
SELECT is((SELECT node_count FROM streetgen.model_network_stats('metrics_m', 0.0)), 7::bigint,
          'model with node_tolerance 0: the near end stays apart');
UPDATE metrics_m.axis SET layer = 1 WHERE ST_XMin(geom) = 0;  -- the north-south axis becomes a bridge
SELECT results_eq(
  $$SELECT node_count, edge_count, degree4_share FROM streetgen.model_network_stats('metrics_m')$$,
  $$VALUES (5::bigint, 3::bigint, 0::float8)$$,
  'model: a bridge crosses without a junction');
SELECT throws_ok($$SELECT streetgen.model_network_stats('no_such_model')$$, '42704', NULL, 'unknown model: 42704');

-- Cancellation: statement_timeout stops a long computation inside C++ (a 180,000-edge network
-- through the engine topology takes several seconds) with PostgreSQL's own 57014.
CREATE TEMP TABLE big AS
SELECT array_agg(ST_AsEWKB(g)) AS geoms
  FROM generate_series(0, 300) i, generate_series(0, 299) j,
       LATERAL (VALUES (ST_MakeLine(ST_MakePoint(j * 10, i * 10 + (j % 3)), ST_MakePoint((j + 1) * 10, i * 10 + ((j + 1) % 3)))),
                       (ST_MakeLine(ST_MakePoint(i * 10, j * 10), ST_MakePoint(i * 10, (j + 1) * 10)))) AS v(g);
CREATE TEMP TABLE outcome (state text, seconds double precision);
SET LOCAL statement_timeout = '300ms';
INSERT INTO outcome SELECT * FROM test_helpers.sqlstate_and_seconds(
  $$SELECT (streetgen._streetgen_network_stats(geoms, 0.5, NULL, true, false, true, '{}')).node_count FROM big$$);
RESET statement_timeout;
SELECT is((SELECT state FROM outcome), '57014', 'statement_timeout cancels network_stats with 57014');
SELECT cmp_ok((SELECT seconds FROM outcome), '<', 3.0::double precision,
              'within the computation, not after it (it runs for several seconds)');
SELECT is((SELECT node_count FROM streetgen.network_stats('LINESTRING(0 0, 1 0)'::geometry)), 2::bigint,
          'the session computes again after the cancel');

SELECT * FROM finish();
ROLLBACK;
