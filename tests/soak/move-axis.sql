-- Moves a random axis by up to 3 m (its nodes and neighbours follow in the recompute).
SELECT max(id) AS maxid FROM axis \gset
\set id random(1, :maxid)
\set dx random(-300, 300)
\set dy random(-300, 300)
WITH e AS (UPDATE axis SET geom = ST_Translate(geom, :dx / 100.0, :dy / 100.0)
            WHERE id = (SELECT id FROM axis WHERE id >= :id ORDER BY id LIMIT 1) RETURNING id)
INSERT INTO soak_log (kind, axis_id, dx_cm, dy_cm) SELECT 'move', id, :dx, :dy FROM e;
