-- Street surfaces: generate() and street_surfaces() on hand-made networks, including every bad
-- input the StreetGen issue lists, each with a defined outcome (a status or a clear error).
BEGIN;
SELECT * FROM no_plan();

SELECT streetgen.create_model('s', 32631);
CREATE FUNCTION pg_temp.axis(wkt text, width float8 DEFAULT 8, speed float8 DEFAULT 50, layer int DEFAULT 0)
  RETURNS bigint LANGUAGE sql AS $$
  INSERT INTO s.axis (geom, roadway_width, speed_kmh, layer)
  VALUES (ST_GeomFromText(wkt, 32631), width, speed, layer) RETURNING id
$$;
-- After each scenario: every output valid, every junction has a surface, no overlap on a layer.
CREATE FUNCTION pg_temp.sound(label text) RETURNS SETOF text LANGUAGE plpgsql AS $$
DECLARE q record;
BEGIN
  SELECT * INTO q FROM streetgen.surface_quality('s');
  RETURN NEXT is(q.invalid_geometries, 0::bigint, label || ': all outputs valid');
  RETURN NEXT is(q.missing_intersections, 0::bigint, label || ': every node of degree >= 2 has an intersection surface');
  RETURN NEXT cmp_ok(q.section_overlap_area, '<', 1e-6::float8, label || ': sections of different axes do not overlap');
END $$;
CREATE FUNCTION pg_temp.reset() RETURNS void LANGUAGE sql AS $$ DELETE FROM s.axis; SELECT streetgen.generate('s'); $$;

-- A cross of two 8 m streets at 50 km/h.
SELECT pg_temp.axis('LINESTRING(-60 0, 60 0)');
SELECT pg_temp.axis('LINESTRING(0 -60, 0 60)');
SELECT results_eq($$SELECT kind, status, count FROM streetgen.generate('s') ORDER BY 1, 2$$,
  $$VALUES ('corner', 'ok', 4::bigint), ('crossing', NULL, 4::bigint), ('intersection', 'ok', 1::bigint),
            ('lane', 'driving', 8::bigint), ('marking', 'centre_line', 4::bigint), ('marking', 'stop_line', 4::bigint),
            ('node', NULL, 5::bigint), ('section', 'ok', 4::bigint), ('sidewalk', 'around', 1::bigint),
            ('sidewalk', 'left', 4::bigint), ('sidewalk', 'right', 4::bigint)$$,
  'cross: 5 nodes, 4 sections, 4 arcs, 1 junction; 2 lanes (8 m, no lane count), a centre line and a stop line per section; sidewalks on both sides and around the junction, a crossing on each arm');
SELECT * FROM pg_temp.sound('cross');
SELECT is((SELECT degree FROM s.node n JOIN s.intersection i ON i.node_id = n.id), 4, 'the junction node has degree 4');
SELECT ok((SELECT bool_and(abs(radius - 7.88) < 0.01) FROM s.corner), 'radius from speed: 50 km/h gives 7.9 m');
SELECT ok((SELECT bool_and(ST_GeometryType(arc) = 'ST_CircularString' AND ST_NPoints(arc) = 3) FROM s.corner),
          'arcs are true CIRCULARSTRINGs');
SELECT ok((SELECT bool_and(ST_HausdorffDistance(ST_CurveToLine(arc), arc_segmentized) < 0.1) FROM s.corner),
          'and the segmentised copy follows the true arc');
SELECT ok((SELECT bool_and(abs(ST_Distance(centre, ST_StartPoint(arc_segmentized)) - radius) < 1e-6) FROM s.corner),
          'arcs are at the radius from their centres');
SELECT is((SELECT count(*) FROM s.section s JOIN s.axis a ON a.id = s.axis_id), 4::bigint, 'every section traces to its axis');

-- Stable keys: a second run leaves every row as it was (same keys, no rewrite).
CREATE TEMP TABLE before AS
  SELECT 'node' t, id::text k, xmin::text x FROM s.node UNION ALL SELECT 'section', axis_id || '/' || part, xmin::text FROM s.section
  UNION ALL SELECT 'corner', concat_ws('/', node_id, axis_a, part_a, end_a, axis_b, part_b, end_b), xmin::text FROM s.corner
  UNION ALL SELECT 'intersection', node_id::text, xmin::text FROM s.intersection;
SELECT count(*) FROM streetgen.generate('s');
SELECT set_eq($$SELECT 'node' t, id::text k, xmin::text x FROM s.node UNION ALL SELECT 'section', axis_id || '/' || part, xmin::text FROM s.section
  UNION ALL SELECT 'corner', concat_ws('/', node_id, axis_a, part_a, end_a, axis_b, part_b, end_b), xmin::text FROM s.corner
  UNION ALL SELECT 'intersection', node_id::text, xmin::text FROM s.intersection$$,
  'SELECT * FROM before', 'a second generate keeps the same keys and rewrites no row');

-- A corner radius override is kept across runs and used.
UPDATE s.corner SET radius_override = 3.0
 WHERE (node_id, axis_a, part_a, end_a, axis_b, part_b, end_b) = (SELECT node_id, axis_a, part_a, end_a, axis_b, part_b, end_b FROM s.corner ORDER BY 1, 2, 3, 4, 5, 6, 7 LIMIT 1);
SELECT count(*) FROM streetgen.generate('s');
SELECT results_eq($$SELECT radius_override, round(radius::numeric, 6) FROM s.corner WHERE radius_override IS NOT NULL$$,
                  $$VALUES (3.0::float8, 3.0::numeric)$$, 'the per-corner override is kept and applied');
-- An axis override applies to its corners.
UPDATE s.axis SET radius_override = 2.0 WHERE id = (SELECT min(id) FROM s.axis);
SELECT count(*) FROM streetgen.generate('s');
SELECT is((SELECT count(*) FROM s.corner WHERE radius_override IS NULL AND abs(radius - 2.0) < 1e-9), 3::bigint,
          'an axis radius_override sets the other corners of that axis');

-- Deleting an axis deletes its sections and corners at once (foreign keys), generate the rest.
DELETE FROM s.axis WHERE id = (SELECT max(id) FROM s.axis);
SELECT is((SELECT count(*) FROM s.section WHERE axis_id NOT IN (SELECT id FROM s.axis)), 0::bigint, 'sections cascade with their axis');
SELECT is((SELECT count(*) FROM s.corner WHERE axis_b NOT IN (SELECT id FROM s.axis) OR axis_a NOT IN (SELECT id FROM s.axis)), 0::bigint,
          'corners cascade with their axes');
SELECT results_eq($$SELECT kind, count(*)::bigint FROM (SELECT kind FROM streetgen.generate('s')) g GROUP BY 1 ORDER BY 1$$,
  $$VALUES ('lane', 1::bigint), ('marking', 1::bigint), ('node', 1::bigint), ('section', 1::bigint), ('sidewalk', 2::bigint)$$,
  'a lone axis: two dead ends, one section, no junction; driving lanes and a centre line, no stop line or crossing at dead ends');

-- Bad input, each with its defined outcome.
SELECT pg_temp.reset();
SELECT pg_temp.axis('LINESTRING(0 0, 100 0)');
SELECT pg_temp.axis('LINESTRING(100 0, 0 0)');
SELECT pg_temp.axis('LINESTRING(0 0, 0 80)');
SELECT count(*) FROM streetgen.generate('s');
SELECT is((SELECT count(*) FROM s.issue WHERE kind = 'duplicate_axis'), 1::bigint, 'duplicate axes: reported as an issue');
SELECT is((SELECT count(*) FROM s.section WHERE status = 'duplicate' AND geom IS NULL), 1::bigint, 'and the duplicate gets no surface');
SELECT * FROM pg_temp.sound('duplicate axes');

SELECT pg_temp.reset();
SELECT pg_temp.axis('LINESTRING(0 0, 100 0)');
SELECT pg_temp.axis('LINESTRING(50 0, 150 0)');
SELECT count(*) FROM streetgen.generate('s');
SELECT is((SELECT count(*) FROM s.issue WHERE kind = 'duplicate_axis'), 1::bigint, 'overlapping axes: the shared stretch is a duplicate');
SELECT * FROM pg_temp.sound('overlapping axes');

SELECT pg_temp.reset();
SELECT pg_temp.axis('LINESTRING(0 0, 100 0)');
SELECT pg_temp.axis('LINESTRING(100 0, 140 -20, 160 20, 100 0)', 6, 30);
SELECT count(*) FROM streetgen.generate('s');
SELECT is((SELECT degree FROM s.node WHERE ST_DWithin(geom, 'SRID=32631;POINT(100 0)', 0.01)), 3, 'a loop: its node has degree 3');
SELECT * FROM pg_temp.sound('loop');

SELECT pg_temp.reset();
SELECT pg_temp.axis('LINESTRING(-60 0, 0 0)');
SELECT pg_temp.axis('LINESTRING(0 0, 10 0)');
SELECT pg_temp.axis('LINESTRING(10 0, 60 0)');
SELECT pg_temp.axis('LINESTRING(0 0, 0 60)');
SELECT pg_temp.axis('LINESTRING(10 0, 10 -60)');
SELECT count(*) FROM streetgen.generate('s');
SELECT ok(EXISTS (SELECT 1 FROM s.corner WHERE status = 'radius_reduced' AND radius < radius_wanted),
          'an axis shorter than the radius: radius_reduced');
SELECT * FROM pg_temp.sound('short axis');

SELECT pg_temp.reset();
SELECT pg_temp.axis('LINESTRING(-60 0, 60 0)', 200, 50);
SELECT pg_temp.axis('LINESTRING(0 -300, 0 300)', 8, 50);
SELECT count(*) FROM streetgen.generate('s');
SELECT is((SELECT count(*) FROM s.intersection), 1::bigint, 'a 200 m wide road: the junction is still built');
SELECT * FROM pg_temp.sound('huge width');
SELECT throws_ok($$SELECT pg_temp.axis('LINESTRING(0 0, 1 1)', 0)$$, '23514', NULL, 'width 0 is refused by the table');
SELECT throws_ok($$SELECT pg_temp.axis('LINESTRING(0 0, 1 1)', 500)$$, '23514', NULL, 'width 500 is refused by the table');

SELECT pg_temp.reset();
SELECT pg_temp.axis('LINESTRING(-60 0, 0 0)');
SELECT pg_temp.axis('LINESTRING(0 0, 60 0)');
SELECT count(*) FROM streetgen.generate('s');
SELECT results_eq($$SELECT status, count(*)::bigint FROM s.corner GROUP BY 1$$, $$VALUES ('convex', 2::bigint)$$,
                  'collinear axes at 180 degrees: no arc on either side');
SELECT is((SELECT status FROM s.intersection), 'ok', 'and a plain junction surface');
SELECT * FROM pg_temp.sound('180 degrees');
UPDATE s.axis SET roadway_width = 12 WHERE id = (SELECT max(id) FROM s.axis);
SELECT count(*) FROM streetgen.generate('s');
SELECT is((SELECT status FROM s.intersection), 'transition', 'a width change at a degree-2 node: a linear transition');
SELECT * FROM pg_temp.sound('width transition');

SELECT pg_temp.reset();
SELECT pg_temp.axis('LINESTRING(0 0, 100 0)');
SELECT pg_temp.axis('LINESTRING(0 0, 100 3)');
SELECT pg_temp.axis('LINESTRING(0 0, -100 0)');
SELECT count(*) FROM streetgen.generate('s');
SELECT ok(EXISTS (SELECT 1 FROM s.corner WHERE status IN ('clamped', 'no_corner', 'sharp', 'min_radius')),
          'axes meeting at almost 0 degrees: a fallback corner status');
SELECT * FROM pg_temp.sound('0 degrees');

SELECT pg_temp.reset();
SELECT pg_temp.axis(format('LINESTRING(0 0, %s %s)', 60 * cos(k * pi() / 4), 60 * sin(k * pi() / 4)), 7, 40) FROM generate_series(0, 7) k;
SELECT count(*) FROM streetgen.generate('s');
SELECT is((SELECT degree FROM s.node n JOIN s.intersection i ON i.node_id = n.id), 8, 'a degree-8 junction');
SELECT is((SELECT count(*) FROM s.corner), 8::bigint, 'with eight corners');
SELECT * FROM pg_temp.sound('degree 8');

SELECT pg_temp.reset();
SELECT pg_temp.axis('LINESTRING(0 0, 60 60, 60 0, 0 60)', 6, 30);
SELECT count(*) FROM streetgen.generate('s');
SELECT is((SELECT degree FROM s.node WHERE ST_DWithin(geom, 'SRID=32631;POINT(30 30)', 0.01)), 4, 'a self-crossing axis: a degree-4 node where it crosses');
SELECT * FROM pg_temp.sound('self-crossing');

SELECT pg_temp.reset();
SELECT pg_temp.axis('LINESTRING(-60 0, 60 0)', 8, 50, 1);
SELECT pg_temp.axis('LINESTRING(0 -60, 0 60)', 8, 50, 0);
SELECT results_eq($$SELECT kind, count FROM streetgen.generate('s') WHERE kind IN ('node', 'intersection') ORDER BY 1$$,
                  $$VALUES ('node', 4::bigint)$$, 'a bridge over a street: no junction between them');

SELECT throws_ok($$SELECT pg_temp.axis('LINESTRING(0 0, 0 0)')$$, '23514', NULL, 'zero-length axes are refused by the table');
SELECT throws_ok($$INSERT INTO s.axis (geom, roadway_width, speed_kmh) VALUES (ST_SetSRID(ST_MakeLine(ST_MakePoint(0, 0), ST_MakePoint('NaN', 1)), 32631), 5, 30)$$,
                 '23514', NULL, 'NaN coordinates are refused by the table');

-- Settings are validated by the table's checks.
SELECT throws_ok($$UPDATE s.settings SET min_radius = -1$$, '23514', NULL, 'a negative min_radius is refused');
SELECT throws_ok($$UPDATE s.settings SET max_radius = 0.01$$, '23514', NULL, 'max_radius below min_radius is refused');

-- generate(): bad model names.
SELECT throws_ok($$SELECT * FROM streetgen.generate(NULL)$$, '22004', NULL, 'generate(NULL)');
SELECT throws_ok($$SELECT * FROM streetgen.generate('nope')$$, '42704', NULL, 'generate of an unknown model');
SELECT throws_ok($$SELECT * FROM streetgen.generate('x; DROP SCHEMA s CASCADE')$$, '42602', NULL, 'generate with an injection attempt');

-- street_surfaces(): stateless, same engine.
SELECT results_eq(
  $$SELECT kind, count(*)::bigint FROM streetgen.street_surfaces(
      $q$SELECT * FROM (VALUES (1, 'SRID=32631;LINESTRING(-60 0, 60 0)'::geometry, 8.0, 50.0),
                               (2, 'SRID=32631;LINESTRING(0 -60, 0 60)'::geometry, 8.0, 50.0)) AS t(id, geom, roadway_width, speed_kmh)$q$)
     GROUP BY 1 ORDER BY 1$$,
  $$VALUES ('corner', 4::bigint), ('crossing', 4::bigint), ('intersection', 1::bigint), ('lane', 8::bigint),
            ('marking', 8::bigint), ('node', 5::bigint), ('section', 4::bigint), ('sidewalk', 9::bigint)$$,
  'street_surfaces on a query: the cross');
SELECT ok((SELECT bool_and(ST_IsValid(geom)) FROM streetgen.street_surfaces('SELECT id, geom, roadway_width, speed_kmh FROM s.axis') WHERE kind IN ('section', 'intersection')),
          'street_surfaces on a model''s axes: valid surfaces');
SELECT results_eq($$SELECT count(*) FROM streetgen.street_surfaces('SELECT id, geom, roadway_width, speed_kmh FROM s.axis WHERE false')$$,
                  $$VALUES (0::bigint)$$, 'no axes, no rows');
SELECT is((SELECT round(max(ST_Distance(centre, ST_StartPoint(arc_segmentized)))::numeric, 2) FROM s.corner), NULL, 'no corners without junctions');
SELECT throws_ok($$SELECT * FROM streetgen.street_surfaces(NULL)$$, '22004', NULL, 'street_surfaces(NULL)');
SELECT throws_ok($$SELECT * FROM streetgen.street_surfaces('SELECT 1 AS id')$$, '22023', NULL, 'a query without the needed columns');
SELECT throws_ok($$SELECT * FROM streetgen.street_surfaces('SELECT 1 AS id, ''SRID=4326;LINESTRING(0 0, 1 1)''::geometry AS geom, 5 AS roadway_width, 30 AS speed_kmh')$$,
                 '22023', NULL, 'axes in a geographic CRS');
SELECT throws_ok($$SELECT * FROM streetgen.street_surfaces('SELECT 1 AS id, ''SRID=32631;LINESTRING(0 0, 1 1)''::geometry AS geom, 0 AS roadway_width, 30 AS speed_kmh')$$,
                 '22023', 'axis 1: roadway_width must be a finite number > 0', 'a zero width, named by axis');
SELECT throws_ok($$SELECT * FROM streetgen.street_surfaces('SELECT 1 AS id, ''SRID=32631;LINESTRING(0 0, 0 0)''::geometry AS geom, 5 AS roadway_width, 30 AS speed_kmh')$$,
                 '22023', 'geometry of axis 1 has zero length', 'a zero-length axis');
SELECT throws_ok($$SELECT * FROM streetgen.street_surfaces('SELECT 1 AS id, ST_SetSRID(ST_MakeLine(ST_MakePoint(0, 0), ST_MakePoint(''NaN'', 1)), 32631) AS geom, 5 AS roadway_width, 30 AS speed_kmh')$$,
                 '22023', 'geometry of axis 1 has a non-finite coordinate', 'a NaN coordinate');
SELECT throws_ok($$SELECT * FROM streetgen.street_surfaces('SELECT 1 AS id, ''SRID=32631;POINT(0 0)''::geometry AS geom, 5 AS roadway_width, 30 AS speed_kmh')$$,
                 '22023', NULL, 'a point instead of a line');
SELECT throws_ok($$SELECT * FROM streetgen.street_surfaces('SELECT 1 AS id, NULL::geometry AS geom, 5 AS roadway_width, 30 AS speed_kmh')$$,
                 '22004', NULL, 'a NULL geometry');
SELECT throws_ok($$SELECT * FROM streetgen.street_surfaces('SELECT id, geom, roadway_width, speed_kmh FROM s.axis', '{"min_radius": -1}')$$,
                 '22023', NULL, 'a negative setting');
SELECT throws_ok($$SELECT * FROM streetgen.street_surfaces('SELECT id, geom, roadway_width, speed_kmh FROM s.axis', '{"radius": 3}')$$,
                 '22023', 'unknown setting "radius"', 'an unknown setting');
SELECT throws_ok($$SELECT * FROM streetgen.street_surfaces('SELECT id, geom, roadway_width, speed_kmh FROM s.axis', '[1]')$$,
                 '22023', NULL, 'settings that are not an object');
SELECT throws_ok($$SELECT * FROM streetgen._streetgen_street_surfaces('{1}', '{}', '{}', '{}', '{}', '{}', '{}', '{}', '{}', '{}', '{}', '{}', '{}', '{}', '{}')$$,
                 '22023', NULL, 'arrays of different lengths at the C level');

SELECT * FROM finish();
ROLLBACK;
