-- Water, bridges and terrain in grow_patches (issue 8): new-york's example patches grown over its
-- convex hull from one seed, seeds 1-3, with no water and no DEM, with an 80 m river across the
-- region, with a DEM (flat west of x = -300, 30 % up east of it; max_slope 10 %), and with both:
-- time, edges, km, bridges, example-based share, edges north of the river, edges steeper than
-- 10 % (PostGIS bilinear heights at both ends), non-bridge edges over the river, km on the slope.
-- The same setup as tests/pgtap/83-patches-terrain.sql. Reads the example server-side
-- (pg_read_file: run as a superuser) in any database with the extension:
--
--   psql -X -d db -v shared="$PWD/../shared/data" -f bench/patches/terrain.sql
--
-- Timings are of one SQL call each, on whatever the machine is doing: read them as an order.
\set ON_ERROR_STOP on
BEGIN;
CREATE TEMP TABLE ex AS SELECT row_number() OVER () AS id, f -> 'properties' ->> 'type' AS road_class, (f -> 'properties' ->> 'roundabout')::boolean AS roundabout, ST_SetSRID(ST_GeomFromGeoJSON(f -> 'geometry'), 0) AS geom
  FROM jsonb_array_elements(pg_read_file(:'shared' || '/examples/patches/new-york.geojson')::jsonb -> 'features') AS f;
CREATE TEMP TABLE pt AS SELECT * FROM streetgen.extract_patches('SELECT id, road_class, roundabout, geom FROM ex');
CREATE TEMP TABLE region AS SELECT ST_ConvexHull(ST_Collect(geom)) AS geom, ST_PointOnSurface(ST_ConvexHull(ST_Collect(geom))) AS centre FROM ex;
CREATE TEMP TABLE river AS SELECT ST_MakeEnvelope(-2200, -900, 900, -820, 0) AS geom;
CREATE TEMP TABLE dem AS SELECT ST_MapAlgebra(ST_AddBand(ST_MakeEmptyRaster(136, 124, -2020, 20, 20, -20, 0, 0, 0), '32BF'::text, 0::double precision), 1, '32BF', 'CASE WHEN -2020 + 20 * ([rast.x] - 0.5) > -300 THEN 0.3 * (-2020 + 20 * ([rast.x] - 0.5) + 300) ELSE 0 END') AS rast;
CREATE TEMP TABLE runs (seed int, variant text, ms double precision, n bigint, km double precision, bridges bigint, share double precision, north bigint, steep bigint, wet bigint, slope_km double precision);
DO $$
DECLARE s int; v text; t0 timestamptz; t1 timestamptz;
BEGIN
  FOR s IN 1..3 LOOP
    FOREACH v IN ARRAY ARRAY['none', 'river', 'dem', 'both'] LOOP
      t0 := clock_timestamp();
      CREATE TEMP TABLE g AS SELECT x.* FROM region r, streetgen.grow_patches('SELECT * FROM pt', r.geom, r.centre, NULL,
        jsonb_build_object('seed', s, 'max_edges', 3000, 'max_slope', 10),
        CASE WHEN v IN ('river', 'both') THEN (SELECT geom FROM river) END, CASE WHEN v IN ('dem', 'both') THEN (SELECT rast FROM dem) END) x;
      t1 := clock_timestamp();
      INSERT INTO runs SELECT s, v, extract(epoch FROM t1 - t0) * 1000, count(*), sum(ST_Length(g.geom)) / 1000, count(*) FILTER (WHERE origin = 'bridge'),
        count(*) FILTER (WHERE origin LIKE 'grow_patches:%')::float8 / count(*), count(*) FILTER (WHERE ST_YMin(g.geom) > -820),
        count(*) FILTER (WHERE abs(ST_Value(d.rast, 1, ST_EndPoint(g.geom), true, 'bilinear') - ST_Value(d.rast, 1, ST_StartPoint(g.geom), true, 'bilinear')) / ST_Length(g.geom) > 0.1 + 1e-6),
        count(*) FILTER (WHERE origin <> 'bridge' AND ST_Intersects(g.geom, (SELECT geom FROM river))),
        sum(ST_Length(ST_Intersection(g.geom, ST_MakeEnvelope(-280, -3000, 1000, 100, 0)))) / 1000
        FROM g, dem d;
      DROP TABLE g;
    END LOOP;
  END LOOP;
END $$;
SELECT variant, string_agg(format('s%s: %s ms, %s edges %s km, %s bridges, share %s, %s north of river, %s steeper than 10%%, %s non-bridge over water, %s km on slope', seed, round(ms), n, round(km::numeric,1), bridges, round(share::numeric, 3), north, steep, wet, round(slope_km::numeric, 1)), E'\n' ORDER BY seed) FROM runs GROUP BY variant ORDER BY 1;
-- The counts of one run (bridges, contour bends, discards, example-based share) at DEBUG1.
SET LOCAL client_min_messages = debug1;
SELECT count(*) FROM region r, streetgen.grow_patches('SELECT * FROM pt', r.geom, r.centre, NULL,
  '{"seed": 1, "max_edges": 3000, "max_slope": 10}', (SELECT geom FROM river), (SELECT rast FROM dem));
ROLLBACK;
