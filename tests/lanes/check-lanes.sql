-- Lanes and markings on real data (run-lanes.sh loads every osm2streets case and three OSM
-- extracts): the acceptance measures of issue 5 on each network, then the invariant of the
-- triggers over random edits of lane counts, one-way flags, lane tags and geometries.
BEGIN;
SELECT * FROM no_plan();

CREATE TEMP TABLE measured AS
  SELECT d.model, d.kind, q.* FROM lane_dataset d, LATERAL streetgen.lane_quality(d.model) q;

SELECT cmp_ok((SELECT count(*) FROM measured WHERE kind = 'osm2streets'), '>=', 25::bigint, 'every osm2streets case is loaded');
SELECT is((SELECT count(*) FROM measured WHERE kind = 'osm'), 3::bigint, 'three OSM extracts are loaded');
SELECT is_empty($$SELECT model FROM measured WHERE sections = 0 OR lanes = 0 OR markings = 0$$,
                'every network has sections, lanes and markings');
SELECT is_empty($$SELECT model, sections_without_lanes FROM measured WHERE sections_without_lanes > 0$$,
                'every section with a surface has lanes');
SELECT is_empty($$SELECT model, invalid_geometries FROM measured WHERE invalid_geometries > 0$$,
                'every lane and marking is valid (ST_IsValid, not empty)');
SELECT is_empty($$SELECT model, max_coverage_difference FROM measured WHERE sections_over_tolerance > 0$$,
                'the lanes of every section cover it: symmetric difference < 0.5 % of its area');
SELECT is_empty($$SELECT model, lane_overlap_area FROM measured WHERE abs(lane_overlap_area) >= 1e-3$$,
                'lanes of a section do not overlap (< 0.001 m2 per network)');
SELECT is_empty($$SELECT model, outside_section_area FROM measured WHERE outside_section_area >= 1e-3$$,
                'no lane reaches out of its section (< 0.001 m2 per network)');
SELECT is_empty($$SELECT model, foreign_overlap_area FROM measured WHERE foreign_overlap_area >= 1e-3$$,
                'no lane crosses into the section of another axis on its layer (< 0.001 m2 per network)');
-- Lane tags were read where OSM has them: Reno tags lanes:forward/backward and turn lanes,
-- Paris bus and cycle lanes.
SELECT cmp_ok((SELECT count(*) FROM reno_east3.lane WHERE turn IS NOT NULL), '>', 0::bigint, 'Reno: turn lanes from turn:lanes');
SELECT cmp_ok((SELECT count(*) FROM reno_east3.lane l JOIN reno_east3.axis a ON a.id = l.axis_id
                WHERE NOT a.oneway AND l.direction = 'both' AND a.tags ? 'lanes:forward'), '>', 0::bigint,
              'Reno: shared centre lanes where lanes exceeds forward + backward');
SELECT cmp_ok((SELECT count(*) FROM paris_11e.lane WHERE type = 'bus'), '>', 0::bigint, 'Paris: bus lanes from busway');
SELECT cmp_ok((SELECT count(*) FROM paris_11e.lane WHERE type = 'cycle' AND direction = 'backward'), '>', 0::bigint,
              'Paris: contraflow cycle lanes');
-- Stop lines only at junctions of three or more streets, within their section.
SELECT is_empty($$SELECT m.axis_id, m.part FROM reno_east3.marking m JOIN reno_east3.section s USING (axis_id, part)
                   JOIN reno_east3.node n ON n.id = CASE WHEN m.position = 0 THEN s.from_node ELSE s.to_node END
                  WHERE m.kind = 'stop_line' AND n.degree < 3$$,
                'Reno: no stop line at a dead end or where a street runs on');

-- The invariant, on Reno: random edits of what shapes the lanes, and of geometry.
CREATE FUNCTION pg_temp.random_lane_edit() RETURNS text LANGUAGE plpgsql AS $$
DECLARE
  r float8 := random();
  v_id bigint;
BEGIN
  SELECT a.id INTO v_id FROM reno_east3.axis a ORDER BY a.id OFFSET floor(random() * (SELECT count(*) FROM reno_east3.axis)) LIMIT 1;
  IF r < 0.2 THEN
    UPDATE reno_east3.axis SET lanes = 1 + floor(random() * 6) WHERE axis.id = v_id;
    RETURN 'lanes of ' || v_id;
  ELSIF r < 0.35 THEN
    UPDATE reno_east3.axis SET oneway = NOT oneway WHERE axis.id = v_id;
    RETURN 'oneway of ' || v_id;
  ELSIF r < 0.6 THEN
    UPDATE reno_east3.axis SET tags = tags || jsonb_build_object(
      (ARRAY['cycleway', 'busway:right', 'lanes:forward', 'turn:lanes:forward', 'cycleway:left'])[1 + floor(random() * 5)::int],
      (ARRAY['lane', 'opposite_lane', '1', '2', 'left|through', 'track', 'junk'])[1 + floor(random() * 7)::int])
     WHERE axis.id = v_id;
    RETURN 'lane tags of ' || v_id;
  ELSIF r < 0.75 THEN
    UPDATE reno_east3.axis SET roadway_width = 3 + random() * 15 WHERE axis.id = v_id;
    RETURN 'width of ' || v_id;
  END IF;
  UPDATE reno_east3.axis SET geom = ST_Translate(geom, (random() - 0.5) * 20, (random() - 0.5) * 20) WHERE axis.id = v_id;
  RETURN 'move ' || v_id;
END $$;
CREATE FUNCTION pg_temp.first_outdated(edits int) RETURNS text LANGUAGE plpgsql AS $$
DECLARE
  what text;
  bad text;
BEGIN
  FOR i IN 1..edits LOOP
    what := pg_temp.random_lane_edit();
    SELECT string_agg(kind || ' ' || key || ' ' || o.what, '; ') INTO bad FROM (SELECT * FROM streetgen.outdated('reno_east3') LIMIT 5) o;
    IF bad IS NOT NULL THEN
      RETURN format('edit %s (%s): %s', i, what, bad);
    END IF;
  END LOOP;
  RETURN NULL;
END $$;
SELECT is((SELECT count(*) FROM streetgen.outdated('reno_east3')), 0::bigint, 'after the import, lanes and markings are current');
-- (Sidewalks and crossings off for the random edits: they are the details layer's invariant, and
-- would triple this one's time.)
UPDATE reno_east3.settings SET default_sidewalk_width = 0, crossing_width = 0;
SELECT setseed(0.5);
SELECT is(pg_temp.first_outdated(60), NULL, 'after each of 60 random lane and geometry edits, the tables equal a full recompute');
SELECT is((SELECT invalid_geometries FROM streetgen.lane_quality('reno_east3')), 0::bigint, 'and every lane and marking is still valid');

SELECT * FROM finish();
ROLLBACK;
