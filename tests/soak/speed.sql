-- Speeds up or slows down a random axis by 5 km/h (the corner radii follow), within 5..130 km/h.
SELECT max(id) AS maxid FROM axis \gset
\set id random(1, :maxid)
\set d 2 * random(0, 1) - 1
WITH e AS (UPDATE axis SET speed_kmh = speed_kmh + :d * 5
            WHERE id = (SELECT id FROM axis WHERE id >= :id ORDER BY id LIMIT 1)
              AND speed_kmh + :d * 5 BETWEEN 5 AND 130 RETURNING id)
INSERT INTO soak_log (kind, axis_id, d) SELECT 'speed', id, :d * 5 FROM e;
