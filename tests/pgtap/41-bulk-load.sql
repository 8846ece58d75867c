-- load_osm_ways into a model without axes loads in bulk: the model's foreign keys are dropped
-- before the load and made again after it. The model must come
-- out with the same relations as a new one, and outputs equal to a full recompute.
BEGIN;
SELECT * FROM no_plan();

-- The relations of a model, with its schema name taken out so that two models compare.
CREATE FUNCTION pg_temp.relations(model text)
  RETURNS TABLE (kind text, name text, definition text)
  LANGUAGE sql AS $$
    SELECT 'index', c.relname::text, replace(pg_get_indexdef(i.indexrelid), model || '.', '')
      FROM pg_index i JOIN pg_class c ON c.oid = i.indexrelid
     WHERE c.relnamespace = model::regnamespace
    UNION ALL
    SELECT 'constraint ' || k.contype::text, c.relname || '.' || k.conname,
           replace(pg_get_constraintdef(k.oid), model || '.', '')
      FROM pg_constraint k JOIN pg_class c ON c.oid = k.conrelid
     WHERE c.relnamespace = model::regnamespace
    UNION ALL
    -- (the bulk load drops the axes' insert trigger and makes it again)
    SELECT 'trigger', c.relname || '.' || t.tgname, replace(pg_get_triggerdef(t.oid), model || '.', '')
      FROM pg_trigger t JOIN pg_class c ON c.oid = t.tgrelid
     WHERE c.relnamespace = model::regnamespace AND NOT t.tgisinternal
  $$;
CREATE FUNCTION pg_temp.foreign_key_oids(model text)
  RETURNS TABLE (name text, oid oid)
  LANGUAGE sql AS $$
    SELECT k.conname::text, k.oid FROM pg_constraint k JOIN pg_class c ON c.oid = k.conrelid
     WHERE c.relnamespace = model::regnamespace AND k.contype = 'f'
  $$;

SELECT streetgen.create_model('reference', 32631);
SELECT streetgen.create_model('bulk', 32631);
CREATE TEMP TABLE before_load AS SELECT * FROM pg_temp.foreign_key_oids('bulk');

-- A grid of 4 x 4 streets, 100 m apart, in Paris (EPSG:32631): junctions of 2, 3 and 4 streets.
CREATE TEMP TABLE grid_staging AS
  SELECT 'osm:way/' || (10 * d + k) AS source, '{"highway": "residential"}'::jsonb AS tags,
         ST_Transform(ST_SetSRID(CASE WHEN d = 0
                                      THEN ST_MakeLine(ST_MakePoint(452000 + 100 * k, 5411000), ST_MakePoint(452000 + 100 * k, 5411300))
                                      ELSE ST_MakeLine(ST_MakePoint(452000, 5411000 + 100 * k), ST_MakePoint(452300, 5411000 + 100 * k)) END,
                                 32631), 4326) AS geom
    FROM generate_series(0, 1) AS d, generate_series(0, 3) AS k;

SELECT results_eq($$SELECT loaded FROM streetgen.load_osm_ways('bulk', 'grid_staging')$$, $$VALUES (8::bigint)$$,
                  'eight ways loaded into the model without axes');
SELECT is((SELECT count(*) FROM pg_temp.foreign_key_oids('bulk') a JOIN before_load b USING (name, oid)), 0::bigint,
          'the load went in bulk: every foreign key was made again');
SELECT set_eq($$SELECT * FROM pg_temp.relations('bulk')$$, $$SELECT * FROM pg_temp.relations('reference')$$,
              'after the bulk load the model has the same keys, foreign keys, checks, indexes and triggers as a new model');
SELECT cmp_ok((SELECT count(*) FROM bulk.section), '>=', 24::bigint, 'sections stored');
SELECT cmp_ok((SELECT count(*) FROM bulk.corner), '>=', 36::bigint, 'corners stored');
SELECT is_empty($$SELECT * FROM streetgen.outdated('bulk')$$, 'the bulk-loaded outputs equal a full recompute');
-- (the bulk load runs the insert trigger's recompute itself, once, after the INSERT)
SELECT is((SELECT string_agg(t.tgname || ' ' || t.tgenabled::text, ', ' ORDER BY t.tgname)
             FROM pg_trigger t WHERE t.tgrelid = 'bulk.axis'::regclass AND NOT t.tgisinternal),
          (SELECT string_agg(t.tgname || ' ' || t.tgenabled::text, ', ' ORDER BY t.tgname)
             FROM pg_trigger t WHERE t.tgrelid = 'reference.axis'::regclass AND NOT t.tgisinternal),
          'after the bulk load the axis triggers are enabled, as in a new model');
SELECT is((SELECT refreshes FROM bulk.refresh_state), (SELECT refreshes FROM reference.refresh_state) + 1,
          'and the load recomputed the model once');
-- (this file runs in a session of its own: the load made the work tables of a whole model's
-- recompute, the engine's output and the blocks', and none of a local one's)
SELECT is(ARRAY(SELECT n FROM unnest(ARRAY['_streetgen_out', '_sg_faces', '_sg_blocks', '_sg_changed_geom', '_sg_scope_out'])
                 AS n WHERE to_regclass('pg_temp.' || n) IS NOT NULL),
          ARRAY['_streetgen_out', '_sg_faces', '_sg_blocks'],
          'a whole model''s recompute makes only the work tables it uses');
SELECT throws_ok($$INSERT INTO bulk.corner (node_id, axis_a, part_a, end_a, axis_b, part_b, end_b, status)
                   SELECT node_id, 999999, part_a, end_a, axis_b, part_b, end_b, status FROM bulk.corner LIMIT 1$$,
                 '23503', NULL, 'the foreign keys hold again: a corner of an unknown axis is refused');
SELECT lives_ok($$DELETE FROM bulk.axis WHERE source = 'osm:way/1'$$, 'an axis deleted after the bulk load');
SELECT is((SELECT count(*) FROM unnest(ARRAY['_sg_changed_geom', '_sg_t_nodes', '_sg_k_nodes', '_sg_s1', '_sg_s2', '_sg_q',
                                             '_sg_context_nodes', '_sg_scope_sections', '_sg_scope_nodes', '_sg_scope_axes',
                                             '_sg_scope_out']) AS n
            WHERE to_regclass('pg_temp.' || n) IS NOT NULL), 11::bigint,
          'the local recompute of an edit made the neighbourhood''s work tables');
SELECT is((SELECT count(*) FROM unnest(ARRAY['_sg_t_nodes_geom', '_sg_scope_out_geom']) AS n WHERE to_regclass('pg_temp.' || n) IS NOT NULL), 2::bigint,
          'with their spatial indexes');
SELECT is_empty($$SELECT s.axis_id FROM bulk.section s WHERE NOT EXISTS (SELECT 1 FROM bulk.axis a WHERE a.id = s.axis_id)
                  UNION ALL SELECT c.axis_a FROM bulk.corner c WHERE NOT EXISTS (SELECT 1 FROM bulk.axis a WHERE a.id IN (c.axis_a, c.axis_b))$$,
                'its sections went with it');
SELECT is_empty($$SELECT * FROM streetgen.outdated('bulk')$$, 'and the outputs still equal a full recompute');

-- Into a model that has axes, the load checks the foreign keys row by row: they stay as they are.
CREATE TEMP TABLE before_second AS SELECT * FROM pg_temp.foreign_key_oids('bulk');
CREATE TEMP TABLE more_staging AS
  SELECT 'osm:way/99' AS source, '{"highway": "residential"}'::jsonb AS tags,
         ST_Transform(ST_SetSRID(ST_MakeLine(ST_MakePoint(452300, 5411300), ST_MakePoint(452400, 5411400)), 32631), 4326) AS geom;
SELECT results_eq($$SELECT loaded FROM streetgen.load_osm_ways('bulk', 'more_staging')$$, $$VALUES (1::bigint)$$,
                  'one more way loaded into the model with axes');
SELECT set_eq($$SELECT * FROM pg_temp.foreign_key_oids('bulk')$$, $$SELECT * FROM before_second$$,
              'a load into a model with axes keeps its foreign keys (no bulk load)');
SELECT is_empty($$SELECT * FROM streetgen.outdated('bulk')$$, 'its outputs equal a full recompute');

-- A bulk load that fails leaves the model as it was, relations included.
SELECT streetgen.create_model('bulk_fail', 32631);
CREATE TEMP TABLE bad_staging (source text, tags jsonb, geom geometry);
INSERT INTO bad_staging SELECT * FROM grid_staging;
INSERT INTO bad_staging VALUES ('osm:way/13', '{"highway": "residential"}', 'SRID=4326;LINESTRING(2.37 48.86, 2.37 95)');
SELECT throws_ok($$SELECT * FROM streetgen.load_osm_ways('bulk_fail', 'bad_staging')$$, '22023', NULL,
                 'a bulk load with a way that cannot be transformed fails');
SELECT set_eq($$SELECT * FROM pg_temp.relations('bulk_fail')$$, $$SELECT * FROM pg_temp.relations('reference')$$,
              'and leaves every relation of the model in place');
SELECT is((SELECT count(*) FROM bulk_fail.axis), 0::bigint, 'and no axis');
SELECT is((SELECT string_agg(t.tgname || ' ' || t.tgenabled::text, ', ' ORDER BY t.tgname)
             FROM pg_trigger t WHERE t.tgrelid = 'bulk_fail.axis'::regclass AND NOT t.tgisinternal),
          (SELECT string_agg(t.tgname || ' ' || t.tgenabled::text, ', ' ORDER BY t.tgname)
             FROM pg_trigger t WHERE t.tgrelid = 'reference.axis'::regclass AND NOT t.tgisinternal),
          'and its axis triggers enabled');

SELECT * FROM finish();
ROLLBACK;
