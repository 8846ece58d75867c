-- Example-based growth (grow_example) on real example patches of ../shared/data/examples/patches
-- (Nishida et al.'s crops of OpenStreetMap, © OpenStreetMap contributors, ODbL 1.0): planarity,
-- region and obstacles, determinism, dead ends, levels, insertion into a model, and every bad
-- input of the issue by SQLSTATE. run-pgtap.sh passes the data folder as streetgen_test.shared_data.
BEGIN;
SELECT * FROM no_plan();

CREATE TEMP TABLE patch AS
SELECT n AS name, row_number() OVER (PARTITION BY n) AS id, f -> 'properties' ->> 'type' AS road_class,
       ST_SetSRID(ST_GeomFromGeoJSON(f -> 'geometry'), 0) AS geom
  FROM unnest(ARRAY['tokyo', 'canberra_south_large', 'new-york']) AS n,
       jsonb_array_elements(pg_read_file(current_setting('streetgen_test.shared_data') || '/examples/patches/' || n
                                         || '.geojson')::jsonb -> 'features') AS f;
SELECT ok((SELECT count(DISTINCT name) = 3 AND count(*) > 2000 FROM patch), 'three real example patches loaded');

-- Regions the size of each example's extent (patch coordinates are local metres, SRID 0); a lake
-- in the middle of the canberra region.
CREATE TEMP TABLE region AS
SELECT name, ST_SetSRID(ST_Expand(ST_Extent(geom)::geometry, 0), 0) AS geom,
       ST_SetSRID(ST_Centroid(ST_Extent(geom)::geometry), 0) AS centre
  FROM patch GROUP BY name;
CREATE TEMP TABLE lake AS
SELECT ST_Buffer(ST_Translate(centre, 300, 200), 250) AS geom FROM region WHERE name = 'canberra_south_large';

CREATE TEMP TABLE grown AS
SELECT 'tokyo'::text AS name, g.* FROM region r, streetgen.grow_example(
  $$SELECT id, road_class, geom FROM patch WHERE name = 'tokyo'$$, r.geom, r.centre, NULL,
  '{"seed": 11, "rotation": false, "max_edges": 1500}') AS g WHERE r.name = 'tokyo'
UNION ALL
SELECT 'canberra', g.* FROM region r, lake l, streetgen.grow_example(
  $$SELECT id, road_class, geom FROM patch WHERE name = 'canberra_south_large'$$, r.geom,
  ST_Collect(ST_Translate(r.centre, -600, -300), ST_Translate(r.centre, 900, 900)), l.geom,
  '{"seed": 11, "max_edges": 1500}') AS g WHERE r.name = 'canberra_south_large'
UNION ALL
SELECT 'new-york', g.* FROM region r, streetgen.grow_example(
  $$SELECT id, road_class, geom FROM patch WHERE name = 'new-york'$$, r.geom, r.centre, NULL,
  '{"seed": 11, "max_edges": 1500, "epsilon": 20}') AS g WHERE r.name = 'new-york';
CREATE INDEX ON grown USING gist (geom);
ANALYZE grown;

SELECT ok((SELECT bool_and(n >= 500) FROM (SELECT count(*) AS n FROM grown GROUP BY name) c)
          AND (SELECT count(DISTINCT name) FROM grown) = 3, 'each example grows at least 500 edges');
SELECT is((SELECT max(n) FROM (SELECT count(*) AS n FROM grown GROUP BY name) c), 1500::bigint,
          'max_edges bounds the output');
SELECT is((SELECT count(*) FROM grown WHERE geom IS NULL OR ST_GeometryType(geom) <> 'ST_LineString'
                                        OR ST_Length(geom) = 0 OR ST_SRID(geom) <> 0), 0::bigint,
          'every edge is a non-degenerate LineString in the region''s SRID');

-- Planarity: two edges meet only at a node they share, and then only at that node.
SELECT is((SELECT count(*) FROM grown a JOIN grown b ON a.name = b.name AND a.id < b.id AND ST_Intersects(a.geom, b.geom)
            WHERE NOT (a.from_node IN (b.from_node, b.to_node) OR a.to_node IN (b.from_node, b.to_node))),
          0::bigint, 'planarity: no two edges cross or touch without a shared node');
SELECT is((SELECT count(*) FROM grown a JOIN grown b ON a.name = b.name AND a.id < b.id AND ST_Intersects(a.geom, b.geom)
            WHERE ST_Dimension(ST_Intersection(a.geom, b.geom)) > 0 OR ST_NPoints(ST_Intersection(a.geom, b.geom)) > 1),
          0::bigint, 'planarity: edges sharing a node do not overlap');
SELECT is((SELECT count(*) FROM grown g JOIN region r ON r.name = CASE g.name WHEN 'canberra' THEN 'canberra_south_large'
                                                                               ELSE g.name END
            WHERE NOT ST_CoveredBy(g.geom, r.geom)), 0::bigint, 'no edge leaves the region');
SELECT is((SELECT count(*) FROM grown g, lake l WHERE g.name = 'canberra' AND ST_Intersects(g.geom, l.geom)), 0::bigint,
          'no edge enters the obstacle');
SELECT ok((SELECT count(*) FROM grown g, lake l WHERE g.name = 'canberra' AND ST_DWithin(g.geom, l.geom, 60)) > 0,
          'the obstacle was in the way (edges reach up to it)');
-- Nodes: one position per id, so from_node / to_node are a graph's node ids.
SELECT is((SELECT count(*) FROM (
             SELECT name, node FROM (SELECT name, from_node AS node, ST_StartPoint(geom) AS p FROM grown
                                     UNION ALL SELECT name, to_node, ST_EndPoint(geom) FROM grown) e
              GROUP BY name, node HAVING count(DISTINCT ST_AsBinary(p)) > 1) bad), 0::bigint,
          'each node id has one position');
SELECT ok((SELECT count(*) FROM (SELECT name, node FROM (SELECT name, from_node AS node FROM grown
                                                         UNION ALL SELECT name, to_node FROM grown) e
                                  GROUP BY name, node HAVING count(*) = 1) dead) > 0,
          'dead ends are kept (the examples have them)');
SELECT ok((SELECT count(*) FROM (SELECT name, node FROM (SELECT name, from_node AS node FROM grown
                                                         UNION ALL SELECT name, to_node FROM grown) e
                                  GROUP BY name, node HAVING count(*) >= 3) j) > 300,
          'junctions are made (snapping and splitting connect the network)');
SELECT is((SELECT count(*) FROM grown g WHERE g.road_class NOT IN (SELECT DISTINCT road_class FROM patch)), 0::bigint,
          'road classes come from the example');
SELECT is((SELECT count(*) FROM grown g
            WHERE g.origin <> 'grow_parametric'
              AND NOT EXISTS (SELECT 1 FROM patch p
                               WHERE p.name = CASE g.name WHEN 'canberra' THEN 'canberra_south_large' ELSE g.name END
                                 AND 'grow_example:' || p.id = g.origin)), 0::bigint,
          'origin names the example edge each grown edge was copied from (or grow_parametric for the fallback)');
-- The parametric fallback (Teng & Bidarra) fires where no example node matches, and only then.
SELECT ok((SELECT count(*) FILTER (WHERE origin = 'grow_parametric') BETWEEN 1 AND count(*) / 5 FROM grown),
          'the parametric fallback grew some edges, and at most a fifth');
SELECT is((SELECT count(*) FROM region r, streetgen.grow_example(
             $$SELECT id, road_class, geom FROM patch WHERE name = 'new-york'$$, r.geom, r.centre, NULL,
             '{"seed": 11, "max_edges": 1500, "epsilon": 20, "fallback": false}') AS g
            WHERE r.name = 'new-york' AND g.origin = 'grow_parametric'), 0::bigint,
          'fallback false: no parametric edge');
-- A model name stands for the model's axes.
SELECT streetgen.create_model('example_model', 0);
INSERT INTO example_model.axis (geom, roadway_width, speed_kmh, road_class)
SELECT geom, 8, 30, road_class FROM patch WHERE name = 'tokyo';
SELECT is((SELECT count(*) FROM region r, streetgen.grow_example('example_model', r.geom, r.centre, NULL,
             '{"seed": 4, "max_edges": 300, "rotation": false}') AS g WHERE r.name = 'tokyo'), 300::bigint,
          'a model name is accepted as the example');
SELECT is((SELECT count(*) FROM region r, streetgen.grow_example('example_model', r.geom, r.centre, NULL,
             '{"seed": 4, "max_edges": 300, "rotation": false}') AS g
            WHERE r.name = 'tokyo' AND g.origin <> 'grow_parametric'
              AND NOT EXISTS (SELECT 1 FROM example_model.axis a WHERE 'grow_example:' || a.id = g.origin)), 0::bigint,
          'and origin names the model''s axis ids');

-- Parametric growth alone (grow_parametric): a square kilometre with a pond, the paper's
-- parameters (length 50 ± 10 m, at least 20 m, degree 2-4, 70 degree minimum angle, snap 20 m).
CREATE TEMP TABLE pond AS SELECT 'POLYGON((600 600, 800 600, 800 800, 600 800, 600 600))'::geometry AS geom;
CREATE TEMP TABLE para AS
SELECT g.* FROM pond, streetgen.grow_parametric('POLYGON((0 0, 1000 0, 1000 1000, 0 1000, 0 0))',
                                               'MULTIPOINT(500 500, 200 200)', pond.geom, '{"seed": 1}') AS g;
CREATE TEMP VIEW para_nodes AS
SELECT node, count(*) AS degree FROM (SELECT from_node AS node FROM para UNION ALL SELECT to_node FROM para) e GROUP BY node;
SELECT ok((SELECT count(*) FROM para) >= 300, 'grow_parametric fills the square (at least 300 edges)');
SELECT is((SELECT count(*) FROM para WHERE origin <> 'grow_parametric' OR road_class <> 'main'), 0::bigint,
          'its edges say grow_parametric, class main');
SELECT is((SELECT count(*) FROM para a JOIN para b ON a.id < b.id AND ST_Intersects(a.geom, b.geom)
            WHERE NOT (a.from_node IN (b.from_node, b.to_node) OR a.to_node IN (b.from_node, b.to_node))),
          0::bigint, 'parametric planarity: no crossing without a shared node');
SELECT is((SELECT count(*) FROM para WHERE NOT ST_CoveredBy(geom, 'POLYGON((0 0, 1000 0, 1000 1000, 0 1000, 0 0))'))
          + (SELECT count(*) FROM para, pond WHERE ST_Intersects(para.geom, pond.geom)), 0::bigint,
          'parametric edges stay in the region and out of the obstacle');
SELECT cmp_ok((SELECT min(ST_Length(geom)) FROM para), '>=', (20 - 1e-9)::double precision, 'no edge shorter than min_length');
SELECT ok((SELECT percentile_cont(0.5) WITHIN GROUP (ORDER BY ST_Length(geom)) BETWEEN 40 AND 60 FROM para),
          'the median edge is length ± length_deviation');
SELECT is((SELECT max(degree) FROM para_nodes), 4::bigint, 'no node above max_degree, and some at it');
SELECT ok((SELECT count(*) FILTER (WHERE degree = 3) > 10 AND count(*) FILTER (WHERE degree = 1) > 0 FROM para_nodes),
          'T junctions and dead ends');
-- The smallest angle between two edges at a node: at least min_angle (70 degrees).
SELECT cmp_ok((SELECT min(least(x, 360 - x)) FROM (SELECT abs(degrees(ST_Azimuth(a.p, a.q) - ST_Azimuth(b.p, b.q))) AS x
                 FROM (SELECT id, from_node AS n, ST_StartPoint(geom) AS p, ST_PointN(geom, 2) AS q FROM para
                       UNION ALL SELECT id, to_node, ST_EndPoint(geom), ST_PointN(geom, 1) FROM para) a
                 JOIN (SELECT id, from_node AS n, ST_StartPoint(geom) AS p, ST_PointN(geom, 2) AS q FROM para
                       UNION ALL SELECT id, to_node, ST_EndPoint(geom), ST_PointN(geom, 1) FROM para) b
                   ON a.n = b.n AND a.id < b.id) d), '>=', (70 - 1e-6)::double precision,
          'no two edges at a node closer than min_angle');
SELECT results_eq(
  $$SELECT ST_AsEWKB(geom) FROM streetgen.grow_parametric('POLYGON((0 0, 1000 0, 1000 1000, 0 1000, 0 0))',
      'POINT(500 500)', NULL, '{"seed": 9, "max_edges": 300}') ORDER BY id$$,
  $$SELECT ST_AsEWKB(geom) FROM streetgen.grow_parametric('POLYGON((0 0, 1000 0, 1000 1000, 0 1000, 0 0))',
      'POINT(500 500)', NULL, '{"seed": 9, "max_edges": 300}') ORDER BY id$$,
  'parametric: the same seed gives the same edges');
SELECT ok((SELECT count(*) FROM (
             (SELECT ST_AsEWKB(geom) FROM streetgen.grow_parametric('POLYGON((0 0, 1000 0, 1000 1000, 0 1000, 0 0))',
                'POINT(500 500)', NULL, '{"seed": 9, "max_edges": 300}'))
             EXCEPT
             (SELECT ST_AsEWKB(geom) FROM streetgen.grow_parametric('POLYGON((0 0, 1000 0, 1000 1000, 0 1000, 0 0))',
                'POINT(500 500)', NULL, '{"seed": 10, "max_edges": 300}'))) d) > 100,
          'parametric: different seeds give different edges');
SELECT ok((SELECT avg(ST_Length(geom)) FROM streetgen.grow_parametric('POLYGON((0 0, 1000 0, 1000 1000, 0 1000, 0 0))',
             'POINT(500 500)', NULL, '{"seed": 2, "length": 120, "length_deviation": 5, "min_length": 60, "snap": 30}'))
          > 100, 'the length parameter sets the street length');
SELECT is((SELECT max(degree) FROM (SELECT node, count(*) AS degree FROM (
             SELECT from_node AS node FROM streetgen.grow_parametric('POLYGON((0 0, 1000 0, 1000 1000, 0 1000, 0 0))',
               'POINT(500 500)', NULL, '{"seed": 2, "min_degree": 2, "max_degree": 3}')
             UNION ALL SELECT to_node FROM streetgen.grow_parametric('POLYGON((0 0, 1000 0, 1000 1000, 0 1000, 0 0))',
               'POINT(500 500)', NULL, '{"seed": 2, "min_degree": 2, "max_degree": 3}')) e GROUP BY node) d), 3::bigint,
          'max_degree bounds the degree');
-- Determinism.
CREATE TEMP VIEW ny AS SELECT geom, road_class FROM patch WHERE name = 'new-york';
SELECT results_eq(
  $$SELECT id, from_node, to_node, road_class, origin, ST_AsEWKB(geom) FROM streetgen.grow_example(
      'SELECT geom, road_class FROM ny', (SELECT geom FROM region WHERE name = 'new-york'),
      (SELECT centre FROM region WHERE name = 'new-york'), NULL, '{"seed": 5, "max_edges": 400}') ORDER BY id$$,
  $$SELECT id, from_node, to_node, road_class, origin, ST_AsEWKB(geom) FROM streetgen.grow_example(
      'SELECT geom, road_class FROM ny', (SELECT geom FROM region WHERE name = 'new-york'),
      (SELECT centre FROM region WHERE name = 'new-york'), NULL, '{"seed": 5, "max_edges": 400}') ORDER BY id$$,
  'the same seed gives the same edges');
SELECT ok((SELECT count(*) FROM (
             (SELECT ST_AsEWKB(geom) FROM streetgen.grow_example('SELECT geom, road_class FROM ny',
                (SELECT geom FROM region WHERE name = 'new-york'), (SELECT centre FROM region WHERE name = 'new-york'),
                NULL, '{"seed": 5, "max_edges": 400}'))
             EXCEPT
             (SELECT ST_AsEWKB(geom) FROM streetgen.grow_example('SELECT geom, road_class FROM ny',
                (SELECT geom FROM region WHERE name = 'new-york'), (SELECT centre FROM region WHERE name = 'new-york'),
                NULL, '{"seed": 6, "max_edges": 400}'))) d) > 100,
          'different seeds give different edges');

-- Output goes into a model's axis table in one statement, and the surfaces follow.
SELECT streetgen.create_model('grown_tokyo', 0);
INSERT INTO grown_tokyo.axis (geom, roadway_width, speed_kmh, road_class, source)
SELECT geom, CASE road_class WHEN 'avenue' THEN 12 ELSE 6 END, CASE road_class WHEN 'avenue' THEN 50 ELSE 30 END,
       road_class, origin
  FROM streetgen.grow_example($$SELECT id, road_class, geom FROM patch WHERE name = 'tokyo'$$,
                              'POLYGON((2500 0, 3100 0, 3100 600, 2500 600, 2500 0))', 'POINT(2800 300)',
                              NULL, '{"seed": 2, "rotation": false, "max_edges": 200}');
SELECT is((SELECT count(*) FROM grown_tokyo.axis), 200::bigint, 'grown edges inserted into a model''s axis table');
SELECT ok((SELECT count(*) FROM grown_tokyo.section) >= 200, 'and the model''s sections follow');

-- Extending an existing network (the paper's Figure 3): tokyo with a 500 m hole cut out; growth
-- starts from the nodes on the hole's border and must respect and join the streets around it.
CREATE TEMP TABLE hole AS SELECT ST_MakeEnvelope(2800, 200, 3300, 700, 0) AS geom;
CREATE TEMP TABLE around AS
SELECT p.id, (ST_Dump(ST_Difference(p.geom, h.geom))).geom AS geom FROM patch p, hole h WHERE p.name = 'tokyo';
CREATE TEMP TABLE border_nodes AS
SELECT DISTINCT ST_AsEWKB(q.pt) AS key, q.pt
  FROM around a, hole h, LATERAL (VALUES (ST_StartPoint(a.geom)), (ST_EndPoint(a.geom))) AS q(pt)
 WHERE ST_DWithin(q.pt, ST_Boundary(h.geom), 1e-6);
SELECT ok((SELECT count(*) FROM border_nodes) >= 20, 'the hole cuts at least 20 streets');
CREATE TEMP TABLE filled AS
SELECT g.* FROM hole h, streetgen.grow_example(
  $$SELECT id, road_class, geom FROM patch WHERE name = 'tokyo'$$, h.geom, (SELECT ST_Collect(pt) FROM border_nodes),
  NULL, '{"seed": 3, "rotation": false}', 'SELECT geom FROM around') AS g;
SELECT ok((SELECT count(*) FROM filled) >= 100, 'the hole fills (at least 100 edges)');
SELECT is((SELECT count(*) FROM filled f, hole h WHERE NOT ST_CoveredBy(f.geom, h.geom)), 0::bigint,
          'the new edges stay in the hole');
SELECT is((SELECT count(*) FROM filled f JOIN around a ON ST_Intersects(f.geom, a.geom)
            WHERE NOT ST_Equals(ST_Intersection(f.geom, a.geom), ST_StartPoint(f.geom))
              AND NOT ST_Equals(ST_Intersection(f.geom, a.geom), ST_EndPoint(f.geom))), 0::bigint,
          'new edges meet the existing streets only at their own ends (no crossing)');
SELECT ok((SELECT count(DISTINCT b.key) FROM border_nodes b JOIN filled f
             ON ST_Equals(ST_StartPoint(f.geom), b.pt) OR ST_Equals(ST_EndPoint(f.geom), b.pt)) >= 10,
          'the streets around the hole are continued into it (at least 10 border nodes joined)');
SELECT is((SELECT count(*) FROM filled a JOIN filled b ON a.id < b.id AND ST_Intersects(a.geom, b.geom)
            WHERE NOT (a.from_node IN (b.from_node, b.to_node) OR a.to_node IN (b.from_node, b.to_node))),
          0::bigint, 'the filled hole is planar');

-- Direction control: a guide curve (a sine across a square) sets θ instead of node matching. Edges
-- within 100 m of it follow its tangent at the nearest point (the tokyo grid and the parametric
-- lattice both have right angles, so the deviation is folded to [0, 45] degrees); without the
-- guide, they do not.
CREATE TEMP TABLE guide AS
SELECT ST_MakeLine(array_agg(ST_MakePoint(x, 750 + 250 * sin(2 * pi() * x / 1500)) ORDER BY x)) AS geom
  FROM generate_series(0, 1500, 10) AS x;
CREATE FUNCTION pg_temp.guide_deviation(edges geometry[]) RETURNS double precision LANGUAGE sql AS $$
  SELECT avg(least(d, 90 - d)) FROM (
    SELECT mod(abs(degrees(ST_Azimuth(ST_StartPoint(e), ST_EndPoint(e))
                           - ST_Azimuth(ST_LineInterpolatePoint(g.geom, greatest(f - 0.002, 0)),
                                        ST_LineInterpolatePoint(g.geom, least(f + 0.002, 1)))))::numeric, 90)::double precision AS d
      FROM unnest(edges) AS e, guide g, LATERAL (SELECT ST_LineLocatePoint(g.geom, ST_Centroid(e)) AS f) l
     WHERE ST_DWithin(e, g.geom, 100)) x
$$;
CREATE TEMP TABLE steered AS
SELECT 'example' AS kind, true AS guided, g.* FROM guide, streetgen.grow_example(
  $$SELECT id, road_class, geom FROM patch WHERE name = 'tokyo'$$, 'POLYGON((0 0, 1500 0, 1500 1500, 0 1500, 0 0))',
  'POINT(10 750)', NULL, '{"seed": 3, "max_edges": 1500}', NULL, guide.geom) AS g
UNION ALL
SELECT 'example', false, g.* FROM streetgen.grow_example(
  $$SELECT id, road_class, geom FROM patch WHERE name = 'tokyo'$$, 'POLYGON((0 0, 1500 0, 1500 1500, 0 1500, 0 0))',
  'POINT(10 750)', NULL, '{"seed": 3, "max_edges": 1500}') AS g
UNION ALL
SELECT 'parametric', true, g.* FROM guide, streetgen.grow_parametric(
  'POLYGON((0 0, 1500 0, 1500 1500, 0 1500, 0 0))', 'POINT(10 750)', NULL, '{"seed": 3, "max_edges": 1500}', NULL,
  guide.geom) AS g
UNION ALL
SELECT 'parametric', false, g.* FROM streetgen.grow_parametric(
  'POLYGON((0 0, 1500 0, 1500 1500, 0 1500, 0 0))', 'POINT(10 750)', NULL, '{"seed": 3, "max_edges": 1500}') AS g;
CREATE TEMP TABLE steering AS
SELECT s.kind, s.guided, count(*) FILTER (WHERE ST_DWithin(s.geom, g.geom, 100)) AS near,
       pg_temp.guide_deviation(array_agg(s.geom)) AS deviation
  FROM steered s, guide g GROUP BY s.kind, s.guided;
SELECT ok((SELECT bool_and(near >= 150) FROM steering), 'at least 150 edges near the guide in each growth');
SELECT cmp_ok((SELECT deviation FROM steering WHERE kind = 'example' AND guided), '<', 10.0::double precision,
              'grow_example with a guide: edges near it follow its tangent (mean deviation below 10 degrees)');
SELECT cmp_ok((SELECT deviation FROM steering WHERE kind = 'example' AND NOT guided), '>', 15.0::double precision,
              'grow_example without the guide: they do not (mean deviation above 15 degrees)');
SELECT cmp_ok((SELECT deviation FROM steering WHERE kind = 'parametric' AND guided), '<', 10.0::double precision,
              'grow_parametric with a guide: edges near it follow its tangent');
SELECT cmp_ok((SELECT deviation FROM steering WHERE kind = 'parametric' AND NOT guided), '>', 15.0::double precision,
              'grow_parametric without the guide: they do not');
SELECT is((SELECT count(*) FROM steered a JOIN steered b ON a.kind = b.kind AND a.guided = b.guided AND a.id < b.id
             AND ST_Intersects(a.geom, b.geom)
            WHERE NOT (a.from_node IN (b.from_node, b.to_node) OR a.to_node IN (b.from_node, b.to_node))),
          0::bigint, 'guided growth stays planar');
SELECT is((SELECT count(*) FROM steered WHERE NOT ST_CoveredBy(geom, 'POLYGON((0 0, 1500 0, 1500 1500, 0 1500, 0 0))')),
          0::bigint, 'guided growth stays in the region');
SELECT results_eq(
  $$SELECT ST_AsEWKB(g.geom) FROM guide, streetgen.grow_example('SELECT geom, road_class FROM patch WHERE name = ''tokyo''',
      'POLYGON((0 0, 1500 0, 1500 1500, 0 1500, 0 0))', 'POINT(10 750)', NULL, '{"seed": 3, "max_edges": 300}', NULL,
      guide.geom) AS g ORDER BY g.id$$,
  $$SELECT ST_AsEWKB(g.geom) FROM guide, streetgen.grow_example('SELECT geom, road_class FROM patch WHERE name = ''tokyo''',
      'POLYGON((0 0, 1500 0, 1500 1500, 0 1500, 0 0))', 'POINT(10 750)', NULL, '{"seed": 3, "max_edges": 300}', NULL,
      guide.geom) AS g ORDER BY g.id$$,
  'guided growth: the same seed gives the same edges');
-- guide_reach: farther than that from the guide, node matching sets θ again (the guide is moved
-- 5 km away; the deviation is still measured against the sine).
SELECT cmp_ok((SELECT pg_temp.guide_deviation(array_agg(g.geom)) FROM guide, streetgen.grow_example(
                 $$SELECT id, road_class, geom FROM patch WHERE name = 'tokyo'$$,
                 'POLYGON((0 0, 1500 0, 1500 1500, 0 1500, 0 0))', 'POINT(10 750)', NULL,
                 '{"seed": 3, "max_edges": 1500, "guide_reach": 1}', NULL,
                 ST_Translate(guide.geom, 0, 5000)) AS g), '>', 15.0::double precision,
              'a guide beyond guide_reach does not steer');

-- Blending (Yu & Steed's Figure 5): two examples, a selection function over space. Each step draws
-- its example from the weights at its node; origin says which example an edge came from
-- (grow_example:<k>:<id>). The share of edges from example 1 (tokyo) falls from west to east
-- across the four quarters of the region, with the gradient and with Gaussian seed points.
CREATE TEMP TABLE blended AS
SELECT 'gradient'::text AS kind, g.* FROM streetgen.grow_example(
  ARRAY[$$SELECT id, road_class, geom FROM patch WHERE name = 'tokyo'$$,
        $$SELECT id, road_class, geom FROM patch WHERE name = 'canberra_south_large'$$],
  'POLYGON((0 0, 2000 0, 2000 1200, 0 1200, 0 0))', 'MULTIPOINT(300 600, 1000 600, 1700 600)', NULL,
  '{"seed": 3, "max_edges": 3000, "blend": "gradient"}') AS g
UNION ALL
SELECT 'points', g.* FROM streetgen.grow_example(
  ARRAY[$$SELECT id, road_class, geom FROM patch WHERE name = 'tokyo'$$,
        $$SELECT id, road_class, geom FROM patch WHERE name = 'canberra_south_large'$$],
  'POLYGON((0 0, 2000 0, 2000 1200, 0 1200, 0 0))', 'MULTIPOINT(300 600, 1000 600, 1700 600)', NULL,
  '{"seed": 3, "max_edges": 3000, "blend": "points", "blend_points": [[0, 600], [2000, 600]], "blend_sigma": 600}') AS g;
CREATE TEMP TABLE blend_share AS
SELECT kind, width_bucket(ST_X(ST_Centroid(geom)), 0, 2000, 4) AS quarter, count(*) AS edges,
       avg((origin LIKE 'grow_example:1:%')::integer) AS share_first
  FROM blended WHERE origin <> 'grow_parametric' GROUP BY 1, 2;
SELECT is((SELECT count(*) FROM blended WHERE origin !~ '^grow_example:[12]:[0-9]+$' AND origin <> 'grow_parametric'),
          0::bigint, 'origin names the example (1 or 2) and its edge');
SELECT ok((SELECT bool_and(edges >= 100) AND count(*) = 8 FROM blend_share), 'at least 100 edges in every quarter');
SELECT ok((SELECT bool_and(d) FROM (SELECT share_first < lag(share_first) OVER (PARTITION BY kind ORDER BY quarter) AS d
                                      FROM blend_share) x WHERE d IS NOT NULL),
          'the share of example 1 decreases from quarter to quarter, west to east (gradient and points)');
SELECT ok((SELECT bool_and(share_first > 0.6) FROM blend_share WHERE quarter = 1)
          AND (SELECT bool_and(share_first < 0.4) FROM blend_share WHERE quarter = 4),
          'example 1 dominates the west quarter, example 2 the east one');
SELECT is((SELECT count(*) FROM blended a JOIN blended b ON a.kind = b.kind AND a.id < b.id AND ST_Intersects(a.geom, b.geom)
            WHERE NOT (a.from_node IN (b.from_node, b.to_node) OR a.to_node IN (b.from_node, b.to_node))),
          0::bigint, 'blended growth stays planar');
SELECT is((SELECT count(*) FROM blended WHERE NOT ST_CoveredBy(geom, 'POLYGON((0 0, 2000 0, 2000 1200, 0 1200, 0 0))')),
          0::bigint, 'blended growth stays in the region');
SELECT results_eq(
  $$SELECT origin, ST_AsEWKB(geom) FROM streetgen.grow_example(ARRAY['SELECT geom FROM patch WHERE name = ''tokyo''', 'SELECT geom FROM ny'],
      'POLYGON((0 0, 2000 0, 2000 1200, 0 1200, 0 0))', 'POINT(1000 600)', NULL,
      '{"seed": 8, "max_edges": 400, "blend": "gradient", "blend_angle": 90}') ORDER BY id$$,
  $$SELECT origin, ST_AsEWKB(geom) FROM streetgen.grow_example(ARRAY['SELECT geom FROM patch WHERE name = ''tokyo''', 'SELECT geom FROM ny'],
      'POLYGON((0 0, 2000 0, 2000 1200, 0 1200, 0 0))', 'POINT(1000 600)', NULL,
      '{"seed": 8, "max_edges": 400, "blend": "gradient", "blend_angle": 90}') ORDER BY id$$,
  'blended growth: the same seed gives the same edges');

-- Realism (issue 7's acceptance measure, as in bench/growth): new-york grown over its own convex
-- hull from one seed point (seeds 1-3), compared with the example inside the hull shrunk by 50 m.
-- Coherent copying (a node first continues the example node its edge was copied to) keeps the
-- per-pair median of the headline metrics' relative differences below 10 %; random candidates
-- only (coherence 0) land further away (measured: 4-7 % against 8-15 % over seeds 1-5).
CREATE TEMP TABLE ny_hull AS SELECT ST_ConvexHull(ST_Collect(geom)) AS geom FROM patch WHERE name = 'new-york';
CREATE TEMP TABLE realism AS
SELECT c.coherence, s.seed, (SELECT score FROM streetgen.compare_networks(
         streetgen.network_stats($$SELECT geom FROM patch WHERE name = 'new-york'$$, 0, ST_Buffer(h.geom, -50), simplify => true),
         streetgen.network_stats(ST_Collect(g.geom), 0, ST_Buffer(h.geom, -50), simplify => true))
        WHERE metric = 'median_abs_relative_difference') AS score
  FROM ny_hull h, (VALUES (0.0), (1.0)) AS c(coherence), generate_series(1, 3) AS s(seed),
       LATERAL streetgen.grow_example($$SELECT id, road_class, geom FROM patch WHERE name = 'new-york'$$, h.geom,
                                      ST_PointOnSurface(h.geom), NULL,
                                      jsonb_build_object('seed', s.seed, 'coherence', c.coherence)) AS g
 GROUP BY c.coherence, s.seed, h.geom;
CREATE TEMP VIEW realism_median AS
SELECT coherence, percentile_cont(0.5) WITHIN GROUP (ORDER BY score) AS score FROM realism GROUP BY coherence;
SELECT cmp_ok((SELECT score FROM realism_median WHERE coherence = 1), '<', 0.10::double precision,
              'new-york regrown (seeds 1-3): median per-pair median of the headline metrics below 10 %');
SELECT cmp_ok((SELECT score FROM realism_median WHERE coherence = 1), '<',
              (SELECT score FROM realism_median WHERE coherence = 0),
              'coherent copying is closer to the example than random candidates only');

-- Every new mode keeps the obstacle: blended and guided growth (both at once) and fill around a
-- lake in the middle of the region.
CREATE TEMP TABLE mixed AS
SELECT g.* FROM guide, streetgen.grow_example(
  ARRAY[$$SELECT id, road_class, geom FROM patch WHERE name = 'tokyo'$$,
        $$SELECT id, road_class, geom FROM patch WHERE name = 'new-york'$$],
  'POLYGON((0 0, 1500 0, 1500 1500, 0 1500, 0 0))', 'POINT(10 750)', ST_Buffer('POINT(750 1100)'::geometry, 200),
  '{"seed": 4, "max_edges": 2000, "blend": "gradient", "fill": true}', NULL, guide.geom) AS g;
SELECT ok((SELECT count(*) FROM mixed) >= 1000, 'blended, guided growth with fill around a lake (at least 1000 edges)');
SELECT is((SELECT count(*) FROM mixed WHERE ST_Intersects(geom, ST_Buffer('POINT(750 1100)'::geometry, 200))
           OR NOT ST_CoveredBy(geom, 'POLYGON((0 0, 1500 0, 1500 1500, 0 1500, 0 0))')), 0::bigint,
          'no edge enters the lake or leaves the region');
SELECT is((SELECT count(*) FROM mixed a JOIN mixed b ON a.id < b.id AND ST_Intersects(a.geom, b.geom)
            WHERE NOT (a.from_node IN (b.from_node, b.to_node) OR a.to_node IN (b.from_node, b.to_node))),
          0::bigint, 'and it stays planar');

-- Bad input, by SQLSTATE.
CREATE TEMP VIEW tokyo AS SELECT geom, road_class FROM patch WHERE name = 'tokyo';
CREATE FUNCTION pg_temp.grow(example text, region text DEFAULT 'POLYGON((2300 -400, 3700 -400, 3700 1390, 2300 1390, 2300 -400))',
                             seeds text DEFAULT 'POINT(3000 500)', params jsonb DEFAULT '{}', obstacles text DEFAULT NULL)
  RETURNS bigint LANGUAGE sql AS $$
  SELECT count(*) FROM streetgen.grow_example(example, region::geometry, seeds::geometry, obstacles::geometry, params)
$$;
SELECT throws_ok($$SELECT pg_temp.grow('SELECT geom FROM tokyo WHERE false')$$, '22023', 'example has no edges',
                 'empty example');
SELECT throws_ok($$SELECT pg_temp.grow('SELECT ''LINESTRING(5 5, 5 5)''::geometry AS geom')$$, '22023',
                 'example has fewer than two distinct nodes', 'example with one node');
SELECT throws_ok($$SELECT pg_temp.grow('SELECT ''POINT(5 5)''::geometry AS geom')$$, '22023', NULL,
                 'example of points');
SELECT throws_ok($$SELECT pg_temp.grow('SELECT 1 AS x')$$, '22023',
                 'the example query must return a geometry column named geom', 'example query without geom');
SELECT throws_ok($$SELECT pg_temp.grow('SELECT geom FROM tokyo', 'POLYGON EMPTY')$$, '22023', 'region is empty',
                 'empty region');
SELECT throws_ok($$SELECT pg_temp.grow('SELECT geom FROM tokyo', 'POLYGON((2300 -400, 3700 1390, 3700 -400, 2300 1390, 2300 -400))')$$,
                 '22023', 'region is not a valid polygon', 'invalid (self-intersecting) region');
SELECT throws_ok($$SELECT pg_temp.grow('SELECT geom FROM tokyo', 'LINESTRING(0 0, 10 10)')$$, '22023',
                 'region must be a Polygon or MultiPolygon', 'region that is not a polygon');
SELECT throws_ok($$SELECT pg_temp.grow('SELECT geom FROM tokyo', 'SRID=4326;POLYGON((2 48, 3 48, 3 49, 2 48))', 'SRID=4326;POINT(2.7 48.3)')$$,
                 '22023', NULL, 'geographic region');
SELECT throws_ok($$SELECT pg_temp.grow('SELECT geom FROM tokyo', seeds => 'POINT(0 0)')$$, '22023',
                 'seed 1 is outside the region', 'seed outside the region');
SELECT throws_ok($$SELECT pg_temp.grow('SELECT geom FROM tokyo', seeds => 'MULTIPOINT(3000 500, 9000 9000)')$$, '22023',
                 'seed 2 is outside the region', 'second seed outside the region');
SELECT throws_ok($$SELECT pg_temp.grow('SELECT geom FROM tokyo', seeds => 'MULTIPOINT EMPTY')$$, '22023',
                 'seeds must hold at least one point', 'no seed');
SELECT throws_ok($$SELECT pg_temp.grow('SELECT geom FROM tokyo', seeds => 'LINESTRING(3000 500, 3010 500)')$$, '22023',
                 'seeds must be points', 'seeds that are not points');
SELECT throws_ok($$SELECT pg_temp.grow('SELECT geom FROM tokyo', seeds => 'SRID=3857;POINT(3000 500)')$$, '22023',
                 'seeds must have the SRID of the region', 'seeds in another SRID');
SELECT throws_ok($$SELECT pg_temp.grow('SELECT geom FROM tokyo', obstacles => 'POLYGON((2900 400, 3100 400, 3100 600, 2900 600, 2900 400))')$$,
                 '22023', 'seed 1 lies in an obstacle', 'seed inside an obstacle');
SELECT throws_ok($$SELECT pg_temp.grow('SELECT geom FROM tokyo', obstacles => 'LINESTRING(0 0, 1 1)')$$, '22023',
                 'obstacles must be polygons', 'obstacle that is not a polygon');
SELECT throws_ok($$SELECT pg_temp.grow('SELECT geom FROM tokyo', params => '{"epsilon": 0}')$$, '22023',
                 'epsilon must be a number > 0 (degrees)', 'epsilon = 0');
SELECT throws_ok($$SELECT pg_temp.grow('SELECT geom FROM tokyo', params => '{"epsilon": -10}')$$, '22023',
                 'epsilon must be a number > 0 (degrees)', 'epsilon < 0');
SELECT throws_ok($$SELECT pg_temp.grow('SELECT geom FROM tokyo', params => '{"epsilon": 200}')$$, '22023',
                 'epsilon must be below 180 degrees', 'epsilon >= 180');
SELECT throws_ok($$SELECT pg_temp.grow('SELECT geom FROM tokyo', params => '{"r": 0}')$$, '22023',
                 'r must be a number > 0', 'r = 0');
SELECT throws_ok($$SELECT pg_temp.grow('SELECT geom FROM tokyo', params => '{"r": -50}')$$, '22023',
                 'r must be a number > 0', 'r < 0');
SELECT throws_ok($$SELECT pg_temp.grow('SELECT geom FROM tokyo', params => '{"snap": 0}')$$, '22023',
                 'snap must be a number > 0', 'snap = 0');
SELECT throws_ok($$SELECT pg_temp.grow('SELECT geom FROM tokyo', params => '{"max_edges": 0}')$$, '22023',
                 'max_edges must be > 0', 'max_edges = 0');
SELECT throws_ok($$SELECT pg_temp.grow('SELECT geom FROM tokyo', params => '{"epslion": 30}')$$, '22023',
                 'unknown params key: epslion', 'unknown params key rejected, not ignored');
SELECT throws_ok($$SELECT pg_temp.grow('SELECT geom FROM tokyo', params => '[1, 2]')$$, '22023',
                 'params must be a json object', 'params that is not an object');
SELECT throws_ok($$SELECT pg_temp.grow('SELECT geom FROM tokyo', params => '{"seed": "abc"}')$$, '22P02', NULL,
                 'a params value of the wrong type');
SELECT throws_ok($$SELECT pg_temp.grow('SELECT geom FROM tokyo') FROM streetgen.grow_example('SELECT geom FROM tokyo',
                   'POLYGON((2300 -400, 3700 -400, 3700 1390, 2300 1390, 2300 -400))', 'POINT(3000 500)', NULL, '{}',
                   'SELECT ''SRID=3857;LINESTRING(0 0, 1 1)''::geometry AS geom')$$, '22023',
                 'the existing network must have the SRID of the region', 'existing network in another SRID');
CREATE FUNCTION pg_temp.para(params jsonb) RETURNS bigint LANGUAGE sql AS $$
  SELECT count(*) FROM streetgen.grow_parametric('POLYGON((0 0, 1000 0, 1000 1000, 0 1000, 0 0))', 'POINT(500 500)',
                                                 NULL, params)
$$;
SELECT throws_ok($$SELECT pg_temp.para('{"epsilon": 30}')$$, '22023', 'unknown params key: epsilon',
                 'grow_parametric rejects example keys');
SELECT throws_ok($$SELECT pg_temp.grow('SELECT geom FROM tokyo', params => '{"length": 30}')$$, '22023',
                 'unknown params key: length', 'grow_example rejects parametric keys');
SELECT throws_ok($$SELECT pg_temp.para('{"length": 0}')$$, '22023', 'length must be a finite number > 0', 'length = 0');
SELECT throws_ok($$SELECT pg_temp.para('{"length_deviation": 50}')$$, '22023', 'length_deviation must be in [0, length)',
                 'length_deviation >= length');
SELECT throws_ok($$SELECT pg_temp.para('{"min_length": 80}')$$, '22023', 'min_length must be in (0, length]',
                 'min_length > length');
SELECT throws_ok($$SELECT pg_temp.para('{"min_degree": 3, "max_degree": 2}')$$, '22023',
                 'degree range must satisfy 1 <= min_degree <= max_degree <= 8', 'min_degree > max_degree');
SELECT throws_ok($$SELECT pg_temp.para('{"min_degree": 0}')$$, '22023',
                 'degree range must satisfy 1 <= min_degree <= max_degree <= 8', 'min_degree 0');
SELECT throws_ok($$SELECT pg_temp.para('{"angle_deviation": 95}')$$, '22023', 'angle_deviation must be in [0, 90) degrees',
                 'angle_deviation >= 90');
SELECT throws_ok($$SELECT pg_temp.para('{"min_angle": 90}')$$, '22023', 'min_angle must be in [0, 90) degrees',
                 'min_angle >= 90');
SELECT throws_ok($$SELECT * FROM streetgen.grow_parametric('POLYGON((0 0, 1 0, 1 1, 0 0))', 'POINT(5 5)')$$, '22023',
                 'seed 1 is outside the region', 'grow_parametric: seed outside the region');
SELECT throws_ok($$SELECT * FROM streetgen.grow_parametric(NULL, 'POINT(0.5 0.2)')$$, '22004', 'region must not be null',
                 'grow_parametric: NULL region');
SELECT throws_ok($$SELECT count(*) FROM streetgen.grow_example('SELECT geom FROM tokyo',
                   'POLYGON((2300 -400, 3700 -400, 3700 1390, 2300 1390, 2300 -400))', 'POINT(3000 500)', NULL, '{}', NULL,
                   'POLYGON((0 0, 1 0, 1 1, 0 0))')$$, '22023', 'guide must be a LineString or MultiLineString',
                 'a guide that is not a line');
SELECT throws_ok($$SELECT count(*) FROM streetgen.grow_example('SELECT geom FROM tokyo',
                   'POLYGON((2300 -400, 3700 -400, 3700 1390, 2300 1390, 2300 -400))', 'POINT(3000 500)', NULL, '{}', NULL,
                   'SRID=3857;LINESTRING(0 0, 1 1)')$$, '22023', 'guide must have the SRID of the region',
                 'a guide in another SRID');
SELECT throws_ok($$SELECT count(*) FROM streetgen.grow_example('SELECT geom FROM tokyo',
                   'POLYGON((2300 -400, 3700 -400, 3700 1390, 2300 1390, 2300 -400))', 'POINT(3000 500)', NULL, '{}', NULL,
                   'LINESTRING(5 5, 5 5)')$$, '22023', 'guide has no segment', 'a guide of one point');
SELECT throws_ok($$SELECT pg_temp.grow('SELECT geom FROM tokyo', params => '{"guide_reach": 0}')$$, '22023',
                 'guide_reach must be a number > 0', 'guide_reach = 0');
CREATE FUNCTION pg_temp.blend(examples text[], params jsonb) RETURNS bigint LANGUAGE sql AS $$
  SELECT count(*) FROM streetgen.grow_example(examples, 'POLYGON((2300 -400, 3700 -400, 3700 1390, 2300 1390, 2300 -400))',
                                              'POINT(3000 500)', NULL, params)
$$;
SELECT throws_ok($$SELECT pg_temp.blend(ARRAY['SELECT geom FROM tokyo', 'SELECT geom FROM ny'], '{}')$$, '22023',
                 'several examples need a blend', 'two examples without a blend');
SELECT throws_ok($$SELECT pg_temp.blend(ARRAY['SELECT geom FROM tokyo', 'SELECT geom FROM ny'], '{"blend": "radial"}')$$,
                 '22023', 'blend must be ''gradient'' or ''points''', 'an unknown blend');
SELECT throws_ok($$SELECT pg_temp.blend(ARRAY['SELECT geom FROM tokyo', 'SELECT geom FROM ny'], '{"blend": "points"}')$$,
                 '22023', 'blend ''points'' needs blend_points', 'blend points without points');
SELECT throws_ok($$SELECT pg_temp.blend(ARRAY['SELECT geom FROM tokyo', 'SELECT geom FROM ny'],
                                        '{"blend": "points", "blend_points": [[0, 0]]}')$$,
                 '22023', 'blend_points must hold one point per example', 'one blend point for two examples');
SELECT throws_ok($$SELECT pg_temp.blend(ARRAY['SELECT geom FROM tokyo', 'SELECT geom FROM ny'],
                                        '{"blend": "points", "blend_points": [[0, 0], [1]]}')$$,
                 '22023', 'blend_points must be an array of [x, y] pairs', 'a malformed blend point');
SELECT throws_ok($$SELECT pg_temp.blend(ARRAY['SELECT geom FROM tokyo', 'SELECT geom FROM ny'],
                                        '{"blend": "points", "blend_points": [[0, 0], [1, 1]], "blend_sigma": 0}')$$,
                 '22023', 'blend_sigma must be a number > 0', 'blend_sigma = 0');
SELECT throws_ok($$SELECT pg_temp.blend(ARRAY['SELECT geom FROM tokyo', 'SELECT geom FROM tokyo WHERE false'],
                                        '{"blend": "gradient"}')$$,
                 '22023', 'example 2 has no edges', 'a blended example without edges');
SELECT throws_ok($$SELECT pg_temp.blend(ARRAY['SELECT geom FROM tokyo', NULL], '{"blend": "gradient"}')$$,
                 '22004', 'example must not be null', 'a NULL example among several');
SELECT throws_ok($$SELECT pg_temp.blend('{}', '{}')$$, '22004', 'example must not be null', 'no example at all');
SELECT throws_ok($$SELECT pg_temp.grow('SELECT geom FROM tokyo', params => '{"coherence": 1.5}')$$, '22023',
                 'coherence must be a number in [0, 1]', 'coherence above 1');
SELECT throws_ok($$SELECT pg_temp.grow('SELECT geom FROM tokyo', params => '{"crop_margin": -1}')$$, '22023',
                 'crop_margin must be a number >= 0', 'negative crop_margin');
SELECT throws_ok($$SELECT * FROM streetgen.grow_example(NULL, 'POLYGON((0 0, 1 0, 1 1, 0 0))', 'POINT(0.5 0.2)')$$,
                 '22004', 'example must not be null', 'NULL example');
SELECT throws_ok($$SELECT * FROM streetgen.grow_example('SELECT geom FROM tokyo', NULL, 'POINT(0.5 0.2)')$$,
                 '22004', 'region must not be null', 'NULL region');
SELECT throws_ok($$SELECT * FROM streetgen.grow_example('SELECT geom FROM tokyo', 'POLYGON((0 0, 1 0, 1 1, 0 0))', NULL)$$,
                 '22004', 'seeds must not be null', 'NULL seeds');

-- A long growth is cancelled by statement_timeout with 57014 (inside the C++ loop, which polls
-- once per step), and the session grows again.
CREATE TEMP TABLE outcome (state text, seconds double precision);
SET LOCAL statement_timeout = '200ms';
INSERT INTO outcome SELECT * FROM test_helpers.sqlstate_and_seconds(
  $$SELECT pg_temp.grow('SELECT geom, road_class FROM tokyo', params => '{"max_edges": 1000000, "candidates": 500}')$$);
RESET statement_timeout;
SELECT is((SELECT state FROM outcome), '57014', 'statement_timeout cancels a long growth with 57014');
SELECT cmp_ok((SELECT seconds FROM outcome), '<', 2.0::double precision, 'within the growth, not after it');
SELECT is(pg_temp.grow('SELECT geom, road_class FROM tokyo', params => '{"max_edges": 10}'), 10::bigint,
          'and the session grows again');

-- fill is on by default for grow_example: a second part of the region that no front can reach (2 km
-- east of the first) is grown from a new seed; with fill off it stays empty.
CREATE TEMP TABLE two_parts AS
SELECT ST_Multi(ST_Union(r.geom, ST_MakeEnvelope(ST_XMax(r.geom) + 2000, ST_YMin(r.geom), ST_XMax(r.geom) + 2600,
                                                 ST_YMin(r.geom) + 600, 0))) AS geom,
       ST_XMax(r.geom) + 2000 AS x_east, r.centre
  FROM region r WHERE r.name = 'tokyo';
CREATE TEMP TABLE fill_default AS
SELECT g.* FROM two_parts t, streetgen.grow_example($$SELECT id, road_class, geom FROM patch WHERE name = 'tokyo'$$,
  t.geom, t.centre, NULL, '{"seed": 5, "rotation": false, "max_edges": 6000}') AS g;
CREATE TEMP TABLE fill_off AS
SELECT g.* FROM two_parts t, streetgen.grow_example($$SELECT id, road_class, geom FROM patch WHERE name = 'tokyo'$$,
  t.geom, t.centre, NULL, '{"seed": 5, "rotation": false, "max_edges": 6000, "fill": false}') AS g;
SELECT ok((SELECT count(*) FROM fill_default f, two_parts t WHERE ST_XMin(f.geom) >= t.x_east) >= 50,
          'fill (on by default) grows the part of the region no front reaches');
SELECT is((SELECT count(*) FROM fill_off f, two_parts t WHERE ST_XMin(f.geom) >= t.x_east), 0::bigint,
          'with fill off that part stays empty');
SELECT is((SELECT count(*) FROM fill_default a JOIN fill_default b ON a.id < b.id AND ST_Intersects(a.geom, b.geom)
            WHERE NOT (a.from_node IN (b.from_node, b.to_node) OR a.to_node IN (b.from_node, b.to_node))),
          0::bigint, 'the filled growth is planar');

SELECT * FROM finish();
ROLLBACK;
