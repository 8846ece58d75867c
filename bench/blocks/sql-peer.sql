-- The SQL block overlay that src/core/streets/blocks.cpp replaced (sql/62-blocks.sql before
-- branch blocks-cxx), kept as the peer of bench/blocks/run.sh: _face_minus in schema blocks_peer,
-- and _compute_blocks in schema :"target" (blocks_peer; or streetgen, inside a transaction the
-- bench rolls back, to time a whole generate() with it). Same result table, pg_temp._sg_blocks.
SET search_path = pg_catalog, streetgen, public, pg_temp;
CREATE SCHEMA IF NOT EXISTS blocks_peer;
CREATE OR REPLACE FUNCTION blocks_peer._face_minus(face geometry, pieces geometry[])
  RETURNS geometry
  LANGUAGE plpgsql IMMUTABLE PARALLEL SAFE
  SET search_path FROM CURRENT
  AS $$
DECLARE
  d geometry;
BEGIN
  BEGIN
    d := ST_CollectionExtract(coalesce(ST_Difference(face, ST_UnaryUnion(ST_Collect(ARRAY(
           SELECT ST_CollectionExtract(ST_Intersection(p, face), 3) FROM unnest(pieces) AS p)))), face), 3);
  EXCEPTION WHEN internal_error THEN
    d := ST_CollectionExtract(coalesce(ST_Difference(face, ST_UnaryUnion(ST_Collect(ARRAY(
           SELECT ST_CollectionExtract(ST_Intersection(p, face, 1e-6), 3) FROM unnest(pieces) AS p)), 1e-6), 1e-6), face), 3);
  END;
  RETURN CASE WHEN ST_IsEmpty(d) THEN NULL ELSE ST_Multi(d) END;
END
$$;

CREATE OR REPLACE FUNCTION :"target"._compute_blocks(model text, area geometry, changed geometry DEFAULT NULL)
  RETURNS void
  LANGUAGE plpgsql VOLATILE
  SET search_path FROM CURRENT
  SET jit = off
  SET enable_seqscan = on SET enable_hashjoin = on SET enable_mergejoin = on
  AS $$
BEGIN
  PERFORM streetgen._work_tables();
  DELETE FROM pg_temp._sg_faces;
  DELETE FROM pg_temp._sg_blocks;
  EXECUTE format($q$
    INSERT INTO pg_temp._sg_faces (face)
    SELECT (ST_Dump(ST_Polygonize(s.centre_line))).geom
      FROM %1$I.section s JOIN %1$I.axis a ON a.id = s.axis_id
     WHERE a.layer = 0 AND s.status <> 'duplicate' AND ($1 IS NULL OR s.centre_line && $1)$q$, model) USING area;
  EXECUTE format($q$
    INSERT INTO pg_temp._sg_blocks (id, face, geom, axis_ids, kind)
    SELECT f.id,
           f.face,
           CASE WHEN kept.id IS NOT NULL THEN kept.geom ELSE blocks_peer._face_minus(f.face, ARRAY(
                 SELECT s.geom FROM %1$I.section s JOIN %1$I.axis a ON a.id = s.axis_id
                  WHERE a.layer = 0 AND s.geom && f.face
                 UNION ALL
                 SELECT i.geom FROM %1$I.intersection i JOIN %1$I.node n ON n.id = i.node_id
                  WHERE n.layer = 0 AND i.geom && f.face
                 UNION ALL
                 SELECT w.geom FROM %1$I.sidewalk w JOIN %1$I.axis a ON a.id = w.axis_id
                  WHERE a.layer = 0 AND w.geom && f.face
                 UNION ALL
                 SELECT w.geom FROM %1$I.sidewalk w JOIN %1$I.node n ON n.id = w.node_id
                  WHERE n.layer = 0 AND w.geom && f.face)) END,
           CASE WHEN kept.id IS NOT NULL THEN kept.axis_ids ELSE coalesce(r.axis_ids, '{}') END,
           CASE WHEN kept.id IS NOT NULL THEN kept.kind
                WHEN ST_Area(f.face) < 2500 AND r.one_way_or_link THEN 'island' ELSE 'block' END
      FROM (SELECT ('x' || substr(md5(ST_AsEWKB(ST_Normalize(g.face))), 1, 16))::bit(64)::bigint AS id, g.face
              FROM pg_temp._sg_faces g) AS f
           LEFT JOIN LATERAL (SELECT b.id, b.geom, b.axis_ids, b.kind FROM %1$I.block b
                               WHERE $2 IS NOT NULL AND b.id = f.id AND NOT (f.face && $2)) AS kept ON true,
           LATERAL (SELECT array_agg(DISTINCT s.axis_id ORDER BY s.axis_id) AS axis_ids,
                           bool_and(a.oneway OR a.road_class LIKE '%%\_link') AS one_way_or_link
                      FROM %1$I.section s JOIN %1$I.axis a ON a.id = s.axis_id
                     WHERE kept.id IS NULL AND a.layer = 0 AND s.status <> 'duplicate' AND s.centre_line && f.face
                       AND ST_DWithin(ST_LineInterpolatePoint(s.centre_line, 0.5), ST_Boundary(f.face), 1e-6)) AS r
     WHERE $1 IS NULL OR f.face @ $1$q$, model) USING area, changed;
END
$$;
