-- Junctions give way to the sections over them and split their overlaps with each other (the
-- engine's separate_overlapping_junctions); the triggers keep that current: a junction's shape
-- now depends on roadways that do not share its node, so an edit of one must rewrite the other.
-- Two carriageways 8 m apart and 10 m wide, each with a branch leaving at 6° from the same
-- abscissa: the two junctions reach over each other and over the other carriageway. Once with
-- sidewalks (their reach widens the refresh's search) and once without (reach 0).
BEGIN;
SELECT * FROM no_plan();

CREATE FUNCTION pg_temp.roadway_overlap(model text) RETURNS double precision LANGUAGE plpgsql AS $$
DECLARE
  a double precision;
BEGIN
  EXECUTE format($q$
    WITH r AS (SELECT 's' || s.axis_id || '/' || s.part AS k, s.geom FROM %1$I.section s WHERE s.geom IS NOT NULL
               UNION ALL SELECT 'j' || i.node_id, i.geom FROM %1$I.intersection i)
    SELECT coalesce(sum(ST_Area(ST_Intersection(a.geom, b.geom, 1e-6))), 0) FROM r a JOIN r b ON a.k < b.k AND a.geom && b.geom$q$,
    model) INTO a;
  RETURN a;
END
$$;

CREATE FUNCTION pg_temp.load(model text, sidewalk double precision) RETURNS void LANGUAGE plpgsql AS $$
BEGIN
  PERFORM streetgen.create_model(model, 32631);
  EXECUTE format('UPDATE %I.settings SET default_sidewalk_width = %s', model, sidewalk);
  EXECUTE format($q$INSERT INTO %I.axis (id, geom, roadway_width, speed_kmh, road_class) OVERRIDING SYSTEM VALUE VALUES
    (1, 'SRID=32631;LINESTRING(-100 0, 100 0)', 10, 50, 'residential'),
    (2, 'SRID=32631;LINESTRING(-100 8, 100 8)', 10, 50, 'residential'),
    (3, 'SRID=32631;LINESTRING(0 0, 100 -10)', 8, 50, 'residential'),
    (4, 'SRID=32631;LINESTRING(0 8, -100 18)', 8, 50, 'residential')$q$, model);
END
$$;

SELECT pg_temp.load('packed', 2);
SELECT pg_temp.load('packed_bare', 0);

SELECT is((SELECT count(*) FROM packed.intersection WHERE status = 'narrowed'), 2::bigint,
          'both junctions reach over the other carriageway and each other: narrowed');
SELECT cmp_ok(pg_temp.roadway_overlap('packed'), '<', 1e-3::double precision, 'and no roadway overlaps another');
SELECT cmp_ok((SELECT count(*) FROM packed.sidewalk), '>', 0::bigint, 'the first model has sidewalks');
SELECT is((SELECT count(*) FROM packed_bare.sidewalk), 0::bigint, 'the second none');

-- Edits that move one junction over the other, or away: the other is rewritten with it.
CREATE FUNCTION pg_temp.edits(model text) RETURNS SETOF text LANGUAGE plpgsql AS $$
DECLARE
  step text;
BEGIN
  FOREACH step IN ARRAY ARRAY[
    -- the first branch's junction slides along its carriageway, under the other one
    'UPDATE %1$I.axis SET geom = ST_Translate(geom, -6, 0) WHERE id = 3',
    -- and the first carriageway follows it to its start point (a new node there)
    'UPDATE %1$I.axis SET geom = ST_SetPoint(geom, 0, ST_SetSRID(ST_MakePoint(-100, -1), 32631)) WHERE id = 1',
    -- the second carriageway widens over the first junction
    'UPDATE %1$I.axis SET roadway_width = 14 WHERE id = 2',
    -- the second branch goes: its junction is gone and the first one keeps what they shared
    'DELETE FROM %1$I.axis WHERE id = 4',
    -- and comes back at another angle
    $s$INSERT INTO %1$I.axis (id, geom, roadway_width, speed_kmh, road_class) OVERRIDING SYSTEM VALUE
       VALUES (4, 'SRID=32631;LINESTRING(-3 8, -100 26)', 8, 50, 'residential')$s$,
    -- the first carriageway moves away from the second: nothing is shared any more
    'UPDATE %1$I.axis SET geom = ST_Translate(geom, 0, -12) WHERE id IN (1, 3)']
  LOOP
    EXECUTE format(step, model);
    RETURN NEXT format('%s, %s: outdated %s, roadway overlap %s m²', model, left(format(step, model), 60),
                       (SELECT count(*) FROM streetgen.outdated(model)), round(pg_temp.roadway_overlap(model)::numeric, 4));
  END LOOP;
END
$$;
CREATE TEMP TABLE done AS SELECT e FROM pg_temp.edits('packed') e UNION ALL SELECT e FROM pg_temp.edits('packed_bare') e;
SELECT is_empty($$SELECT e FROM done WHERE e NOT LIKE '%outdated 0,%'$$,
                'after every edit the outputs equal a full recompute, with and without sidewalks');
SELECT is_empty($$SELECT e FROM done WHERE e NOT LIKE '%roadway overlap 0.0000 m²'$$,
                'and no roadway overlaps another');
SELECT is((SELECT count(*) FROM done), 12::bigint, 'six edits on each model');

SELECT * FROM finish();
ROLLBACK;
