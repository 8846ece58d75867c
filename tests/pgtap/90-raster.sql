-- Road rasters (StreetGAN): rasterise_network and raster_to_network on real example patches of
-- ../shared/data/examples/patches (Nishida et al.'s crops of OpenStreetMap, © OpenStreetMap
-- contributors, ODbL 1.0): the raster's shape, the round trip example -> raster -> graph
-- evaluated with network_stats (the issue's 20 % dead-end bound), insertion into a model, and
-- every bad input by SQLSTATE. run-pgtap.sh passes the data folder as streetgen_test.shared_data.
BEGIN;
SELECT * FROM no_plan();

CREATE TEMP TABLE patch AS
SELECT n AS name, ST_SetSRID(ST_GeomFromGeoJSON(f -> 'geometry'), 0) AS geom
  FROM unnest(ARRAY['new-york', 'canberra_south_large']) AS n,
       jsonb_array_elements(pg_read_file(current_setting('streetgen_test.shared_data') || '/examples/patches/' || n
                                         || '.geojson')::jsonb -> 'features') AS f;
SELECT ok((SELECT count(DISTINCT name) = 2 AND count(*) > 1000 FROM patch), 'two real example patches loaded');

-- ---- rasterise_network ----
CREATE TEMP TABLE paper AS SELECT streetgen.rasterise_network($$SELECT geom FROM patch WHERE name = 'new-york'$$) AS rast;
SELECT is((SELECT ARRAY[ST_NumBands(rast)::text, ST_BandPixelType(rast), coalesce(ST_BandNoDataValue(rast)::text, 'none'),
                        ST_ScaleX(rast)::text, ST_ScaleY(rast)::text, ST_SRID(rast)::text] FROM paper),
          ARRAY['1', '8BUI', 'none', '3', '-3', '0'], 'one 8BUI band without nodata, 3 m pixels, the edges'' SRID');
SELECT is((SELECT array_agg(DISTINCT v ORDER BY v) FROM paper, unnest(ST_DumpValues(rast, 1)) AS v), ARRAY[0, 1]::double precision[],
          'pixels are 0 (background) or 1 (road)');
SELECT ok((SELECT ST_Covers(ST_Envelope(rast), ST_Expand(e, 22.5)) AND ST_Area(ST_Envelope(rast)) < ST_Area(ST_Expand(e, 22.5 + 3))
             FROM paper, (SELECT ST_Extent(geom)::geometry AS e FROM patch WHERE name = 'new-york') x),
          'the default extent is the edges'' box grown by half the road width, on whole pixels');
SELECT ok((SELECT ST_UpperLeftX(rast)::numeric % 3 = 0 AND ST_UpperLeftY(rast)::numeric % 3 = 0 FROM paper),
          'the grid is aligned on multiples of the pixel size');
-- Road exactly where a pixel centre is within half the road width of an edge: on every edge's
-- midpoint, and, pixel by pixel on a coarser raster (10 m, 5 px: 25 m), road if and only if an
-- edge is that close, up to GEOS's buffer, whose round ends and joins are chords (8 per
-- quarter circle: at most 25 m x (1 - cos(pi / 16)) = 0.48 m inside the true circle).
SELECT is((SELECT count(*) FROM paper, patch p WHERE p.name = 'new-york'
            AND ST_Value(rast, 1, ST_LineInterpolatePoint(p.geom, 0.5)) <> 1), 0::bigint, 'every edge''s midpoint is road');
CREATE TEMP TABLE ny_edges AS SELECT geom FROM patch WHERE name = 'new-york';
CREATE INDEX ON ny_edges USING gist (geom);
CREATE TEMP TABLE coarse AS
SELECT c.val, c.geom FROM ST_PixelAsCentroids(streetgen.rasterise_network('SELECT geom FROM ny_edges', 10, 5), 1, false) AS c;
SELECT ok((SELECT count(*) = 69000 AND count(*) FILTER (WHERE val = 1) > 20000 FROM coarse), 'the coarse raster, 69,000 pixels');
SELECT is((SELECT count(*) FROM coarse c
            WHERE (c.val = 1) <> EXISTS (SELECT 1 FROM ny_edges e WHERE ST_DWithin(e.geom, c.geom, 25))
              AND NOT EXISTS (SELECT 1 FROM ny_edges e WHERE ST_DWithin(e.geom, c.geom, 25 + 0.5)
                                                        AND NOT ST_DWithin(e.geom, c.geom, 25 - 0.5))),
          0::bigint, 'a pixel is road if and only if its centre is within half the road width of an edge');
SELECT is((SELECT ARRAY[ST_Width(r), ST_Height(r), ST_UpperLeftX(r)::integer, ST_UpperLeftY(r)::integer]
             FROM (SELECT streetgen.rasterise_network($$SELECT geom FROM patch WHERE name = 'new-york'$$, 2, 5,
                                                      ST_MakeEnvelope(-101, -199, 99, 1, 0)) AS r) s),
          ARRAY[101, 101, -102, 2], 'an explicit extent, snapped outwards to the pixel grid');
SELECT is((SELECT array_agg(ST_Value(r, 1, p::geometry) ORDER BY p)
             FROM (SELECT streetgen.rasterise_network($$SELECT 'LINESTRING(0 0, 100 0)'::geometry AS geom
                                                      UNION ALL SELECT 'MULTILINESTRING((0 50, 100 50), (50 0, 50 100))'$$, 3, 5) AS r) s,
                  unnest(ARRAY['POINT(30 0)', 'POINT(30 50)', 'POINT(50 80)', 'POINT(80 25)']) AS p),
          ARRAY[1, 1, 1, 0]::double precision[], 'LineStrings and MultiLineStrings together');
SELECT is((SELECT (ST_SummaryStats(streetgen.rasterise_network('SELECT geom FROM patch WHERE false', 3, 15,
                                                               ST_MakeEnvelope(0, 0, 30, 30, 0)), 1, false)).sum),
          0::double precision, 'no edges and an extent: an all-background raster');

-- ---- raster_to_network on the paper's rasters (3 m, 15 px, the paper's defaults) ----
CREATE TEMP TABLE traced AS SELECT t.* FROM paper, streetgen.raster_to_network(rast) AS t;
SELECT ok((SELECT count(*) > 300 FROM traced), 'the new-york raster traces to a network');
SELECT is((SELECT count(*) FROM traced WHERE geom IS NULL OR ST_GeometryType(geom) <> 'ST_LineString' OR ST_SRID(geom) <> 0
                                        OR ST_Length(geom) = 0), 0::bigint, 'non-degenerate LineStrings in the raster''s SRID');
SELECT is((SELECT count(*) FROM (SELECT from_node AS n, ST_StartPoint(geom) AS p FROM traced
                                 UNION SELECT to_node, ST_EndPoint(geom) FROM traced) s
            GROUP BY n HAVING count(DISTINCT ST_AsEWKB(p)) > 1), NULL, 'one position per node id');
SELECT is((SELECT array_agg(id ORDER BY id) FROM traced), (SELECT array_agg(i) FROM generate_series(1, (SELECT count(*) FROM traced)::integer) i)::bigint[],
          'edge ids 1..n');
SELECT results_eq($$SELECT id, from_node, to_node, ST_AsEWKB(geom) FROM paper, streetgen.raster_to_network(rast) ORDER BY id$$,
                  $$SELECT id, from_node, to_node, ST_AsEWKB(geom) FROM traced ORDER BY id$$, 'deterministic');

-- ---- The round trip the issue evaluates: example -> raster -> graph, network_stats compared ----
-- Settings for a clean (rasterised, not generated) raster: roads 7 px = 21 m wide, about a real
-- street with its sidewalks, so that parallel streets 30 m apart stay apart (at the paper's 15 px
-- = 45 m they merge); two dilations instead of five (there are no generator gaps to close); dead
-- ends shorter than 12 m pruned (the example's own cul-de-sac stubs are 10-40 m). Measured with
-- them: dead-end share -15 % (new-york) and +7 % (canberra), total length -7 % and -4 %.
CREATE TEMP TABLE roundtrip AS
SELECT p.name, streetgen.network_stats(format('SELECT geom FROM patch WHERE name = %L', p.name)) AS example,
       streetgen.network_stats(format($q$SELECT t.geom FROM streetgen.raster_to_network(
         streetgen.rasterise_network(%L, 3, 7),
         '{"dilate": 2, "min_dead_end_length": 12}') AS t$q$, format('SELECT geom FROM patch WHERE name = %L', p.name))) AS traced
  FROM (SELECT DISTINCT name FROM patch) p;
SELECT ok(abs((traced).dead_end_share - (example).dead_end_share) <= 0.2 * (example).dead_end_share,
          format('%s: dead-end share %s within 20 %% of the example''s %s', name, round((traced).dead_end_share::numeric, 3),
                 round((example).dead_end_share::numeric, 3)))
  FROM roundtrip ORDER BY name;
-- Total length: thinning cuts no road short (dead ends are carried on to the paint's end), so
-- what is lost is the example's stubs shorter than the pruning length, and curves smoothed and
-- simplified within 3 m: 10 % bounds both with margin.
SELECT ok(abs((traced).total_length - (example).total_length) <= 0.10 * (example).total_length,
          format('%s: total length %s m within 10 %% of the example''s %s m', name, round((traced).total_length),
                 round((example).total_length)))
  FROM roundtrip ORDER BY name;
SELECT ok(abs((traced).connected_node_ratio - (example).connected_node_ratio) <= 0.1 * (example).connected_node_ratio,
          format('%s: CNR %s within 10 %% of the example''s %s', name, round((traced).connected_node_ratio::numeric, 3),
                 round((example).connected_node_ratio::numeric, 3)))
  FROM roundtrip ORDER BY name;
SELECT ok((SELECT abs((traced).block_area_median / (example).block_area_median - 1) < 0.15 FROM roundtrip WHERE name = 'new-york'),
          'new-york: median block area within 15 % of the example''s');

-- Straight into a model's axis table.
SELECT streetgen.create_model('traced_ny', 0);
INSERT INTO traced_ny.axis (geom, roadway_width, speed_kmh, road_class, source)
SELECT geom, 8, 30, 'residential', 'raster_to_network:' || id FROM traced;
SELECT is((SELECT count(*) FROM traced_ny.axis), (SELECT count(*) FROM traced), 'traced edges inserted into a model''s axis table');
SELECT ok((SELECT count(*) FROM traced_ny.section) >= (SELECT count(*) FROM traced), 'and the model''s sections follow');

-- A generator's output: 32BF in [-1, 1], road above 0.
CREATE TEMP TABLE float_raster AS
SELECT ST_MapAlgebra(rast, 1, '32BF', '[rast] * 2 - 1') AS rast FROM paper;
SELECT is((SELECT ST_BandPixelType(rast) FROM float_raster), '32BF', 'a 32BF raster in [-1, 1]');
SELECT results_eq($$SELECT id, from_node, to_node, ST_AsEWKB(geom) FROM float_raster, streetgen.raster_to_network(rast, '{"threshold": 0}') ORDER BY id$$,
                  $$SELECT id, from_node, to_node, ST_AsEWKB(geom) FROM traced ORDER BY id$$,
                  'traces like the 8BUI raster with threshold 0');
SELECT is((SELECT count(*) FROM float_raster, streetgen.raster_to_network(ST_MapAlgebra(rast, 1, '32BF', '[rast] - 3'))),
          0::bigint, 'an all-background raster gives no edges');

-- ---- Gap closing: a broken T (2 m pixels, 5 px roads; the side road's paint stops 33 m short) ----
CREATE TEMP TABLE broken_t AS
SELECT streetgen.rasterise_network($$SELECT 'LINESTRING(0 160, 202 160)'::geometry AS geom
                                   UNION ALL SELECT 'LINESTRING(101 0, 101 117)'$$, 2, 5,
                                   ST_MakeEnvelope(0, 0, 202, 202, 0)) AS rast;
SELECT is((SELECT count(*) FROM broken_t, streetgen.raster_to_network(rast, '{"erode": 0, "dilate": 0}')), 3::bigint,
          'a dead end is joined to the road ahead of it: a T of three edges');
SELECT is((SELECT count(*) FROM (SELECT n FROM broken_t, streetgen.raster_to_network(rast, '{"erode": 0, "dilate": 0}') t,
                                        LATERAL (VALUES (t.from_node), (t.to_node)) v(n) GROUP BY n HAVING count(*) = 3) j),
          1::bigint, 'one junction where the gap was');
SELECT is((SELECT count(*) FROM broken_t, streetgen.raster_to_network(rast, '{"erode": 0, "dilate": 0, "max_gap": 0}')),
          2::bigint, 'max_gap 0: no gap closing, the road and a dead end');
SELECT is((SELECT count(*) FROM broken_t, streetgen.raster_to_network(rast, '{"erode": 0, "dilate": 0, "max_gap": 30}')),
          2::bigint, 'a gap longer than max_gap stays open');

-- ---- Bad input, by SQLSTATE ----
CREATE TEMP TABLE tiny AS
SELECT ST_AddBand(ST_MakeEmptyRaster(8, 8, 0, 8, 1, -1, 0, 0, 0), '8BUI'::text, 0, NULL) AS rast;
SELECT throws_ok($$SELECT * FROM streetgen.raster_to_network(NULL)$$, '22004', 'rast must not be null', 'NULL raster');
SELECT throws_ok($$SELECT * FROM tiny, streetgen.raster_to_network(ST_AddBand(rast, '8BUI'::text, 0, NULL))$$, '22023',
                 'rast must have exactly one band', 'two bands');
SELECT throws_ok($$SELECT * FROM streetgen.raster_to_network(ST_MakeEmptyRaster(8, 8, 0, 8, 1, -1, 0, 0, 0))$$, '22023',
                 'rast must have exactly one band', 'no band');
SELECT throws_ok($$SELECT * FROM streetgen.raster_to_network(ST_MakeEmptyRaster(0, 0, 0, 0, 1, -1, 0, 0, 0))$$, '22023',
                 'rast is empty', 'an empty raster');
SELECT throws_ok($$SELECT * FROM streetgen.raster_to_network(ST_AddBand(ST_MakeEmptyRaster(8, 8, 0, 8, 1, -1, 0, 0, 0), '16BUI'::text, 0, NULL))$$,
                 '22023', 'rast must have pixel type 8BUI, 32BF, 64BF or 1BB', '16BUI pixel type');
SELECT throws_ok($$SELECT * FROM tiny, streetgen.raster_to_network(ST_AddBand(ST_MakeEmptyRaster(rast), '8BUI'::text, 1, NULL))$$,
                 '22000', 'rast has no background pixel', 'an all-road raster');
SELECT throws_ok($$SELECT * FROM tiny, streetgen.raster_to_network(rast, '{"tolerance": 3}')$$, '22023',
                 'unknown params key: tolerance', 'unknown params key');
SELECT throws_ok($$SELECT * FROM tiny, streetgen.raster_to_network(rast, '{"simplify_tolerance": -1}')$$, '22023',
                 'simplify_tolerance must be a finite number >= 0', 'negative tolerance');
SELECT throws_ok($$SELECT * FROM tiny, streetgen.raster_to_network(rast, '{"max_gap": -1}')$$, '22023',
                 'max_gap must be a finite number >= 0', 'negative max_gap');
SELECT throws_ok($$SELECT * FROM tiny, streetgen.raster_to_network(rast, '{"gap_angle": 120}')$$, '22023',
                 'gap_angle must be between 0 and 90 (degrees)', 'gap_angle over 90');
SELECT throws_ok($$SELECT * FROM tiny, streetgen.raster_to_network(rast, '{"gap_angle": "wide"}')$$, '22023',
                 'params.gap_angle must be a number', 'a string for gap_angle');
SELECT throws_ok($$SELECT * FROM tiny, streetgen.raster_to_network(rast, '{"min_block_area": "big"}')$$, '22023',
                 'params.min_block_area must be a number', 'a string for a number');
SELECT throws_ok($$SELECT * FROM tiny, streetgen.raster_to_network(rast, '{"erode": 1.5}')$$, '22023',
                 'params.erode must be an integer', 'a fraction for an integer');
SELECT throws_ok($$SELECT * FROM tiny, streetgen.raster_to_network(rast, '{"dilate": -2}')$$, '22023',
                 'dilate must be between 0 and 100', 'negative dilation');
SELECT throws_ok($$SELECT * FROM tiny, streetgen.raster_to_network(rast, '{"smooth_iterations": 1e12}')$$, '22023',
                 'params.smooth_iterations must be between 0 and 100', 'a huge integer');
SELECT throws_ok($$SELECT * FROM tiny, streetgen.raster_to_network(rast, '[1]')$$, '22023',
                 'params must be a json object', 'params not an object');

SELECT throws_ok($$SELECT streetgen.rasterise_network(NULL)$$, '22004', 'edges must not be null', 'NULL edges');
SELECT throws_ok($$SELECT streetgen.rasterise_network('SELECT geom FROM patch', 0)$$, '22023',
                 'pixel_size must be a number > 0 (metres)', 'pixel_size 0');
SELECT throws_ok($$SELECT streetgen.rasterise_network('SELECT geom FROM patch', 3, 0)$$, '22023',
                 'road_width_px must be an integer >= 1', 'road_width_px 0');
SELECT throws_ok($$SELECT streetgen.rasterise_network('SELECT 1 AS x')$$, '22023',
                 'the edges query must return a geometry column named geom', 'no geom column');
SELECT throws_ok($$SELECT streetgen.rasterise_network('SELECT ''POINT(1 1)''::geometry AS geom')$$, '22023',
                 'edges must be LineStrings or MultiLineStrings', 'points');
SELECT throws_ok($$SELECT streetgen.rasterise_network('SELECT ''SRID=3857;LINESTRING(0 0, 9 9)''::geometry AS geom UNION ALL SELECT geom FROM patch')$$,
                 '22023', 'edges must share one SRID', 'mixed SRIDs');
SELECT throws_ok($$SELECT streetgen.rasterise_network('SELECT ''SRID=4326;LINESTRING(2 48, 2.1 48.1)''::geometry AS geom')$$,
                 '22023', 'edges SRID 4326 is a geographic CRS, not a projected one in metres', 'degrees');
SELECT throws_ok($$SELECT streetgen.rasterise_network('SELECT geom FROM patch WHERE false')$$, '22023',
                 'edges are empty and no extent is given', 'no edges, no extent');
SELECT throws_ok($$SELECT streetgen.rasterise_network('SELECT geom FROM patch', 0.01)$$, '22023', NULL, 'too many pixels');
SELECT throws_ok($$SELECT streetgen.rasterise_network('SELECT geom FROM patch', 3, 15, 'SRID=3857;POLYGON((0 0, 1 0, 1 1, 0 0))')$$,
                 '22023', 'extent must have the SRID of the edges', 'extent in another SRID');

-- Cancellation: one road pixel dilated and eroded 100 times each on 4000 x 4000 pixels runs for
-- about a second on a fast machine (0.94 s; 2000 x 2000 pixels dilated alone took 0.13 s there,
-- under the timeout); statement_timeout must stop it inside the C++ loops with PostgreSQL's own 57014.
CREATE TEMP TABLE big AS
SELECT ST_AsBinary(ST_SetValue(ST_AddBand(ST_MakeEmptyRaster(4000, 4000, 0, 4000, 1, -1, 0, 0, 0), '8BUI'::text, 0, NULL),
                               1, 2000, 2000, 1)) AS wkb;
CREATE TEMP TABLE outcome (state text, seconds double precision);
SET LOCAL statement_timeout = '200ms';
INSERT INTO outcome SELECT * FROM test_helpers.sqlstate_and_seconds(
  $$SELECT count(*) FROM big, streetgen._streetgen_raster_to_network(wkb, 0.5, 100, 100, 100, 25, 5, 3, 60, 30)$$);
RESET statement_timeout;
SELECT is((SELECT state FROM outcome), '57014', 'statement_timeout cancels raster_to_network with 57014');
SELECT cmp_ok((SELECT seconds FROM outcome), '<', 2.0::double precision, 'within the computation, not after it');

SELECT * FROM finish();
ROLLBACK;
