-- Moves one vertex (an end point half the time on two-point axes) of a random axis by up to 2 m.
SELECT max(id) AS maxid FROM axis \gset
\set id random(1, :maxid)
\set v random(0, 9999)
\set dx random(-200, 200)
\set dy random(-200, 200)
WITH e AS (UPDATE axis SET geom = ST_SetPoint(geom, :v % ST_NPoints(geom),
                                              ST_Translate(ST_PointN(geom, :v % ST_NPoints(geom) + 1), :dx / 100.0, :dy / 100.0))
            WHERE id = (SELECT id FROM axis WHERE id >= :id ORDER BY id LIMIT 1)
           RETURNING id, :v % ST_NPoints(geom) AS vertex)
INSERT INTO soak_log (kind, axis_id, vertex, dx_cm, dy_cm) SELECT 'vertex', id, vertex, :dx, :dy FROM e;
