-- City blocks (issue 5): the bounded faces of the ground-level axis network minus the street
-- surfaces and sidewalks on them. The StreetGen paper takes the faces of PostGIS Topology and
-- subtracts the surfaces with boolean operations, so that blocks exist where some streets are
-- missing; here the faces come from PostGIS's ST_Polygonize of the sections' centre lines (the
-- axis parts node to node, already split at every junction by the engine's topology, so the
-- line work is noded), which drops dangling axes (they do not split a face) and leaves the
-- unbounded outside of the network without a block. Bridges and tunnels (layer <> 0) neither
-- bound faces nor are subtracted: a block is what lies between the streets on the ground.
-- Traffic islands are the faces of under 2,500 m2 bounded only by one-way axes and links (the
-- gap between dual carriageways), or by a link and at most two other axes (the triangle between
-- a slip lane and the roads it joins, two-way ones included): kind 'island'.

-- Each face minus the union of the pieces (street surfaces, sidewalks) on it, in C++ (src/core/
-- streets/blocks.cpp): one row per face, face_index from 1, geom NULL when nothing is left. The
-- pieces are clipped to the face before their union (the far side of each street drops out; a
-- piece inside the face is taken as is). Floating-point overlay first; where GEOS throws on nearly
-- coincident edges (it does on a few real junctions), the face again on a grid of grid_size
-- (OverlayNG with a grid size never fails, but is three times slower): an edit is never aborted by
-- a block. In SQL this was one ST_Intersection per face and piece, each converting the face to
-- GEOS again (73 s of Paris' 159 s generate).
-- The pieces come in three arrays, read as one list in the order sections, junctions, sidewalks.
-- The sidewalks' array, the largest, is the first argument: PostgreSQL builds an array argument
-- from a copy of each element, so while an array is made it is held twice, and those made before
-- it once. The largest made first, Reisterstown's 12 MB of pieces take at most 14 MB while they
-- are made, against 24 in one array (the blocks' spike: 75 -> 57-62 MB of the import's backend).
-- The order of the pieces is the order of the tables' rows: the union of a face's pieces, and so
-- the last bits of its block, follow it.
CREATE FUNCTION streetgen._streetgen_faces_minus(faces bytea[], sidewalks bytea[], sections bytea[], junctions bytea[],
                                                 grid_size double precision, OUT face_index integer, OUT geom bytea)
  RETURNS SETOF record
  LANGUAGE c IMMUTABLE PARALLEL SAFE
  COST 100000 ROWS 1000
  AS 'MODULE_PATHNAME', '_streetgen_faces_minus';

-- The blocks of MODEL whose faces lie inside AREA (all of them when AREA is NULL), from its
-- stored sections, junctions and sidewalks, into pg_temp._sg_blocks. With CHANGED (the box
-- around every street surface and sidewalk a refresh rewrote, old and new), a face that keeps
-- its key and does not meet CHANGED keeps its stored block: nothing it is cut by has changed (an
-- edit of one street recomputed every block of its box, twenty-five faces on Liechtenstein).
-- The face itself must miss the box, not only its own box: Liechtenstein's faces are large and
-- ragged, and over 40 random edits the faces cut again fell from 735,000 m² to 429,000 m² on
-- average.
-- The faces to cut again go to the overlay in one call, with every ground-level piece in the box
-- around them (the overlay finds each face's own pieces with a tree).
CREATE FUNCTION streetgen._compute_blocks(model text, area geometry, changed geometry DEFAULT NULL)
  RETURNS void
  LANGUAGE plpgsql VOLATILE
  SET search_path FROM CURRENT
  SET jit = off
  SET enable_seqscan = on SET enable_hashjoin = on SET enable_mergejoin = on
  AS $$
DECLARE
  extent geometry;
  details boolean;
BEGIN
  PERFORM streetgen._work_tables(ARRAY['_sg_faces', '_sg_blocks']);
  DELETE FROM pg_temp._sg_faces;
  DELETE FROM pg_temp._sg_blocks;
  -- (a model of street surfaces only has no blocks: _store_blocks then deletes any stored ones)
  EXECUTE format('SELECT s.details FROM %I.settings s', model) INTO details;
  IF NOT details THEN
    RETURN;
  END IF;
  EXECUTE format($q$
    INSERT INTO pg_temp._sg_faces (face)
    SELECT (ST_Dump(ST_Polygonize(s.centre_line))).geom
      FROM %1$I.section s JOIN %1$I.axis a ON a.id = s.axis_id
     WHERE a.layer = 0 AND s.status <> 'duplicate' AND ($1 IS NULL OR s.centre_line && $1)$q$, model) USING area;
  EXECUTE format($q$
    INSERT INTO pg_temp._sg_blocks (id, face, geom, axis_ids, kind, cut)
    SELECT f.id,
           f.face,
           kept.geom,
           CASE WHEN kept.id IS NOT NULL THEN kept.axis_ids ELSE coalesce(r.axis_ids, '{}') END,
           CASE WHEN kept.id IS NOT NULL THEN kept.kind
                WHEN ST_Area(f.face) < 2500 AND (r.one_way_or_link OR (r.has_link AND r.axis_count <= 3)) THEN 'island'
                ELSE 'block' END,
           kept.id IS NULL
      FROM (SELECT ('x' || substr(md5(ST_AsEWKB(ST_Normalize(g.face))), 1, 16))::bit(64)::bigint AS id, g.face
              FROM pg_temp._sg_faces g) AS f
           LEFT JOIN LATERAL (SELECT b.id, b.geom, b.axis_ids, b.kind FROM %1$I.block b
                               WHERE $2 IS NOT NULL AND b.id = f.id AND NOT ST_Intersects(f.face, $2)) AS kept ON true,
           LATERAL (SELECT array_agg(DISTINCT s.axis_id ORDER BY s.axis_id) AS axis_ids,
                           bool_and(a.oneway OR a.road_class LIKE '%%\_link') AS one_way_or_link,
                           bool_or(a.road_class LIKE '%%\_link') AS has_link, count(DISTINCT s.axis_id) AS axis_count
                      FROM %1$I.section s JOIN %1$I.axis a ON a.id = s.axis_id
                     WHERE kept.id IS NULL AND a.layer = 0 AND s.status <> 'duplicate' AND s.centre_line && f.face
                       AND ST_DWithin(ST_LineInterpolatePoint(s.centre_line, 0.5), ST_Boundary(f.face), 1e-6)) AS r
     WHERE $1 IS NULL OR f.face @ $1$q$, model) USING area, changed;
  SELECT ST_SetSRID(ST_Extent(b.face)::geometry, min(ST_SRID(b.face))) INTO extent FROM pg_temp._sg_blocks b WHERE b.cut;
  IF extent IS NULL THEN
    RETURN;
  END IF;
  -- (a materialized CTE: the overlay runs once whatever the plan; joined as a subquery, a
  -- nested loop once sorted every face again for each of Paris' 13,140 rows)
  EXECUTE format($q$
    WITH c AS MATERIALIZED (
      SELECT x.ids[r.face_index] AS id, r.geom
        FROM (SELECT array_agg(k.id ORDER BY k.id) AS ids, array_agg(ST_AsEWKB(k.face) ORDER BY k.id) AS faces
                FROM pg_temp._sg_blocks k WHERE k.cut) AS x,
             streetgen._streetgen_faces_minus(x.faces,
               ARRAY(SELECT ST_AsEWKB(w.geom) FROM %1$I.sidewalk w JOIN %1$I.axis a ON a.id = w.axis_id
                      WHERE a.layer = 0 AND w.geom && $1
                     UNION ALL
                     SELECT ST_AsEWKB(w.geom) FROM %1$I.sidewalk w JOIN %1$I.node n ON n.id = w.node_id
                      WHERE n.layer = 0 AND w.geom && $1),
               ARRAY(SELECT ST_AsEWKB(s.geom) FROM %1$I.section s JOIN %1$I.axis a ON a.id = s.axis_id
                      WHERE a.layer = 0 AND s.geom && $1),
               ARRAY(SELECT ST_AsEWKB(i.geom) FROM %1$I.intersection i JOIN %1$I.node n ON n.id = i.node_id
                      WHERE n.layer = 0 AND i.geom && $1),
               1e-6) AS r
       WHERE r.geom IS NOT NULL)
    UPDATE pg_temp._sg_blocks b SET geom = ST_GeomFromEWKB(c.geom) FROM c WHERE b.id = c.id AND b.cut$q$, model) USING extent;
END
$$;

-- Writes the blocks: all of them (REGION NULL), or those a change inside REGION (the box
-- around everything a local recompute rewrote, old and new) can have touched. Faces are not
-- local: one axis can close a ring of kilometres whose other lines lie far from the change (a
-- soak found a 9.9 km2 face missing when faces were searched in a growing box). So the faces of
-- the whole ground-level network are polygonized on every refresh (26 ms for Liechtenstein's
-- 3,763 sections), and only the overlay is local: a face that keeps its key (a hash of the face)
-- and lies off REGION keeps its stored block; new faces and faces over REGION are cut again;
-- blocks whose face is gone are deleted.
CREATE FUNCTION streetgen._store_blocks(model text, region geometry)
  RETURNS void
  LANGUAGE plpgsql VOLATILE
  SET search_path FROM CURRENT
  SET jit = off
  SET enable_seqscan = on SET enable_hashjoin = on SET enable_mergejoin = on
  AS $$
BEGIN
  IF region IS NOT NULL AND ST_IsEmpty(region) THEN
    region := NULL;
  END IF;
  PERFORM streetgen._compute_blocks(model, NULL, ST_Envelope(region));
  EXECUTE format($q$
    DELETE FROM %1$I.block b WHERE NOT EXISTS (SELECT 1 FROM pg_temp._sg_blocks n WHERE n.id = b.id)$q$, model);
  EXECUTE format($q$
    INSERT INTO %1$I.block AS t (id, face, geom, axis_ids, kind)
    SELECT n.id, n.face, n.geom, n.axis_ids, n.kind FROM pg_temp._sg_blocks n
    ON CONFLICT (id) DO UPDATE SET face = EXCLUDED.face, geom = EXCLUDED.geom, axis_ids = EXCLUDED.axis_ids,
                                   kind = EXCLUDED.kind
     WHERE (t.face, t.geom, t.axis_ids, t.kind) IS DISTINCT FROM (EXCLUDED.face, EXCLUDED.geom, EXCLUDED.axis_ids, EXCLUDED.kind)$q$, model);
END
$$;

-- How sound a model's details are, the acceptance measures of issue 5 for sidewalks, crossings
-- and blocks: invalid geometries; the area of sidewalks on a roadway of their layer (the
-- sections and junctions) and of sidewalks overlapping each other; crossings outside their
-- section; and how blocks, street surfaces and sidewalks tile the bounded faces of the
-- ground-level network: face_area, the area covered twice inside the faces by what the details
-- add (overlap_area: sidewalks on roadways or on each other, blocks on streets), the area where
-- roadways (sections, junctions) overlap each other there (roadway_overlap_area: the engine splits
-- such overlaps, see surface_quality), and the area covered by nothing (gap_area). Overlays
-- snap to a micrometre grid (OverlayNG with a grid size): without it GEOS throws on some
-- nearly coincident edges of real networks.
CREATE FUNCTION streetgen.detail_quality(model text,
    OUT sidewalks bigint, OUT crossings bigint, OUT blocks bigint, OUT invalid_geometries bigint,
    OUT sidewalk_area double precision, OUT sidewalk_roadway_overlap_area double precision,
    OUT sidewalk_overlap_area double precision, OUT crossing_outside_area double precision,
    OUT face_area double precision, OUT overlap_area double precision, OUT roadway_overlap_area double precision,
    OUT gap_area double precision)
  RETURNS record
  LANGUAGE plpgsql STABLE
  SET search_path FROM CURRENT
  SET jit = off
  AS $$
BEGIN
  PERFORM streetgen.model_srid(model);
  -- (w and roadway are inlined, not materialized: each block's face and each sidewalk finds its
  -- neighbours by box through the tables' GiST indexes. Materialized, as a CTE used twice is by
  -- default, every one of those lookups read them whole: Reisterstown 323 s -> 35 s, the same sums;
  -- Paris more than 27 minutes, cancelled -> 5.7 minutes.)
  EXECUTE format($q$
    WITH w AS NOT MATERIALIZED (
      SELECT w.*, coalesce(a.layer, n.layer) AS layer
        FROM %1$I.sidewalk w LEFT JOIN %1$I.axis a ON a.id = w.axis_id LEFT JOIN %1$I.node n ON n.id = w.node_id),
    roadway AS NOT MATERIALIZED (
      SELECT s.geom, a.layer FROM %1$I.section s JOIN %1$I.axis a ON a.id = s.axis_id WHERE s.geom IS NOT NULL
      UNION ALL SELECT i.geom, n.layer FROM %1$I.intersection i JOIN %1$I.node n ON n.id = i.node_id),
    tiles AS (
      SELECT ST_Area(b.face) AS a, coalesce(ST_Area(b.geom), 0) AS b, p.r_sum, p.w_sum, ST_Area(p.r_union) AS r_union,
             ST_Area(p.s_union) AS s_union,
             CASE WHEN b.geom IS NULL OR p.s_union IS NULL THEN 0 ELSE ST_Area(ST_Intersection(b.geom, p.s_union, 1e-6)) END AS bs
        FROM %1$I.block b,
             LATERAL (SELECT coalesce(sum(ST_Area(x.piece)) FILTER (WHERE x.roadway), 0) AS r_sum,
                             coalesce(sum(ST_Area(x.piece)) FILTER (WHERE NOT x.roadway), 0) AS w_sum,
                             coalesce(ST_Union(x.piece, 1e-6) FILTER (WHERE x.roadway), 'GEOMETRYCOLLECTION EMPTY') AS r_union,
                             ST_Union(x.piece, 1e-6) AS s_union
                        FROM (SELECT g.roadway, ST_CollectionExtract(ST_Intersection(b.face, g.geom, 1e-6), 3) AS piece
                                FROM (SELECT true AS roadway, geom FROM roadway WHERE layer = 0 AND geom && b.face
                                      UNION ALL SELECT false, geom FROM w WHERE layer = 0 AND geom && b.face) AS g) AS x) AS p)
    SELECT (SELECT count(*) FROM %1$I.sidewalk),
           (SELECT count(*) FROM %1$I.crossing),
           (SELECT count(*) FROM %1$I.block),
           (SELECT count(*) FROM %1$I.sidewalk WHERE NOT ST_IsValid(geom) OR ST_IsEmpty(geom))
             + (SELECT count(*) FROM %1$I.crossing WHERE NOT ST_IsValid(geom) OR ST_IsEmpty(geom))
             + (SELECT count(*) FROM %1$I.block WHERE NOT ST_IsValid(face) OR (geom IS NOT NULL AND NOT ST_IsValid(geom))),
           coalesce((SELECT sum(ST_Area(geom)) FROM %1$I.sidewalk), 0),
           coalesce((SELECT sum(ST_Area(ST_Intersection(w.geom, r.geom, 1e-6))) FROM w JOIN roadway r ON r.geom && w.geom AND r.layer = w.layer), 0),
           coalesce((SELECT sum(ST_Area(ST_Intersection(a.geom, b.geom, 1e-6)))
                       FROM w a JOIN w b ON a.geom && b.geom AND a.layer = b.layer
                        AND (coalesce(a.axis_id, 0), coalesce(a.part, 0), coalesce(a.node_id, 0), a.side)
                          < (coalesce(b.axis_id, 0), coalesce(b.part, 0), coalesce(b.node_id, 0), b.side)), 0),
           coalesce((SELECT sum(ST_Area(ST_Difference(c.geom, s.geom, 1e-6))) FROM %1$I.crossing c JOIN %1$I.section s USING (axis_id, part)), 0),
           coalesce((SELECT sum(a) FROM tiles), 0),
           coalesce((SELECT sum(r_union + w_sum - s_union + bs) FROM tiles), 0),
           coalesce((SELECT sum(r_sum - r_union) FROM tiles), 0),
           coalesce((SELECT sum(a - (b + s_union - bs)) FROM tiles), 0)
  $q$, model)
  INTO sidewalks, crossings, blocks, invalid_geometries, sidewalk_area, sidewalk_roadway_overlap_area,
       sidewalk_overlap_area, crossing_outside_area, face_area, overlap_area, roadway_overlap_area, gap_area;
END
$$;
COMMENT ON FUNCTION streetgen.detail_quality(text) IS
  'Checks a model''s sidewalks, crossings and blocks: validity, sidewalks on roadways or on each other, crossings outside their section, and how blocks, street surfaces and sidewalks tile the network''s bounded faces';
