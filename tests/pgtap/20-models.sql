-- Models: creation, the axis table's typing and CHECK constraints, and every bad input of
-- create_model / drop_model / model_srid, asserted by SQLSTATE.
BEGIN;
SELECT * FROM no_plan();

SELECT lives_ok($$SELECT streetgen.create_model('city', 32631)$$, 'create_model(city, 32631)');
SELECT has_schema('city');
SELECT has_table('city', 'axis', 'the model has an axis table');
SELECT col_type_is('city', 'axis', 'geom', 'geometry(LineString,32631)', 'axis.geom is typed with the model SRID');
SELECT tables_are('city', ARRAY['axis', 'settings', 'node', 'section', 'corner', 'intersection', 'lane', 'marking', 'sidewalk', 'crossing', 'block', 'issue', 'refresh_state'], 'the model''s tables');
SELECT triggers_are('city', 'axis', ARRAY['axis_lock_outputs', 'axis_refresh_insert', 'axis_refresh_update', 'axis_refresh_delete', 'axis_refresh_truncate'], 'the axis triggers keep the surfaces current');
SELECT col_type_is('city', 'corner', 'arc', 'geometry(CircularString,32631)', 'corner arcs are true circular strings');
SELECT col_type_is('city', 'intersection', 'geom', 'geometry(Polygon,32631)', 'intersections are polygons');
SELECT is((SELECT count(*) FROM city.settings), 1::bigint, 'the model has one settings row, copied from the defaults');
SELECT col_is_pk('city', 'axis', 'id', 'axis.id is the primary key');
SELECT columns_are('city', 'axis', ARRAY['id', 'geom', 'roadway_width', 'lanes', 'speed_kmh', 'road_class', 'oneway',
  'sidewalk_width', 'layer', 'structure', 'source', 'radius_override', 'tags', 'estimated']);
SELECT results_eq($$SELECT srid FROM streetgen.model WHERE name = 'city'$$, $$VALUES (32631)$$, 'the model is registered');
SELECT is(streetgen.model_srid('city'), 32631, 'model_srid');

-- A good row goes in; each bad row is refused by the constraint that names the problem.
SELECT lives_ok($$INSERT INTO city.axis (geom, roadway_width, speed_kmh)
                  VALUES ('SRID=32631;LINESTRING(0 0, 50 0, 80 30)', 7.5, 50)$$, 'a valid axis is accepted');
CREATE FUNCTION pg_temp.insert_axis(geom text, width text DEFAULT '6', speed text DEFAULT '30', extra_col text DEFAULT NULL,
                                    extra_val text DEFAULT NULL) RETURNS text LANGUAGE sql AS $$
  SELECT format('INSERT INTO city.axis (geom, roadway_width, speed_kmh%s) VALUES (%s, %s, %s%s)',
                coalesce(', ' || extra_col, ''), geom, width, speed, coalesce(', ' || extra_val, ''))
$$;
SELECT throws_ok(pg_temp.insert_axis($$'SRID=32631;LINESTRING(0 0, 10 0)'$$, '-3'), '23514', NULL, 'negative width');
SELECT throws_ok(pg_temp.insert_axis($$'SRID=32631;LINESTRING(0 0, 10 0)'$$, '0'), '23514', NULL, 'zero width');
SELECT throws_ok(pg_temp.insert_axis($$'SRID=32631;LINESTRING(0 0, 10 0)'$$, $$'NaN'$$), '23514', NULL, 'NaN width');
SELECT throws_ok(pg_temp.insert_axis($$'SRID=32631;LINESTRING(0 0, 10 0)'$$, $$'Infinity'$$), '23514', NULL, 'infinite width');
SELECT throws_ok(pg_temp.insert_axis($$'SRID=32631;LINESTRING(0 0, 10 0)'$$, 'NULL'), '23502', NULL, 'missing width');
SELECT throws_ok(pg_temp.insert_axis($$'SRID=32631;LINESTRING(0 0, 10 0)'$$, '6', '0'), '23514', NULL, 'zero speed');
SELECT throws_ok(pg_temp.insert_axis($$'SRID=32631;LINESTRING(0 0, 10 0)'$$, '6', $$'NaN'$$), '23514', NULL, 'NaN speed');
SELECT throws_ok(pg_temp.insert_axis($$'SRID=32631;LINESTRING(0 0, 10 0)'$$, '6', '30', 'lanes', '0'), '23514', NULL, 'zero lanes');
SELECT throws_ok(pg_temp.insert_axis($$'SRID=32631;LINESTRING(0 0, 10 0)'$$, '6', '30', 'layer', '9'), '23514', NULL, 'layer out of range');
SELECT throws_ok(pg_temp.insert_axis($$'SRID=32631;LINESTRING(0 0, 10 0)'$$, '6', '30', 'structure', $$'ramp'$$), '23514', NULL, 'unknown structure');
SELECT throws_ok(pg_temp.insert_axis($$'SRID=32631;LINESTRING(0 0, 10 0)'$$, '6', '30', 'sidewalk_width', '-1'), '23514', NULL, 'negative sidewalk width');
SELECT throws_ok(pg_temp.insert_axis($$'SRID=32631;LINESTRING(0 0, 10 0)'$$, '6', '30', 'radius_override', $$'NaN'$$), '23514', NULL, 'NaN radius override');
SELECT throws_ok(pg_temp.insert_axis($$'SRID=32631;LINESTRING(0 0, 10 0)'$$, '6', '30', 'road_class', $$' '$$), '23514', NULL, 'blank road class');
SELECT throws_ok(pg_temp.insert_axis($$'SRID=32631;LINESTRING(0 0, 10 0)'$$, '6', '30', 'tags', $$'[1]'$$), '23514', NULL, 'tags must be an object');
SELECT throws_ok(pg_temp.insert_axis($$'SRID=32631;LINESTRING EMPTY'$$), '23514', NULL, 'empty line');
SELECT throws_ok(pg_temp.insert_axis($$'SRID=32631;LINESTRING(5 5, 5 5)'$$), '23514', NULL, 'zero-length line');
SELECT throws_ok(pg_temp.insert_axis($$ST_SetSRID(ST_MakeLine(ST_MakePoint(0, 0), ST_MakePoint('NaN', 1)), 32631)$$), '23514', NULL, 'NaN coordinate');
SELECT throws_ok(pg_temp.insert_axis($$ST_SetSRID(ST_MakeLine(ST_MakePoint(0, 0), ST_MakePoint(1, 'Infinity')), 32631)$$), '23514', NULL, 'infinite coordinate');
SELECT throws_ok(pg_temp.insert_axis($$'SRID=4326;LINESTRING(0 0, 1 1)'$$), '22023', NULL, 'wrong SRID');
SELECT throws_ok(pg_temp.insert_axis($$'SRID=32631;POINT(0 0)'$$), '22023', NULL, 'not a LineString');
SELECT throws_ok(pg_temp.insert_axis('NULL'), '23502', NULL, 'missing geometry');
SELECT is((SELECT count(*) FROM city.axis), 1::bigint, 'only the valid axis is stored');
-- PostGIS gives a geometry without SRID the column's SRID: coordinates in the model's CRS.
SELECT lives_ok(pg_temp.insert_axis($$'LINESTRING(0 0, 1 1)'$$), 'a geometry without SRID is taken to be in the model SRID');
SELECT is((SELECT ST_SRID(geom) FROM city.axis ORDER BY id DESC LIMIT 1), 32631, 'and stored with it');

-- create_model: bad names (NULL, not identifiers, injection attempts, reserved) and SRIDs.
SELECT throws_ok($$SELECT streetgen.create_model(NULL, 32631)$$, '22004', NULL, 'NULL name');
SELECT throws_ok($$SELECT streetgen.create_model('x', NULL)$$, '22004', NULL, 'NULL srid');
SELECT throws_ok($$SELECT streetgen.create_model('', 32631)$$, '42602', NULL, 'empty name');
SELECT throws_ok($$SELECT streetgen.create_model('Paris', 32631)$$, '42602', NULL, 'upper case name');
SELECT throws_ok($$SELECT streetgen.create_model('9lives', 32631)$$, '42602', NULL, 'name starting with a digit');
SELECT throws_ok($$SELECT streetgen.create_model(repeat('a', 64), 32631)$$, '42602', NULL, 'name too long');
SELECT throws_ok($$SELECT streetgen.create_model('x; DROP SCHEMA city CASCADE', 32631)$$, '42602', NULL, 'injection with ;');
SELECT throws_ok($$SELECT streetgen.create_model('x"; DROP SCHEMA city CASCADE; --', 32631)$$, '42602', NULL, 'injection with a quote');
SELECT has_schema('city', 'the injection attempts dropped nothing');
SELECT throws_ok($$SELECT streetgen.create_model('public', 32631)$$, '42939', NULL, 'public is reserved');
SELECT throws_ok($$SELECT streetgen.create_model('streetgen', 32631)$$, '42939', NULL, 'streetgen is reserved');
SELECT throws_ok($$SELECT streetgen.create_model('pg_roads', 32631)$$, '42939', NULL, 'pg_ prefix is reserved');
SELECT throws_ok($$SELECT streetgen.create_model('select', 32631)$$, '42939', NULL, 'SQL reserved word');
SELECT throws_ok($$SELECT streetgen.create_model('x', 4326)$$, '22023', NULL, 'geographic SRID');
SELECT throws_ok($$SELECT streetgen.create_model('x', 2263)$$, '22023', NULL, 'SRID in US feet');
SELECT throws_ok($$SELECT streetgen.create_model('x', 999999)$$, '22023', NULL, 'unknown SRID');
SELECT throws_ok($$SELECT streetgen.create_model('x', -1)$$, '22023', NULL, 'negative SRID');
SELECT hasnt_schema('x', 'no failed call left a schema behind');
SELECT throws_ok($$SELECT streetgen.create_model('city', 32631)$$, '42P06', 'model "city" already exists', 'duplicate model');
CREATE SCHEMA not_a_model;
SELECT throws_ok($$SELECT streetgen.create_model('not_a_model', 32631)$$, '42P06', NULL, 'an existing unrelated schema');
SELECT lives_ok($$SELECT streetgen.create_model('local_metres', 0)$$, 'SRID 0 (local metric coordinates) is allowed');
SELECT col_type_is('local_metres', 'axis', 'geom', 'geometry(LineString)', 'SRID 0 model geometry type');

-- drop_model and model_srid.
SELECT throws_ok($$SELECT streetgen.drop_model(NULL)$$, '22004', NULL, 'drop_model(NULL)');
SELECT throws_ok($$SELECT streetgen.drop_model('nope')$$, '42704', 'model "nope" does not exist', 'drop an unknown model');
SELECT throws_ok($$SELECT streetgen.drop_model('not_a_model')$$, '42704', NULL, 'drop a schema that is not a model');
SELECT has_schema('not_a_model', 'drop_model never drops a schema that is not a model');
SELECT throws_ok($$SELECT streetgen.drop_model('public')$$, '42704', NULL, 'drop public');
SELECT throws_ok($$SELECT streetgen.drop_model('city; DROP SCHEMA public')$$, '42602', NULL, 'drop_model injection');
SELECT has_schema('public', 'public survives');
SELECT throws_ok($$SELECT streetgen.model_srid('nope')$$, '42704', NULL, 'model_srid of an unknown model');
SELECT throws_ok($$SELECT streetgen.model_srid(NULL)$$, '22004', NULL, 'model_srid(NULL)');
SELECT lives_ok($$SELECT streetgen.drop_model('city')$$, 'drop_model(city)');
SELECT hasnt_schema('city', 'the schema is gone');
SELECT is_empty($$SELECT 1 FROM streetgen.model WHERE name = 'city'$$, 'the registry row is gone');
SELECT lives_ok($$SELECT streetgen.create_model('city', 32632)$$, 'the name can be reused after a drop');

-- Ordinary users: create_model runs with the caller's rights; nobody can drop, or unregister,
-- someone else's model.
CREATE ROLE streetgen_alice;
CREATE ROLE streetgen_bob;
SELECT format('GRANT CREATE ON DATABASE %I TO streetgen_alice, streetgen_bob', current_database()) \gexec
SET LOCAL ROLE streetgen_alice;
SELECT lives_ok($$SELECT streetgen.create_model('alices', 32631)$$, 'an ordinary user creates a model');
SELECT is((SELECT nspowner::regrole::text FROM pg_namespace WHERE nspname = 'alices'), 'streetgen_alice', 'and owns its schema');
SELECT lives_ok($$INSERT INTO alices.axis (geom, roadway_width, speed_kmh) VALUES ('SRID=32631;LINESTRING(0 0, 1 0)', 5, 30)$$,
                'and writes its axes');
RESET ROLE;
SET LOCAL ROLE streetgen_bob;
SELECT throws_ok($$SELECT streetgen.drop_model('alices')$$, '42501', NULL, 'another user cannot drop it');
SELECT throws_ok($$INSERT INTO streetgen.model (name, srid, created_by) VALUES ('fake', 32631, 'streetgen_alice')$$, '42501', NULL,
                 'nor register a model in someone else''s name');
SELECT is((SELECT count(*) FROM streetgen.model WHERE name = 'alices'), 1::bigint, 'the model is still registered');
DELETE FROM streetgen.model WHERE name = 'alices';
RESET ROLE;
SELECT is((SELECT count(*) FROM streetgen.model WHERE name = 'alices'), 1::bigint, 'a direct DELETE by another user removes nothing');
SELECT has_schema('alices', 'and the schema is intact');

SELECT * FROM finish();
ROLLBACK;
