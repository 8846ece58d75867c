-- A new axis from the node at the end of a random axis to one of that node's four nearest
-- neighbours: new junctions and crossings among existing streets.
SELECT max(id) AS maxid FROM axis \gset
\set id random(1, :maxid)
\set k random(1, 4)
WITH a AS (SELECT n.geom FROM axis x,
                  LATERAL (SELECT geom FROM node ORDER BY geom <-> ST_EndPoint(x.geom) LIMIT 1) n
            WHERE x.id = (SELECT id FROM axis WHERE id >= :id ORDER BY id LIMIT 1)),
     b AS (SELECT n.geom FROM a, LATERAL (SELECT geom FROM node ORDER BY geom <-> a.geom OFFSET :k LIMIT 1) n),
     e AS (INSERT INTO axis (geom, roadway_width, speed_kmh, source)
           SELECT ST_MakeLine(a.geom, b.geom), 6, 30, 'soak' FROM a, b WHERE ST_Distance(a.geom, b.geom) > 1
           RETURNING id, geom, roadway_width, speed_kmh)
INSERT INTO soak_log (kind, axis_id, geom, roadway_width, speed_kmh)
SELECT 'insert', id, geom, roadway_width, speed_kmh FROM e;
