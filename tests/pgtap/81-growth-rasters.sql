-- Growth controlled by PostGIS rasters (issue 7, items 2 and 3): a weight raster whose band k
-- weighs example k over space (blending), and a direction raster of azimuths that sets θ
-- (direction control), on real example patches of ../shared/data/examples/patches (© OpenStreetMap
-- contributors, ODbL 1.0). The rasters are built here with ST_MakeEmptyRaster, ST_AddBand and
-- ST_SetValues, and the tests read them back with ST_Value, independently of the C++ sampling.
BEGIN;
SELECT * FROM no_plan();

CREATE TEMP TABLE patch AS
SELECT n AS name, row_number() OVER (PARTITION BY n) AS id, f -> 'properties' ->> 'type' AS road_class,
       ST_SetSRID(ST_GeomFromGeoJSON(f -> 'geometry'), 0) AS geom
  FROM unnest(ARRAY['tokyo', 'canberra_south_large']) AS n,
       jsonb_array_elements(pg_read_file(current_setting('streetgen_test.shared_data') || '/examples/patches/' || n
                                         || '.geojson')::jsonb -> 'features') AS f;
SELECT ok((SELECT count(DISTINCT name) = 2 AND count(*) > 1000 FROM patch), 'two real example patches loaded');

-- ---- Direction raster ------------------------------------------------------------------------
-- 30 x 30 cells of 50 m over the square (0..1500)²: azimuth 40° in the west half, 60° in the east
-- half; a copy whose east half is nodata. The tokyo example's streets run at about 5-10° (mod 90°),
-- and every growth here has rotation off, so without the raster they keep that frame.
CREATE TEMP TABLE field AS
SELECT 'full'::text AS kind,
       ST_SetValues(ST_SetValues(ST_AddBand(ST_MakeEmptyRaster(30, 30, 0, 1500, 50, -50, 0, 0, 0), '32BF'::text,
                                            0::float8, -9999::float8),
                                 1, 1, 1, 15, 30, 40::float8), 1, 16, 1, 15, 30, 60::float8) AS rast
UNION ALL
SELECT 'west', ST_SetValues(ST_AddBand(ST_MakeEmptyRaster(30, 30, 0, 1500, 50, -50, 0, 0, 0), '32BF'::text,
                                       -9999::float8, -9999::float8),
                            1, 1, 1, 15, 30, 40::float8);
SELECT is((SELECT array_agg(ST_Value(rast, ST_MakePoint(x, 700)) ORDER BY x) FROM field, unnest(ARRAY[100, 1400]) AS x
            WHERE kind = 'full'), ARRAY[40, 60]::double precision[], 'the direction raster reads 40° west, 60° east');
SELECT is((SELECT ST_Value(rast, ST_MakePoint(1400, 700)) FROM field WHERE kind = 'west'), NULL,
          'the west-only raster is nodata in the east');

-- An edge's deviation from the field at its centroid (azimuths folded to [0, 45]: the tokyo grid
-- and the parametric lattice have right angles), ST_Value on the full raster.
CREATE FUNCTION pg_temp.field_deviation(e geometry) RETURNS double precision LANGUAGE sql AS $$
  SELECT least(d, 90 - d) FROM (
    SELECT mod(abs(degrees(ST_Azimuth(ST_StartPoint(e), ST_EndPoint(e))) - ST_Value(f.rast, ST_Centroid(e)))::numeric,
               90)::double precision AS d
      FROM field f WHERE f.kind = 'full') x
$$;

CREATE TEMP TABLE directed AS
SELECT 'example'::text AS kind, 'full'::text AS field, g.* FROM field f, streetgen.grow_example(
  $$SELECT id, road_class, geom FROM patch WHERE name = 'tokyo'$$, 'POLYGON((0 0, 1500 0, 1500 1500, 0 1500, 0 0))',
  'MULTIPOINT(300 750, 1200 750)', NULL, '{"seed": 3, "max_edges": 1500, "rotation": false}', direction => f.rast) AS g
 WHERE f.kind = 'full'
UNION ALL
SELECT 'example', 'west', g.* FROM field f, streetgen.grow_example(
  $$SELECT id, road_class, geom FROM patch WHERE name = 'tokyo'$$, 'POLYGON((0 0, 1500 0, 1500 1500, 0 1500, 0 0))',
  'MULTIPOINT(300 750, 1200 750)', NULL, '{"seed": 3, "max_edges": 1500, "rotation": false}', direction => f.rast) AS g
 WHERE f.kind = 'west'
UNION ALL
SELECT 'example', 'none', g.* FROM streetgen.grow_example(
  $$SELECT id, road_class, geom FROM patch WHERE name = 'tokyo'$$, 'POLYGON((0 0, 1500 0, 1500 1500, 0 1500, 0 0))',
  'MULTIPOINT(300 750, 1200 750)', NULL, '{"seed": 3, "max_edges": 1500, "rotation": false}') AS g
UNION ALL
SELECT 'parametric', 'full', g.* FROM field f, streetgen.grow_parametric(
  'POLYGON((0 0, 1500 0, 1500 1500, 0 1500, 0 0))', 'MULTIPOINT(300 750, 1200 750)', NULL,
  '{"seed": 3, "max_edges": 1000, "rotation": false}', direction => f.rast) AS g
 WHERE f.kind = 'full'
UNION ALL
SELECT 'parametric', 'none', g.* FROM streetgen.grow_parametric(
  'POLYGON((0 0, 1500 0, 1500 1500, 0 1500, 0 0))', 'MULTIPOINT(300 750, 1200 750)', NULL,
  '{"seed": 3, "max_edges": 1000, "rotation": false}') AS g;
-- Away from the seam (100 m either side of x = 750).
CREATE TEMP TABLE direction_deviation AS
SELECT kind, field, CASE WHEN ST_X(ST_Centroid(geom)) < 650 THEN 'west' ELSE 'east' END AS side, count(*) AS edges,
       avg(pg_temp.field_deviation(geom)) AS deviation
  FROM directed WHERE abs(ST_X(ST_Centroid(geom)) - 750) > 100 GROUP BY 1, 2, 3;
SELECT ok((SELECT bool_and(edges >= 100) AND count(*) = 10 FROM direction_deviation),
          'at least 100 edges on each side of each growth');
SELECT cmp_ok((SELECT max(deviation) FROM direction_deviation WHERE field = 'full'), '<', 10.0::double precision,
              'grow_example and grow_parametric with a direction raster: edges follow its azimuth on both sides '
              '(mean deviation below 10 degrees)');
SELECT cmp_ok((SELECT min(deviation) FROM direction_deviation WHERE field = 'none'), '>', 15.0::double precision,
              'without it, they do not (mean deviation above 15 degrees)');
SELECT cmp_ok((SELECT deviation FROM direction_deviation WHERE field = 'west' AND side = 'west'), '<',
              10.0::double precision, 'a raster with values in the west only: the west follows it');
SELECT cmp_ok((SELECT deviation FROM direction_deviation WHERE field = 'west' AND side = 'east'), '>',
              15.0::double precision, 'and its nodata east falls back to node matching');
SELECT is((SELECT count(*) FROM directed a JOIN directed b ON a.kind = b.kind AND a.field = b.field AND a.id < b.id
                                                          AND ST_Intersects(a.geom, b.geom)
            WHERE NOT (a.from_node IN (b.from_node, b.to_node) OR a.to_node IN (b.from_node, b.to_node))),
          0::bigint, 'growth along a direction raster stays planar');
SELECT is((SELECT count(*) FROM directed WHERE NOT ST_CoveredBy(geom, 'POLYGON((0 0, 1500 0, 1500 1500, 0 1500, 0 0))')),
          0::bigint, 'growth along a direction raster stays in the region');
SELECT results_eq(
  $$SELECT ST_AsEWKB(g.geom) FROM field f, streetgen.grow_example('SELECT geom FROM patch WHERE name = ''tokyo''',
      'POLYGON((0 0, 1500 0, 1500 1500, 0 1500, 0 0))', 'POINT(300 750)', NULL, '{"seed": 5, "max_edges": 300}',
      direction => f.rast) AS g WHERE f.kind = 'full' ORDER BY g.id$$,
  $$SELECT ST_AsEWKB(g.geom) FROM field f, streetgen.grow_example('SELECT geom FROM patch WHERE name = ''tokyo''',
      'POLYGON((0 0, 1500 0, 1500 1500, 0 1500, 0 0))', 'POINT(300 750)', NULL, '{"seed": 5, "max_edges": 300}',
      direction => f.rast) AS g WHERE f.kind = 'full' ORDER BY g.id$$,
  'growth along a direction raster: the same seed gives the same edges');

-- ---- Weight raster ---------------------------------------------------------------------------
-- Two examples over 2000 x 1200 m; 20 x 12 cells of 100 m. 'split': band 1 (tokyo) weighs 1 in
-- the west half and 0 in the east, band 2 (canberra) the reverse. 'west': only the west half has
-- values (canberra 1, tokyo 0), the east is nodata in both bands.
CREATE TEMP TABLE weight AS
SELECT 'split'::text AS kind,
       ST_SetValues(ST_SetValues(ST_AddBand(ST_AddBand(ST_MakeEmptyRaster(20, 12, 0, 1200, 100, -100, 0, 0, 0),
                                                       '32BF'::text, 0::float8, -1::float8),
                                            '32BF'::text, 0::float8, -1::float8),
                                 1, 1, 1, 10, 12, 1::float8), 2, 11, 1, 10, 12, 1::float8) AS rast
UNION ALL
SELECT 'west',
       ST_SetValues(ST_SetValues(ST_AddBand(ST_AddBand(ST_MakeEmptyRaster(20, 12, 0, 1200, 100, -100, 0, 0, 0),
                                                       '32BF'::text, -1::float8, -1::float8),
                                            '32BF'::text, -1::float8, -1::float8),
                                 1, 1, 1, 10, 12, 0::float8), 2, 1, 1, 10, 12, 1::float8);
SELECT is((SELECT array_agg(ST_Value(rast, b, ST_MakePoint(x, 600)) ORDER BY x, b) FROM weight, unnest(ARRAY[100, 1900]) AS x,
                  generate_series(1, 2) AS b WHERE kind = 'split'), ARRAY[1, 0, 0, 1]::double precision[],
          'the split weight raster reads tokyo 1 / canberra 0 in the west, the reverse in the east');

CREATE TEMP TABLE weighted AS
SELECT w.kind, g.* FROM weight w, streetgen.grow_example(
  ARRAY[$$SELECT id, road_class, geom FROM patch WHERE name = 'tokyo'$$,
        $$SELECT id, road_class, geom FROM patch WHERE name = 'canberra_south_large'$$],
  'POLYGON((0 0, 2000 0, 2000 1200, 0 1200, 0 0))', 'MULTIPOINT(300 600, 1000 600, 1700 600)', NULL,
  '{"seed": 3, "max_edges": 3000, "blend": "points", "blend_points": [[2000, 600], [0, 600]], "blend_sigma": 600}',
  weights => w.rast) AS g
UNION ALL
SELECT 'none', g.* FROM weight w, streetgen.grow_example(
  ARRAY[$$SELECT id, road_class, geom FROM patch WHERE name = 'tokyo'$$,
        $$SELECT id, road_class, geom FROM patch WHERE name = 'canberra_south_large'$$],
  'POLYGON((0 0, 2000 0, 2000 1200, 0 1200, 0 0))', 'MULTIPOINT(300 600, 1000 600, 1700 600)', NULL,
  '{"seed": 3, "max_edges": 3000}', weights => w.rast) AS g WHERE w.kind = 'west';
CREATE TEMP TABLE weight_share AS
SELECT kind, width_bucket(ST_X(ST_Centroid(geom)), 0, 2000, 4) AS quarter, count(*) AS edges,
       count(*) FILTER (WHERE origin LIKE 'grow_example:1:%') AS first,
       count(*) FILTER (WHERE origin LIKE 'grow_example:2:%') AS second
  FROM weighted WHERE origin <> 'grow_parametric' GROUP BY 1, 2;
SELECT ok((SELECT bool_and(edges >= 50) AND count(*) = 12 FROM weight_share), 'at least 50 edges in every quarter');
SELECT is((SELECT array_agg(first ORDER BY quarter) FROM weight_share WHERE kind = 'split' AND quarter IN (1, 4))
            || (SELECT array_agg(second ORDER BY quarter) FROM weight_share WHERE kind = 'split' AND quarter IN (1, 4)),
          ARRAY[(SELECT edges FROM weight_share WHERE kind = 'split' AND quarter = 1), 0,
                0, (SELECT edges FROM weight_share WHERE kind = 'split' AND quarter = 4)],
          'weights 1/0: only tokyo''s edges in the west quarter, only canberra''s in the east one '
          '(the raster overrides blend_points, which say the reverse)');
SELECT is((SELECT first FROM weight_share WHERE kind = 'west' AND quarter = 1), 0::bigint,
          'a raster with values in the west only: canberra alone there');
SELECT cmp_ok((SELECT first::double precision / edges FROM weight_share WHERE kind = 'west' AND quarter = 4), '>', 0.6::double precision,
              'and its nodata east falls back to blend_points (tokyo''s point is in the east)');
SELECT ok((SELECT first > 0 AND second > 0 FROM weight_share WHERE kind = 'none' AND quarter = 4)
          AND (SELECT first FROM weight_share WHERE kind = 'none' AND quarter = 1) = 0,
          'without blend, nodata means every example alike (both in the east), the raster still decides the west');
-- North and south: the raster's first row is its north edge (ST_UpperLeftY), as the C++ side reads it.
CREATE TEMP TABLE weighted_ns AS
SELECT g.* FROM streetgen.grow_example(
  ARRAY[$$SELECT id, road_class, geom FROM patch WHERE name = 'tokyo'$$,
        $$SELECT id, road_class, geom FROM patch WHERE name = 'canberra_south_large'$$],
  'POLYGON((0 0, 2000 0, 2000 1200, 0 1200, 0 0))', 'MULTIPOINT(700 200, 1300 1000)', NULL, '{"seed": 3, "max_edges": 2000}',
  weights => ST_SetValues(ST_SetValues(ST_AddBand(ST_AddBand(ST_MakeEmptyRaster(20, 12, 0, 1200, 100, -100, 0, 0, 0),
                                                             '32BF'::text, 0::float8, NULL::float8),
                                                  '32BF'::text, 0::float8, NULL::float8),
                                       1, 1, 1, 20, 6, 1::float8), 2, 1, 7, 20, 6, 1::float8)) AS g;
SELECT ok((SELECT count(*) FILTER (WHERE origin LIKE 'grow_example:1:%') >= 50
                  AND count(*) FILTER (WHERE origin LIKE 'grow_example:2:%') = 0
             FROM weighted_ns WHERE ST_Y(ST_Centroid(geom)) > 900)
          AND (SELECT count(*) FILTER (WHERE origin LIKE 'grow_example:2:%') >= 20
                      AND count(*) FILTER (WHERE origin LIKE 'grow_example:1:%') = 0
                 FROM weighted_ns WHERE ST_Y(ST_Centroid(geom)) < 300),
          'weights by rows: tokyo alone in the north (the raster''s first rows), canberra alone in the south');
SELECT is((SELECT count(*) FROM weighted a JOIN weighted b ON a.kind = b.kind AND a.id < b.id AND ST_Intersects(a.geom, b.geom)
            WHERE NOT (a.from_node IN (b.from_node, b.to_node) OR a.to_node IN (b.from_node, b.to_node))),
          0::bigint, 'growth blended by a weight raster stays planar');

-- ---- Bad rasters -----------------------------------------------------------------------------
CREATE FUNCTION pg_temp.one_band(rast_srid integer, w integer, h integer, ulx float8, uly float8, value float8,
                                 nodata float8 DEFAULT NULL) RETURNS raster LANGUAGE sql AS $$
  SELECT ST_AddBand(ST_MakeEmptyRaster(w, h, ulx, uly, 100, -100, 0, 0, rast_srid), '32BF'::text, value, nodata)
$$;
CREATE FUNCTION pg_temp.steer(rast raster) RETURNS bigint LANGUAGE sql AS $$
  SELECT count(*) FROM streetgen.grow_example('SELECT geom FROM patch WHERE name = ''tokyo''',
    'POLYGON((0 0, 1500 0, 1500 1500, 0 1500, 0 0))', 'POINT(300 750)', NULL, '{"seed": 1, "max_edges": 50}',
    direction => rast)
$$;
CREATE FUNCTION pg_temp.weigh(rast raster, examples integer DEFAULT 2) RETURNS bigint LANGUAGE sql AS $$
  SELECT count(*) FROM streetgen.grow_example(
    (ARRAY['SELECT geom FROM patch WHERE name = ''tokyo''', 'SELECT geom FROM patch WHERE name = ''canberra_south_large''',
           'SELECT geom FROM patch WHERE name = ''tokyo'''])[1:examples],
    'POLYGON((0 0, 1500 0, 1500 1500, 0 1500, 0 0))', 'POINT(300 750)', NULL, '{"seed": 1, "max_edges": 50}',
    weights => rast)
$$;
SELECT throws_ok($$SELECT pg_temp.steer(pg_temp.one_band(3857, 15, 15, 0, 1500, 30))$$, '22023',
                 'direction raster must have the SRID of the region', 'a direction raster in another SRID');
SELECT throws_ok($$SELECT pg_temp.steer(pg_temp.one_band(0, 15, 15, 5000, 1500, 30))$$, '22023',
                 'direction raster does not overlap the region', 'a direction raster away from the region');
SELECT throws_ok($$SELECT pg_temp.steer(ST_AddBand(pg_temp.one_band(0, 15, 15, 0, 1500, 30), '32BF'::text, 0::float8, NULL::float8))$$,
                 '22023', 'direction raster must have one band', 'a direction raster of two bands');
SELECT throws_ok($$SELECT pg_temp.steer(ST_SetValue(pg_temp.one_band(0, 15, 15, 0, 1500, 30), 1, 3, 3, 'NaN'::float8))$$,
                 '22023', 'direction raster holds NaN', 'a NaN direction that is not nodata');
SELECT throws_ok($$SELECT pg_temp.steer(ST_SetSkew(pg_temp.one_band(0, 15, 15, 0, 1500, 30), 1, 0))$$, '22023',
                 'direction raster must not be skewed', 'a skewed direction raster');
SELECT throws_ok($$SELECT pg_temp.steer(ST_MakeEmptyRaster(15, 15, 0, 1500, 100, -100, 0, 0, 0))$$, '22023',
                 'direction raster is empty', 'a direction raster without a band');
SELECT ok(pg_temp.steer(ST_SetValue(pg_temp.one_band(0, 15, 15, 0, 1500, 30, 'NaN'), 1, 3, 3, 'NaN'::float8)) > 0,
          'NaN as the band''s nodata value is nodata (defined: no control there)');
SELECT throws_ok($$SELECT pg_temp.weigh(pg_temp.one_band(3857, 15, 15, 0, 1500, 1))$$, '22023',
                 'weights raster must have one band per example', 'one band for two examples');
SELECT throws_ok($$SELECT pg_temp.weigh(ST_AddBand(pg_temp.one_band(3857, 15, 15, 0, 1500, 1), '32BF'::text, 1::float8, NULL::float8))$$,
                 '22023', 'weights raster must have the SRID of the region', 'a weight raster in another SRID');
SELECT throws_ok($$SELECT pg_temp.weigh(ST_AddBand(pg_temp.one_band(0, 15, 15, 0, 1500, 1), '32BF'::text, 1::float8, NULL::float8), 3)$$,
                 '22023', 'weights raster must have one band per example', 'two bands for three examples');
SELECT throws_ok($$SELECT pg_temp.weigh(ST_AddBand(pg_temp.one_band(0, 15, 15, -3000, 1500, 1), '32BF'::text, 1::float8, NULL::float8))$$,
                 '22023', 'weights raster does not overlap the region', 'a weight raster away from the region');
SELECT throws_ok($$SELECT pg_temp.weigh(ST_AddBand(pg_temp.one_band(0, 15, 15, 0, 1500, 1), '32BF'::text, -0.5::float8, NULL::float8))$$,
                 '22023', 'weights raster must hold finite weights >= 0', 'a negative weight');
SELECT throws_ok($$SELECT pg_temp.weigh(ST_AddBand(pg_temp.one_band(0, 15, 15, 0, 1500, 1), '32BF'::text, 'NaN'::float8, NULL::float8))$$,
                 '22023', 'weights raster holds NaN', 'a NaN weight that is not nodata');
SELECT throws_ok($$SELECT pg_temp.weigh(pg_temp.one_band(0, 15, 15, 0, 1500, 1), 1)$$, '22023',
                 'weights need several examples', 'a weight raster for one example');
SELECT ok(pg_temp.weigh(ST_AddBand(pg_temp.one_band(0, 15, 15, 0, 1500, 0), '32BF'::text, 0::float8, NULL::float8)) > 0,
          'weights 0 everywhere: defined (no control, every example alike)');
SELECT * FROM finish();
ROLLBACK;
