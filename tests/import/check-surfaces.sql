-- Street surfaces on every imported real network (run-import.sh loads them): the acceptance
-- measures hold on each.
BEGIN;
SELECT * FROM no_plan();

CREATE TEMP TABLE generated AS
  SELECT f.model, (SELECT sum(g.count) FROM streetgen.generate(f.model) g) AS rows_generated FROM import_fact f;
CREATE TEMP TABLE measured AS
  SELECT f.model, q.* FROM import_fact f, LATERAL streetgen.surface_quality(f.model) q;

SELECT cmp_ok((SELECT count(*) FROM measured), '>=', 6::bigint, 'surfaces generated for every imported network');
SELECT is_empty($$SELECT model, invalid_geometries FROM measured WHERE invalid_geometries > 0$$,
                'every generated geometry is valid (ST_IsValid)');
SELECT is_empty($$SELECT model, missing_intersections FROM measured WHERE missing_intersections > 0$$,
                'every node of degree >= 2 has an intersection surface');
SELECT is_empty($$SELECT model, section_overlap_ratio FROM measured WHERE section_overlap_ratio >= 0.001$$,
                'sections of different axes on a layer overlap by less than 0.1 % of the surface');
SELECT is_empty($$SELECT model, intersection_overlap_area, surface_area FROM measured
                   WHERE intersection_overlap_area >= 0.001 * greatest(surface_area, 1e-9)$$,
                'junctions overlap sections or other junctions of their layer by less than 0.1 % of the surface');
SELECT is_empty($$SELECT model FROM measured WHERE intersections = 0 OR sections = 0$$,
                'every network has sections and intersections');

-- Munich imported again as street surfaces only (streetgen-import -c details=false): the same
-- nodes, sections, corners and junctions as the full import, and no lanes, markings, crossings,
-- sidewalks or blocks.
SELECT is((SELECT details FROM munich_surfaces.settings), false, 'streetgen-import -c details=false set the new model''s setting');
SELECT cmp_ok((SELECT count(*) FROM munich_surfaces.section), '>', 0::bigint, 'the surfaces-only import built the sections');
SELECT is((SELECT count(*) FROM munich_surfaces.lane) + (SELECT count(*) FROM munich_surfaces.marking)
          + (SELECT count(*) FROM munich_surfaces.crossing) + (SELECT count(*) FROM munich_surfaces.sidewalk)
          + (SELECT count(*) FROM munich_surfaces.block), 0::bigint,
          'and no lanes, markings, crossings, sidewalks or blocks');
SELECT set_eq($$SELECT a.source, s.part, s.status, ST_AsEWKB(s.geom) FROM munich_surfaces.section s JOIN munich_surfaces.axis a ON a.id = s.axis_id$$,
              $$SELECT a.source, s.part, s.status, ST_AsEWKB(s.geom) FROM munich.section s JOIN munich.axis a ON a.id = s.axis_id$$,
              'its sections are the full import''s, to the byte (axes matched by their OSM source)');
SELECT set_eq($$SELECT i.status, ST_AsEWKB(i.geom) FROM munich_surfaces.intersection i$$,
              $$SELECT i.status, ST_AsEWKB(i.geom) FROM munich.intersection i$$,
              'and so are its junctions');
SELECT set_eq($$SELECT c.status, c.radius, ST_AsEWKB(c.arc) FROM munich_surfaces.corner c$$,
              $$SELECT c.status, c.radius, ST_AsEWKB(c.arc) FROM munich.corner c$$,
              'and its corners');
SELECT is_empty('SELECT * FROM streetgen.outdated(''munich_surfaces'')', 'a surfaces-only model equals a full recompute');

SELECT * FROM finish();
ROLLBACK;
