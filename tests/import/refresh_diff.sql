-- pg_temp.refresh_diff(model): what differs between the model's tables (kept current by the
-- triggers) and a full recompute of the same axes. No rows: the invariant holds. Geometries are
-- equal when within 1e-6 m of each other (Hausdorff), numbers within 1e-6.
CREATE FUNCTION pg_temp.refresh_diff(model text)
  RETURNS TABLE (kind text, key text, what text)
  LANGUAGE plpgsql AS $$
BEGIN
  PERFORM streetgen._compute_model(model);
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
           CASE WHEN t.axis_id IS NULL THEN 'missing' WHEN o.axis_id IS NULL THEN 'extra' ELSE 'differs' END
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
           CASE WHEN t.node_id IS NULL THEN 'missing' WHEN o.node_id IS NULL THEN 'extra' ELSE 'differs' END
      FROM %1$I.intersection t FULL JOIN (SELECT * FROM o WHERE o.kind = 'intersection') o ON o.node_id = t.node_id
     WHERE t.node_id IS NULL OR o.node_id IS NULL OR t.status <> o.status
        OR ST_HausdorffDistance(t.geom, ST_GeomFromEWKB(o.geom)) > 1e-6
    UNION ALL
    (SELECT 'issue', concat_ws('/', axis_id, kind, detail), 'differs' FROM (
       (SELECT axis_id, kind, detail FROM %1$I.issue EXCEPT ALL SELECT axis_id, status, detail FROM o WHERE kind = 'issue')
       UNION ALL
       (SELECT axis_id, status, detail FROM o WHERE kind = 'issue' EXCEPT ALL SELECT axis_id, kind, detail FROM %1$I.issue)) d)
  $q$, model);
END
$$;
