-- The invariant of the always-current triggers on a real city: after each of 200 random edits
-- (moves of axes and of single vertices, new axes between junctions, deletions, width and
-- speed changes), the tables equal a full recompute of the same axes (streetgen.outdated is
-- empty). Deterministic: setseed.
BEGIN;
SELECT * FROM no_plan();

CREATE FUNCTION pg_temp.random_edit(model text) RETURNS text LANGUAGE plpgsql AS $$
DECLARE
  r float8 := random();
  id bigint;
  n int;
BEGIN
  EXECUTE format('SELECT id FROM %I.axis ORDER BY id OFFSET floor(random() * (SELECT count(*) FROM %I.axis)) LIMIT 1', model, model)
    INTO id;
  IF r < 0.25 THEN
    EXECUTE format('UPDATE %I.axis SET geom = ST_Translate(geom, $1, $2) WHERE id = $3', model)
      USING (random() - 0.5) * 30, (random() - 0.5) * 30, id;
    RETURN 'move ' || id;
  ELSIF r < 0.45 THEN
    EXECUTE format('SELECT ST_NPoints(geom) FROM %I.axis WHERE id = $1', model) INTO n USING id;
    EXECUTE format('UPDATE %I.axis SET geom = ST_SetPoint(geom, $1, ST_Translate(ST_PointN(geom, $1 + 1), $2, $3)) WHERE id = $4', model)
      USING floor(random() * n)::int, (random() - 0.5) * 20, (random() - 0.5) * 20, id;
    RETURN 'move a vertex of ' || id;
  ELSIF r < 0.6 THEN
    EXECUTE format($q$INSERT INTO %1$I.axis (geom, roadway_width, speed_kmh)
      SELECT ST_MakeLine(a.geom, b.geom), 3 + random() * 8, 20 + random() * 40
        FROM (SELECT geom FROM %1$I.node ORDER BY random() LIMIT 1) a,
             LATERAL (SELECT geom FROM %1$I.node n2 WHERE ST_DWithin(n2.geom, a.geom, 150) AND NOT ST_Equals(n2.geom, a.geom)
                       ORDER BY random() LIMIT 1) b$q$, model);
    RETURN 'insert';
  ELSIF r < 0.75 THEN
    EXECUTE format('DELETE FROM %I.axis WHERE id = $1', model) USING id;
    RETURN 'delete ' || id;
  ELSIF r < 0.9 THEN
    EXECUTE format('UPDATE %I.axis SET roadway_width = 3 + random() * 12 WHERE id = $1', model) USING id;
    RETURN 'width of ' || id;
  END IF;
  EXECUTE format('UPDATE %I.axis SET speed_kmh = 10 + random() * 80 WHERE id = $1', model) USING id;
  RETURN 'speed of ' || id;
END $$;

-- The first edit after which the tables are not current, or NULL.
CREATE FUNCTION pg_temp.first_outdated(model text, edits int) RETURNS text LANGUAGE plpgsql AS $$
DECLARE
  what text;
  bad text;
BEGIN
  FOR i IN 1..edits LOOP
    what := pg_temp.random_edit(model);
    SELECT string_agg(kind || ' ' || key || ' ' || o.what, '; ') INTO bad FROM (SELECT * FROM streetgen.outdated(model) LIMIT 5) o;
    IF bad IS NOT NULL THEN
      RETURN format('edit %s (%s): %s', i, what, bad);
    END IF;
  END LOOP;
  RETURN NULL;
END $$;

SELECT is((SELECT count(*) FROM streetgen.outdated('paris_11e')), 0::bigint, 'after the import, the surfaces are current');
SELECT setseed(0.42);
SELECT is(pg_temp.first_outdated('paris_11e', 200), NULL, 'after each of 200 random edits, the tables equal a full recompute');
SELECT is((SELECT invalid_geometries FROM streetgen.surface_quality('paris_11e')), 0::bigint, 'and every output is still valid');

SELECT * FROM finish();
ROLLBACK;
