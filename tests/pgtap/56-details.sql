-- Sidewalks, crossings and blocks (issue 5, items 3-4): the sidewalk rule, the geometry on small
-- networks whose answers are known, bad input, and the triggers keeping the three tables current.
BEGIN;
SELECT * FROM no_plan();

-- The sidewalk rule: sides from tags or class, widths from tags, the column, then the default.
SELECT is(streetgen.sidewalk_widths('residential', NULL, '{}', 2), ARRAY[2, 2]::float8[], 'a residential street: both sides, the default width');
SELECT is(streetgen.sidewalk_widths('motorway', NULL, '{}', 2), ARRAY[0, 0]::float8[], 'a motorway: none');
SELECT is(streetgen.sidewalk_widths('service', NULL, '{}', 2), ARRAY[0, 0]::float8[], 'a service road: none');
SELECT is(streetgen.sidewalk_widths('service', NULL, '{"sidewalk": "both"}', 2), ARRAY[2, 2]::float8[], 'tags win over the class');
SELECT is(streetgen.sidewalk_widths('residential', 3.5, '{}', 2), ARRAY[3.5, 3.5]::float8[], 'the sidewalk_width column');
SELECT is(streetgen.sidewalk_widths('residential', 0, '{}', 2), ARRAY[0, 0]::float8[], 'sidewalk_width 0: none');
SELECT is(streetgen.sidewalk_widths('residential', NULL, '{"sidewalk": "left"}', 2), ARRAY[2, 0]::float8[], 'sidewalk=left');
SELECT is(streetgen.sidewalk_widths('residential', NULL, '{"sidewalk": "right", "sidewalk:right:width": "1.8 m"}', 2),
          ARRAY[0, 1.8]::float8[], 'sidewalk=right with its width');
SELECT is(streetgen.sidewalk_widths('residential', NULL, '{"sidewalk": "separate"}', 2), ARRAY[0, 0]::float8[],
          'sidewalk=separate: drawn as its own way, none here');
SELECT is(streetgen.sidewalk_widths('residential', NULL, '{"sidewalk:both": "no"}', 2), ARRAY[0, 0]::float8[], 'sidewalk:both=no');
SELECT is(streetgen.sidewalk_widths('primary', NULL, '{"sidewalk:left": "yes", "sidewalk:right": "separate", "sidewalk:width": "3"}', 2),
          ARRAY[3, 0]::float8[], 'sidewalk:left / sidewalk:right and sidewalk:width');
SELECT is(streetgen.sidewalk_widths('residential', NULL, '{"sidewalk": "left", "oneway": "-1"}', 2), ARRAY[0, 2]::float8[],
          'oneway=-1: the importer reverses the way, so left becomes right');
SELECT is(streetgen.sidewalk_widths('residential', NULL, '{"sidewalk:width": "300"}', 2), ARRAY[2, 2]::float8[],
          'an absurd tagged width (300 m) counts as missing');
SELECT is(streetgen.sidewalk_widths('residential', NULL, '{"sidewalk:width": "wide"}', 2), ARRAY[2, 2]::float8[],
          'an unreadable tagged width counts as missing');
SELECT is(streetgen.sidewalk_widths('residential', NULL, '{"sidewalk": "junk"}', 2), ARRAY[0, 0]::float8[],
          'an unknown sidewalk value: no sidewalk claimed');
SELECT is(streetgen.sidewalk_widths(NULL, NULL, '[1]', 2), ARRAY[2, 2]::float8[], 'tags that are not an object: ignored');

-- A block of four streets (100 m squares, 8 m wide, 30 km/h) with one more street beyond it.
SELECT streetgen.create_model('dt', 32631);
CREATE FUNCTION pg_temp.axis(wkt text, speed float8 DEFAULT 30, class text DEFAULT 'residential') RETURNS bigint LANGUAGE sql AS $$
  INSERT INTO dt.axis (geom, roadway_width, speed_kmh, road_class) VALUES (ST_GeomFromText(wkt, 32631), 8, speed, class) RETURNING id
$$;
CREATE FUNCTION pg_temp.sound(label text) RETURNS SETOF text LANGUAGE plpgsql AS $$
DECLARE q record;
BEGIN
  SELECT * INTO q FROM streetgen.detail_quality('dt');
  RETURN NEXT is(q.invalid_geometries, 0::bigint, label || ': sidewalks, crossings and blocks valid');
  RETURN NEXT cmp_ok(q.sidewalk_roadway_overlap_area, '<', 1e-6::float8, label || ': no sidewalk on a roadway');
  RETURN NEXT cmp_ok(q.sidewalk_overlap_area, '<', 1e-6::float8, label || ': sidewalks do not overlap');
  RETURN NEXT cmp_ok(q.crossing_outside_area, '<', 1e-6::float8, label || ': crossings lie in their section');
  RETURN NEXT cmp_ok(q.overlap_area, '<', 1e-6 * greatest(q.face_area, 1), label || ': blocks and streets do not overlap in the faces');
  RETURN NEXT cmp_ok(q.gap_area, '<', 1e-6 * greatest(q.face_area, 1), label || ': blocks and streets leave no gap in the faces');
  RETURN NEXT is_empty('SELECT * FROM streetgen.outdated(''dt'')', label || ': sidewalks, crossings and blocks equal a full recompute');
END $$;
SELECT pg_temp.axis('LINESTRING(0 0, 100 0)') AS south \gset
SELECT pg_temp.axis('LINESTRING(100 0, 100 100)') AS east \gset
SELECT pg_temp.axis('LINESTRING(100 100, 0 100)') AS north \gset
SELECT pg_temp.axis('LINESTRING(0 100, 0 0)') AS west \gset
SELECT pg_temp.axis('LINESTRING(100 0, 200 0)') AS beyond \gset
SELECT * FROM pg_temp.sound('a square block');

SELECT is((SELECT count(*) FROM dt.sidewalk WHERE axis_id IS NOT NULL), 10::bigint, 'two sidewalks per section');
SELECT is((SELECT count(*) FROM dt.sidewalk WHERE side = 'around'), 4::bigint, 'one around each junction');
SELECT ok((SELECT bool_and(abs(ST_Area(w.geom) - 2 * (s.end_border - s.start_border)) < 1e-6)
             FROM dt.sidewalk w JOIN dt.section s USING (axis_id, part) WHERE s.axis_id = :south),
          'a straight section''s sidewalk: 2 m wide between its border lines');
-- Around a corner the sidewalk follows the curb arc: every point of its inner edge is at the
-- arc's radius from the arc's centre (30 km/h: r = (0.35 x 30 / 3.6)^2 / 3 = 2.84 m).
SELECT ok((SELECT bool_and(abs(ST_Distance(c.centre, ST_ClosestPoint(w.geom, ST_LineInterpolatePoint(c.arc_segmentized, 0.5))) - c.radius) < 1e-3)
             FROM dt.corner c JOIN dt.sidewalk w ON w.node_id = c.node_id
            WHERE c.status = 'ok' AND c.radius > 0),
          'the junction sidewalk meets each curb arc at its middle');
SELECT ok((SELECT bool_and(ST_DWithin(w.geom, s.geom, 1e-6))
             FROM dt.sidewalk w JOIN dt.section s USING (axis_id, part)),
          'a section''s sidewalk touches its roadway (it starts at the curb)');

-- Crossings: at the junction of degree 3 only (corners of degree 2 are a street running on),
-- across the roadway, crossing_width long; the stop line goes behind it.
SELECT results_eq($$SELECT c.axis_id, c.position FROM dt.crossing c ORDER BY 1, 2$$,
                  format('VALUES (%s::bigint, 1::smallint), (%s::bigint, 0::smallint), (%s::bigint, 0::smallint)', :south, :east, :beyond),
                  'a crossing on each arm of the T junction, at the end that meets it');
SELECT ok((SELECT bool_and(abs(ST_Area(geom) - 8 * 3) < 1e-6) FROM dt.crossing), 'a crossing is 8 m across and 3 m along the axis');
SELECT ok((SELECT bool_and(ST_Distance(m.geom, c.geom) > 0.9)
             FROM dt.marking m JOIN dt.crossing c ON c.axis_id = m.axis_id AND c.part = m.part AND c.position = m.position
            WHERE m.kind = 'stop_line'),
          'stop lines stand a metre behind the crossing');
UPDATE dt.settings SET crossing_width = 0;
SELECT is((SELECT count(*) FROM dt.crossing), 0::bigint, 'crossing_width 0: no crossings (new settings recompute the model)');
UPDATE dt.settings SET crossing_width = 3, crossing_max_speed_kmh = 20;
SELECT is((SELECT count(*) FROM dt.crossing), 0::bigint, 'no crossing on streets faster than crossing_max_speed_kmh');
UPDATE dt.settings SET crossing_max_speed_kmh = 50;

-- Blocks: one face, the square minus the streets and sidewalks; the street beyond bounds none
-- (a dangling axis does not split a face, the outside has no block).
SELECT is((SELECT count(*) FROM dt.block), 1::bigint, 'one block');
SELECT is((SELECT round(ST_Area(face)) FROM dt.block), 10000::float8, 'its face is the square between the axes');
SELECT is((SELECT axis_ids FROM dt.block), ARRAY[:south, :east, :north, :west]::bigint[], 'the block knows the axes around it');
SELECT ok((SELECT ST_Area(geom) BETWEEN (100 - 2 * 6) ^ 2 - 50 AND (100 - 2 * 6) ^ 2 FROM dt.block),
          'the block is the square less 4 m of roadway and 2 m of sidewalk on each side (rounded corners)');
SELECT pg_temp.axis('LINESTRING(50 0, 50 40)') AS dangle \gset
SELECT is((SELECT count(*) FROM dt.block), 1::bigint, 'a dangling axis into the block does not split it');
SELECT ok((SELECT NOT ST_Intersects(geom, 'SRID=32631;POINT(50 20)'::geometry) FROM dt.block), 'but its street is cut out of the block');
SELECT * FROM pg_temp.sound('with a dangling axis');

-- The triggers keep them current.
UPDATE dt.axis SET sidewalk_width = 4 WHERE id = :north;
SELECT ok((SELECT bool_and(width = 4) FROM dt.sidewalk WHERE axis_id = :north) AND (SELECT count(*) FROM dt.sidewalk WHERE axis_id = :north) = 2,
          'an UPDATE of sidewalk_width rewrites that street''s sidewalks');
SELECT ok((SELECT bool_and(width = 4) FROM dt.sidewalk s JOIN dt.node n ON n.id = s.node_id WHERE :north = ANY (n.axis_ids)),
          'and those around its junctions');
SELECT * FROM pg_temp.sound('after a width edit');
UPDATE dt.axis SET tags = '{"sidewalk": "no"}' WHERE id = :west;
SELECT is((SELECT count(*) FROM dt.sidewalk WHERE axis_id = :west), 0::bigint, 'a sidewalk tag edit removes them');
SELECT * FROM pg_temp.sound('after a tag edit');
UPDATE dt.axis SET geom = 'SRID=32631;LINESTRING(0 100, -20 50, 0 0)' WHERE id = :west;
SELECT ok((SELECT abs(ST_Area(face) - 11000) < 1e-6 FROM dt.block), 'bending an axis outwards grows the face');
SELECT * FROM pg_temp.sound('after a move');
DELETE FROM dt.axis WHERE id = :north;
SELECT is((SELECT count(*) FROM dt.block), 0::bigint, 'deleting a side opens the face: no block');
SELECT is((SELECT count(*) FROM dt.sidewalk WHERE axis_id = :north), 0::bigint, 'its sidewalks go with its sections');
SELECT * FROM pg_temp.sound('after a delete');
INSERT INTO dt.axis (geom, roadway_width, speed_kmh) VALUES ('SRID=32631;LINESTRING(0 100, 100 100)', 8, 30);
SELECT is((SELECT count(*) FROM dt.block), 1::bigint, 'an INSERT closing the face makes the block again');
SELECT * FROM pg_temp.sound('after an insert');

-- Street surfaces only (settings.details false): no lanes, markings, crossings, sidewalks or
-- blocks, and the street surfaces themselves unchanged; details true again brings them back.
CREATE TEMP VIEW street_surface_rows AS
  SELECT 'section' AS kind, axis_id || '/' || part AS key, status, md5(ST_AsEWKB(geom)::text) AS g FROM dt.section
  UNION ALL SELECT 'intersection', node_id::text, status, md5(ST_AsEWKB(geom)::text) FROM dt.intersection
  UNION ALL SELECT 'corner', concat_ws('/', node_id, axis_a, part_a, end_a, axis_b, part_b, end_b), status,
                   md5(ST_AsEWKB(arc)::text) FROM dt.corner
  UNION ALL SELECT 'node', id::text, degree::text, md5(ST_AsEWKB(geom)::text) FROM dt.node;
-- (lanes, markings, crossings, sidewalks, blocks)
CREATE TEMP VIEW detail_counts AS
  SELECT ARRAY[(SELECT count(*) FROM dt.lane), (SELECT count(*) FROM dt.marking), (SELECT count(*) FROM dt.crossing),
               (SELECT count(*) FROM dt.sidewalk), (SELECT count(*) FROM dt.block)] AS counts;
CREATE TEMP TABLE surfaces_with_details AS SELECT * FROM street_surface_rows;
CREATE TEMP TABLE details_before AS SELECT * FROM detail_counts;
SELECT ok((SELECT 0 < ALL (counts) FROM details_before),
          'the model has lanes, markings, crossings, sidewalks and a block to begin with');
UPDATE dt.settings SET details = false;
SELECT is((SELECT counts FROM detail_counts), ARRAY[0, 0, 0, 0, 0]::bigint[],
          'details false: no lanes, markings, crossings, sidewalks or blocks (new settings recompute the model)');
SELECT set_eq('SELECT * FROM street_surface_rows', 'SELECT * FROM surfaces_with_details',
              'and the same nodes, sections, corners and junctions, to the byte');
UPDATE dt.axis SET speed_kmh = 40 WHERE id = :south;
SELECT is((SELECT counts FROM detail_counts), ARRAY[0, 0, 0, 0, 0]::bigint[], 'an edit of a surfaces-only model makes no details');
SELECT is_empty('SELECT * FROM streetgen.outdated(''dt'')', 'a surfaces-only model equals a full recompute after an edit');
UPDATE dt.axis SET speed_kmh = 30 WHERE id = :south;
UPDATE dt.settings SET details = true;
SELECT is((SELECT counts FROM detail_counts), (SELECT counts FROM details_before), 'details true again: every detail is back');
SELECT set_eq('SELECT * FROM street_surface_rows', 'SELECT * FROM surfaces_with_details', 'on the same surfaces');
SELECT is((SELECT count(*) FROM streetgen.street_surfaces('SELECT id, geom, roadway_width, speed_kmh FROM dt.axis', '{"details": false}')
            WHERE kind IN ('lane', 'marking', 'crossing', 'sidewalk')), 0::bigint,
          'street_surfaces with details false returns the surfaces only');
SELECT is((SELECT count(*) FROM streetgen.street_surfaces('SELECT id, geom, roadway_width, speed_kmh FROM dt.axis', '{"details": false}')
            WHERE kind = 'intersection'), (SELECT count(*) FROM dt.intersection),
          'with every junction');
SELECT throws_ok($$SELECT * FROM streetgen.street_surfaces('SELECT id, geom, roadway_width, speed_kmh FROM dt.axis', '{"details": "some"}')$$,
                 '22P02', NULL, 'details must be a boolean');

-- Traffic islands: the face between the two one-way carriageways of a dual carriageway.
SELECT streetgen.create_model('di', 32631);
INSERT INTO di.axis (geom, roadway_width, speed_kmh, road_class, oneway) VALUES
  ('SRID=32631;LINESTRING(-100 0, 0 0)', 12, 50, 'primary', false),
  ('SRID=32631;LINESTRING(0 0, 20 10, 80 10, 100 0)', 6, 50, 'primary', true),
  ('SRID=32631;LINESTRING(100 0, 80 -10, 20 -10, 0 0)', 6, 50, 'primary', true),
  ('SRID=32631;LINESTRING(100 0, 200 0)', 12, 50, 'primary', false);
SELECT results_eq('SELECT kind, round(ST_Area(face)) FROM di.block', $$VALUES ('island', 1600::float8)$$,
                  'the gap between the carriageways is a traffic island');
SELECT ok((SELECT geom IS NULL OR ST_Area(geom) < 1600 FROM di.block), 'the island is what the carriageways and sidewalks leave');
UPDATE di.axis SET oneway = false WHERE road_class = 'primary' AND ST_Length(geom) < 150 AND ST_NPoints(geom) = 4;
SELECT is((SELECT kind FROM di.block), 'block', 'two-way streets around it: a block, not an island');
SELECT is_empty('SELECT * FROM streetgen.outdated(''di'')', 'islands equal a full recompute');

-- Bad input.
SELECT throws_ok(format('UPDATE dt.axis SET sidewalk_width = -1 WHERE id = %s', :south), '23514', NULL, 'a negative sidewalk_width');
SELECT throws_ok(format('UPDATE dt.axis SET sidewalk_width = 100 WHERE id = %s', :south), '23514', NULL, 'an absurd sidewalk_width (100 m)');
SELECT throws_ok(format($$UPDATE dt.axis SET sidewalk_width = 'NaN' WHERE id = %s$$, :south), '23514', NULL, 'a NaN sidewalk_width');
SELECT throws_ok('UPDATE dt.settings SET default_sidewalk_width = -2', '23514', NULL, 'a negative default_sidewalk_width');
SELECT throws_ok('UPDATE dt.settings SET crossing_width = 50', '23514', NULL, 'an absurd crossing_width');
SELECT throws_ok($$SELECT * FROM streetgen.street_surfaces('SELECT 1 AS id, ''SRID=32631;LINESTRING(0 0, 50 0)''::geometry AS geom,
                                                                  8 AS roadway_width, 30 AS speed_kmh', '{"default_sidewalk_width": -1}')$$,
                 '22023', NULL, 'street_surfaces with a negative default_sidewalk_width');
SELECT throws_ok($$SELECT * FROM streetgen.street_surfaces('SELECT 1 AS id, ''SRID=32631;LINESTRING(0 0, 50 0)''::geometry AS geom,
                                                                  8 AS roadway_width, 30 AS speed_kmh', '{"crossing_width": -1}')$$,
                 '22023', NULL, 'street_surfaces with a negative crossing_width');
SELECT throws_ok($$SELECT * FROM streetgen._streetgen_street_surfaces('{1}', ARRAY[ST_AsEWKB('SRID=32631;LINESTRING(0 0, 50 0)'::geometry)],
                   '{8}', '{30}', '{}', '{}', '{0.5,0.35,3,0.15,25,3,0.5,5,5,30,3,50}', '{}', '{}', '{}', '{}', '{}', '{}', '{-1}', '{2}')$$,
                 '22023', NULL, 'a negative sidewalk width at the C level');
SELECT throws_ok($$SELECT * FROM streetgen._streetgen_street_surfaces('{1}', ARRAY[ST_AsEWKB('SRID=32631;LINESTRING(0 0, 50 0)'::geometry)],
                   '{8}', '{30}', '{}', '{}', '{0.5,0.35,3,0.15,25,3,0.5,5,5,30,3,50}', '{}', '{}', '{}', '{}', '{}', '{}', '{1, 2}', '{2}')$$,
                 '22023', NULL, 'sidewalk arrays of another length at the C level');
SELECT throws_ok($$SELECT * FROM streetgen.detail_quality('no_such_model')$$, '42704', NULL, 'detail_quality of a missing model');
SELECT throws_ok($$SELECT * FROM streetgen.detail_quality(NULL)$$, '22004', NULL, 'detail_quality(NULL)');

-- The block overlay (C++): bad input gives its SQLSTATE, a face with nothing on it is itself, a
-- face covered by a piece is NULL.
SELECT throws_ok($$SELECT * FROM streetgen._streetgen_faces_minus(ARRAY['\x0102'::bytea], '{}', '{}', '{}', 1e-6)$$, '22000', NULL,
                 '_streetgen_faces_minus: a face that is not EWKB');
SELECT throws_ok($$SELECT * FROM streetgen._streetgen_faces_minus('{}', '{}', '{}', '{}', NULL)$$, '22004', NULL,
                 '_streetgen_faces_minus: a NULL grid size');
SELECT throws_ok($$SELECT * FROM streetgen._streetgen_faces_minus('{}', '{}', '{}', '{}', 0)$$, '22023', NULL,
                 '_streetgen_faces_minus: a grid size of 0');
-- (the pieces come in three arrays, sidewalks, sections, junctions: each one cuts)
SELECT results_eq(
  $$SELECT f.face_index, round(ST_Area(ST_GeomFromEWKB(f.geom))), GeometryType(ST_GeomFromEWKB(f.geom)), ST_SRID(ST_GeomFromEWKB(f.geom))
      FROM streetgen._streetgen_faces_minus(
             ARRAY[ST_AsEWKB('SRID=32631;POLYGON((0 0, 100 0, 100 100, 0 100, 0 0))'::geometry),
                   ST_AsEWKB('SRID=32631;POLYGON((200 0, 210 0, 210 10, 200 10, 200 0))'::geometry), NULL],
             ARRAY[ST_AsEWKB('SRID=32631;POLYGON((-5 -5, 105 -5, 105 5, -5 5, -5 -5))'::geometry), NULL],
             ARRAY[ST_AsEWKB('SRID=32631;POLYGON((-5 95, 105 95, 105 105, -5 105, -5 95))'::geometry)],
             ARRAY[ST_AsEWKB('SRID=32631;POLYGON((199 -1, 211 -1, 211 11, 199 11, 199 -1))'::geometry), NULL], 1e-6) AS f
     ORDER BY 1$$,
  $$VALUES (1, 9000::float8, 'MULTIPOLYGON', 32631), (2, NULL, NULL, NULL), (3, NULL, NULL, NULL)$$,
  '_streetgen_faces_minus: what the pieces of all three arrays leave of each face, NULL when nothing');

SELECT * FROM finish();
ROLLBACK;
