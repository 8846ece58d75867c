-- Deletes a random axis (its sections, corners and issues go by cascade, before the recompute).
SELECT max(id) AS maxid FROM axis \gset
\set id random(1, :maxid)
WITH e AS (DELETE FROM axis WHERE id = (SELECT id FROM axis WHERE id >= :id ORDER BY id LIMIT 1) RETURNING id)
INSERT INTO soak_log (kind, axis_id) SELECT 'delete', id FROM e;
