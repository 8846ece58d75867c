-- After the soak: no committed edit lost (the axis table equals the originals with the audit log
-- replayed), the outputs equal a full recompute, and every output geometry is valid.
-- psql variables: model, min_edits.
SET search_path = :"model", public;
SELECT plan(6);

SELECT cmp_ok((SELECT count(*) FROM soak_log), '>=', :min_edits::bigint,
              'the soak committed at least ' || :min_edits || ' edits');

-- Every logged insert is there unless a logged delete removed it, every other logged delete is
-- gone, and nothing appeared or vanished behind the log's back.
SELECT set_eq('SELECT id FROM axis',
              $$SELECT id FROM soak_original UNION SELECT axis_id FROM soak_log WHERE kind = 'insert'
                EXCEPT SELECT axis_id FROM soak_log WHERE kind = 'delete'$$,
              'the axes are the original ones plus the logged inserts minus the logged deletes');

-- Width and speed changes are additive: a lost update leaves the sum short.
SELECT is_empty($$
  WITH base AS (SELECT id, roadway_width, speed_kmh FROM soak_original
                UNION ALL SELECT axis_id, roadway_width, speed_kmh FROM soak_log WHERE kind = 'insert')
  SELECT a.id, a.roadway_width, b.roadway_width + w.sum AS logged_width, a.speed_kmh, b.speed_kmh + s.sum AS logged_speed
    FROM axis a JOIN base b USING (id),
         LATERAL (SELECT coalesce(sum(d), 0) AS sum FROM soak_log l WHERE l.axis_id = a.id AND l.kind = 'width') w,
         LATERAL (SELECT coalesce(sum(d), 0) AS sum FROM soak_log l WHERE l.axis_id = a.id AND l.kind = 'speed') s
   WHERE abs(a.roadway_width - (b.roadway_width + w.sum)) > 1e-9 OR abs(a.speed_kmh - (b.speed_kmh + s.sum)) > 1e-9
$$, 'every committed width and speed change is in the axis table');

-- Axis moves and vertex moves both translate vertices, so they commute: each vertex is where
-- its original position plus every logged move of its axis and of itself puts it.
SELECT is_empty($$
  WITH base AS (SELECT id, geom FROM soak_original UNION ALL SELECT axis_id, geom FROM soak_log WHERE kind = 'insert')
  SELECT a.id, p.k
    FROM axis a JOIN base b USING (id),
         LATERAL generate_series(1, greatest(ST_NPoints(a.geom), ST_NPoints(b.geom))) AS p (k),
         LATERAL (SELECT coalesce(sum(dx_cm), 0) / 100.0 AS dx, coalesce(sum(dy_cm), 0) / 100.0 AS dy FROM soak_log l
                   WHERE l.axis_id = a.id AND (l.kind = 'move' OR (l.kind = 'vertex' AND l.vertex = p.k - 1))) m
   WHERE ST_NPoints(a.geom) <> ST_NPoints(b.geom)
      OR ST_Distance(ST_PointN(a.geom, p.k), ST_Translate(ST_PointN(b.geom, p.k), m.dx, m.dy)) > 1e-6
$$, 'every committed move of an axis or a vertex is in the axis table');

SELECT is_empty(format('SELECT * FROM streetgen.outdated(%L)', :'model'),
                'the outputs equal a full recompute of the axes (streetgen.outdated is empty)');

SELECT is_empty($$
  SELECT 'section', axis_id || '/' || part FROM section WHERE NOT ST_IsValid(geom) OR NOT ST_IsValid(centre_line)
  UNION ALL SELECT 'intersection', node_id::text FROM intersection WHERE NOT ST_IsValid(geom)
  UNION ALL SELECT 'corner', node_id || '/' || axis_a || '/' || axis_b FROM corner WHERE NOT ST_IsValid(arc_segmentized)
  UNION ALL SELECT 'node', id::text FROM node WHERE NOT ST_IsValid(geom)
$$, 'every section, intersection, corner arc and node geometry is valid');

SELECT * FROM finish();
