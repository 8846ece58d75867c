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

SELECT * FROM finish();
ROLLBACK;
