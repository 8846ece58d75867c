-- Growing networks II, terrain and water: grow_patches with a water polygon (no street crosses it
-- but arterial bridges) and a DEM (no street steeper than max_slope; statistical streets bend
-- along the contour), on the real example patches of ../shared/data/examples/patches/new-york
-- (Nishida et al.'s crop of OpenStreetMap, © OpenStreetMap contributors, ODbL 1.0) with a river
-- band across its region and a synthetic DEM built with PostGIS raster functions; every bad
-- input by SQLSTATE.
BEGIN;
SELECT * FROM no_plan();

CREATE TEMP TABLE ex AS
SELECT row_number() OVER () AS id, f -> 'properties' ->> 'type' AS road_class,
       (f -> 'properties' ->> 'roundabout')::boolean AS roundabout,
       ST_SetSRID(ST_GeomFromGeoJSON(f -> 'geometry'), 0) AS geom
  FROM jsonb_array_elements(pg_read_file(current_setting('streetgen_test.shared_data')
                                         || '/examples/patches/new-york.geojson')::jsonb -> 'features') AS f;
CREATE TEMP TABLE pt AS SELECT * FROM streetgen.extract_patches('SELECT id, road_class, roundabout, geom FROM ex');
SELECT ok((SELECT count(DISTINCT patch_id) FROM pt WHERE 'arterial' = ANY (tags)) > 10,
          'new-york: arterial patches (its avenues)');
CREATE TEMP TABLE region AS
SELECT ST_ConvexHull(ST_Collect(geom)) AS geom, ST_PointOnSurface(ST_ConvexHull(ST_Collect(geom))) AS centre FROM ex;
-- A river 80 m wide across the whole region, north of the seed.
CREATE TEMP TABLE river AS SELECT ST_MakeEnvelope(-2200, -900, 900, -820, 0) AS geom;
SELECT ok((SELECT ST_NumGeometries(ST_Difference(r.geom, w.geom)) = 2 AND ST_Y(r.centre) < -900 FROM region r, river w),
          'the river splits the region in two, the seed south of it');

CREATE FUNCTION pg_temp.grow(params jsonb, water geometry DEFAULT NULL, dem raster DEFAULT NULL) RETURNS SETOF record
  LANGUAGE sql AS $$
  SELECT g.* FROM region r, streetgen.grow_patches('SELECT * FROM pt', r.geom, r.centre, NULL, params, water, dem) AS g
$$;
CREATE TEMP TABLE grown AS
SELECT * FROM pg_temp.grow('{"seed": 7, "max_edges": 3000}', (SELECT geom FROM river))
  AS g(id bigint, from_node bigint, to_node bigint, road_class text, origin text, geom geometry);
CREATE TEMP TABLE dry AS
SELECT * FROM pg_temp.grow('{"seed": 7, "max_edges": 3000}')
  AS g(id bigint, from_node bigint, to_node bigint, road_class text, origin text, geom geometry);

-- Water and bridges.
SELECT ok((SELECT count(*) FROM grown WHERE origin = 'bridge') >= 3, 'bridges appear where the river splits the region');
SELECT is((SELECT count(*) FROM grown g, river w WHERE ST_Intersects(g.geom, w.geom) AND g.origin <> 'bridge'), 0::bigint,
          'no street but a bridge touches the water');
SELECT is((SELECT count(*) FROM grown g, river w WHERE g.road_class = 'street' AND ST_Intersects(g.geom, w.geom)), 0::bigint,
          'no local street crosses water');
SELECT is((SELECT count(*) FROM grown g, river w WHERE g.origin = 'bridge'
             AND NOT (g.road_class IN ('avenue', 'highway') AND ST_Crosses(g.geom, w.geom)
                      AND NOT ST_Intersects(ST_StartPoint(g.geom), w.geom) AND NOT ST_Intersects(ST_EndPoint(g.geom), w.geom)
                      AND (ST_Y(ST_StartPoint(g.geom)) < -900) <> (ST_Y(ST_EndPoint(g.geom)) < -900))),
          0::bigint, 'every bridge is an arterial from bank to bank, its ends on land');
SELECT ok((SELECT max(ST_Length(geom)) FROM grown WHERE origin = 'bridge') <= 300 + 2
          AND (SELECT min(ST_Length(geom)) FROM grown WHERE origin = 'bridge') >= 80,
          'bridges span the river (80 m) within bridge_distance (300 m)');
SELECT ok((SELECT count(*) FROM grown WHERE ST_YMin(geom) > -820) > 100,
          'the growth goes on across the river (over 100 edges on the far bank)');
SELECT ok((SELECT count(*) FROM dry d, river w WHERE ST_Intersects(d.geom, w.geom)) > 20,
          'without water the same growth runs through the river band (the test could fail)');
SELECT is((SELECT count(*) FROM grown a JOIN grown b ON a.id < b.id AND ST_Intersects(a.geom, b.geom)
            WHERE NOT (a.from_node IN (b.from_node, b.to_node) OR a.to_node IN (b.from_node, b.to_node))),
          0::bigint, 'planarity: no two edges (bridges included) cross without a shared node');
SELECT is((SELECT count(*) FROM grown g, region r WHERE NOT ST_CoveredBy(g.geom, r.geom)), 0::bigint, 'no edge leaves the region');
SELECT is((SELECT count(*) FROM grown WHERE origin !~ '^(grow_patches:[0-9]+|grow_parametric|bridge)$'), 0::bigint,
          'origin: a patch, the statistical fallback, or bridge');
SELECT ok((SELECT count(*) FILTER (WHERE origin LIKE 'grow_patches:%')::float8 / count(*) FROM grown) > 0.6,
          'the example-based share stays above 60 % with the river');
-- bridge_distance: 0 turns bridges off, one narrower than the river finds no far bank.
SELECT is((SELECT count(*) FROM pg_temp.grow('{"seed": 7, "max_edges": 3000, "bridge_distance": 0}', (SELECT geom FROM river))
             AS g(id bigint, from_node bigint, to_node bigint, road_class text, origin text, geom geometry)
            WHERE origin = 'bridge' OR ST_YMax(geom) > -820), 0::bigint,
          'bridge_distance 0: no bridge, nothing on the far bank');
SELECT is((SELECT count(*) FROM pg_temp.grow('{"seed": 7, "max_edges": 3000, "bridge_distance": 60}', (SELECT geom FROM river))
             AS g(id bigint, from_node bigint, to_node bigint, road_class text, origin text, geom geometry)
            WHERE origin = 'bridge'), 0::bigint, 'bridge_distance narrower than the river: no bridge');
SELECT is((SELECT count(*) FROM (
             (SELECT id, origin, ST_AsEWKB(geom) FROM grown
              EXCEPT SELECT id, origin, ST_AsEWKB(geom) FROM pg_temp.grow('{"seed": 7, "max_edges": 3000}', (SELECT geom FROM river))
                AS g(id bigint, from_node bigint, to_node bigint, road_class text, origin text, geom geometry))) d),
          0::bigint, 'determinism with water: the same seed gives the same rows');
-- Straight into a model's axes: bridges on layer 1, joined to the streets at their ends.
SELECT streetgen.create_model('bridged', 0);
INSERT INTO bridged.axis (geom, roadway_width, speed_kmh, road_class, layer, source)
SELECT g.geom, CASE g.road_class WHEN 'street' THEN 6 ELSE 12 END, CASE g.road_class WHEN 'street' THEN 30 ELSE 50 END,
       g.road_class, CASE g.origin WHEN 'bridge' THEN 1 ELSE 0 END, g.origin
  FROM grown g WHERE EXISTS (SELECT 1 FROM grown b WHERE b.origin = 'bridge' AND ST_DWithin(b.geom, g.geom, 150));
SELECT is((SELECT count(*) FROM bridged.axis a WHERE a.layer = 1 AND NOT EXISTS (SELECT 1 FROM bridged.section s WHERE s.axis_id = a.id)),
          0::bigint, 'every bridge axis (layer 1) gets its section');
SELECT ok((SELECT count(*) FROM bridged.axis WHERE layer = 1) = (SELECT count(*) FROM grown WHERE origin = 'bridge')
          AND (SELECT bool_and(n.degree >= 2) FROM bridged.node n JOIN bridged.axis a ON a.layer = 1
                 AND ST_DWithin(n.geom, a.geom, 0.001) AND ST_Intersects(n.geom, ST_Boundary(a.geom))),
          'bridge ends are junctions with the streets on either bank');

-- Terrain: a DEM of 20 m cells, flat west of x = -300, 30 % up to the east of it.
CREATE TEMP TABLE dem AS
SELECT ST_MapAlgebra(ST_AddBand(ST_MakeEmptyRaster(136, 124, -2020, 20, 20, -20, 0, 0, 0), '32BF'::text, 0::double precision),
                     1, '32BF', 'CASE WHEN -2020 + 20 * ([rast.x] - 0.5) > -300 THEN 0.3 * (-2020 + 20 * ([rast.x] - 0.5) + 300) ELSE 0 END')
       AS rast;
SELECT ok((SELECT ST_Value(rast, 1, 'POINT(-1000 -1000)'::geometry) = 0 AND abs(ST_Value(rast, 1, 'POINT(0 -1000)'::geometry) - 90) < 4
             FROM dem), 'the DEM: flat in the west, 30 % up in the east');
CREATE TEMP TABLE hilly AS
SELECT * FROM pg_temp.grow('{"seed": 7, "max_edges": 3000, "max_slope": 10}', NULL, (SELECT rast FROM dem))
  AS g(id bigint, from_node bigint, to_node bigint, road_class text, origin text, geom geometry);
CREATE FUNCTION pg_temp.grade(g geometry) RETURNS double precision LANGUAGE sql AS $$
  SELECT abs(ST_Value(d.rast, 1, ST_EndPoint(g), true, 'bilinear') - ST_Value(d.rast, 1, ST_StartPoint(g), true, 'bilinear'))
         / ST_Length(g) FROM dem d
$$;
SELECT ok((SELECT count(*) FROM hilly) > 500, 'the growth with the DEM grows (over 500 edges)');
SELECT is((SELECT count(*) FROM hilly WHERE pg_temp.grade(geom) > 0.10 + 1e-6), 0::bigint,
          'no street is steeper than max_slope (10 %) on the DEM');
SELECT ok((SELECT count(*) FROM dry WHERE pg_temp.grade(geom) > 0.10 + 1e-6) > 50,
          'without the DEM the same growth climbs the slope (the test could fail)');
SELECT ok((SELECT sum(ST_Length(ST_Intersection(geom, ST_MakeEnvelope(-280, -3000, 1000, 100, 0)))) FROM hilly) > 5000,
          'streets on the slope bend along its contours (over 5 km of them) rather than stop at its foot');
SELECT is((SELECT count(*) FROM hilly WHERE origin = 'bridge'), 0::bigint, 'no water, no bridge');
-- NULL cells are unknown terrain: a DEM of nodata constrains nothing (the same rows as none).
SELECT is((SELECT count(*) FROM (
             SELECT id, origin, ST_AsEWKB(geom) FROM dry
             EXCEPT
             SELECT id, origin, ST_AsEWKB(geom)
               FROM pg_temp.grow('{"seed": 7, "max_edges": 3000}', NULL,
                                 (SELECT ST_SetBandNoDataValue(ST_MapAlgebra(rast, 1, '32BF', '-9999'), -9999) FROM dem))
                 AS g(id bigint, from_node bigint, to_node bigint, road_class text, origin text, geom geometry)) d),
          0::bigint, 'a DEM of nodata cells: the same rows as without a DEM');
-- Water and DEM together, three seeds: bridges (their decks too) and every street under max_slope.
SELECT ok((SELECT bool_and(bridges > 0 AND steep = 0) FROM (
             SELECT s, count(*) FILTER (WHERE origin = 'bridge') AS bridges,
                    count(*) FILTER (WHERE pg_temp.grade(geom) > 0.1 + 1e-6) AS steep
               FROM generate_series(1, 3) AS s,
                    LATERAL pg_temp.grow(jsonb_build_object('seed', s, 'max_edges', 3000, 'max_slope', 10),
                                         (SELECT geom FROM river), (SELECT rast FROM dem))
                      AS g(id bigint, from_node bigint, to_node bigint, road_class text, origin text, geom geometry)
              GROUP BY s) c),
          'water and DEM together (seeds 1-3): bridges, and no street or bridge steeper than max_slope');

-- Bad input.
SELECT throws_ok($$SELECT * FROM pg_temp.grow('{}', NULL, (SELECT ST_SetSRID(rast, 3857) FROM dem))
                   AS g(id bigint, from_node bigint, to_node bigint, road_class text, origin text, geom geometry)$$,
                 '22023', 'dem raster must have the SRID of the region', 'a DEM with another SRID (22023)');
SELECT throws_ok($$SELECT * FROM pg_temp.grow('{}', NULL, (SELECT ST_SetUpperLeft(rast, 1e6, 1e6) FROM dem))
                   AS g(id bigint, from_node bigint, to_node bigint, road_class text, origin text, geom geometry)$$,
                 '22023', 'dem raster does not overlap the region', 'a DEM that does not overlap the region (22023)');
SELECT throws_ok($$SELECT * FROM pg_temp.grow('{}', NULL, (SELECT ST_AddBand(rast, '32BF'::text, 0::double precision) FROM dem))
                   AS g(id bigint, from_node bigint, to_node bigint, road_class text, origin text, geom geometry)$$,
                 '22023', 'dem raster must have one band', 'a DEM of two bands (22023)');
SELECT throws_ok($$SELECT * FROM pg_temp.grow('{}', NULL, (SELECT ST_MakeEmptyRaster(rast) FROM dem))
                   AS g(id bigint, from_node bigint, to_node bigint, road_class text, origin text, geom geometry)$$,
                 '22023', 'dem raster is empty', 'a DEM without a band (22023)');
SELECT throws_ok($$SELECT * FROM pg_temp.grow('{}', (SELECT ST_Buffer(geom, 10) FROM region))
                   AS g(id bigint, from_node bigint, to_node bigint, road_class text, origin text, geom geometry)$$,
                 '22023', 'water covers the whole region', 'water over the whole region (22023)');
SELECT throws_ok($$SELECT * FROM pg_temp.grow('{}', (SELECT ST_Buffer(centre, 50) FROM region))
                   AS g(id bigint, from_node bigint, to_node bigint, road_class text, origin text, geom geometry)$$,
                 '22023', 'seed 1 lies in water', 'a seed in water (22023)');
SELECT throws_ok($$SELECT * FROM pg_temp.grow('{}', (SELECT ST_SetSRID(geom, 3857) FROM river))
                   AS g(id bigint, from_node bigint, to_node bigint, road_class text, origin text, geom geometry)$$,
                 '22023', 'water must have the SRID of the region', 'water with another SRID (22023)');
SELECT throws_ok($$SELECT * FROM pg_temp.grow('{}', 'LINESTRING(-2000 -860, 600 -860)'::geometry)
                   AS g(id bigint, from_node bigint, to_node bigint, road_class text, origin text, geom geometry)$$,
                 '22023', 'water must be polygons', 'water that is not polygonal (22023)');
SELECT throws_ok($$SELECT * FROM pg_temp.grow('{"max_slope": 0}')
                   AS g(id bigint, from_node bigint, to_node bigint, road_class text, origin text, geom geometry)$$,
                 '22023', 'max_slope must be a number > 0', 'max_slope 0 (22023)');
SELECT throws_ok($$SELECT * FROM pg_temp.grow('{"max_slope": "steep"}')
                   AS g(id bigint, from_node bigint, to_node bigint, road_class text, origin text, geom geometry)$$,
                 '22023', 'max_slope must be a number > 0', 'max_slope not a number (22023)');
SELECT throws_ok($$SELECT * FROM pg_temp.grow('{"bridge_distance": -1}')
                   AS g(id bigint, from_node bigint, to_node bigint, road_class text, origin text, geom geometry)$$,
                 '22023', 'bridge_distance must be a number >= 0', 'a negative bridge_distance (22023)');
SELECT throws_ok($$SELECT * FROM pg_temp.grow('{"bridge_turn": 90}')
                   AS g(id bigint, from_node bigint, to_node bigint, road_class text, origin text, geom geometry)$$,
                 '22023', 'bridge_turn must be a number in [0, 90) (degrees)', 'bridge_turn 90 (22023)');
-- The issue's other two, with water and a DEM given: an empty patch table, patches without connectors.
SELECT throws_ok($$SELECT * FROM streetgen.grow_patches('SELECT * FROM pt WHERE false', (SELECT geom FROM region),
                   (SELECT centre FROM region), NULL, '{}', (SELECT geom FROM river), (SELECT rast FROM dem))$$,
                 '22023', 'patches has no rows', 'an empty patch table, with water and a DEM (22023)');
SELECT throws_ok($$SELECT * FROM streetgen.grow_patches('SELECT patch_id, ''inner'' AS role, geom FROM pt',
                   (SELECT geom FROM region), (SELECT centre FROM region), NULL, '{}', (SELECT geom FROM river),
                   (SELECT rast FROM dem))$$,
                 '22023', 'no patch has a connector', 'patches without connectors, with water and a DEM (22023)');
SELECT lives_ok($$SELECT count(*) FROM streetgen.grow_patches('SELECT * FROM pt', (SELECT geom FROM region),
                  (SELECT centre FROM region), NULL, '{"max_edges": 50}', 'GEOMETRYCOLLECTION EMPTY'::geometry, NULL)$$,
                'empty water is no water');

SELECT * FROM finish();
ROLLBACK;
