-- Always current: the axis triggers keep every output equal to a full recompute, through
-- inserts, updates and deletes; what does not shape surfaces recomputes nothing; bad edits are
-- refused with the row and leave the outputs as they were.
BEGIN;
SELECT * FROM no_plan();

SELECT streetgen.create_model('live', 32631);
INSERT INTO live.axis (id, geom, roadway_width, speed_kmh) OVERRIDING SYSTEM VALUE VALUES
  (1, 'SRID=32631;LINESTRING(-80 0, 0 0)', 8, 50), (2, 'SRID=32631;LINESTRING(0 0, 80 0)', 8, 50),
  (3, 'SRID=32631;LINESTRING(0 -80, 0 0)', 6, 30), (4, 'SRID=32631;LINESTRING(0 0, 0 80)', 6, 30),
  (5, 'SRID=32631;LINESTRING(80 0, 80 80)', 6, 30);
SELECT is((SELECT count(*) FROM live.intersection), 2::bigint, 'an INSERT builds the surfaces at once: two junctions');
SELECT is((SELECT count(*) FROM streetgen.outdated('live')), 0::bigint, 'and they equal a full recompute');
-- (outdated itself: a stored sidewalk moved by hand is named, with how far it lies from its
-- recompute; moved back, the model is current again)
CREATE TEMP TABLE moved_sidewalk AS SELECT node_id FROM live.sidewalk WHERE node_id IS NOT NULL ORDER BY node_id LIMIT 1;
UPDATE live.sidewalk SET geom = ST_Translate(geom, 0.25, 0) WHERE node_id = (SELECT node_id FROM moved_sidewalk);
SELECT results_eq($$SELECT kind, key, what FROM streetgen.outdated('live')$$,
                  $$SELECT 'sidewalk', concat_ws('/', node_id, 'around'), 'differs by 0.250000 m' FROM moved_sidewalk$$,
                  'outdated names a stored sidewalk moved by hand, 0.25 m from its recompute');
UPDATE live.sidewalk SET geom = ST_Translate(geom, -0.25, 0) WHERE node_id = (SELECT node_id FROM moved_sidewalk);
SELECT is((SELECT count(*) FROM streetgen.outdated('live')), 0::bigint, 'moved back: current');

CREATE FUNCTION pg_temp.refreshes() RETURNS bigint LANGUAGE sql AS $$ SELECT refreshes FROM live.refresh_state $$;
CREATE TEMP TABLE area0 AS SELECT ST_Area(i.geom) a FROM live.intersection i JOIN live.node n ON n.id = i.node_id
                           WHERE ST_Equals(n.geom, 'SRID=32631;POINT(0 0)');

UPDATE live.axis SET roadway_width = 14 WHERE id = 1;
SELECT is((SELECT count(*) FROM streetgen.outdated('live')), 0::bigint, 'a width change: current');
SELECT ok((SELECT ST_Area(i.geom) FROM live.intersection i JOIN live.node n ON n.id = i.node_id WHERE ST_Equals(n.geom, 'SRID=32631;POINT(0 0)'))
          > (SELECT a FROM area0), 'and the junction grew with it');
UPDATE live.axis SET geom = ST_Translate(geom, 5, 0) WHERE id = 5;
SELECT is((SELECT count(*) FROM streetgen.outdated('live')), 0::bigint, 'an axis moved off its junction: current');
SELECT is((SELECT count(*) FROM live.node WHERE degree >= 2), 1::bigint, 'and its junction is gone');
DELETE FROM live.axis WHERE id = 4;
SELECT is((SELECT count(*) FROM streetgen.outdated('live')), 0::bigint, 'a deleted axis: current');
SELECT is((SELECT count(*) FROM live.section WHERE axis_id = 4), 0::bigint, 'its sections are gone');
INSERT INTO live.axis (id, geom, roadway_width, speed_kmh) OVERRIDING SYSTEM VALUE VALUES (6, 'SRID=32631;LINESTRING(-40 -40, 40 40)', 7, 40);
SELECT is((SELECT count(*) FROM streetgen.outdated('live')), 0::bigint, 'a new axis crossing the junction: current');

-- A recompute plans its neighbourhood lookups with its own search_path and planner settings;
-- they end with it, and the rest of the editor's transaction keeps its own.
CREATE TEMP TABLE settings_before AS SELECT current_setting('search_path') AS path;
SET LOCAL enable_mergejoin = off;
UPDATE live.axis SET roadway_width = 7 WHERE id = 5;
SELECT is(current_setting('search_path'), (SELECT path FROM settings_before), 'an edit leaves the search_path as it was');
SELECT is(ARRAY[current_setting('enable_seqscan'), current_setting('enable_hashjoin'), current_setting('enable_mergejoin')],
          ARRAY['on', 'on', 'off'], 'and the planner settings as they were');
RESET enable_mergejoin;
SELECT is((SELECT count(*) FROM streetgen.outdated('live')), 0::bigint, 'a width change in that transaction: current');

-- What does not shape the surfaces recomputes nothing.
CREATE TEMP TABLE before_tags AS SELECT pg_temp.refreshes() AS n;
UPDATE live.axis SET tags = '{"name": "Rue X"}', source = 'me' WHERE id = 1;
SELECT is(pg_temp.refreshes(), (SELECT n FROM before_tags), 'editing tags or source does not recompute');

-- The user's overrides take effect through the same triggers.
UPDATE live.corner SET radius_override = 1.5
 WHERE (node_id, axis_a, part_a, end_a, axis_b, part_b, end_b) = (SELECT node_id, axis_a, part_a, end_a, axis_b, part_b, end_b
                                                                    FROM live.corner WHERE status = 'ok' ORDER BY 1, 2, 3, 4, 5, 6, 7 LIMIT 1);
SELECT is((SELECT round(radius::numeric, 6) FROM live.corner WHERE radius_override IS NOT NULL), 1.5, 'a corner override applies at once');
SELECT is((SELECT count(*) FROM streetgen.outdated('live')), 0::bigint, 'and the model is current');
UPDATE live.settings SET turn_speed_ratio = 0.2;
SELECT ok((SELECT bool_and(radius < 3) FROM live.corner WHERE status = 'ok' AND radius_override IS NULL),
          'new settings recompute everything (slower turns, smaller radii)');
SELECT is((SELECT count(*) FROM streetgen.outdated('live')), 0::bigint, 'current');

-- A bad edit is refused, with its row, and changes nothing.
CREATE TEMP TABLE snapshot AS
  SELECT 'section' t, axis_id || '/' || part k, ST_AsEWKB(geom) g FROM live.section
  UNION ALL SELECT 'intersection', node_id::text, ST_AsEWKB(geom) FROM live.intersection;
SELECT throws_like($$UPDATE live.axis SET geom = ST_SetSRID(ST_MakeLine(ST_MakePoint(0, 0), ST_MakePoint('NaN', 1)), 32631) WHERE id = 2$$,
                   '%axis_geom_finite%', 'an invalid geometry is refused by its check');
SELECT throws_ok($$UPDATE live.axis SET roadway_width = -1 WHERE id = 2$$, '23514', NULL, 'a negative width is refused');
CREATE FUNCTION pg_temp.error_detail(sql text) RETURNS text LANGUAGE plpgsql AS $$
DECLARE d text;
BEGIN
  EXECUTE sql;
  RETURN NULL;
EXCEPTION WHEN check_violation THEN
  GET STACKED DIAGNOSTICS d = PG_EXCEPTION_DETAIL;
  RETURN d;
END $$;
SELECT matches(pg_temp.error_detail('UPDATE live.axis SET roadway_width = -1 WHERE id = 2'), '^Failing row contains \(2, ',
               'the error names the row (its id comes first)');
SELECT set_eq($$SELECT 'section' t, axis_id || '/' || part k, ST_AsEWKB(geom) g FROM live.section
                UNION ALL SELECT 'intersection', node_id::text, ST_AsEWKB(geom) FROM live.intersection$$,
              'SELECT * FROM snapshot', 'the refused edits left every output as it was');

-- A failure inside the recompute (here the intersection table refuses what it is given) fails
-- the edit, and the edit and the outputs roll back together.
ALTER TABLE live.intersection ADD CONSTRAINT refuse_everything CHECK (status = 'nothing') NOT VALID;
SELECT throws_like($$UPDATE live.axis SET roadway_width = 10 WHERE id = 2$$, '%refuse_everything%',
                   'an edit whose recompute fails, fails');
ALTER TABLE live.intersection DROP CONSTRAINT refuse_everything;
SELECT set_eq($$SELECT 'section' t, axis_id || '/' || part k, ST_AsEWKB(geom) g FROM live.section
                UNION ALL SELECT 'intersection', node_id::text, ST_AsEWKB(geom) FROM live.intersection$$,
              'SELECT * FROM snapshot', 'and no output was half updated');
SELECT is((SELECT roadway_width FROM live.axis WHERE id = 2), 8::float8, 'nor the axis changed');
SELECT is((SELECT count(*) FROM streetgen.outdated('live')), 0::bigint, 'the model is still current');

-- TRUNCATE ... CASCADE empties what refers to the axes without their triggers: the statement
-- trigger recomputes, and no node or junction is left behind.
TRUNCATE live.axis CASCADE;
SELECT is((SELECT count(*) FROM live.node) + (SELECT count(*) FROM live.intersection), 0::bigint,
          'a TRUNCATE of the axes leaves no node or junction behind');
INSERT INTO live.axis (id, geom, roadway_width, speed_kmh) OVERRIDING SYSTEM VALUE VALUES
  (1, 'SRID=32631;LINESTRING(-80 0, 0 0)', 8, 50), (2, 'SRID=32631;LINESTRING(0 0, 80 0)', 8, 50),
  (3, 'SRID=32631;LINESTRING(0 -80, 0 0)', 6, 30);
SELECT is((SELECT count(*) FROM streetgen.outdated('live')), 0::bigint, 'and new axes after it are current');

-- New settings of a model with nothing in it recompute nothing (an import sets them before it
-- loads); once it has axes, they recompute it. Counted by PostgreSQL's function statistics of
-- this transaction.
SET LOCAL track_functions = 'pl';
CREATE FUNCTION pg_temp.computes() RETURNS bigint LANGUAGE sql AS
  $$ SELECT coalesce(pg_stat_get_xact_function_calls('streetgen._compute_model(text, bigint[])'::regprocedure), 0) $$;
SELECT streetgen.create_model('settings_first', 32631);
CREATE TEMP TABLE computes_before AS SELECT pg_temp.computes() AS n;
UPDATE settings_first.settings SET details = false;
SELECT is(pg_temp.computes(), (SELECT n FROM computes_before), 'new settings of an empty model run no recompute');
INSERT INTO settings_first.axis (geom, roadway_width, speed_kmh) VALUES
  ('SRID=32631;LINESTRING(-80 0, 0 0)', 8, 50), ('SRID=32631;LINESTRING(0 0, 80 0)', 8, 50),
  ('SRID=32631;LINESTRING(0 -80, 0 0)', 6, 30);
SELECT is((SELECT count(*) FROM settings_first.intersection), 1::bigint, 'its first axes get their junction');
SELECT is((SELECT count(*) FROM settings_first.lane), 0::bigint, 'under the settings set before them (details off: no lanes)');
UPDATE settings_first.settings SET details = true;
SELECT is(pg_temp.computes(), (SELECT n FROM computes_before) + 2, 'with axes, new settings recompute (the insert once, the settings once)');
SELECT ok((SELECT count(*) FROM settings_first.lane) > 0, 'and their lanes appear');
SELECT is((SELECT count(*) FROM streetgen.outdated('settings_first')), 0::bigint, 'the model is current');
TRUNCATE settings_first.axis CASCADE;
SELECT is((SELECT count(*) FROM settings_first.node) + (SELECT count(*) FROM settings_first.block), 0::bigint,
          'a TRUNCATE still clears the nodes left behind');

SELECT throws_ok($$SELECT * FROM streetgen.outdated('nope')$$, '42704', NULL, 'outdated() of an unknown model');
SELECT throws_ok($$SELECT * FROM streetgen.outdated(NULL)$$, '22004', NULL, 'outdated(NULL)');

SELECT * FROM finish();
ROLLBACK;
