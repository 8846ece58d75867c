-- Sidewalks, crossings and blocks on real data (run-details.sh loads every osm2streets case and
-- three OSM extracts): the acceptance measures of issue 5 on each network, one test per
-- property, then the invariant of the triggers over random edits.
BEGIN;
SELECT * FROM no_plan();

CREATE TEMP TABLE measured AS
  SELECT d.model, d.kind, q.* FROM detail_dataset d, LATERAL streetgen.detail_quality(d.model) q;

SELECT cmp_ok((SELECT count(*) FROM measured WHERE kind = 'osm2streets'), '>=', 25::bigint, 'every osm2streets case is loaded');
SELECT is((SELECT count(*) FROM measured WHERE kind = 'osm'), 3::bigint, 'three OSM extracts are loaded');
SELECT is_empty($$SELECT model FROM measured WHERE kind = 'osm' AND (sidewalks = 0 OR crossings = 0 OR blocks = 0)$$,
                'every OSM extract has sidewalks, crossings and blocks');
SELECT is_empty($$SELECT model, invalid_geometries FROM measured WHERE invalid_geometries > 0$$,
                'every sidewalk, crossing and block is valid (ST_IsValid, not empty)');
SELECT is_empty($$SELECT model, sidewalk_roadway_overlap_area FROM measured
                   WHERE sidewalk_roadway_overlap_area >= 0.001 * greatest(sidewalk_area, 1e-9)$$,
                'sidewalks do not overlap a roadway of their layer (< 0.1 % of their area)');
SELECT is_empty($$SELECT model, sidewalk_overlap_area FROM measured WHERE sidewalk_overlap_area >= 0.001 * greatest(sidewalk_area, 1e-9)$$,
                'sidewalks do not overlap each other (< 0.1 % of their area)');
SELECT is_empty($$SELECT model, crossing_outside_area FROM measured WHERE crossing_outside_area >= 1e-3$$,
                'crossings lie in their section (< 0.001 m2 per network)');
SELECT is_empty($$SELECT model, overlap_area, face_area FROM measured WHERE overlap_area >= 0.001 * face_area AND face_area > 0$$,
                'blocks, sidewalks and the street surfaces do not overlap inside the network''s bounded faces (< 0.1 % of their area)');
SELECT is_empty($$SELECT model, roadway_overlap_area, face_area FROM measured WHERE roadway_overlap_area >= 0.001 * face_area AND face_area > 0$$,
                'roadways (sections, junctions) do not overlap each other inside the network''s bounded faces (< 0.1 % of their area)');
SELECT is_empty($$SELECT model, gap_area, face_area FROM measured WHERE abs(gap_area) >= 0.001 * face_area AND face_area > 0$$,
                'blocks, street surfaces and sidewalks leave no gap in the network''s bounded faces (< 0.1 % of their area)');
-- Traffic islands where the geometry makes them: between the carriageways of a dual carriageway
-- and in the triangle of a slip lane.
CREATE FUNCTION pg_temp.islands(model text) RETURNS bigint LANGUAGE plpgsql AS $f$
DECLARE
  n bigint;
BEGIN
  EXECUTE format('SELECT count(*) FROM %I.block WHERE kind = ''island''', model) INTO n;
  RETURN n;
END
$f$;
SELECT is_empty($$SELECT d.model, pg_temp.islands(d.model) FROM detail_dataset d
                   WHERE d.model IN ('c_northgate_dual_carriageway', 'c_seattle_slip_lane', 'c_arizona_highways')
                     AND pg_temp.islands(d.model) = 0$$,
                'dual carriageways and slip lanes have traffic islands');
SELECT is((SELECT count(*) FROM detail_dataset d
            WHERE d.model IN ('c_northgate_dual_carriageway', 'c_seattle_slip_lane', 'c_arizona_highways')), 3::bigint,
          'and those three cases are loaded');
-- Blocks are the faces: as many as PostGIS finds in the layer-0 axes, noded (an independent
-- count: ST_Node of the raw axes, not the engine's topology; ends the engine snapped make the
-- difference, so within 2 %).
SELECT is_empty($$SELECT p.model, p.blocks, p.faces FROM (
                    SELECT 'paris_11e' AS model, (SELECT count(*) FROM paris_11e.block) AS blocks,
                           (SELECT count(*) FROM (SELECT (ST_Dump(ST_Polygonize(g))).geom
                                                    FROM (SELECT (ST_Dump(ST_Node(ST_Collect(geom)))).geom AS g
                                                            FROM paris_11e.axis WHERE layer = 0) n) f) AS faces) p
                   WHERE abs(p.blocks - p.faces) > 0.02 * p.faces$$,
                'Paris 11e: one block per bounded face of the ground-level axes');
-- Tags were read: Paris tags sidewalks on many streets.
SELECT cmp_ok((SELECT count(*) FROM paris_11e.sidewalk w JOIN paris_11e.axis a ON a.id = w.axis_id
                WHERE a.tags ?| ARRAY['sidewalk', 'sidewalk:both', 'sidewalk:left', 'sidewalk:right']), '>', 0::bigint,
              'Paris: sidewalks on streets with sidewalk tags');
SELECT is_empty($$SELECT w.axis_id FROM paris_11e.sidewalk w JOIN paris_11e.axis a ON a.id = w.axis_id
                   WHERE a.tags->>'sidewalk' IN ('no', 'none', 'separate')
                      OR (a.tags->>'sidewalk' IS NULL AND NOT a.tags ?| ARRAY['sidewalk:both', 'sidewalk:left', 'sidewalk:right']
                          AND a.road_class IN ('motorway', 'trunk', 'service', 'living_street'))$$,
                'Paris: no sidewalk where tags say none or separate, nor by class rule on service roads and living streets');
SELECT is_empty($$SELECT c.axis_id FROM paris_11e.crossing c JOIN paris_11e.node n ON n.id = c.node_id
                   JOIN paris_11e.axis a ON a.id = c.axis_id
                  WHERE n.degree < 3 OR a.speed_kmh > 50$$,
                'Paris: crossings only at junctions of three or more streets, on streets of 50 km/h or less');

-- The invariant, on Paris 11e: random edits of sidewalks, widths and geometries, deletions and
-- insertions.
CREATE FUNCTION pg_temp.random_detail_edit() RETURNS text LANGUAGE plpgsql AS $$
DECLARE
  r float8 := random();
  v_id bigint;
BEGIN
  SELECT a.id INTO v_id FROM paris_11e.axis a ORDER BY a.id OFFSET floor(random() * (SELECT count(*) FROM paris_11e.axis)) LIMIT 1;
  IF r < 0.2 THEN
    UPDATE paris_11e.axis SET sidewalk_width = round((random() * 6)::numeric, 1) WHERE axis.id = v_id;
    RETURN 'sidewalk_width of ' || v_id;
  ELSIF r < 0.35 THEN
    UPDATE paris_11e.axis SET tags = tags || jsonb_build_object(
      (ARRAY['sidewalk', 'sidewalk:left', 'sidewalk:right:width', 'sidewalk:both'])[1 + floor(random() * 4)::int],
      (ARRAY['both', 'left', 'no', 'separate', 'yes', '3.5', 'junk'])[1 + floor(random() * 7)::int])
     WHERE axis.id = v_id;
    RETURN 'sidewalk tags of ' || v_id;
  ELSIF r < 0.5 THEN
    UPDATE paris_11e.axis SET roadway_width = 3 + random() * 15 WHERE axis.id = v_id;
    RETURN 'width of ' || v_id;
  ELSIF r < 0.6 THEN
    DELETE FROM paris_11e.axis WHERE axis.id = v_id;
    RETURN 'delete ' || v_id;
  ELSIF r < 0.7 THEN
    INSERT INTO paris_11e.axis (geom, roadway_width, speed_kmh, road_class)
    SELECT ST_MakeLine(ST_StartPoint(a.geom), ST_EndPoint(b.geom)), 6, 30, 'residential'
      FROM paris_11e.axis a, paris_11e.axis b
     WHERE a.id = v_id AND b.id <> a.id AND ST_DWithin(ST_StartPoint(a.geom), ST_EndPoint(b.geom), 150)
       AND ST_Distance(ST_StartPoint(a.geom), ST_EndPoint(b.geom)) > 20
     ORDER BY b.id LIMIT 1;
    RETURN 'insert near ' || v_id;
  END IF;
  UPDATE paris_11e.axis SET geom = ST_Translate(geom, (random() - 0.5) * 20, (random() - 0.5) * 20) WHERE axis.id = v_id;
  RETURN 'move ' || v_id;
END $$;
CREATE FUNCTION pg_temp.first_outdated(edits int) RETURNS text LANGUAGE plpgsql AS $$
DECLARE
  what text;
  bad text;
BEGIN
  FOR i IN 1..edits LOOP
    what := pg_temp.random_detail_edit();
    SELECT string_agg(kind || ' ' || key || ' ' || o.what, '; ') INTO bad FROM (SELECT * FROM streetgen.outdated('paris_11e') LIMIT 5) o;
    IF bad IS NOT NULL THEN
      RETURN format('edit %s (%s): %s', i, what, bad);
    END IF;
  END LOOP;
  RETURN NULL;
END $$;
SELECT is((SELECT count(*) FROM streetgen.outdated('paris_11e')), 0::bigint, 'after the import, sidewalks, crossings and blocks are current');
SELECT setseed(0.25);
SELECT is(pg_temp.first_outdated(25), NULL, 'after each of 25 random sidewalk, width, geometry, delete and insert edits, the tables equal a full recompute');
SELECT is((SELECT invalid_geometries FROM streetgen.detail_quality('paris_11e')), 0::bigint, 'and every sidewalk, crossing and block is still valid');

SELECT * FROM finish();
ROLLBACK;
