-- Diagnosis of a failed soak (not run by run-soak.sh): replays the soak's log in commit order in
-- one session, on a fresh import of the same city as model "replay", and names the first edit
-- after which streetgen.outdated is not empty. None: the failure needed concurrency. In the soak's
-- database (streetgen_soak), e.g. checking after every 100th edit, then every edit from the
-- window found (re-import first):
--   scripts/streetgen-import -m replay ../shared/data/osm/liechtenstein.osm.pbf
--   psql -v from=1 -v every=100 -f tests/soak/replay.sql
-- A failure seen only in a CI log (its cluster gone): run-soak.sh printed the log between
-- soak_log:begin and soak_log:end. In a fresh database with streetgen:
--   scripts/streetgen-import -m replay ../shared/data/osm/liechtenstein.osm.pbf
--   psql -v model=replay -f tests/soak/setup.sql
--   psql -c 'ALTER TABLE soak_log DISABLE TRIGGER commit_order'
--   sed -n '/^soak_log:begin/,/^soak_log:end/{//!p}' ci.log | psql -c '\copy soak_log FROM STDIN CSV'
--   psql -v from=1 -v every=100 -f tests/soak/replay.sql
CREATE TEMP TABLE replay_id (soak_id bigint PRIMARY KEY, id bigint);

CREATE FUNCTION pg_temp.apply(l soak_log) RETURNS void LANGUAGE plpgsql AS $$
DECLARE
  a bigint := coalesce((SELECT id FROM pg_temp.replay_id WHERE soak_id = l.axis_id), l.axis_id);
BEGIN
  CASE l.kind
    WHEN 'move' THEN UPDATE replay.axis SET geom = ST_Translate(geom, l.dx_cm / 100.0, l.dy_cm / 100.0) WHERE id = a;
    WHEN 'vertex' THEN UPDATE replay.axis
      SET geom = ST_SetPoint(geom, l.vertex, ST_Translate(ST_PointN(geom, l.vertex + 1), l.dx_cm / 100.0, l.dy_cm / 100.0))
      WHERE id = a;
    WHEN 'width' THEN UPDATE replay.axis SET roadway_width = roadway_width + l.d WHERE id = a;
    WHEN 'speed' THEN UPDATE replay.axis SET speed_kmh = speed_kmh + l.d WHERE id = a;
    WHEN 'delete' THEN DELETE FROM replay.axis WHERE id = a;
    WHEN 'insert' THEN
      WITH i AS (INSERT INTO replay.axis (geom, roadway_width, speed_kmh, source)
                 VALUES (l.geom, l.roadway_width, l.speed_kmh, 'soak') RETURNING id)
      INSERT INTO pg_temp.replay_id SELECT l.axis_id, id FROM i;
  END CASE;
END
$$;

-- Each edit commits on its own, as in the soak (a procedure, so that a long replay is not one
-- transaction).
CREATE PROCEDURE pg_temp.replay(first bigint, every integer) LANGUAGE plpgsql AS $$
DECLARE
  l soak_log;
  n bigint := 0;
  total bigint := (SELECT count(*) FROM soak_log);
  bad text;
BEGIN
  FOR l IN SELECT * FROM soak_log ORDER BY refresh, seq LOOP
    n := n + 1;
    PERFORM pg_temp.apply(l);
    COMMIT;
    CONTINUE WHEN n < first OR ((n - first + 1) % every <> 0 AND n < total);
    SELECT string_agg(kind || ' ' || key || ' ' || what, '; ') INTO bad FROM streetgen.outdated('replay');
    IF bad IS NOT NULL THEN
      RAISE WARNING 'after edit % (% of axis %, soak_log.seq %): %', n, l.kind, l.axis_id, l.seq, bad;
      RETURN;
    END IF;
  END LOOP;
  RAISE WARNING 'all % edits replayed, the outputs current at every check', n;
END
$$;

CALL pg_temp.replay(:from, :every);
