-- Street surfaces (StreetGen): one C call computes the whole network; SQL stores the result.

CREATE FUNCTION streetgen._streetgen_street_surfaces(
    ids bigint[], geoms bytea[], widths double precision[], speeds double precision[], layers integer[],
    radius_overrides double precision[], settings double precision[],
    override_nodes bigint[], override_keys bigint[], override_radii double precision[],
    lanes integer[], oneways boolean[], lane_tags text[], sidewalk_left double precision[],
    sidewalk_right double precision[],
    OUT kind text, OUT node_id bigint, OUT to_node bigint, OUT axis_id bigint, OUT part bigint, OUT end_a boolean,
    OUT axis_b bigint, OUT part_b bigint, OUT end_b boolean, OUT status text, OUT detail text, OUT degree integer,
    OUT layer integer, OUT radius double precision, OUT radius_wanted double precision,
    OUT start_border double precision, OUT end_border double precision, OUT axis_ids bigint[],
    OUT geom bytea, OUT geom2 bytea, OUT geom3 bytea, OUT item integer, OUT width double precision,
    OUT direction text)
  RETURNS SETOF record
  LANGUAGE c IMMUTABLE PARALLEL SAFE
  COST 100000 ROWS 10000
  AS 'MODULE_PATHNAME', '_streetgen_street_surfaces';

-- The OSM tags that shape a street's lanes (and, by its street parking and placement, where its
-- roadway lies), as "key=value" lines for the engine (sorted: equal tags give equal text, so the
-- update trigger can compare them). The engine reads sides and directions along the stored axis:
-- oneway=-1 ways are stored reversed by the importer, so their keys' left and right, forward and
-- backward swap here (parking:left of the way is parking:right of the axis). placement, which
-- counts lanes from the way's left, is passed as it is. NULL without such tags.
-- Most ways have none (Reisterstown: 457 of 4,560), and the listing costs a query a way (28 us):
-- a look at the tags' text first, which finds every such key (as '"lanes"', '"parking:...'),
-- in a function of one expression without a SET clause, which PostgreSQL inlines.
CREATE FUNCTION streetgen._lane_tags_listed(tags jsonb)
  RETURNS text
  LANGUAGE sql IMMUTABLE PARALLEL SAFE
  SET search_path FROM CURRENT
  AS $$
    SELECT string_agg(k.key || '=' || replace(t.value, E'\n', ' '), E'\n' ORDER BY k.key)
      FROM jsonb_each_text(CASE WHEN jsonb_typeof(tags) = 'object' THEN tags ELSE '{}' END) AS t,
           LATERAL (SELECT CASE WHEN lower(tags->>'oneway') IN ('-1', 'reverse')
                                THEN array_to_string(ARRAY(
                                       SELECT CASE p WHEN 'left' THEN 'right' WHEN 'right' THEN 'left'
                                                     WHEN 'forward' THEN 'backward' WHEN 'backward' THEN 'forward'
                                                     ELSE p END
                                         FROM unnest(string_to_array(t.key, ':')) WITH ORDINALITY AS u(p, i) ORDER BY i), ':')
                                ELSE t.key END AS key) AS k
     WHERE t.key ~ '^(lanes|turn:lanes|cycleway|busway|parking|placement)(:|$)'
  $$;
CREATE FUNCTION streetgen._lane_tags(tags jsonb)
  RETURNS text
  LANGUAGE sql IMMUTABLE PARALLEL SAFE
  AS $$
    SELECT CASE WHEN tags::text ~ '"(lanes|turn:lanes|cycleway|busway|parking|placement)[:"]'
                THEN streetgen._lane_tags_listed(tags) END
  $$;

-- Sidewalk widths (left, right looking along the axis) of one axis, the rule behind sidewalks:
--   which sides: the OSM tags sidewalk=both|yes|left|right|no|none|separate, then
--   sidewalk:both|left|right=yes|no|separate (a side tagged separate is drawn as its own way, so
--   it is not here); without any of these tags, by class: none on motorways, trunk roads, their
--   links, service roads, living streets (shared space), tracks and bus ways, both sides on every
--   other class;
--   how wide: sidewalk:<side>:width, sidewalk:both:width, sidewalk:width, then the axis'
--   sidewalk_width column (0: no sidewalk at all), then DEFAULT_WIDTH (the model's
--   settings.default_sidewalk_width).
-- oneway=-1 ways are stored reversed by the importer, so their left and right tags swap.
-- Widths outside (0, 20] m in tags are tagging mistakes and count as missing.
CREATE FUNCTION streetgen.sidewalk_widths(road_class text, sidewalk_width double precision, tags jsonb,
                                          default_width double precision)
  RETURNS double precision[]
  LANGUAGE plpgsql IMMUTABLE PARALLEL SAFE
  SET search_path FROM CURRENT
  -- (PL/pgSQL: its expressions are planned once per session; the same rule as an SQL function
  -- with a SET clause was planned on every call, 0.75 ms per axis)
  AS $$
DECLARE
  t jsonb := CASE WHEN jsonb_typeof(tags) = 'object' THEN tags ELSE '{}'::jsonb END;
  main text := lower(t->>'sidewalk');
  both_ text := lower(t->>'sidewalk:both');
  by_class boolean := NOT coalesce(road_class IN ('motorway', 'motorway_link', 'trunk', 'trunk_link', 'service',
                                                  'living_street', 'track', 'busway', 'raceway'), false);
  has boolean;
  side text;
  w double precision;
  l double precision := 0;
  r double precision := 0;
  k text;
BEGIN
  FOREACH side IN ARRAY ARRAY['left', 'right'] LOOP
    k := lower(t->>('sidewalk:' || side));
    IF k IN ('yes', 'no', 'separate', 'none') THEN
      has := k = 'yes';
    ELSIF both_ IN ('yes', 'no', 'separate', 'none') THEN
      has := both_ = 'yes';
    ELSIF main IS NOT NULL THEN
      has := main IN ('both', 'yes', side);
    ELSE
      has := by_class;
    END IF;
    IF NOT has THEN
      CONTINUE;
    END IF;
    w := NULL;
    FOREACH k IN ARRAY ARRAY['sidewalk:' || side || ':width', 'sidewalk:both:width', 'sidewalk:width'] LOOP
      IF t ? k THEN
        w := streetgen.osm_parse_length(t->>k);
        IF w > 0 AND w <= 20 THEN
          EXIT;
        END IF;
        w := NULL;
      END IF;
    END LOOP;
    w := coalesce(w, sidewalk_width, default_width);
    IF side = 'left' THEN l := w; ELSE r := w; END IF;
  END LOOP;
  IF lower(t->>'oneway') IN ('-1', 'reverse') THEN
    RETURN ARRAY[r, l];
  END IF;
  RETURN ARRAY[l, r];
END
$$;
COMMENT ON FUNCTION streetgen.sidewalk_widths(text, double precision, jsonb, double precision) IS
  'Sidewalk widths {left, right} (m, looking along the axis) from road class, sidewalk_width and OSM sidewalk tags: the rule the sidewalks follow';

-- The tags that shape sidewalks, as sorted "key=value" lines (the update trigger compares them).
CREATE FUNCTION streetgen._sidewalk_tags(tags jsonb)
  RETURNS text
  LANGUAGE sql IMMUTABLE PARALLEL SAFE
  SET search_path FROM CURRENT
  AS $$
    SELECT string_agg(t.key || '=' || t.value, E'\n' ORDER BY t.key)
      FROM jsonb_each_text(CASE WHEN jsonb_typeof(tags) = 'object' THEN tags ELSE '{}' END) AS t
     WHERE t.key ~ '^sidewalk(:|$)' OR t.key = 'oneway'
  $$;

-- Runs the engine on MODEL's axes (all of them, or those whose id is in CONTEXT), its settings
-- and corner overrides, into the work table pg_temp._streetgen_out (see _work_tables). Axes go in by
-- id: the engine's results do not depend on the order, but sorted input makes that easy to see.
CREATE FUNCTION streetgen._compute_model(model text, context bigint[] DEFAULT NULL)
  RETURNS void
  LANGUAGE plpgsql VOLATILE
  SET search_path FROM CURRENT
  SET jit = off
  -- (_refresh turns them off for its index lookups; these statements join unindexed work tables)
  SET enable_seqscan = on SET enable_hashjoin = on SET enable_mergejoin = on
  -- (for the work table's ANALYZE below: a sample of 3,000 rows gives the store's plans their
  -- row counts by kind; the default 30,000 read a city's whole output, 0.2 s of Reisterstown)
  SET default_statistics_target = 10
  AS $$
DECLARE
  details boolean;
BEGIN
  PERFORM streetgen._work_tables(ARRAY['_streetgen_out']);
  TRUNCATE pg_temp._streetgen_out;
  EXECUTE format('SELECT s.details FROM %I.settings s', model) INTO details;
  EXECUTE format($q$
    INSERT INTO pg_temp._streetgen_out
    SELECT o.*
      FROM (SELECT array_agg(a.id ORDER BY a.id) AS ids,
                   array_agg(ST_AsEWKB(a.geom) ORDER BY a.id) AS geoms,
                   array_agg(a.roadway_width ORDER BY a.id) AS widths,
                   array_agg(a.speed_kmh ORDER BY a.id) AS speeds,
                   array_agg(a.layer::integer ORDER BY a.id) AS layers,
                   array_agg(a.radius_override ORDER BY a.id) AS radii,
                   array_agg(a.lanes::integer ORDER BY a.id) AS lanes,
                   array_agg(a.oneway ORDER BY a.id) AS oneways,
                   array_agg(streetgen._lane_tags(a.tags) ORDER BY a.id) AS lane_tags,
                   array_agg(w.widths[1] ORDER BY a.id) AS sidewalk_left,
                   array_agg(w.widths[2] ORDER BY a.id) AS sidewalk_right
              FROM %1$I.axis a,
                   -- (sidewalks are details: without them, no widths, and the engine draws none)
                   LATERAL (SELECT CASE WHEN $2 THEN streetgen.sidewalk_widths(a.road_class, a.sidewalk_width, a.tags,
                                                             (SELECT s.default_sidewalk_width FROM %1$I.settings s)) END AS widths) AS w
             WHERE $1 IS NULL OR a.id = ANY ($1)) AS x,
           (SELECT streetgen._settings_vector(to_jsonb(s) - 'singleton') AS v FROM %1$I.settings s) AS st,
           (SELECT array_agg(k ORDER BY c.node_id, c.axis_a, c.part_a, c.end_a, c.axis_b, c.part_b, c.end_b, i) AS keys
              FROM %1$I.corner c, unnest(ARRAY[c.axis_a, c.part_a, c.end_a::int, c.axis_b, c.part_b, c.end_b::int])
                                  WITH ORDINALITY AS u(k, i)
             WHERE c.radius_override IS NOT NULL) AS ov_keys,
           (SELECT array_agg(c.node_id ORDER BY c.node_id, c.axis_a, c.part_a, c.end_a, c.axis_b, c.part_b, c.end_b) AS nodes,
                   array_agg(c.radius_override ORDER BY c.node_id, c.axis_a, c.part_a, c.end_a, c.axis_b, c.part_b, c.end_b) AS radii
              FROM %1$I.corner c WHERE c.radius_override IS NOT NULL) AS ov,
           streetgen._streetgen_street_surfaces(coalesce(x.ids, '{}'), coalesce(x.geoms, '{}'), coalesce(x.widths, '{}'),
                                                coalesce(x.speeds, '{}'), coalesce(x.layers, '{}'), coalesce(x.radii, '{}'),
                                                st.v, coalesce(ov.nodes, '{}'), coalesce(ov_keys.keys, '{}'),
                                                coalesce(ov.radii, '{}'), coalesce(x.lanes, '{}'),
                                                coalesce(x.oneways, '{}'), coalesce(x.lane_tags, '{}'),
                                                coalesce(x.sidewalk_left, '{}'), coalesce(x.sidewalk_right, '{}')) AS o
  $q$, model) USING context, details;
  -- A whole model's output is large: the statements that store it plan with real numbers. A
  -- local recompute's is a few hundred rows, planned well enough from the table's size, and an
  -- ANALYZE would cost as much as storing them.
  -- Only the columns the store joins and filters on: no plan reads the geometries' statistics.
  IF context IS NULL THEN
    ANALYZE pg_temp._streetgen_out (kind, node_id, to_node, axis_id, part, end_a, axis_b, part_b, end_b, status, item);
  END IF;
END
$$;

-- Writes pg_temp._streetgen_out into MODEL's tables. Whole model (SCOPED false), or only the
-- rows in scope (SCOPED true): nodes in pg_temp._sg_scope_nodes, sections in
-- pg_temp._sg_scope_sections, issues of axes in pg_temp._sg_scope_axes; rows out of scope are
-- neither written nor deleted. Stale rows go first (children, then nodes last, once nothing
-- refers to them); upserts leave unchanged rows alone; a corner's radius_override is the user's
-- and is kept.
--
-- A whole model into a table that is empty (a bulk load, the first run after create_model) has
-- nothing to delete or update there: the rows go in by plain INSERT, without the upsert's
-- speculative insertion and its arbiter index probe, and the table's stale-row DELETE is skipped.
-- The same rows result (the engine's keys are unique, so an upsert into an empty table only
-- ever inserts). Recomputes are serialised by _lock_outputs' row lock, so a table found empty
-- stays empty until this store writes it. INSERTs of a kind the engine did not return (the
-- details of a surfaces-only model) are skipped too: each would scan the whole work table.
CREATE FUNCTION streetgen._store(model text, scoped boolean)
  RETURNS void
  LANGUAGE plpgsql VOLATILE
  SET search_path FROM CURRENT
  SET jit = off
  -- (_refresh turns them off for its index lookups; these statements join unindexed work tables)
  SET enable_seqscan = on SET enable_hashjoin = on SET enable_mergejoin = on
  -- (for the ANALYZE at the end: samples of 3,000 rows; the default 30,000 read most of a city's
  -- tables, and later edits look rows up by key and by box, for which the smaller sample plans
  -- the same index scans)
  SET default_statistics_target = 10
  AS $$
DECLARE
  srid integer := streetgen.model_srid(model);
  target text;
  reads text;
  statement text;
  upsert text;
  produced text[];          -- the kinds of rows the engine returned (whole model only)
  was_empty text[] := '{}'; -- the tables that were empty when the store began (whole model only)
  is_empty boolean;
  node_scope text := CASE WHEN scoped THEN '%s IN (SELECT id FROM pg_temp._sg_scope_nodes)' ELSE 'true OR %s IS NULL' END;
  section_scope text := CASE WHEN scoped
    THEN '(%s, %s) IN (SELECT axis_id, part FROM pg_temp._sg_scope_sections)' ELSE 'true OR (%s, %s) IS NULL' END;
  -- An issue about one part follows its section's scope, or its node's when that part has no
  -- section (a dropped loop, a duplicate); one about a whole axis, its axis'.
  issue_scope text := CASE WHEN scoped
    THEN '(CASE WHEN %2$s IS NULL THEN %1$s IN (SELECT id FROM pg_temp._sg_scope_axes)
                ELSE (%1$s, %2$s) IN (SELECT axis_id, part FROM pg_temp._sg_scope_sections)
                     OR %3$s IN (SELECT id FROM pg_temp._sg_scope_nodes) END)'
    ELSE 'true OR (%1$s, %2$s, %3$s) IS NULL' END;
BEGIN
  IF NOT scoped THEN
    SELECT array_agg(o.kind) INTO produced FROM (SELECT DISTINCT o.kind FROM pg_temp._streetgen_out o) AS o;
    FOREACH target IN ARRAY ARRAY['node', 'section', 'lane', 'marking', 'corner', 'intersection', 'sidewalk',
                                  'crossing', 'issue'] LOOP
      EXECUTE format('SELECT NOT EXISTS (SELECT 1 FROM %I.%I)', model, target) INTO is_empty;
      IF is_empty THEN
        was_empty := was_empty || target;
      END IF;
    END LOOP;
  END IF;
  -- (target: the table written; reads: the kind of engine rows read, NULL for none; upsert: the
  -- ON CONFLICT clause of an INSERT, left out when the table was empty)
  FOR target, reads, statement, upsert IN
    SELECT * FROM (VALUES
      ('corner', 'corner',
       $q$DELETE FROM %1$I.corner c WHERE (%3$s) AND NOT EXISTS (
      SELECT 1 FROM pg_temp._streetgen_out o WHERE o.kind = 'corner' AND o.node_id = c.node_id
         AND o.axis_id = c.axis_a AND o.part = c.part_a AND o.end_a = c.end_a
         AND o.axis_b = c.axis_b AND o.part_b = c.part_b AND o.end_b = c.end_b)$q$,
       NULL),
      ('intersection', 'intersection',
       $q$DELETE FROM %1$I.intersection i WHERE (%4$s) AND NOT EXISTS (
      SELECT 1 FROM pg_temp._streetgen_out o WHERE o.kind = 'intersection' AND o.node_id = i.node_id)$q$,
       NULL),
      ('lane', 'lane',
       $q$DELETE FROM %1$I.lane s WHERE (%5$s) AND NOT EXISTS (
      SELECT 1 FROM pg_temp._streetgen_out o WHERE o.kind = 'lane' AND o.axis_id = s.axis_id AND o.part = s.part
         AND o.item = s.lane_index)$q$,
       NULL),
      ('marking', 'marking',
       $q$DELETE FROM %1$I.marking s WHERE (%5$s) AND NOT EXISTS (
      SELECT 1 FROM pg_temp._streetgen_out o WHERE o.kind = 'marking' AND o.axis_id = s.axis_id AND o.part = s.part
         AND o.status = s.kind AND o.item = s.position)$q$,
       NULL),
      ('sidewalk', 'sidewalk',
       $q$DELETE FROM %1$I.sidewalk s WHERE s.node_id IS NULL AND (%5$s) AND NOT EXISTS (
      SELECT 1 FROM pg_temp._streetgen_out o WHERE o.kind = 'sidewalk' AND o.node_id IS NULL AND o.axis_id = s.axis_id
         AND o.part = s.part AND o.status = s.side)$q$,
       NULL),
      ('sidewalk', 'sidewalk',
       $q$DELETE FROM %1$I.sidewalk s WHERE s.node_id IS NOT NULL AND (%11$s) AND NOT EXISTS (
      SELECT 1 FROM pg_temp._streetgen_out o WHERE o.kind = 'sidewalk' AND o.node_id = s.node_id AND o.axis_id IS NULL)$q$,
       NULL),
      ('crossing', 'crossing',
       $q$DELETE FROM %1$I.crossing s WHERE (%5$s) AND NOT EXISTS (
      SELECT 1 FROM pg_temp._streetgen_out o WHERE o.kind = 'crossing' AND o.axis_id = s.axis_id AND o.part = s.part
         AND o.item = s.position)$q$,
       NULL),
      ('section', 'section',
       $q$DELETE FROM %1$I.section s WHERE (%5$s) AND NOT EXISTS (
      SELECT 1 FROM pg_temp._streetgen_out o WHERE o.kind = 'section' AND o.axis_id = s.axis_id AND o.part = s.part)$q$,
       NULL),
      ('node', 'node',
       $q$INSERT INTO %1$I.node AS t (id, geom, degree, layer, axis_ids)
    SELECT o.node_id, ST_SetSRID(ST_GeomFromEWKB(o.geom), %2$s), o.degree, o.layer, o.axis_ids
      FROM pg_temp._streetgen_out o WHERE o.kind = 'node' AND (%6$s)$q$,
       $q$
    ON CONFLICT (id) DO UPDATE SET geom = EXCLUDED.geom, degree = EXCLUDED.degree, layer = EXCLUDED.layer,
                                   axis_ids = EXCLUDED.axis_ids
     WHERE (t.geom, t.degree, t.layer, t.axis_ids) IS DISTINCT FROM
           (EXCLUDED.geom, EXCLUDED.degree, EXCLUDED.layer, EXCLUDED.axis_ids)$q$),
      ('section', 'section',
       $q$INSERT INTO %1$I.section AS t (axis_id, part, from_node, to_node, status, start_border, end_border, centre_line, geom)
    SELECT o.axis_id, o.part, o.node_id, o.to_node, o.status, o.start_border, o.end_border,
           ST_SetSRID(ST_GeomFromEWKB(o.geom2), %2$s), ST_SetSRID(ST_GeomFromEWKB(o.geom), %2$s)
      FROM pg_temp._streetgen_out o WHERE o.kind = 'section' AND (%7$s)$q$,
       $q$
    ON CONFLICT (axis_id, part) DO UPDATE SET from_node = EXCLUDED.from_node, to_node = EXCLUDED.to_node,
        status = EXCLUDED.status, start_border = EXCLUDED.start_border, end_border = EXCLUDED.end_border,
        centre_line = EXCLUDED.centre_line, geom = EXCLUDED.geom
     WHERE (t.from_node, t.to_node, t.status, t.start_border, t.end_border, t.centre_line, t.geom) IS DISTINCT FROM
           (EXCLUDED.from_node, EXCLUDED.to_node, EXCLUDED.status, EXCLUDED.start_border, EXCLUDED.end_border,
            EXCLUDED.centre_line, EXCLUDED.geom)$q$),
      ('lane', 'lane',
       $q$INSERT INTO %1$I.lane AS t (axis_id, part, lane_index, type, direction, width, turn, geom)
    SELECT o.axis_id, o.part, o.item, o.status, o.direction, o.width, o.detail,
           ST_Multi(ST_CollectionExtract(ST_SetSRID(ST_GeomFromEWKB(o.geom), %2$s), 3))
      FROM pg_temp._streetgen_out o WHERE o.kind = 'lane' AND (%7$s)$q$,
       $q$
    ON CONFLICT (axis_id, part, lane_index) DO UPDATE SET type = EXCLUDED.type, direction = EXCLUDED.direction,
        width = EXCLUDED.width, turn = EXCLUDED.turn, geom = EXCLUDED.geom
     WHERE (t.type, t.direction, t.width, t.turn, t.geom) IS DISTINCT FROM
           (EXCLUDED.type, EXCLUDED.direction, EXCLUDED.width, EXCLUDED.turn, EXCLUDED.geom)$q$),
      ('marking', 'marking',
       $q$INSERT INTO %1$I.marking AS t (axis_id, part, kind, position, style, geom)
    SELECT o.axis_id, o.part, o.status, o.item, o.detail,
           ST_Multi(ST_CollectionExtract(ST_SetSRID(ST_GeomFromEWKB(o.geom), %2$s), 2))
      FROM pg_temp._streetgen_out o WHERE o.kind = 'marking' AND (%7$s)$q$,
       $q$
    ON CONFLICT (axis_id, part, kind, position) DO UPDATE SET style = EXCLUDED.style, geom = EXCLUDED.geom
     WHERE (t.style, t.geom) IS DISTINCT FROM (EXCLUDED.style, EXCLUDED.geom)$q$),
      ('corner', 'corner',
       $q$INSERT INTO %1$I.corner AS t (node_id, axis_a, part_a, end_a, axis_b, part_b, end_b, status, radius_wanted, radius,
                                 centre, arc, arc_segmentized)
    SELECT o.node_id, o.axis_id, o.part, o.end_a, o.axis_b, o.part_b, o.end_b, o.status, o.radius_wanted, o.radius,
           ST_SetSRID(ST_GeomFromEWKB(o.geom3), %2$s), ST_SetSRID(ST_GeomFromEWKB(o.geom), %2$s),
           ST_SetSRID(ST_GeomFromEWKB(o.geom2), %2$s)
      FROM pg_temp._streetgen_out o WHERE o.kind = 'corner' AND (%6$s)$q$,
       $q$
    ON CONFLICT (node_id, axis_a, part_a, end_a, axis_b, part_b, end_b) DO UPDATE SET status = EXCLUDED.status,
        radius_wanted = EXCLUDED.radius_wanted, radius = EXCLUDED.radius, centre = EXCLUDED.centre, arc = EXCLUDED.arc,
        arc_segmentized = EXCLUDED.arc_segmentized
     WHERE (t.status, t.radius_wanted, t.radius, t.centre, t.arc, t.arc_segmentized) IS DISTINCT FROM
           (EXCLUDED.status, EXCLUDED.radius_wanted, EXCLUDED.radius, EXCLUDED.centre, EXCLUDED.arc, EXCLUDED.arc_segmentized)$q$),
      ('intersection', 'intersection',
       $q$INSERT INTO %1$I.intersection AS t (node_id, status, axis_ids, geom)
    SELECT o.node_id, o.status, n.axis_ids, ST_SetSRID(ST_GeomFromEWKB(o.geom), %2$s)
      FROM pg_temp._streetgen_out o
      JOIN pg_temp._streetgen_out n ON n.kind = 'node' AND n.node_id = o.node_id
     WHERE o.kind = 'intersection' AND (%6$s)$q$,
       $q$
    ON CONFLICT (node_id) DO UPDATE SET status = EXCLUDED.status, axis_ids = EXCLUDED.axis_ids, geom = EXCLUDED.geom
     WHERE (t.status, t.axis_ids, t.geom) IS DISTINCT FROM (EXCLUDED.status, EXCLUDED.axis_ids, EXCLUDED.geom)$q$),
      ('sidewalk', 'sidewalk',
       $q$INSERT INTO %1$I.sidewalk AS t (axis_id, part, side, width, geom)
    SELECT o.axis_id, o.part, o.status, o.width, ST_Multi(ST_CollectionExtract(ST_SetSRID(ST_GeomFromEWKB(o.geom), %2$s), 3))
      FROM pg_temp._streetgen_out o WHERE o.kind = 'sidewalk' AND o.node_id IS NULL AND (%7$s)$q$,
       $q$
    ON CONFLICT (axis_id, part, side) WHERE node_id IS NULL DO UPDATE SET width = EXCLUDED.width, geom = EXCLUDED.geom
     WHERE (t.width, t.geom) IS DISTINCT FROM (EXCLUDED.width, EXCLUDED.geom)$q$),
      ('sidewalk', 'sidewalk',
       $q$INSERT INTO %1$I.sidewalk AS t (node_id, side, width, geom)
    SELECT o.node_id, o.status, o.width, ST_Multi(ST_CollectionExtract(ST_SetSRID(ST_GeomFromEWKB(o.geom), %2$s), 3))
      FROM pg_temp._streetgen_out o WHERE o.kind = 'sidewalk' AND o.axis_id IS NULL AND (%6$s)$q$,
       $q$
    ON CONFLICT (node_id) WHERE node_id IS NOT NULL DO UPDATE SET width = EXCLUDED.width, geom = EXCLUDED.geom
     WHERE (t.width, t.geom) IS DISTINCT FROM (EXCLUDED.width, EXCLUDED.geom)$q$),
      ('crossing', 'crossing',
       $q$INSERT INTO %1$I.crossing AS t (axis_id, part, position, node_id, width, geom)
    SELECT o.axis_id, o.part, o.item, o.node_id, o.width, ST_Multi(ST_CollectionExtract(ST_SetSRID(ST_GeomFromEWKB(o.geom), %2$s), 3))
      FROM pg_temp._streetgen_out o WHERE o.kind = 'crossing' AND (%7$s)$q$,
       $q$
    ON CONFLICT (axis_id, part, position) DO UPDATE SET node_id = EXCLUDED.node_id, width = EXCLUDED.width, geom = EXCLUDED.geom
     WHERE (t.node_id, t.width, t.geom) IS DISTINCT FROM (EXCLUDED.node_id, EXCLUDED.width, EXCLUDED.geom)$q$),
      ('node', 'node',
       $q$DELETE FROM %1$I.node t WHERE (%8$s) AND NOT EXISTS (
      SELECT 1 FROM pg_temp._streetgen_out o WHERE o.kind = 'node' AND o.node_id = t.id)$q$,
       NULL),
      ('issue', NULL,
       $q$DELETE FROM %1$I.issue i WHERE (%9$s)$q$,
       NULL),
      ('issue', 'issue',
       $q$INSERT INTO %1$I.issue (axis_id, part, kind, detail, node_id)
    SELECT o.axis_id, o.part, o.status, o.detail, o.node_id FROM pg_temp._streetgen_out o WHERE o.kind = 'issue' AND (%10$s)$q$,
       NULL)
    ) AS s (target, reads, statement, upsert)
  LOOP
    -- (was_empty is filled for a whole model only)
    IF target = ANY (was_empty) AND statement LIKE 'DELETE%' THEN
      CONTINUE;
    END IF;
    IF NOT scoped AND statement LIKE 'INSERT%' AND NOT reads = ANY (coalesce(produced, '{}')) THEN
      CONTINUE;
    END IF;
    IF upsert IS NOT NULL AND NOT target = ANY (was_empty) THEN
      statement := statement || upsert;
    END IF;
    EXECUTE format(statement, model, srid,
                   format(node_scope, 'c.node_id'), format(node_scope, 'i.node_id'),
                   format(section_scope, 's.axis_id', 's.part'), format(node_scope, 'o.node_id'),
                   format(section_scope, 'o.axis_id', 'o.part'), format(node_scope, 't.id'),
                   format(issue_scope, 'i.axis_id', 'i.part', 'i.node_id'), format(issue_scope, 'o.axis_id', 'o.part', 'o.node_id'),
                   format(node_scope, 's.node_id'));
  END LOOP;
  -- After a whole model (a bulk load, new settings) the statistics are stale or missing until
  -- autovacuum comes by, and the next edits' neighbourhood searches would plan as if the tables
  -- were empty (seconds instead of milliseconds). What those plans need is each table's row
  -- count and its keys' statistics: the searches by box go through the GiST indexes whatever
  -- the geometries' statistics say (PostGIS assumes a small share of rows without them). The
  -- geometry, jsonb and array columns' statistics were three quarters of this ANALYZE's time
  -- (PostGIS's histogram of each geometry column, sorting the tags' jsonb and the nodes'
  -- axis_ids), so they are left out. A column list leaves the table due for autovacuum's full
  -- ANALYZE, which fills them in later.
  IF NOT scoped THEN
    EXECUTE format('ANALYZE %1$I.axis (id, roadway_width, lanes, speed_kmh, road_class, oneway, sidewalk_width, layer,
                                       structure, radius_override),
                            %1$I.node (id, degree, layer),
                            %1$I.section (axis_id, part, from_node, to_node, status, start_border, end_border),
                            %1$I.corner (node_id, axis_a, part_a, end_a, axis_b, part_b, end_b, status, radius_override),
                            %1$I.intersection (node_id, status),
                            %1$I.lane (axis_id, part, lane_index, type, direction, width, turn),
                            %1$I.marking (axis_id, part, kind, position, style),
                            %1$I.sidewalk (axis_id, part, node_id, side, width),
                            %1$I.crossing (axis_id, part, position, node_id, width)', model);
    PERFORM streetgen._store_blocks(model, NULL);
  END IF;
END
$$;

CREATE FUNCTION streetgen.generate(model text, OUT kind text, OUT status text, OUT count bigint)
  RETURNS SETOF record
  LANGUAGE plpgsql VOLATILE
  SET search_path FROM CURRENT
  SET jit = off
  AS $$
BEGIN
  PERFORM streetgen.model_srid(model);  -- 22004, 42602, 42704 for bad names
  PERFORM streetgen._lock_outputs(model);
  PERFORM streetgen._compute_model(model);
  PERFORM streetgen._store(model, false);
  RETURN QUERY SELECT o.kind, o.status, count(*) FROM pg_temp._streetgen_out o GROUP BY 1, 2 ORDER BY 1, 2;
END
$$;
COMMENT ON FUNCTION streetgen.generate(text) IS
  'Recomputes the street surfaces of a whole model and upserts node, section, corner, intersection, lane, marking (stable keys); returns counts by kind and status';

-- Stateless: street surfaces of the axes a query returns, for any GIS client. The query must
-- return id (bigint), geom (LineString, projected CRS in metres), roadway_width and speed_kmh;
-- layer, radius_override, lanes, oneway, tags (jsonb, OSM), road_class and sidewalk_width are used
-- when present (sidewalks follow streetgen.sidewalk_widths). It runs
-- with the caller's rights. ITEM is a lane's index or a marking's position, DETAIL a lane's
-- turn or a marking's style (and an issue's text).
CREATE FUNCTION streetgen.street_surfaces(axes text, settings jsonb DEFAULT '{}',
    OUT kind text, OUT node_id bigint, OUT axis_id bigint, OUT part bigint, OUT status text, OUT geom geometry,
    OUT item integer, OUT detail text)
  RETURNS SETOF record
  LANGUAGE plpgsql VOLATILE
  SET search_path FROM CURRENT
  SET jit = off
  AS $$
DECLARE
  columns text[];
  srid integer;
  vector double precision[] := streetgen._settings_vector(settings);
  default_sidewalk double precision;
BEGIN
  SELECT s.default_sidewalk_width INTO default_sidewalk
    FROM jsonb_populate_record((SELECT d FROM streetgen.default_settings d), settings) s;
  IF axes IS NULL THEN
    RAISE EXCEPTION 'axes must not be null' USING ERRCODE = 'null_value_not_allowed';
  END IF;
  EXECUTE format('CREATE OR REPLACE TEMP VIEW _streetgen_axes AS %s', axes);
  SELECT array_agg(a.attname::text) INTO columns
    FROM pg_attribute a WHERE a.attrelid = 'pg_temp._streetgen_axes'::regclass AND a.attnum > 0;
  IF NOT columns @> ARRAY['id', 'geom', 'roadway_width', 'speed_kmh'] THEN
    RAISE EXCEPTION 'the axes query must return columns id, geom, roadway_width and speed_kmh'
      USING ERRCODE = 'invalid_parameter_value', DETAIL = format('It returns: %s.', array_to_string(columns, ', '));
  END IF;
  SELECT ST_SRID(q.geom) INTO srid FROM pg_temp._streetgen_axes q LIMIT 1;
  IF srid IS NOT NULL THEN
    PERFORM streetgen._require_metric_srid(srid, 'axes SRID');
  END IF;
  RETURN QUERY EXECUTE format($q$
    SELECT o.kind, o.node_id, o.axis_id, o.part, o.status,
           ST_SetSRID(ST_GeomFromEWKB(coalesce(o.geom, o.geom3)), %1$s), o.item, o.detail
      FROM (SELECT array_agg(q.id::bigint) AS ids, array_agg(ST_AsEWKB(q.geom)) AS geoms,
                   array_agg(q.roadway_width::float8) AS widths, array_agg(q.speed_kmh::float8) AS speeds,
                   array_agg(%2$s) AS layers, array_agg(%3$s) AS radii, array_agg(%4$s) AS lanes,
                   array_agg(%5$s) AS oneways, array_agg(%6$s) AS lane_tags,
                   array_agg(w.widths[1]) AS sidewalk_left, array_agg(w.widths[2]) AS sidewalk_right
              FROM pg_temp._streetgen_axes q,
                   LATERAL (SELECT streetgen.sidewalk_widths(%7$s, %8$s, %9$s, $2) AS widths) AS w) AS x,
           streetgen._streetgen_street_surfaces(coalesce(x.ids, '{}'), coalesce(x.geoms, '{}'), coalesce(x.widths, '{}'),
                                                coalesce(x.speeds, '{}'), coalesce(x.layers, '{}'), coalesce(x.radii, '{}'),
                                                $1, '{}', '{}', '{}', coalesce(x.lanes, '{}'), coalesce(x.oneways, '{}'),
                                                coalesce(x.lane_tags, '{}'), coalesce(x.sidewalk_left, '{}'),
                                                coalesce(x.sidewalk_right, '{}')) AS o
  $q$, coalesce(srid, 0),
       CASE WHEN 'layer' = ANY(columns) THEN 'q.layer::integer' ELSE '0' END,
       CASE WHEN 'radius_override' = ANY(columns) THEN 'q.radius_override::float8' ELSE 'NULL::float8' END,
       CASE WHEN 'lanes' = ANY(columns) THEN 'q.lanes::integer' ELSE 'NULL::integer' END,
       CASE WHEN 'oneway' = ANY(columns) THEN 'q.oneway::boolean' ELSE 'false' END,
       CASE WHEN 'tags' = ANY(columns) THEN 'streetgen._lane_tags(q.tags::jsonb)' ELSE 'NULL::text' END,
       CASE WHEN 'road_class' = ANY(columns) THEN 'q.road_class::text' ELSE 'NULL::text' END,
       CASE WHEN 'sidewalk_width' = ANY(columns) THEN 'q.sidewalk_width::float8' ELSE 'NULL::float8' END,
       CASE WHEN 'tags' = ANY(columns) THEN 'q.tags::jsonb' ELSE '''{}''::jsonb' END)
  USING vector, default_sidewalk;
  DROP VIEW pg_temp._streetgen_axes;
END
$$;
COMMENT ON FUNCTION streetgen.street_surfaces(text, jsonb) IS
  'Street surfaces (nodes, sections, corner arcs, intersections, lanes, markings, issues) of the axes a query returns; nothing is stored';

-- (Overlaps are measured with ST_Intersection alone: GEOS 3.11's ST_Intersects predicate can
-- throw on valid polygons with nearly coincident edges, OverlayNG does not.)
-- How sound a model's generated surfaces are: validity, missing junctions, and overlaps on one
-- layer (a bridge over a street overlaps it in plan, rightly). The acceptance measures of the
-- street surfaces; also handy after editing settings.
CREATE FUNCTION streetgen.surface_quality(model text,
    OUT nodes bigint, OUT junctions bigint, OUT intersections bigint, OUT missing_intersections bigint,
    OUT sections bigint, OUT invalid_geometries bigint, OUT surface_area double precision,
    OUT section_overlap_area double precision, OUT section_overlap_ratio double precision,
    OUT intersection_overlap_area double precision)
  RETURNS record
  LANGUAGE plpgsql STABLE
  SET search_path FROM CURRENT
  SET jit = off
  AS $$
BEGIN
  PERFORM streetgen.model_srid(model);
  EXECUTE format($q$
    SELECT (SELECT count(*) FROM %1$I.node),
           (SELECT count(*) FROM %1$I.node WHERE degree >= 2),
           (SELECT count(*) FROM %1$I.intersection),
           (SELECT count(*) FROM %1$I.node n WHERE n.degree >= 2
               AND NOT EXISTS (SELECT 1 FROM %1$I.intersection i WHERE i.node_id = n.id)),
           (SELECT count(*) FROM %1$I.section WHERE geom IS NOT NULL),
           (SELECT count(*) FROM %1$I.section WHERE geom IS NOT NULL AND NOT ST_IsValid(geom))
             + (SELECT count(*) FROM %1$I.intersection WHERE NOT ST_IsValid(geom))
             + (SELECT count(*) FROM %1$I.corner WHERE arc_segmentized IS NOT NULL AND NOT ST_IsValid(arc_segmentized)),
           coalesce((SELECT sum(ST_Area(geom)) FROM %1$I.section), 0)
             + coalesce((SELECT sum(ST_Area(geom)) FROM %1$I.intersection), 0),
           coalesce((SELECT sum(ST_Area(ST_Intersection(a.geom, b.geom)))
                       FROM %1$I.section a
                       JOIN %1$I.axis xa ON xa.id = a.axis_id
                       JOIN %1$I.section b ON a.axis_id < b.axis_id AND a.geom && b.geom
                       JOIN %1$I.axis xb ON xb.id = b.axis_id AND xb.layer = xa.layer
                      ), 0),
           coalesce((SELECT sum(ST_Area(ST_Intersection(i.geom, s.geom)))
                       FROM %1$I.intersection i
                       JOIN %1$I.node n ON n.id = i.node_id
                       JOIN %1$I.section s ON i.geom && s.geom
                       JOIN %1$I.axis x ON x.id = s.axis_id AND x.layer = n.layer
                      ), 0)
             + coalesce((SELECT sum(ST_Area(ST_Intersection(a.geom, b.geom)))
                           FROM %1$I.intersection a
                           JOIN %1$I.node na ON na.id = a.node_id
                           JOIN %1$I.intersection b ON a.node_id < b.node_id AND a.geom && b.geom
                           JOIN %1$I.node nb ON nb.id = b.node_id AND nb.layer = na.layer
                          ), 0)
  $q$, model)
  INTO nodes, junctions, intersections, missing_intersections, sections, invalid_geometries, surface_area,
       section_overlap_area, intersection_overlap_area;
  section_overlap_ratio := CASE WHEN surface_area > 0 THEN section_overlap_area / surface_area ELSE 0 END;
END
$$;
COMMENT ON FUNCTION streetgen.surface_quality(text) IS
  'Checks a model''s generated surfaces: invalid geometries, junctions without surface, overlap between sections of different axes';

-- How sound a model's lanes and markings are, the acceptance measures of issue 5: per section the
-- symmetric difference between the section and the union of its lanes (relative to the section's
-- area), the overlap of lanes of one section (sum of their areas minus their union's), the area
-- of lanes outside their own section, and the area of lanes inside a section of another axis on
-- the same layer (parts of one axis that overlap at a tight bend are the surfaces' matter:
-- surface_quality).
CREATE FUNCTION streetgen.lane_quality(model text,
    OUT sections bigint, OUT sections_without_lanes bigint, OUT lanes bigint, OUT markings bigint,
    OUT invalid_geometries bigint, OUT max_coverage_difference double precision,
    OUT sections_over_tolerance bigint, OUT lane_overlap_area double precision,
    OUT outside_section_area double precision, OUT foreign_overlap_area double precision)
  RETURNS record
  LANGUAGE plpgsql STABLE
  SET search_path FROM CURRENT
  SET jit = off
  AS $$
BEGIN
  PERFORM streetgen.model_srid(model);
  EXECUTE format($q$
    WITH per_section AS (
      SELECT s.axis_id, s.part, ST_Area(s.geom) AS area, l.n, l.lane_area,
             ST_Area(ST_SymDifference(s.geom, l.u)) AS difference, ST_Area(l.u) AS union_area
        FROM %1$I.section s
        JOIN LATERAL (SELECT count(*) AS n, sum(ST_Area(x.geom)) AS lane_area, ST_Union(x.geom) AS u
                        FROM %1$I.lane x WHERE x.axis_id = s.axis_id AND x.part = s.part) AS l ON true
       WHERE s.geom IS NOT NULL AND l.n > 0)
    SELECT (SELECT count(*) FROM %1$I.section WHERE geom IS NOT NULL),
           (SELECT count(*) FROM %1$I.section s WHERE s.geom IS NOT NULL
               AND NOT EXISTS (SELECT 1 FROM %1$I.lane x WHERE x.axis_id = s.axis_id AND x.part = s.part)),
           (SELECT count(*) FROM %1$I.lane),
           (SELECT count(*) FROM %1$I.marking),
           (SELECT count(*) FROM %1$I.lane WHERE NOT ST_IsValid(geom))
             + (SELECT count(*) FROM %1$I.marking WHERE NOT ST_IsValid(geom) OR ST_IsEmpty(geom)),
           coalesce((SELECT max(difference / area) FROM per_section WHERE area > 0), 0),
           (SELECT count(*) FROM per_section WHERE area > 0 AND difference / area >= 0.005),
           coalesce((SELECT sum(lane_area - union_area) FROM per_section), 0),
           coalesce((SELECT sum(ST_Area(ST_Difference(x.geom, s.geom)))
                       FROM %1$I.lane x JOIN %1$I.section s USING (axis_id, part)), 0),
           coalesce((SELECT sum(ST_Area(ST_Intersection(x.geom, s.geom)))
                       FROM %1$I.lane x
                       JOIN %1$I.axis xa ON xa.id = x.axis_id
                       JOIN %1$I.section s ON s.geom && x.geom AND s.axis_id <> x.axis_id
                       JOIN %1$I.axis sa ON sa.id = s.axis_id AND sa.layer = xa.layer), 0)
  $q$, model)
  INTO sections, sections_without_lanes, lanes, markings, invalid_geometries, max_coverage_difference,
       sections_over_tolerance, lane_overlap_area, outside_section_area, foreign_overlap_area;
END
$$;
COMMENT ON FUNCTION streetgen.lane_quality(text) IS
  'Checks a model''s lanes and markings: validity, how exactly the lanes of each section cover it, overlaps between lanes, lanes outside their section or inside another axis'' section';
