-- Always current: statement-level triggers on <model>.axis recompute only the neighbourhood of
-- the axes a statement changed, with the same engine as generate(), so that after any sequence
-- of edits the tables equal a full generate() of the same axes (tests/pgtap/60-refresh.sql
-- checks this on random edits of a real city).

-- Every recompute of a model (generate, a trigger) first updates the model's refresh_state row:
-- recomputes queue on its lock in READ COMMITTED, and fail with 40001 under REPEATABLE READ or
-- SERIALIZABLE, where a recompute could not see a concurrent one's result.
CREATE FUNCTION streetgen._lock_outputs(model text)
  RETURNS void
  LANGUAGE plpgsql VOLATILE
  SET search_path FROM CURRENT
  AS $$
BEGIN
  EXECUTE format('UPDATE %I.refresh_state SET refreshes = refreshes + 1, refreshed_at = clock_timestamp()', model);
END
$$;

-- The work tables of a recompute: temporary, made once per session, each when first wanted
-- (WANTED: their names; NULL: all). Granted to PUBLIC: one session may recompute as several
-- roles. The engine's output (_streetgen_out) is truncated before each run (see
-- _compute_model); the small neighbourhood tables are emptied by _empty_work_tables. The
-- neighbourhood's sections are kept as their envelopes: only bounding boxes are compared, and
-- small rows keep a table of many emptied edits small. (A whole model's recompute, an import's,
-- wants three of the fourteen: making all of them, their grants and indexes was about 25 ms of
-- backend CPU, a fiftieth of a city's import.)
CREATE FUNCTION streetgen._work_tables(wanted text[] DEFAULT NULL)
  RETURNS void
  LANGUAGE plpgsql VOLATILE
  SET search_path FROM CURRENT
  AS $$
DECLARE
  definition text;
  name text;
BEGIN
  FOREACH definition IN ARRAY ARRAY[
    '_streetgen_out (kind text, node_id bigint, to_node bigint, axis_id bigint, part bigint, end_a boolean, axis_b bigint,
                     part_b bigint, end_b boolean, status text, detail text, degree integer, layer integer,
                     radius double precision, radius_wanted double precision, start_border double precision,
                     end_border double precision, axis_ids bigint[], geom bytea, geom2 bytea, geom3 bytea,
                     item integer, width double precision, direction text)',
    '_sg_changed_geom (geom geometry)',
    '_sg_t_nodes (id bigint, geom geometry)',
    '_sg_k_nodes (id bigint)',
    '_sg_s1 (axis_id bigint, part bigint, from_node bigint, to_node bigint, envelope geometry)',
    '_sg_s2 (axis_id bigint, part bigint, from_node bigint, to_node bigint, envelope geometry)',
    '_sg_q (axis_id bigint, part bigint, from_node bigint, to_node bigint)',
    '_sg_context_nodes (id bigint)',
    '_sg_scope_sections (axis_id bigint, part bigint)',
    '_sg_scope_nodes (id bigint)',
    '_sg_scope_axes (id bigint)',
    '_sg_scope_out (geom geometry)',
    '_sg_faces (face geometry)',
    '_sg_blocks (id bigint, face geometry, geom geometry, axis_ids bigint[], kind text, cut boolean)'] LOOP
    name := split_part(definition, ' ', 1);
    IF (wanted IS NOT NULL AND NOT name = ANY (wanted)) OR to_regclass('pg_temp.' || name) IS NOT NULL THEN
      CONTINUE;
    END IF;
    EXECUTE 'CREATE TEMP TABLE ' || definition;
    EXECUTE format('GRANT ALL ON pg_temp.%I TO PUBLIC', name);
    -- (spatial joins against the engine's output: thousands of rows on either side after a
    -- large edit, where a nested loop of distance tests took seconds)
    IF name IN ('_sg_t_nodes', '_sg_scope_out') THEN
      EXECUTE format('CREATE INDEX %I ON pg_temp.%I USING gist (geom)', name || '_geom', name);
    END IF;
  END LOOP;
END
$$;

-- Empties the neighbourhood work tables before a local recompute. DELETE, not TRUNCATE: a
-- TRUNCATE gives a table a new file (made now, unlinked at commit) and makes every cached plan
-- that reads it plan again; with ANALYZE, that was about a third of a small edit's time.
-- Deleted rows stay on their pages (temporary tables are never vacuumed, and a transaction's
-- own deletions cannot be pruned before it ends), so past 256 kB the tables are truncated after
-- all: every few hundred edits, or once in a while in a long editing transaction.
CREATE FUNCTION streetgen._empty_work_tables()
  RETURNS void
  LANGUAGE plpgsql VOLATILE
  SET search_path FROM CURRENT
  AS $$
BEGIN
  PERFORM streetgen._work_tables();
  IF pg_relation_size('pg_temp._sg_changed_geom') + pg_relation_size('pg_temp._sg_t_nodes')
     + pg_relation_size('pg_temp._sg_k_nodes') + pg_relation_size('pg_temp._sg_s1') + pg_relation_size('pg_temp._sg_s2')
     + pg_relation_size('pg_temp._sg_q') + pg_relation_size('pg_temp._sg_context_nodes')
     + pg_relation_size('pg_temp._sg_scope_sections') + pg_relation_size('pg_temp._sg_scope_nodes')
     + pg_relation_size('pg_temp._sg_scope_axes') + pg_relation_size('pg_temp._sg_scope_out') > 256 * 1024 THEN
    TRUNCATE pg_temp._sg_changed_geom, pg_temp._sg_t_nodes, pg_temp._sg_k_nodes, pg_temp._sg_s1, pg_temp._sg_s2,
             pg_temp._sg_q, pg_temp._sg_context_nodes, pg_temp._sg_scope_sections, pg_temp._sg_scope_nodes,
             pg_temp._sg_scope_axes, pg_temp._sg_scope_out;
  ELSE
    DELETE FROM pg_temp._sg_changed_geom;
    DELETE FROM pg_temp._sg_t_nodes;
    DELETE FROM pg_temp._sg_k_nodes;
    DELETE FROM pg_temp._sg_s1;
    DELETE FROM pg_temp._sg_s2;
    DELETE FROM pg_temp._sg_q;
    DELETE FROM pg_temp._sg_context_nodes;
    DELETE FROM pg_temp._sg_scope_sections;
    DELETE FROM pg_temp._sg_scope_nodes;
    DELETE FROM pg_temp._sg_scope_axes;
    DELETE FROM pg_temp._sg_scope_out;
  END IF;
END
$$;

-- The box around the stored rows in a local recompute's scope (sections with their centre
-- lines and sidewalks, junctions and theirs), NULL when there are none. Run under _refresh's
-- search_path (the model first).
CREATE FUNCTION streetgen._scope_extent(model text)
  RETURNS geometry
  LANGUAGE plpgsql VOLATILE
  SET search_path FROM CURRENT
  AS $$
DECLARE
  result geometry;
BEGIN
  EXECUTE format($q$
    SELECT ST_Envelope(ST_Collect(g)) FROM (
      SELECT ST_Envelope(ST_Collect(s.centre_line, coalesce(s.geom, s.centre_line))) AS g FROM pg_temp._sg_scope_sections k
        JOIN %1$I.section s USING (axis_id, part)
      UNION ALL SELECT ST_Envelope(w.geom) FROM pg_temp._sg_scope_sections k JOIN %1$I.sidewalk w USING (axis_id, part)
      UNION ALL SELECT ST_Envelope(i.geom) FROM pg_temp._sg_scope_nodes k JOIN %1$I.intersection i ON i.node_id = k.id
      UNION ALL SELECT ST_Envelope(w.geom) FROM pg_temp._sg_scope_nodes k JOIN %1$I.sidewalk w ON w.node_id = k.id) AS x$q$,
    model) INTO result;
  RETURN result;
END
$$;

-- The axes around the sidewalks and junctions that the last local refresh of MODEL wrote (its
-- scope, in the session's work tables) where a sidewalk overlaps a roadway or another sidewalk of
-- its layer, or a junction a section or another junction of its layer, by more than 1e-2 m²: the
-- axes of both. NULL when none does. Pairs are sought by box and measured exactly (60 ms for 100
-- sidewalks); 1e-2 m² is far above the traces of the micrometre grid along shared edges (under
-- 1e-3 m²).
CREATE FUNCTION streetgen._axes_of_overlapping_outputs(model text)
  RETURNS bigint[]
  LANGUAGE plpgsql STABLE
  SET search_path FROM CURRENT
  AS $$
DECLARE
  axes bigint[];
BEGIN
  EXECUTE format($q$
    WITH written AS (
      SELECT w.axis_id, w.part, w.node_id, w.side, w.geom, a.layer
        FROM pg_temp._sg_scope_sections k JOIN %1$I.sidewalk w USING (axis_id, part) JOIN %1$I.axis a ON a.id = w.axis_id
      UNION ALL
      SELECT w.axis_id, w.part, w.node_id, w.side, w.geom, n.layer
        FROM pg_temp._sg_scope_nodes k JOIN %1$I.sidewalk w ON w.node_id = k.id JOIN %1$I.node n ON n.id = k.id),
    written_junction AS (
      SELECT i.node_id, i.geom, n.layer
        FROM pg_temp._sg_scope_nodes k JOIN %1$I.intersection i ON i.node_id = k.id JOIN %1$I.node n ON n.id = k.id),
    overlapping AS (
      SELECT w.axis_id AS owner_axis, w.node_id AS owner_node, x.axis_id, x.node_id
        FROM written w,
             LATERAL (SELECT s.axis_id, NULL::bigint AS node_id, s.geom FROM %1$I.section s JOIN %1$I.axis a ON a.id = s.axis_id
                       WHERE s.geom && w.geom AND a.layer = w.layer AND NOT (s.axis_id = w.axis_id AND s.part = w.part)
                      UNION ALL
                      SELECT NULL, i.node_id, i.geom FROM %1$I.intersection i JOIN %1$I.node n ON n.id = i.node_id
                       WHERE i.geom && w.geom AND n.layer = w.layer AND i.node_id IS DISTINCT FROM w.node_id
                      UNION ALL
                      SELECT o.axis_id, o.node_id, o.geom FROM %1$I.sidewalk o
                        LEFT JOIN %1$I.axis a ON a.id = o.axis_id LEFT JOIN %1$I.node n ON n.id = o.node_id
                       WHERE o.geom && w.geom AND coalesce(a.layer, n.layer) = w.layer
                         AND NOT (o.axis_id IS NOT DISTINCT FROM w.axis_id AND o.part IS NOT DISTINCT FROM w.part
                                  AND o.node_id IS NOT DISTINCT FROM w.node_id AND o.side = w.side)) AS x
       WHERE ST_Intersects(w.geom, x.geom) AND ST_Area(ST_Intersection(w.geom, x.geom)) > 1e-2
      -- (junctions give way to every section and split their overlaps with each other)
      UNION ALL
      SELECT NULL, j.node_id, x.axis_id, x.node_id
        FROM written_junction j,
             LATERAL (SELECT s.axis_id, NULL::bigint AS node_id, s.geom FROM %1$I.section s JOIN %1$I.axis a ON a.id = s.axis_id
                       WHERE s.geom && j.geom AND a.layer = j.layer
                      UNION ALL
                      SELECT NULL, i.node_id, i.geom FROM %1$I.intersection i JOIN %1$I.node n ON n.id = i.node_id
                       WHERE i.geom && j.geom AND n.layer = j.layer AND i.node_id <> j.node_id) AS x
       WHERE ST_Area(ST_Intersection(j.geom, x.geom, 1e-6)) > 1e-2)
    SELECT array_agg(DISTINCT a ORDER BY a) FROM (
      SELECT owner_axis AS a FROM overlapping WHERE owner_axis IS NOT NULL
      UNION ALL SELECT axis_id FROM overlapping WHERE axis_id IS NOT NULL
      UNION ALL SELECT unnest(n.axis_ids) FROM overlapping o JOIN %1$I.node n ON n.id IN (o.owner_node, o.node_id)) AS r$q$,
    model) INTO axes;
  RETURN axes;
END
$$;

-- The incremental recompute after the axes CHANGED were inserted, updated or deleted (OLD_GEOMS:
-- the geometries the updated and deleted ones had).
--
-- What a change reaches, in the graph of the last result (node, section):
--   T: the nodes on the changed axes or near them, and the ends of the sections they touch or
--      touched;
--   K: T and the nodes one section away (their corners see how long that section is, and
--      whether T is a dead end);
--   S1: the sections ending at K, those of the changed axes, and those near the changed
--      geometries (a section they overlap now or overlapped before);
--   S2: S1 and the sections overlapping S1 (the midline split of overlaps may move).
-- K, the ends of S2 and S2 itself are recomputed and rewritten (the scope), with their new
-- counterparts. What the engine needs to compute them exactly as a full run would: the axes
-- through the ends of S2 and of the sections overlapping S2 (Q), and through the nodes one
-- section away from them: a corner looks one node ahead along each of its axes, for the length
-- of that part and whether the node ahead is a dead end. (Two sections away was the first
-- guess; one holds the invariant over 700 random edits of two cities and costs half as much.)
-- Parts are keyed by where they start along their axis, so nothing farther away changes key.
--
-- The statements name the model's tables without a schema, under a search_path that puts the
-- model first (after pg_catalog), so that they are static SQL: PL/pgSQL plans each once per
-- session (and again for another model) instead of on every edit. (The model's schema before
-- PostGIS's lets whoever can create objects in it, its owner, shadow a function for the
-- editors' sessions; the owner of the axis table can run code in them anyway, with a trigger.
-- After PostGIS's, a table of the same name there, a "node" in public, would be read instead.) Generic plans: the work
-- tables hold a few dozen rows and the lookups go by index whatever the arrays hold.
CREATE FUNCTION streetgen._refresh(model text, changed bigint[], old_geoms geometry[], may_repair boolean DEFAULT true)
  RETURNS void
  LANGUAGE plpgsql VOLATILE
  SET search_path FROM CURRENT
  SET jit = off
  SET plan_cache_mode = force_generic_plan
  -- (in the SET clause so that the set_config below ends with the function, not the transaction)
  SET enable_seqscan = on SET enable_hashjoin = on SET enable_mergejoin = on
  AS $$
DECLARE
  tol double precision;
  max_width double precision;
  touched bigint[];
  context bigint[];
  reach double precision;  -- how far sidewalks reach beyond a roadway, twice (two sidewalks between roadways)
  changed_region geometry; -- the box around what the recompute rewrites, old and new: where blocks may change
  axis_count bigint;
  round integer;
  grown bigint;
  widened bigint := 0;
  converged boolean := false;
  repair bigint[];        -- axes around written sidewalks that overlap a roadway or sidewalk
BEGIN
  PERFORM streetgen._lock_outputs(model);
  IF coalesce(cardinality(changed), 0) = 0 THEN
    RETURN;
  END IF;
  PERFORM set_config('search_path',
                     format('pg_catalog, %I, %s', model, regexp_replace(current_setting('search_path'), '^\s*pg_catalog\s*,\s*', '')),
                     true);
  -- (max by the width index; the axis count from the statistics, counted only if there are none)
  SELECT s.snap_tolerance, coalesce((SELECT a.roadway_width FROM axis a ORDER BY a.roadway_width DESC LIMIT 1), 0),
         (SELECT c.reltuples::bigint FROM pg_class c WHERE c.oid = 'axis'::regclass)
    INTO tol, max_width, axis_count
    FROM settings s;
  IF axis_count < 0 THEN
    SELECT count(*) INTO axis_count FROM axis;
  END IF;
  -- A change that touches a large part of the model: one full run is cheaper than the search.
  IF cardinality(changed) > least(500, axis_count / 5) THEN
    PERFORM streetgen._compute_model(model);
    PERFORM streetgen._store(model, false);
    PERFORM pg_notify('qgis', model);
    RETURN;
  END IF;
  -- (the widest sidewalk by the width index, and the changed axes' new ones)
  SELECT 2 * greatest(coalesce((SELECT w.width FROM sidewalk w ORDER BY w.width DESC LIMIT 1), 0),
                      coalesce((SELECT max(greatest(x.widths[1], x.widths[2]))
                                  FROM axis a, settings st,
                                       LATERAL (SELECT streetgen.sidewalk_widths(a.road_class, a.sidewalk_width, a.tags,
                                                                                 st.default_sidewalk_width) AS widths) AS x
                                 WHERE a.id = ANY (changed)), 0))
    INTO reach;

  -- From here on every lookup in the model's tables goes by index: the plans are generic, made
  -- once, and without statistics on the work tables the planner would guess them at thousands
  -- of rows and hash whole tables (a hundred ms per edit). The engine run, the store and the
  -- statements after the engine run, which join its unindexed output, turn them on again (a
  -- cached plan keeps the settings it was made with, and each statement always runs with the
  -- same ones).
  PERFORM set_config('enable_seqscan', 'off', true), set_config('enable_hashjoin', 'off', true),
          set_config('enable_mergejoin', 'off', true);
  PERFORM streetgen._empty_work_tables();
  INSERT INTO pg_temp._sg_changed_geom
  SELECT g AS geom FROM unnest(old_geoms) AS g WHERE g IS NOT NULL
  UNION ALL SELECT a.geom FROM axis a WHERE a.id = ANY (changed);

  -- Axes the change touches: for the scope of the issue table.
  SELECT array_agg(DISTINCT id) INTO touched FROM (
    SELECT unnest(changed) AS id
    UNION ALL SELECT a.id FROM pg_temp._sg_changed_geom g,
               LATERAL (SELECT a.id FROM axis a WHERE a.geom && ST_Expand(g.geom, tol + 1e-6)
                                                  AND ST_DWithin(a.geom, g.geom, tol + 1e-6)) AS a) AS k;

  INSERT INTO pg_temp._sg_t_nodes
  SELECT n.id, n.geom FROM node n WHERE n.axis_ids && changed
  -- A node's points are within the tolerance of each other in a chain, so a node near a
  -- changed geometry may take in (or lose) one of its points without sharing an axis yet.
  UNION SELECT n.id, n.geom FROM pg_temp._sg_changed_geom g,
         LATERAL (SELECT n.id, n.geom FROM node n
                   WHERE n.geom && ST_Expand(g.geom, 3 * (tol + 1e-6)) AND ST_DWithin(n.geom, g.geom, 3 * (tol + 1e-6))) AS n
  UNION SELECT n.id, n.geom
          FROM pg_temp._sg_changed_geom g,
               LATERAL (SELECT unnest(ARRAY[s.from_node, s.to_node]) AS id FROM section s
                         WHERE s.centre_line && ST_Expand(g.geom, tol + 1e-6) AND ST_DWithin(s.centre_line, g.geom, tol + 1e-6)) AS e,
               LATERAL (SELECT n.id, n.geom FROM node n WHERE n.id = e.id) AS n;
  INSERT INTO pg_temp._sg_k_nodes
  SELECT id FROM pg_temp._sg_t_nodes
  UNION SELECT s.to_node FROM pg_temp._sg_t_nodes t, LATERAL (SELECT s.to_node FROM section s WHERE s.from_node = t.id) AS s
  UNION SELECT s.from_node FROM pg_temp._sg_t_nodes t, LATERAL (SELECT s.from_node FROM section s WHERE s.to_node = t.id) AS s;
  -- (Envelopes grown by the sidewalks' reach: a sidewalk gives way to every roadway and earlier
  -- sidewalk it reaches, so a section's sidewalks change when anything within their reach does,
  -- and the engine must be given what lies within their reach.)
  INSERT INTO pg_temp._sg_s1
  SELECT s.axis_id, s.part, s.from_node, s.to_node, ST_Expand(ST_Envelope(s.geom), reach) FROM unnest(changed) AS c (id),
         LATERAL (SELECT s.* FROM section s WHERE s.axis_id = c.id) AS s
  UNION SELECT s.axis_id, s.part, s.from_node, s.to_node, ST_Expand(ST_Envelope(s.geom), reach) FROM pg_temp._sg_k_nodes k,
         LATERAL (SELECT s.* FROM section s WHERE s.from_node = k.id) AS s
  UNION SELECT s.axis_id, s.part, s.from_node, s.to_node, ST_Expand(ST_Envelope(s.geom), reach) FROM pg_temp._sg_k_nodes k,
         LATERAL (SELECT s.* FROM section s WHERE s.to_node = k.id) AS s
  UNION SELECT s.axis_id, s.part, s.from_node, s.to_node, ST_Expand(ST_Envelope(s.geom), reach) FROM pg_temp._sg_changed_geom g,
         LATERAL (SELECT s.* FROM section s WHERE s.geom && ST_Expand(g.geom, max_width + reach)) AS s
  UNION SELECT s.axis_id, s.part, s.from_node, s.to_node, ST_Expand(ST_Envelope(s.geom), reach) FROM pg_temp._sg_changed_geom g,
         LATERAL (SELECT i.node_id FROM intersection i WHERE i.geom && ST_Expand(g.geom, max_width + reach)) AS j,
         LATERAL (SELECT s.* FROM section s WHERE s.from_node = j.node_id
                  UNION ALL SELECT s.* FROM section s WHERE s.to_node = j.node_id) AS s;
  INSERT INTO pg_temp._sg_s2
  SELECT p.axis_id, p.part, p.from_node, p.to_node, ST_Expand(ST_Envelope(p.geom), reach) FROM pg_temp._sg_s1 k,
         LATERAL (SELECT p.* FROM section p WHERE p.geom && k.envelope) AS p
  -- A junction's sidewalk gives way to the sidewalks around junctions near it: the sections at
  -- junctions within reach come in, so that those junctions are in scope with their context
  -- (their own sections may have no surface to be found by).
  UNION SELECT p.axis_id, p.part, p.from_node, p.to_node, ST_Expand(ST_Envelope(p.geom), reach) FROM pg_temp._sg_s1 k,
         LATERAL (SELECT i.node_id FROM intersection i WHERE i.geom && k.envelope) AS j,
         LATERAL (SELECT p.* FROM section p WHERE p.from_node = j.node_id
                  UNION ALL SELECT p.* FROM section p WHERE p.to_node = j.node_id) AS p
  UNION SELECT axis_id, part, from_node, to_node, envelope FROM pg_temp._sg_s1;
  -- The engine cannot be trusted beyond its context: an axis whose nodes were not all given is
  -- cut too long there. Such a section may overlap a section in scope where the true one does
  -- not; so when the output shows an unvetted section near the scope, its old sections join Q
  -- (those near the scope, and those under it: cut too long, it may reach the scope from a
  -- stretch whose old sections stopped short of it) and the context grows (rarely needed more
  -- than once).
  FOR round IN 1..6 LOOP
    PERFORM set_config('enable_seqscan', 'off', true), set_config('enable_hashjoin', 'off', true),
            set_config('enable_mergejoin', 'off', true);
    -- The junction of a node in scope is cut from the sections at that node, and a narrowed one
    -- among them was split with a section it overlapped: so that section joins Q as well (a soak
    -- found a junction recomputed without an axis that overlapped one of its sections but did not
    -- share its node). The sections at the node are in the context already (one section beyond).
    -- (again after the scope widened: the sections it took in, with their own reach)
    IF round = 1 OR widened > 0 THEN
      INSERT INTO pg_temp._sg_q
      SELECT x.* FROM (
        WITH ends (id) AS (SELECT from_node FROM pg_temp._sg_s2 UNION SELECT to_node FROM pg_temp._sg_s2),
        narrowed_at_ends AS (
          SELECT s.geom
            FROM ends e,
                 LATERAL (SELECT s.geom FROM section s WHERE s.from_node = e.id AND s.status = 'narrowed'
                          UNION ALL SELECT s.geom FROM section s WHERE s.to_node = e.id AND s.status = 'narrowed') AS s)
        SELECT p.axis_id, p.part, p.from_node, p.to_node FROM pg_temp._sg_s2 k,
               LATERAL (SELECT p.* FROM section p WHERE p.geom && k.envelope) AS p
        -- (stored sections overlap no more: the pieces of a split touch along the split line; a
        -- distance, not ST_Intersects, which can fail on such touching rings)
        UNION SELECT p.axis_id, p.part, p.from_node, p.to_node FROM narrowed_at_ends k,
               LATERAL (SELECT p.* FROM section p
                         WHERE p.geom && ST_Expand(k.geom, 1e-3) AND ST_DWithin(p.geom, k.geom, 1e-3)) AS p
        -- The junction sidewalk of an end of S2 is rewritten, and gives way to the roadways and
        -- sidewalk claims within its reach: the sections there join Q, so that they are computed, with
        -- their context. (A soak found one written too large: a section whose sidewalk claim cut it
        -- had not been given at all, and nothing in the output could call for it.)
        UNION SELECT p.axis_id, p.part, p.from_node, p.to_node FROM ends e,
               LATERAL (SELECT i.geom FROM intersection i WHERE i.node_id = e.id) AS j,
               LATERAL (SELECT p.* FROM section p WHERE p.geom && ST_Expand(j.geom, reach)) AS p
        -- The junctions within its reach too, by their sections (a surface the engine is not given
        -- does not cut it): a replay found a junction sidewalk written over a junction 3.7 m away
        -- whose sections all began beyond its reach.
        UNION SELECT p.axis_id, p.part, p.from_node, p.to_node FROM ends e,
               LATERAL (SELECT i.geom FROM intersection i WHERE i.node_id = e.id) AS j,
               LATERAL (SELECT n.node_id FROM intersection n WHERE n.geom && ST_Expand(j.geom, reach)) AS n,
               LATERAL (SELECT p.* FROM section p WHERE p.from_node = n.node_id
                        UNION ALL SELECT p.* FROM section p WHERE p.to_node = n.node_id) AS p
        UNION SELECT axis_id, part, from_node, to_node FROM pg_temp._sg_s2
      ) AS x
       WHERE NOT EXISTS (SELECT 1 FROM pg_temp._sg_q q WHERE q.axis_id = x.axis_id AND q.part = x.part);
    END IF;
    DELETE FROM pg_temp._sg_context_nodes;
    INSERT INTO pg_temp._sg_context_nodes
    WITH base (node) AS (
      SELECT from_node FROM pg_temp._sg_q UNION SELECT to_node FROM pg_temp._sg_q UNION SELECT id FROM pg_temp._sg_k_nodes)
    SELECT node FROM base
    UNION SELECT x.node
            FROM base b,
                 LATERAL (SELECT s.to_node FROM section s WHERE s.from_node = b.node
                          UNION ALL SELECT s.from_node FROM section s WHERE s.to_node = b.node) AS x (node);
    SELECT array_agg(DISTINCT id) INTO context FROM (
      SELECT unnest(n.axis_ids) AS id FROM pg_temp._sg_context_nodes c, LATERAL (SELECT n.axis_ids FROM node n WHERE n.id = c.id) AS n
      UNION ALL SELECT axis_id FROM pg_temp._sg_q
      UNION ALL SELECT unnest(touched)) AS c;

    PERFORM streetgen._compute_model(model, context);
    -- What reads the engine's output (thousands of rows for a large edit, no index) joins by
    -- hash: with nested loops a 100-axis edit of Paris took 20 s.
    PERFORM set_config('enable_seqscan', 'on', true), set_config('enable_hashjoin', 'on', true),
            set_config('enable_mergejoin', 'on', true);

    -- The sections that may be rewritten, and the narrowed ones at their ends (a junction may be
    -- cut from those, and what narrowed them must be right): what was split with one of them
    -- touches it in the output. (Boxes alone, long diagonal sections' especially, called for
    -- many needless runs.)
    DELETE FROM pg_temp._sg_scope_out;
    INSERT INTO pg_temp._sg_scope_out
    WITH ends (id) AS (SELECT from_node FROM pg_temp._sg_s2 UNION SELECT to_node FROM pg_temp._sg_s2
                       UNION SELECT id FROM pg_temp._sg_k_nodes)
    SELECT ST_GeomFromEWKB(o.geom) FROM pg_temp._streetgen_out o
     WHERE o.kind = 'section' AND o.geom IS NOT NULL
       AND (o.axis_id = ANY (changed)
            OR EXISTS (SELECT 1 FROM pg_temp._sg_s2 k WHERE k.axis_id = o.axis_id AND k.part = o.part)
            OR (o.status = 'narrowed' AND (o.node_id IN (SELECT id FROM ends) OR o.to_node IN (SELECT id FROM ends))))
    -- The narrowed junctions at the ends: what they gave way to (sections over them, junctions
    -- overlapping them, which now touch them) must be right.
    UNION ALL
    SELECT ST_GeomFromEWKB(o.geom) FROM pg_temp._streetgen_out o
     WHERE o.kind = 'intersection' AND o.geom IS NOT NULL AND o.status = 'narrowed' AND o.node_id IN (SELECT id FROM ends)
    -- The sidewalks that may be rewritten, as their boxes grown by the sidewalks' reach: a
    -- section cut too long where the context ends would have cut them short, by its roadway or
    -- by its own sidewalk's claim (which reaches beyond its roadway).
    UNION ALL
    SELECT ST_Expand(ST_Envelope(ST_GeomFromEWKB(o.geom)), reach) FROM pg_temp._streetgen_out o
     WHERE o.kind = 'sidewalk'
       AND (o.axis_id = ANY (changed)
            OR EXISTS (SELECT 1 FROM pg_temp._sg_s2 k WHERE k.axis_id = o.axis_id AND k.part = o.part)
            OR o.node_id IN (SELECT id FROM ends));
    INSERT INTO pg_temp._sg_q (axis_id, part, from_node, to_node)
    WITH candidates AS MATERIALIZED (
      SELECT o.axis_id, ST_GeomFromEWKB(o.geom) AS geom FROM pg_temp._streetgen_out o
       WHERE o.kind = 'section' AND o.geom IS NOT NULL
         AND NOT EXISTS (SELECT 1 FROM pg_temp._sg_q q WHERE q.axis_id = o.axis_id AND q.part = o.part)
         AND NOT (o.axis_id = ANY (changed))),
    unvetted AS (
      SELECT c.axis_id, c.geom FROM candidates c
       WHERE EXISTS (SELECT 1 FROM pg_temp._sg_scope_out k
                      WHERE k.geom && ST_Expand(c.geom, 1e-3) AND ST_DWithin(c.geom, k.geom, 1e-3))),
    -- A junction surface is a roadway too: one near the scope whose node is not an end of Q (its
    -- axes were given, those one section beyond it not) may be cut wrong, its section there taken
    -- for absorbed or not, and a junction sidewalk in scope gives way to it. Its sections join Q.
    -- (A soak found a junction sidewalk left too large by a neighbour's surface: the section
    -- between them absorbed, without a surface for the search above to find it by.)
    trusted (id) AS (SELECT from_node FROM pg_temp._sg_q UNION SELECT to_node FROM pg_temp._sg_q
                     UNION SELECT id FROM pg_temp._sg_k_nodes),
    unvetted_junctions AS (
      SELECT o.node_id FROM pg_temp._streetgen_out o
       WHERE o.kind = 'intersection' AND o.geom IS NOT NULL
         AND o.node_id NOT IN (SELECT id FROM trusted)
         AND EXISTS (SELECT 1 FROM pg_temp._sg_scope_out k
                      WHERE k.geom && ST_Expand(ST_GeomFromEWKB(o.geom), 1e-3)
                        AND ST_DWithin(ST_GeomFromEWKB(o.geom), k.geom, 1e-3)))
    SELECT p.axis_id, p.part, p.from_node, p.to_node FROM section p
     WHERE p.axis_id IN (SELECT axis_id FROM unvetted)
       AND (EXISTS (SELECT 1 FROM pg_temp._sg_s2 k WHERE p.geom && ST_Expand(k.envelope, max_width))
            OR EXISTS (SELECT 1 FROM unvetted u WHERE u.axis_id = p.axis_id AND p.geom && u.geom))
       AND NOT EXISTS (SELECT 1 FROM pg_temp._sg_q q WHERE q.axis_id = p.axis_id AND q.part = p.part)
    UNION
    SELECT p.axis_id, p.part, p.from_node, p.to_node FROM unvetted_junctions j,
           LATERAL (SELECT p.* FROM section p WHERE p.from_node = j.node_id
                    UNION ALL SELECT p.* FROM section p WHERE p.to_node = j.node_id) AS p
     WHERE NOT EXISTS (SELECT 1 FROM pg_temp._sg_q q WHERE q.axis_id = p.axis_id AND q.part = p.part);
    GET DIAGNOSTICS grown = ROW_COUNT;
    -- Sidewalks follow the roadways within their reach, and a rewritten roadway can change where
    -- no edit did: a section of S2 split anew with one of S1, the junction at its end cut from
    -- it. Every section with a sidewalk within reach of a roadway that this run changes (new
    -- against stored, either way) joins the scope, and the sections at junctions within reach
    -- (their junction sidewalks); the run is repeated with their context. (A soak found sidewalks
    -- of two narrowed sections left over a junction surface that a neighbour's edit had moved.)
    -- Without sidewalks (reach 0) this runs too: a junction gives way to the roadways over it,
    -- so one that a moved roadway overlaps, or overlapped, is rewritten with it.
    INSERT INTO pg_temp._sg_s2
    WITH ends (id) AS (SELECT from_node FROM pg_temp._sg_s2 UNION SELECT to_node FROM pg_temp._sg_s2
                       UNION SELECT id FROM pg_temp._sg_k_nodes),
    out_roadway AS MATERIALIZED (
      SELECT o.axis_id, o.part, NULL::bigint AS node_id, ST_GeomFromEWKB(o.geom) AS geom FROM pg_temp._streetgen_out o
       WHERE o.kind = 'section' AND o.geom IS NOT NULL
         AND (o.axis_id = ANY (changed)
              OR EXISTS (SELECT 1 FROM pg_temp._sg_s2 k WHERE k.axis_id = o.axis_id AND k.part = o.part))
      UNION ALL
      SELECT NULL, NULL, o.node_id, ST_GeomFromEWKB(o.geom) FROM pg_temp._streetgen_out o
       WHERE o.kind = 'intersection' AND o.geom IS NOT NULL AND o.node_id IN (SELECT id FROM ends)),
    moved (geom) AS (
      SELECT r.geom FROM out_roadway r
       WHERE r.node_id IS NULL
         AND NOT EXISTS (SELECT 1 FROM section s WHERE s.axis_id = r.axis_id AND s.part = r.part AND ST_OrderingEquals(s.geom, r.geom))
      UNION ALL SELECT r.geom FROM out_roadway r
       WHERE r.node_id IS NOT NULL
         AND NOT EXISTS (SELECT 1 FROM intersection i WHERE i.node_id = r.node_id AND ST_OrderingEquals(i.geom, r.geom))
      UNION ALL SELECT s.geom FROM pg_temp._sg_s2 k, LATERAL (SELECT s.geom FROM section s
                                                            WHERE s.axis_id = k.axis_id AND s.part = k.part) AS s
       WHERE s.geom IS NOT NULL
         AND NOT EXISTS (SELECT 1 FROM out_roadway r WHERE r.axis_id = k.axis_id AND r.part = k.part AND ST_OrderingEquals(s.geom, r.geom))
      UNION ALL SELECT i.geom FROM ends e, LATERAL (SELECT i.geom FROM intersection i WHERE i.node_id = e.id) AS i
       WHERE NOT EXISTS (SELECT 1 FROM out_roadway r WHERE r.node_id = e.id AND ST_OrderingEquals(i.geom, r.geom))),
    reached AS (
      SELECT p.axis_id, p.part, p.from_node, p.to_node, p.geom FROM moved m,
             LATERAL (SELECT p.* FROM section p WHERE p.geom && ST_Expand(m.geom, reach) AND ST_DWithin(p.geom, m.geom, reach)) AS p
      UNION
      SELECT p.axis_id, p.part, p.from_node, p.to_node, p.geom FROM moved m,
             LATERAL (SELECT i.node_id FROM intersection i
                       WHERE i.geom && ST_Expand(m.geom, reach) AND ST_DWithin(i.geom, m.geom, reach)) AS j,
             LATERAL (SELECT p.* FROM section p WHERE p.from_node = j.node_id
                      UNION ALL SELECT p.* FROM section p WHERE p.to_node = j.node_id) AS p)
    SELECT r.axis_id, r.part, r.from_node, r.to_node, ST_Expand(ST_Envelope(r.geom), reach) FROM reached r
     WHERE NOT EXISTS (SELECT 1 FROM pg_temp._sg_s2 k WHERE k.axis_id = r.axis_id AND k.part = r.part);
    GET DIAGNOSTICS widened = ROW_COUNT;
    converged := grown = 0 AND widened = 0;
    EXIT WHEN converged;
  END LOOP;
  -- (a scope still growing after six runs: one full run instead, which is always right)
  IF NOT converged THEN
    PERFORM streetgen._compute_model(model);
    PERFORM streetgen._store(model, false);
    PERFORM pg_notify('qgis', model);
    RETURN;
  END IF;

  -- The scope: what was there (old) and what is there now (new) within reach of the change.
  -- New sections come from the changed axes, or lie between nodes of K and new nodes on the
  -- changed axes (an axis split or joined where a changed axis touches it). The engine's output
  -- beyond the scope is not trusted: a section leaving the context may run past a node whose
  -- axes were not given.
  INSERT INTO pg_temp._sg_scope_sections
    WITH new_nodes AS (
      SELECT id FROM pg_temp._sg_k_nodes
      UNION SELECT n.node_id FROM pg_temp._streetgen_out n WHERE n.kind = 'node' AND n.axis_ids && changed
      -- A node of T that lost or gained a point is a new node (a new id) nearby.
      UNION SELECT n.node_id FROM (SELECT o.node_id, ST_GeomFromEWKB(o.geom) AS geom FROM pg_temp._streetgen_out o
                                    WHERE o.kind = 'node') AS n
             WHERE EXISTS (SELECT 1 FROM pg_temp._sg_t_nodes t WHERE t.geom && ST_Expand(n.geom, 3 * (tol + 1e-6))
                                                                 AND ST_DWithin(n.geom, t.geom, 3 * (tol + 1e-6))))
    SELECT axis_id, part FROM pg_temp._sg_s2
    UNION SELECT o.axis_id, o.part FROM pg_temp._streetgen_out o
           WHERE o.kind = 'section'
             AND (o.axis_id = ANY (changed)
                  OR (o.node_id IN (SELECT id FROM new_nodes) AND o.to_node IN (SELECT id FROM new_nodes)));
  INSERT INTO pg_temp._sg_scope_nodes
  SELECT id FROM pg_temp._sg_k_nodes
  UNION SELECT o.node_id FROM pg_temp._streetgen_out o WHERE o.kind = 'node' AND o.axis_ids && changed
  -- (lateral: a lookup by key per section in scope, whatever the planner guesses of their number)
  UNION SELECT e.id FROM pg_temp._sg_scope_sections k,
         LATERAL (SELECT unnest(ARRAY[s.from_node, s.to_node]) AS id FROM section s
                   WHERE s.axis_id = k.axis_id AND s.part = k.part) AS e
  UNION SELECT o.node_id FROM pg_temp._streetgen_out o JOIN pg_temp._sg_scope_sections k USING (axis_id, part)
         WHERE o.kind = 'section'
  UNION SELECT o.to_node FROM pg_temp._streetgen_out o JOIN pg_temp._sg_scope_sections k USING (axis_id, part)
         WHERE o.kind = 'section';
  INSERT INTO pg_temp._sg_scope_axes
    SELECT unnest(touched) AS id UNION SELECT axis_id FROM pg_temp._sg_scope_sections;
  ANALYZE pg_temp._sg_scope_nodes;
  ANALYZE pg_temp._sg_scope_sections;
  ANALYZE pg_temp._sg_scope_axes;

  -- Blocks: the faces around what the store rewrites change (old extent here, new after it),
  -- and those around the changed axes (a deleted axis' sections are gone already).
  changed_region := streetgen._scope_extent(model);
  PERFORM streetgen._store(model, true);
  SELECT ST_Envelope(ST_Collect(g)) INTO changed_region
    FROM (SELECT changed_region AS g
          UNION ALL SELECT streetgen._scope_extent(model)
          UNION ALL SELECT ST_Expand(ST_Envelope(c.geom), max_width + reach) FROM pg_temp._sg_changed_geom c) AS x
   WHERE g IS NOT NULL;
  PERFORM streetgen._store_blocks(model, changed_region);
  PERFORM pg_notify('qgis', model);

  -- A check of what was written: a sidewalk never overlaps a roadway or another sidewalk of its
  -- layer, nor a junction a section or another junction (the engine cuts them so), and when one
  -- does here, the engine was not given something within its reach: the search above has missed
  -- a case (soaks found such cases one in about a thousand edits, each fixed since). The axes of
  -- both then count as changed, once (a local refresh around them, with their whole
  -- neighbourhood); a second miss runs the full model. (A soak's first runs of this check also
  -- caught the engine itself writing a sidewalk over a roadway, a GEOS overlay fault fixed since:
  -- every edit nearby then ran the full model.)
  repair := streetgen._axes_of_overlapping_outputs(model);
  IF repair IS NOT NULL THEN
    RAISE LOG 'streetgen: refresh of % wrote overlapping outputs near axes %; %', model, repair,
              CASE WHEN may_repair THEN 'refreshing around them' ELSE 'running the full model' END;
    IF may_repair THEN
      PERFORM streetgen._refresh(model, repair, '{}', false);
    ELSE
      PERFORM streetgen._compute_model(model);
      PERFORM streetgen._store(model, false);
    END IF;
  END IF;
END
$$;

-- How far a stored geometry lies from its full recompute, for outdated's 'differs' (a few
-- micrometres is float noise in a context-dependent overlay; metres, a recompute that missed
-- something): ' by <Hausdorff distance> m', empty when either is NULL.
CREATE FUNCTION streetgen._apart(stored geometry, recomputed geometry)
  RETURNS text
  LANGUAGE sql IMMUTABLE PARALLEL SAFE
  SET search_path FROM CURRENT
  AS $$
  SELECT coalesce(' by ' || round(ST_HausdorffDistance(stored, recomputed)::numeric, 6) || ' m', '')
$$;

-- Rows of MODEL's tables that differ from a full recompute of its axes: none when the tables are
-- current (the invariant the triggers keep). Geometries count as equal within 1e-6 m
-- (Hausdorff), numbers within 1e-6. For tests, and for anyone who wants to check.
CREATE FUNCTION streetgen.outdated(model text, OUT kind text, OUT key text, OUT what text)
  RETURNS SETOF record
  LANGUAGE plpgsql VOLATILE
  SET search_path FROM CURRENT
  SET jit = off
  AS $$
BEGIN
  PERFORM streetgen.model_srid(model);
  PERFORM streetgen._compute_model(model);
  -- (blocks from the stored surfaces: equal to a full recompute's when the rest is current)
  PERFORM streetgen._compute_blocks(model, NULL);
  RETURN QUERY EXECUTE format($q$
    WITH o AS (SELECT * FROM pg_temp._streetgen_out),
    near AS (SELECT 1e-6::float8 AS eps)
    SELECT 'node', coalesce(t.id, o.node_id)::text,
           CASE WHEN t.id IS NULL THEN 'missing' WHEN o.node_id IS NULL THEN 'extra' ELSE 'differs' END
      FROM %1$I.node t FULL JOIN (SELECT * FROM o WHERE o.kind = 'node') o ON o.node_id = t.id
     WHERE t.id IS NULL OR o.node_id IS NULL OR t.degree <> o.degree OR t.layer <> o.layer OR t.axis_ids <> o.axis_ids
        OR ST_Distance(t.geom, ST_GeomFromEWKB(o.geom)) > 1e-6
    UNION ALL
    SELECT 'section', coalesce(t.axis_id, o.axis_id) || '/' || coalesce(t.part, o.part),
           CASE WHEN t.axis_id IS NULL THEN 'missing' WHEN o.axis_id IS NULL THEN 'extra'
                ELSE 'differs' || streetgen._apart(t.geom, ST_GeomFromEWKB(o.geom)) END
      FROM %1$I.section t FULL JOIN (SELECT * FROM o WHERE o.kind = 'section') o ON o.axis_id = t.axis_id AND o.part = t.part
     WHERE t.axis_id IS NULL OR o.axis_id IS NULL OR t.from_node <> o.node_id OR t.to_node <> o.to_node
        OR t.status <> o.status OR abs(t.start_border - o.start_border) > 1e-6 OR abs(t.end_border - o.end_border) > 1e-6
        OR ST_HausdorffDistance(t.centre_line, ST_GeomFromEWKB(o.geom2)) > 1e-6
        OR (t.geom IS NULL) <> (o.geom IS NULL)
        OR (t.geom IS NOT NULL AND ST_HausdorffDistance(t.geom, ST_GeomFromEWKB(o.geom)) > 1e-6)
    UNION ALL
    SELECT 'corner', concat_ws('/', coalesce(t.node_id, o.node_id), coalesce(t.axis_a, o.axis_id), coalesce(t.part_a, o.part),
                               coalesce(t.end_a, o.end_a), coalesce(t.axis_b, o.axis_b), coalesce(t.part_b, o.part_b), coalesce(t.end_b, o.end_b)),
           CASE WHEN t.node_id IS NULL THEN 'missing' WHEN o.node_id IS NULL THEN 'extra' ELSE 'differs' END
      FROM %1$I.corner t FULL JOIN (SELECT * FROM o WHERE o.kind = 'corner') o
        ON o.node_id = t.node_id AND o.axis_id = t.axis_a AND o.part = t.part_a AND o.end_a = t.end_a
       AND o.axis_b = t.axis_b AND o.part_b = t.part_b AND o.end_b = t.end_b
     WHERE t.node_id IS NULL OR o.node_id IS NULL OR t.status <> o.status
        OR abs(coalesce(t.radius, 0) - coalesce(o.radius, 0)) > 1e-6
        OR (t.arc_segmentized IS NULL) <> (o.geom2 IS NULL)
        OR (t.arc_segmentized IS NOT NULL AND ST_HausdorffDistance(t.arc_segmentized, ST_GeomFromEWKB(o.geom2)) > 1e-6)
    UNION ALL
    SELECT 'intersection', coalesce(t.node_id, o.node_id)::text,
           CASE WHEN t.node_id IS NULL THEN 'missing' WHEN o.node_id IS NULL THEN 'extra'
                ELSE 'differs' || streetgen._apart(t.geom, ST_GeomFromEWKB(o.geom)) END
      FROM %1$I.intersection t FULL JOIN (SELECT * FROM o WHERE o.kind = 'intersection') o ON o.node_id = t.node_id
     WHERE t.node_id IS NULL OR o.node_id IS NULL OR t.status <> o.status
        OR ST_HausdorffDistance(t.geom, ST_GeomFromEWKB(o.geom)) > 1e-6
    UNION ALL
    SELECT 'lane', concat_ws('/', coalesce(t.axis_id, o.axis_id), coalesce(t.part, o.part), coalesce(t.lane_index, o.item)),
           CASE WHEN t.axis_id IS NULL THEN 'missing' WHEN o.axis_id IS NULL THEN 'extra' ELSE 'differs' END
      FROM %1$I.lane t FULL JOIN (SELECT * FROM o WHERE o.kind = 'lane') o
        ON o.axis_id = t.axis_id AND o.part = t.part AND o.item = t.lane_index
     WHERE t.axis_id IS NULL OR o.axis_id IS NULL OR t.type <> o.status OR t.direction <> o.direction
        OR abs(t.width - o.width) > 1e-6 OR t.turn IS DISTINCT FROM o.detail
        OR ST_HausdorffDistance(t.geom, ST_GeomFromEWKB(o.geom)) > 1e-6
    UNION ALL
    SELECT 'marking', concat_ws('/', coalesce(t.axis_id, o.axis_id), coalesce(t.part, o.part), coalesce(t.kind, o.status),
                                coalesce(t.position, o.item)),
           CASE WHEN t.axis_id IS NULL THEN 'missing' WHEN o.axis_id IS NULL THEN 'extra' ELSE 'differs' END
      FROM %1$I.marking t FULL JOIN (SELECT * FROM o WHERE o.kind = 'marking') o
        ON o.axis_id = t.axis_id AND o.part = t.part AND o.status = t.kind AND o.item = t.position
     WHERE t.axis_id IS NULL OR o.axis_id IS NULL OR t.style <> o.detail
        OR ST_HausdorffDistance(t.geom, ST_GeomFromEWKB(o.geom)) > 1e-6
    UNION ALL
    SELECT 'sidewalk', concat_ws('/', coalesce(t.axis_id, o.axis_id), coalesce(t.part, o.part), coalesce(t.node_id, o.node_id),
                                 coalesce(t.side, o.status)),
           CASE WHEN t.side IS NULL THEN 'missing' WHEN o.status IS NULL THEN 'extra'
                ELSE 'differs' || streetgen._apart(t.geom, ST_GeomFromEWKB(o.geom)) END
      FROM %1$I.sidewalk t FULL JOIN (SELECT * FROM o WHERE o.kind = 'sidewalk') o
        ON o.axis_id IS NOT DISTINCT FROM t.axis_id AND o.part IS NOT DISTINCT FROM t.part
       AND o.node_id IS NOT DISTINCT FROM t.node_id AND o.status = t.side
     WHERE t.side IS NULL OR o.status IS NULL OR abs(t.width - o.width) > 1e-6
        OR ST_HausdorffDistance(t.geom, ST_GeomFromEWKB(o.geom)) > 1e-6
    UNION ALL
    SELECT 'crossing', concat_ws('/', coalesce(t.axis_id, o.axis_id), coalesce(t.part, o.part), coalesce(t.position, o.item)),
           CASE WHEN t.axis_id IS NULL THEN 'missing' WHEN o.axis_id IS NULL THEN 'extra' ELSE 'differs' END
      FROM %1$I.crossing t FULL JOIN (SELECT * FROM o WHERE o.kind = 'crossing') o
        ON o.axis_id = t.axis_id AND o.part = t.part AND o.item = t.position
     WHERE t.axis_id IS NULL OR o.axis_id IS NULL OR t.node_id <> o.node_id OR abs(t.width - o.width) > 1e-6
        OR ST_HausdorffDistance(t.geom, ST_GeomFromEWKB(o.geom)) > 1e-6
    UNION ALL
    SELECT 'block', coalesce(t.id, b.id)::text,
           CASE WHEN t.id IS NULL THEN 'missing' WHEN b.id IS NULL THEN 'extra'
                ELSE 'differs' || streetgen._apart(t.geom, b.geom) END
      FROM %1$I.block t FULL JOIN pg_temp._sg_blocks b ON b.id = t.id
     WHERE t.id IS NULL OR b.id IS NULL OR t.axis_ids <> b.axis_ids OR t.kind <> b.kind
        OR ST_HausdorffDistance(t.face, b.face) > 1e-6
        OR (t.geom IS NULL) <> (b.geom IS NULL)
        OR (t.geom IS NOT NULL AND ST_HausdorffDistance(t.geom, b.geom) > 1e-6)
    UNION ALL
    (SELECT 'issue', concat_ws('/', axis_id, part, kind, detail), 'differs' FROM (
       (SELECT axis_id, part, kind, detail, node_id FROM %1$I.issue
        EXCEPT ALL SELECT axis_id, part, status, detail, node_id FROM o WHERE kind = 'issue')
       UNION ALL
       (SELECT axis_id, part, status, detail, node_id FROM o WHERE kind = 'issue'
        EXCEPT ALL SELECT axis_id, part, kind, detail, node_id FROM %1$I.issue)) d)
  $q$, model);
END
$$;
COMMENT ON FUNCTION streetgen.outdated(text) IS
  'Rows of a model''s generated tables that differ from a full recompute (none when current): kind, key, missing/extra/differs (sections, junctions, sidewalks and blocks: differs by the Hausdorff distance between the stored and recomputed geometry, m)';

-- Before any row of a statement is touched: the model's lock first. Taken only in the AFTER
-- trigger, a DELETE had already locked the rows its cascade removes (sections, corners) when it
-- queued behind another session's recompute, which then needed those rows: a deadlock (40P01).
CREATE FUNCTION streetgen._lock_outputs_first()
  RETURNS trigger
  LANGUAGE plpgsql
  SET search_path FROM CURRENT
  AS $$
BEGIN
  -- (the same row lock as the recompute's UPDATE, without counting a recompute: an edit of tags
  -- alone recomputes nothing)
  EXECUTE format('SELECT 1 FROM %I.refresh_state FOR NO KEY UPDATE', TG_TABLE_SCHEMA);
  RETURN NULL;
END
$$;

-- Trigger functions: one per event, since each sees different transition tables.
CREATE FUNCTION streetgen._axis_inserted()
  RETURNS trigger
  LANGUAGE plpgsql
  SET search_path FROM CURRENT
  AS $$
BEGIN
  PERFORM streetgen._refresh(TG_TABLE_SCHEMA, (SELECT array_agg(id) FROM new_rows), '{}');
  RETURN NULL;
END
$$;

-- Only what shapes the surfaces, lanes and sidewalks counts; an edit of source, or of tags other
-- than the lane and sidewalk tags (streetgen._lane_tags, streetgen._sidewalk_tags), recomputes
-- nothing.
CREATE FUNCTION streetgen._axis_updated()
  RETURNS trigger
  LANGUAGE plpgsql
  SET search_path FROM CURRENT
  AS $$
DECLARE
  ids bigint[];
  geoms geometry[];
BEGIN
  SELECT array_agg(coalesce(n.id, o.id)), array_agg(o.geom) INTO ids, geoms
    FROM old_rows o FULL JOIN new_rows n ON n.id = o.id
   WHERE (o.geom, o.roadway_width, o.speed_kmh, o.layer, o.radius_override, o.lanes, o.oneway,
          streetgen._lane_tags(o.tags), o.road_class, o.sidewalk_width, streetgen._sidewalk_tags(o.tags))
         IS DISTINCT FROM (n.geom, n.roadway_width, n.speed_kmh, n.layer, n.radius_override, n.lanes, n.oneway,
          streetgen._lane_tags(n.tags), n.road_class, n.sidewalk_width, streetgen._sidewalk_tags(n.tags));
  IF ids IS NOT NULL THEN
    PERFORM streetgen._refresh(TG_TABLE_SCHEMA, ids, geoms);
  END IF;
  RETURN NULL;
END
$$;

CREATE FUNCTION streetgen._axis_deleted()
  RETURNS trigger
  LANGUAGE plpgsql
  SET search_path FROM CURRENT
  AS $$
BEGIN
  PERFORM streetgen._refresh(TG_TABLE_SCHEMA, (SELECT array_agg(id) FROM old_rows), (SELECT array_agg(geom) FROM old_rows));
  RETURN NULL;
END
$$;

-- A corner's radius_override takes effect at once: its two axes count as changed.
CREATE FUNCTION streetgen._corner_override_changed()
  RETURNS trigger
  LANGUAGE plpgsql
  SET search_path FROM CURRENT
  AS $$
DECLARE
  ids bigint[];
BEGIN
  SELECT array_agg(DISTINCT a) INTO ids
    FROM (SELECT n.axis_a AS a FROM new_rows n JOIN old_rows o USING (node_id, axis_a, part_a, end_a, axis_b, part_b, end_b)
           WHERE n.radius_override IS DISTINCT FROM o.radius_override
          UNION ALL
          SELECT n.axis_b FROM new_rows n JOIN old_rows o USING (node_id, axis_a, part_a, end_a, axis_b, part_b, end_b)
           WHERE n.radius_override IS DISTINCT FROM o.radius_override) AS c;
  IF ids IS NOT NULL THEN
    PERFORM streetgen._refresh(TG_TABLE_SCHEMA, ids, '{}');
  END IF;
  RETURN NULL;
END
$$;

-- New settings change everything, and a TRUNCATE of the axes (with CASCADE, which empties the
-- tables that refer to them without their triggers) leaves nodes and junctions behind: a full
-- recompute.
CREATE FUNCTION streetgen._settings_changed()
  RETURNS trigger
  LANGUAGE plpgsql
  SET search_path FROM CURRENT
  AS $$
DECLARE
  anything boolean;
BEGIN
  PERFORM streetgen._lock_outputs(TG_TABLE_SCHEMA);
  -- A model with no axes and no outputs left has nothing to recompute: the engine's run and the
  -- stores on an empty model were 12-20 ms of every import, which sets its settings before it
  -- loads. Looked at after the lock, so an insert that committed first is seen. (Every output
  -- but block and issue hangs off a node by foreign key: node, block and issue cover them all;
  -- after a TRUNCATE of the axes, nodes and blocks are left and are cleared below.)
  EXECUTE format('SELECT EXISTS (SELECT FROM %1$I.axis) OR EXISTS (SELECT FROM %1$I.node)
                      OR EXISTS (SELECT FROM %1$I.block) OR EXISTS (SELECT FROM %1$I.issue)',
                 TG_TABLE_SCHEMA) INTO anything;
  IF anything THEN
    PERFORM streetgen._compute_model(TG_TABLE_SCHEMA);
    PERFORM streetgen._store(TG_TABLE_SCHEMA, false);
  END IF;
  PERFORM pg_notify('qgis', TG_TABLE_SCHEMA);
  RETURN NULL;
END
$$;

CREATE FUNCTION streetgen._create_triggers(name text)
  RETURNS void
  LANGUAGE plpgsql VOLATILE
  SET search_path FROM CURRENT
  AS $$
BEGIN
  EXECUTE format($ddl$
    CREATE TRIGGER axis_lock_outputs BEFORE INSERT OR UPDATE OR DELETE OR TRUNCATE ON %1$I.axis
      FOR EACH STATEMENT EXECUTE FUNCTION streetgen._lock_outputs_first();
    CREATE TRIGGER axis_refresh_truncate AFTER TRUNCATE ON %1$I.axis
      FOR EACH STATEMENT EXECUTE FUNCTION streetgen._settings_changed();
    CREATE TRIGGER corner_lock_outputs BEFORE UPDATE ON %1$I.corner
      FOR EACH STATEMENT EXECUTE FUNCTION streetgen._lock_outputs_first();
    CREATE TRIGGER settings_lock_outputs BEFORE UPDATE ON %1$I.settings
      FOR EACH STATEMENT EXECUTE FUNCTION streetgen._lock_outputs_first();
    CREATE TRIGGER axis_refresh_insert AFTER INSERT ON %1$I.axis
      REFERENCING NEW TABLE AS new_rows FOR EACH STATEMENT EXECUTE FUNCTION streetgen._axis_inserted();
    CREATE TRIGGER axis_refresh_update AFTER UPDATE ON %1$I.axis
      REFERENCING OLD TABLE AS old_rows NEW TABLE AS new_rows FOR EACH STATEMENT EXECUTE FUNCTION streetgen._axis_updated();
    CREATE TRIGGER axis_refresh_delete AFTER DELETE ON %1$I.axis
      REFERENCING OLD TABLE AS old_rows FOR EACH STATEMENT EXECUTE FUNCTION streetgen._axis_deleted();
    CREATE TRIGGER corner_override AFTER UPDATE ON %1$I.corner
      REFERENCING OLD TABLE AS old_rows NEW TABLE AS new_rows FOR EACH STATEMENT EXECUTE FUNCTION streetgen._corner_override_changed();
    CREATE TRIGGER settings_refresh AFTER UPDATE ON %1$I.settings
      FOR EACH STATEMENT EXECUTE FUNCTION streetgen._settings_changed();
  $ddl$, name);
END
$$;
