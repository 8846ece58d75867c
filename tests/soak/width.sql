-- Widens or narrows a random axis by 0.5 m; an edit that would leave 2..30 m does nothing (and
-- logs nothing), so the widths cannot drift out of the table's range.
SELECT max(id) AS maxid FROM axis \gset
\set id random(1, :maxid)
\set d 2 * random(0, 1) - 1
WITH e AS (UPDATE axis SET roadway_width = roadway_width + :d * 0.5
            WHERE id = (SELECT id FROM axis WHERE id >= :id ORDER BY id LIMIT 1)
              AND roadway_width + :d * 0.5 BETWEEN 2 AND 30 RETURNING id)
INSERT INTO soak_log (kind, axis_id, d) SELECT 'width', id, :d * 0.5 FROM e;
