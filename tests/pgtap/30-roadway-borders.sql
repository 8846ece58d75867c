-- The first geometry SRF through the whole boundary: EWKB in and out, GEOS, errors by SQLSTATE,
-- and cancellation of a long GEOS computation by statement_timeout.
BEGIN;
SELECT * FROM no_plan();

SELECT results_eq(
  $$SELECT side, ST_AsText(geom), ST_SRID(geom) FROM streetgen.roadway_borders('SRID=32631;LINESTRING(0 0, 100 0)', 8)$$,
  $$VALUES ('left', 'LINESTRING(0 4,100 4)', 32631), ('right', 'LINESTRING(0 -4,100 -4)', 32631)$$,
  'straight axis: borders at half the width, SRID kept');

-- On a polyline every border vertex is at half the width from the axis, and the border is on
-- its side: checked with PostGIS, independently of GEOS's offset code.
CREATE TEMP TABLE bent AS SELECT 'SRID=32631;LINESTRING(0 0, 40 0, 60 25, 60 70, 20 90)'::geometry AS axis;
SELECT is_empty(
  $$SELECT 1 FROM bent, streetgen.roadway_borders(axis, 9) b, ST_DumpPoints(b.geom) p
     WHERE abs(ST_Distance(p.geom, axis) - 4.5) > 1e-6$$,
  'polyline: every border vertex is 4.5 m from the axis');
SELECT ok((SELECT bool_and(CASE b.side WHEN 'left' THEN ST_Y(ST_StartPoint(b.geom)) > 0 ELSE ST_Y(ST_StartPoint(b.geom)) < 0 END)
             FROM bent, streetgen.roadway_borders(axis, 9) b),
          'left border starts on the left of the axis (y > 0 for an axis heading east)');
SELECT is((SELECT count(*) FROM bent, streetgen.roadway_borders(axis, 9)), 2::bigint, 'two borders');
SELECT is((SELECT count(*) FROM streetgen.roadway_borders('LINESTRING(0 0, 10 0)', 3)), 2::bigint,
          'SRID 0 (local coordinates) is accepted');

-- Bad input: SQLSTATE and no crash.
SELECT throws_ok($$SELECT * FROM streetgen.roadway_borders(NULL, 4)$$, '22004', 'axis must not be null', 'NULL axis');
SELECT throws_ok($$SELECT * FROM streetgen.roadway_borders('SRID=32631;LINESTRING(0 0, 10 0)', NULL)$$, '22004', 'roadway_width must not be null', 'NULL width');
SELECT throws_ok($$SELECT * FROM streetgen.roadway_borders('SRID=32631;LINESTRING EMPTY', 4)$$, '22023', 'axis is empty', 'empty axis');
SELECT throws_ok($$SELECT * FROM streetgen.roadway_borders('SRID=32631;LINESTRING(3 3, 3 3)', 4)$$, '22023', 'axis has zero length', 'zero-length axis');
SELECT throws_ok($$SELECT * FROM streetgen.roadway_borders('SRID=32631;POINT(0 0)', 4)$$, '22023', 'axis must be a LineString', 'point');
SELECT throws_ok($$SELECT * FROM streetgen.roadway_borders('SRID=32631;MULTILINESTRING((0 0, 1 1))', 4)$$, '22023', NULL, 'multilinestring');
SELECT throws_ok($$SELECT * FROM streetgen.roadway_borders(ST_SetSRID(ST_MakeLine(ST_MakePoint(0, 0), ST_MakePoint('NaN', 1)), 32631), 4)$$,
                 '22023', 'axis has a non-finite coordinate', 'NaN coordinate');
SELECT throws_ok($$SELECT * FROM streetgen.roadway_borders(ST_SetSRID(ST_MakeLine(ST_MakePoint(0, 0), ST_MakePoint(1, '-Infinity')), 32631), 4)$$,
                 '22023', 'axis has a non-finite coordinate', 'infinite coordinate');
SELECT throws_ok($$SELECT * FROM streetgen.roadway_borders('SRID=32631;LINESTRING(0 0, 10 0)', -1)$$, '22023', NULL, 'negative width');
SELECT throws_ok($$SELECT * FROM streetgen.roadway_borders('SRID=32631;LINESTRING(0 0, 10 0)', 'NaN')$$, '22023', NULL, 'NaN width');
SELECT throws_ok($$SELECT * FROM streetgen.roadway_borders('SRID=32631;LINESTRING(0 0, 10 0)', 'Infinity')$$, '22023', NULL, 'infinite width');
SELECT throws_ok($$SELECT * FROM streetgen.roadway_borders('SRID=4326;LINESTRING(0 0, 1 1)', 4)$$, '22023', NULL, 'geographic SRID');
SELECT throws_ok($$SELECT * FROM streetgen.roadway_borders('SRID=999999;LINESTRING(0 0, 1 1)', 4)$$, '22023', NULL, 'unknown SRID');
SELECT throws_ok($$SELECT * FROM streetgen._streetgen_roadway_borders('\x0102'::bytea, 4)$$, '22000', 'axis is not valid EWKB', 'garbage EWKB at the C level');
SELECT throws_ok($$SELECT * FROM streetgen._streetgen_roadway_borders(NULL, 4)$$, '22004', NULL, 'NULL at the C level');

-- Cancellation: statement_timeout interrupts GEOS inside the offset computation (which takes
-- far longer than the timeout on this 300,000-vertex zigzag) and PostgreSQL's own 57014 error
-- comes out; the session stays usable.
CREATE TEMP TABLE huge AS
  SELECT ST_SetSRID(ST_MakeLine(ARRAY(SELECT ST_MakePoint(i, (i % 2) * 3 + sin(i / 100.0) * 50)
                                        FROM generate_series(1, 300000) AS i)), 32631) AS axis;
CREATE TEMP TABLE outcome (state text, seconds double precision);
SET LOCAL statement_timeout = '500ms';
INSERT INTO outcome SELECT * FROM test_helpers.sqlstate_and_seconds('SELECT count(*) FROM huge, streetgen.roadway_borders(axis, 6)');
RESET statement_timeout;
SELECT is((SELECT state FROM outcome), '57014', 'statement_timeout cancels a long GEOS computation with 57014');
SELECT cmp_ok((SELECT seconds FROM outcome), '<', 15.0::double precision,
              'the cancel is honoured within the computation, not after it (it runs for over a minute)');
SELECT is((SELECT count(*) FROM streetgen.roadway_borders('SRID=32631;LINESTRING(0 0, 1 0)', 1)), 2::bigint,
          'the next GEOS call in the session is not hit by a stale interrupt');

SELECT * FROM finish();
ROLLBACK;
