-- Locality of the engine, which the local refresh relies on: what it computes for a street or a
-- junction does not depend on what else it was given beyond that thing's reach. Tokyo's example
-- streets (© OpenStreetMap contributors, ODbL 1.0), moved to UTM-sized coordinates (the
-- micrometre grid of the sidewalks is then near the float noise of the coordinates), with 300
-- straight streets of 60 m laid across them at random (crossings the topology finds in its own
-- order, which changes with every axis given): the whole network, then the same less a 300 m
-- strip at its west edge (the axes that lie in it). Every output 400 m or more east of the strip
-- must be the same, bit for bit.
-- (A soak found a junction sidewalk one grid step from its full recompute after an edit 1.5 km
-- away: its blockers were taken away in the engine's junction order. Here 5 junction sidewalks
-- came out differently before they were taken away by key.)
BEGIN;
SELECT * FROM no_plan();
SET LOCAL client_min_messages = warning;

SELECT streetgen.create_model('locality', 32632);
-- (the engine is run by hand below: the triggers would compute it on every insert)
ALTER TABLE locality.axis DISABLE TRIGGER USER;
INSERT INTO locality.axis (geom, roadway_width, speed_kmh)
SELECT ST_SetSRID(ST_Translate(ST_Force2D(ST_GeomFromGeoJSON(f -> 'geometry')), 540000, 5218000), 32632),
       CASE WHEN f -> 'properties' ->> 'type' IN ('primary', 'secondary', 'trunk', 'motorway') THEN 9 ELSE 6 END, 30
  FROM jsonb_array_elements(pg_read_file(current_setting('streetgen_test.shared_data') || '/examples/patches/tokyo.geojson')::jsonb
                            -> 'features') AS f;
SELECT setseed(0.5);
INSERT INTO locality.axis (geom, roadway_width, speed_kmh)
SELECT ST_MakeLine(p, ST_Translate(p, 60 * cos(t), 60 * sin(t))), 6, 30
  FROM (SELECT ST_SetSRID(ST_MakePoint(e.x0 + random() * (e.x1 - e.x0), e.y0 + random() * (e.y1 - e.y0)), 32632) AS p,
               random() * 2 * pi() AS t
          FROM (SELECT ST_XMin(x) AS x0, ST_XMax(x) AS x1, ST_YMin(x) AS y0, ST_YMax(x) AS y1
                  FROM (SELECT ST_Extent(geom)::geometry AS x FROM locality.axis) AS q) AS e,
               generate_series(1, 300)) AS r;
CREATE TEMP TABLE strip AS SELECT ST_XMin(ST_Extent(geom)) + 300 AS x FROM locality.axis;

SELECT streetgen._compute_model('locality');
CREATE TEMP TABLE whole AS SELECT * FROM pg_temp._streetgen_out;
SELECT streetgen._compute_model('locality', (SELECT array_agg(id) FROM locality.axis WHERE ST_XMax(geom) > (SELECT x FROM strip)));
CREATE TEMP TABLE compared AS
SELECT w.kind, w.geom IS NOT DISTINCT FROM o.geom AND w.geom2 IS NOT DISTINCT FROM o.geom2 AS same
  FROM whole w
  LEFT JOIN pg_temp._streetgen_out o
    ON o.kind = w.kind AND o.axis_id IS NOT DISTINCT FROM w.axis_id AND o.part IS NOT DISTINCT FROM w.part
   AND o.node_id IS NOT DISTINCT FROM w.node_id AND o.status IS NOT DISTINCT FROM w.status AND o.item IS NOT DISTINCT FROM w.item
   AND o.axis_b IS NOT DISTINCT FROM w.axis_b AND o.part_b IS NOT DISTINCT FROM w.part_b
   AND o.end_a IS NOT DISTINCT FROM w.end_a AND o.end_b IS NOT DISTINCT FROM w.end_b
 WHERE w.geom IS NOT NULL AND ST_XMin(ST_GeomFromEWKB(w.geom)) > (SELECT x FROM strip) + 400;

SELECT ok((SELECT count(*) FROM compared WHERE kind = 'sidewalk') > 2000 AND (SELECT count(*) FROM compared WHERE kind = 'intersection') > 500,
          'the outputs compared: over 2,000 sidewalks and 500 junctions 400 m beyond the strip');
SELECT is((SELECT count(*) FROM compared WHERE kind = 'sidewalk' AND NOT same), 0::bigint,
          'every sidewalk beyond the strip is the same, bit for bit, without the strip''s axes');
SELECT is_empty($$SELECT kind, count(*) FROM compared WHERE NOT same GROUP BY kind$$,
                'and so is every other output (sections, junctions, corners, lanes, markings, crossings, nodes)');

SELECT * FROM finish();
ROLLBACK;
