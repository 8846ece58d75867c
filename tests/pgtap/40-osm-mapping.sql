-- The OSM tag mapping (one definition for both import paths), the UTM zone choice, and
-- load_osm_ways on a hand-made staging table.
BEGIN;
SELECT * FROM no_plan();

-- Lengths and speeds as mappers write them.
SELECT results_eq(
  $$SELECT streetgen.osm_parse_length(v) FROM unnest(ARRAY['7', '7.5 m', '7,5', ' 12 metres ', '24''', '10 ft', '8''6"', 'wide', '', NULL]) WITH ORDINALITY AS t(v, i) ORDER BY i$$,
  $$VALUES (7.0::float8), (7.5), (7.5), (12.0), (24 * 0.3048::float8), (10 * 0.3048::float8), (8 * 0.3048::float8 + 6 * 0.0254::float8), (NULL), (NULL), (NULL)$$,
  'osm_parse_length reads metres, commas, feet and feet-inches');
SELECT results_eq(
  $$SELECT streetgen.osm_parse_speed(v) FROM unnest(ARRAY['50', '30 mph', '10 knots', 'walk', 'DE:urban', 'FR:rural', 'DE:zone30', 'DE:zone:20', 'RU:living_street', '50;30', 'none', 'signals', '0', '900', NULL]) WITH ORDINALITY AS t(v, i) ORDER BY i$$,
  $$VALUES (50.0::float8), (30 * 1.609344::float8), (10 * 1.852::float8), (7), (50), (90), (30), (20), (20), (50), (NULL), (NULL), (NULL), (NULL), (NULL)$$,
  'osm_parse_speed reads km/h, mph, knots, walk and country zones; no limit or junk is NULL');
SELECT results_eq(
  $$SELECT streetgen.osm_parse_lanes(v) FROM unnest(ARRAY['2', ' 3 ', '2;3', '0', '-1', 'two', '99', NULL]) WITH ORDINALITY AS t(v, i) ORDER BY i$$,
  $$VALUES (2::smallint), (3::smallint), (2::smallint), (NULL::smallint), (NULL), (NULL), (NULL), (NULL)$$,
  'osm_parse_lanes: positive counts up to 20, the first of a list');

-- What is driveable.
SELECT ok(streetgen.osm_is_driveable('{"highway": "residential"}'), 'residential is driveable');
SELECT ok(streetgen.osm_is_driveable('{"highway": "service", "service": "alley"}'), 'an alley is driveable');
SELECT ok(NOT streetgen.osm_is_driveable('{"highway": "footway"}'), 'footway is not');
SELECT ok(NOT streetgen.osm_is_driveable('{"highway": "service", "service": "parking_aisle"}'), 'parking aisle is not');
SELECT ok(NOT streetgen.osm_is_driveable('{"highway": "pedestrian", "area": "yes"}'), 'pedestrian area is not');
SELECT ok(NOT streetgen.osm_is_driveable('{"highway": "residential", "motor_vehicle": "no"}'), 'motor_vehicle=no is not');
SELECT ok(NOT streetgen.osm_is_driveable('{"building": "yes"}'), 'no highway tag is not');

-- Attributes: tags win, the class table fills the gaps, and estimated says which.
SELECT results_eq(
  $$SELECT roadway_width, lanes, speed_kmh, road_class, oneway, reverse_geometry, layer, structure, estimated
      FROM streetgen.osm_axis_attributes('{"highway": "residential"}')$$,
  $$VALUES (5.5::float8, 2::smallint, 30::float8, 'residential', false, false, 0::smallint, NULL::text,
            ARRAY['lanes', 'roadway_width', 'speed_kmh'])$$,
  'untagged residential: 2 lanes x 2.75 m, 30 km/h, all estimated');
SELECT results_eq(
  $$SELECT roadway_width, lanes, speed_kmh, oneway, estimated
      FROM streetgen.osm_axis_attributes('{"highway": "primary", "lanes": "3", "maxspeed": "30 mph", "width": "11.5"}')$$,
  $$VALUES (11.5::float8, 3::smallint, 30 * 1.609344::float8, false, '{}'::text[])$$,
  'tagged primary: width, lanes and speed from tags');
SELECT results_eq(
  $$SELECT roadway_width, lanes, estimated FROM streetgen.osm_axis_attributes('{"highway": "secondary", "lanes": "3"}')$$,
  $$VALUES (3 * 3.25::float8, 3::smallint, ARRAY['roadway_width', 'speed_kmh'])$$,
  'width from tagged lanes x lane width');
-- Street parking in the roadway adds to an estimated width (by the engine's rule: parallel 2 m,
-- perpendicular 5 m, half on the kerb half of it); a tagged width already holds it.
SELECT results_eq(
  $$SELECT roadway_width FROM streetgen.osm_axis_attributes('{"highway": "secondary", "lanes": "2", "parking:left": "lane",
                                                               "parking:right": "half_on_kerb", "parking:right:orientation": "perpendicular"}')$$,
  $$VALUES (2 * 3.25::float8 + 2.0 + 2.5)$$,
  'street parking widens an estimated roadway');
SELECT results_eq(
  $$SELECT roadway_width FROM streetgen.osm_axis_attributes('{"highway": "residential", "width": "11", "parking:both": "lane"}')$$,
  $$VALUES (11::float8)$$,
  'a tagged width already holds the parking');
SELECT results_eq(
  $$SELECT roadway_width, estimated FROM streetgen.osm_axis_attributes('{"highway": "tertiary", "width": "1"}')$$,
  $$VALUES (2 * 3.0::float8, ARRAY['lanes', 'roadway_width', 'speed_kmh'])$$,
  'an implausible width (1 m on a road) is replaced by the estimate');
-- Each key the mapping reads behind a look at the tags first (the loader skips the parsing of
-- widths, directional speeds and street parking for ways without such a key): tagged alone, each
-- is still read.
SELECT results_eq(
  $$SELECT a.roadway_width, a.estimated
      FROM unnest(ARRAY['{"highway": "residential", "est_width": "7"}',
                        '{"highway": "residential", "est:width": "8 m"}',
                        '{"highway": "residential", "width:carriageway": "6.5", "width": "12"}',
                        '{"highway": "residential", "parking:right": "lane"}',
                        '{"highway": "residential", "name": "\"parking:left\" lane"}']::jsonb[]) WITH ORDINALITY AS t(tags, i),
           LATERAL streetgen.osm_axis_attributes(t.tags) AS a ORDER BY t.i$$,
  $$VALUES (7::float8, ARRAY['lanes', 'speed_kmh']), (8, ARRAY['lanes', 'speed_kmh']), (6.5, ARRAY['lanes', 'speed_kmh']),
           (2 * 2.75 + 2.0, ARRAY['lanes', 'roadway_width', 'speed_kmh']),
           (2 * 2.75, ARRAY['lanes', 'roadway_width', 'speed_kmh'])$$,
  'est_width, est:width, width:carriageway before width, parking:<side> alone; "parking:" in a value is no key');
SELECT results_eq(
  $$SELECT a.speed_kmh, a.estimated
      FROM unnest(ARRAY['{"highway": "residential", "maxspeed:forward": "50", "maxspeed:backward": "30"}',
                        '{"highway": "residential", "maxspeed:backward": "25 mph"}']::jsonb[]) WITH ORDINALITY AS t(tags, i),
           LATERAL streetgen.osm_axis_attributes(t.tags) AS a ORDER BY t.i$$,
  $$VALUES (30::float8, ARRAY['lanes', 'roadway_width']), (25 * 1.609344::float8, ARRAY['lanes', 'roadway_width'])$$,
  'maxspeed:forward / maxspeed:backward without maxspeed: the lower one');
SELECT results_eq(
  $$SELECT a.sidewalk_width
      FROM unnest(ARRAY['{"highway": "residential", "sidewalk:width": "2.5"}',
                        '{"highway": "residential", "sidewalk:both:width": "3", "sidewalk:width": "2"}',
                        '{"highway": "residential"}']::jsonb[]) WITH ORDINALITY AS t(tags, i),
           LATERAL streetgen.osm_axis_attributes(t.tags) AS a ORDER BY t.i$$,
  $$VALUES (2.5::float8), (3), (NULL)$$,
  'sidewalk:width, sidewalk:both:width first, none without either');
SELECT results_eq(
  $$SELECT lanes FROM streetgen.osm_axis_attributes('{"highway": "tertiary", "lanes:forward": "2", "lanes:backward": "1"}')$$,
  $$VALUES (3::smallint)$$, 'lanes from lanes:forward + lanes:backward');
SELECT results_eq(
  $$SELECT lanes, roadway_width FROM streetgen.osm_axis_attributes('{"highway": "residential", "lanes": "0"}')$$,
  $$VALUES (2::smallint, 5.5::float8)$$, 'lanes=0 falls back to the class default');
SELECT results_eq(
  $$SELECT oneway, reverse_geometry, lanes FROM streetgen.osm_axis_attributes('{"highway": "residential", "oneway": "-1"}')$$,
  $$VALUES (true, true, 1::smallint)$$, 'oneway=-1: one-way, geometry to be reversed, one-way default lanes');
SELECT results_eq(
  $$SELECT a.oneway FROM unnest(ARRAY[
      '{"highway": "motorway"}', '{"highway": "motorway", "oneway": "no"}', '{"highway": "tertiary", "junction": "roundabout"}',
      '{"highway": "tertiary", "oneway": "reversible"}', '{"highway": "tertiary", "oneway": "yes"}']::jsonb[]) WITH ORDINALITY AS u(t, i),
      streetgen.osm_axis_attributes(u.t) AS a ORDER BY u.i$$,
  $$VALUES (true), (false), (true), (false), (true)$$,
  'implied one-way on motorways and roundabouts; explicit tags win');
SELECT results_eq(
  $$SELECT a.layer, a.structure FROM unnest(ARRAY[
      '{"highway": "primary", "bridge": "yes"}', '{"highway": "primary", "bridge": "viaduct", "layer": "2"}',
      '{"highway": "primary", "tunnel": "yes"}', '{"highway": "primary", "tunnel": "building_passage"}',
      '{"highway": "primary", "layer": "-9"}', '{"highway": "primary", "layer": "high"}', '{"highway": "primary", "bridge": "no"}']::jsonb[])
      WITH ORDINALITY AS u(t, i), streetgen.osm_axis_attributes(u.t) AS a ORDER BY u.i$$,
  $$VALUES (1::smallint, 'bridge'::text), (2::smallint, 'bridge'), (-1::smallint, 'tunnel'), (0::smallint, 'tunnel'),
           (-5::smallint, NULL), (0::smallint, NULL), (0::smallint, NULL)$$,
  'layer from tags, bridge above and tunnel below by default, clamped to -5..5');
SELECT throws_ok($$SELECT streetgen.osm_axis_attributes(NULL)$$, '22004', NULL, 'NULL tags');
SELECT throws_ok($$SELECT streetgen.osm_axis_attributes('{"highway": "footway"}')$$, '22023', NULL, 'a class that is not driveable');

-- UTM zones.
SELECT results_eq(
  $$SELECT streetgen.utm_srid(ST_SetSRID(ST_MakePoint(x, y), 4326)) FROM (VALUES
      (2.37, 48.86), (7.42, 43.73), (11.97, 57.70), (-122.28, 37.81), (-47.9, -15.8), (15.6, 78.2), (179.9, 0.0)) AS t(x, y)$$,
  $$VALUES (32631), (32632), (32632), (32610), (32723), (32633), (32660)$$,
  'utm_srid: Paris, Monaco, Gothenburg (Norway exception), Oakland, Brasilia, Svalbard, the antimeridian');
SELECT is(streetgen.utm_srid('SRID=3857;POINT(261000 6250000)'), 32631, 'utm_srid of a projected geometry');
SELECT throws_ok($$SELECT streetgen.utm_srid(NULL)$$, '22004', NULL, 'utm_srid(NULL)');
SELECT throws_ok($$SELECT streetgen.utm_srid('SRID=4326;POINT EMPTY')$$, '22023', NULL, 'utm_srid of an empty geometry');
SELECT throws_ok($$SELECT streetgen.utm_srid('POINT(1 2)')$$, '22023', NULL, 'utm_srid without SRID');
SELECT throws_ok($$SELECT streetgen.utm_srid('SRID=4326;POINT(0 89)')$$, '22023', NULL, 'utm_srid near the pole');
SELECT throws_ok($$SELECT streetgen.utm_srid(ST_SetSRID(ST_MakePoint('NaN', 1), 4326))$$, '22023', NULL, 'utm_srid of a NaN point');

-- load_osm_ways on a staging table: filtering, mapping, reversal, transformation, counts.
SELECT streetgen.create_model('staged', 32631);
CREATE TEMP TABLE staging (source text, tags jsonb, geom geometry);
INSERT INTO staging VALUES
  ('osm:way/1', '{"highway": "residential", "name": "Rue A"}', 'SRID=4326;LINESTRING(2.3700 48.8600, 2.3710 48.8600)'),
  ('osm:way/2', '{"highway": "primary", "oneway": "-1", "maxspeed": "30"}', 'SRID=4326;LINESTRING(2.3700 48.8610, 2.3710 48.8610)'),
  ('osm:way/3', '{"highway": "footway"}', 'SRID=4326;LINESTRING(2.3700 48.8620, 2.3710 48.8620)'),
  ('osm:way/4', '{"highway": "service"}', 'SRID=4326;LINESTRING(2.3700 48.8630, 2.3700 48.8630)'),
  ('osm:way/5', '{"highway": "pedestrian", "area": "yes"}', 'SRID=4326;POLYGON((2.37 48.86, 2.371 48.86, 2.371 48.861, 2.37 48.86))');
SELECT results_eq($$SELECT loaded, not_driveable, degenerate FROM streetgen.load_osm_ways('staged', 'staging')$$,
                  $$VALUES (2::bigint, 2::bigint, 1::bigint)$$,
                  'two roads loaded; footway and pedestrian area not driveable; a zero-length way counted as degenerate');
SELECT results_eq($$SELECT source, road_class, speed_kmh, oneway, ST_SRID(geom) FROM staged.axis ORDER BY source$$,
                  $$VALUES ('osm:way/1', 'residential', 30::float8, false, 32631), ('osm:way/2', 'primary', 30::float8, true, 32631)$$,
                  'mapped attributes and the model SRID');
SELECT ok((SELECT ST_X(ST_StartPoint(geom)) > ST_X(ST_EndPoint(geom)) FROM staged.axis WHERE source = 'osm:way/2'),
          'the oneway=-1 way is stored in its direction of travel (reversed)');
SELECT cmp_ok((SELECT abs(ST_Length(geom) - ST_Length(ST_Transform('SRID=4326;LINESTRING(2.3700 48.8600, 2.3710 48.8600)'::geometry, 32631)))
                 FROM staged.axis WHERE source = 'osm:way/1'), '<', 1e-6::float8, 'transformed to the model SRID');
SELECT is((SELECT tags->>'name' FROM staged.axis WHERE source = 'osm:way/1'), 'Rue A', 'the way''s tags are kept');
SELECT throws_ok($$SELECT * FROM streetgen.load_osm_ways('nope', 'staging')$$, '42704', NULL, 'load into an unknown model');
SELECT throws_ok($$SELECT * FROM streetgen.load_osm_ways(NULL, 'staging')$$, '22004', NULL, 'load with a NULL model');
SELECT throws_ok($$SELECT * FROM streetgen.load_osm_ways('staged', NULL)$$, '22004', NULL, 'load with a NULL staging table');
SELECT throws_ok($$SELECT * FROM streetgen.load_osm_ways('staged', 'no_such_table')$$, '42P01', NULL, 'load from a missing table');
CREATE TEMP TABLE staging_no_srid (source text, tags jsonb, geom geometry);
INSERT INTO staging_no_srid VALUES ('osm:way/9', '{"highway": "residential"}', 'LINESTRING(2.37 48.86, 2.371 48.86)');
SELECT throws_ok($$SELECT * FROM streetgen.load_osm_ways('staged', 'staging_no_srid')$$, '22023', NULL, 'staged geometries without SRID');
CREATE TEMP TABLE staging_bad_geom (source text, tags jsonb, geom geometry);
INSERT INTO staging_bad_geom VALUES
  ('osm:way/10', '{"highway": "residential"}', ST_SetSRID(ST_MakeLine(ST_MakePoint(2.37, 48.86), ST_MakePoint('NaN', 48.86)), 4326)),
  ('osm:way/11', '{"highway": "residential"}', 'SRID=4326;LINESTRING EMPTY'),
  ('osm:way/12', '{"highway": "residential"}', NULL);
SELECT results_eq($$SELECT loaded, not_driveable, degenerate FROM streetgen.load_osm_ways('staged', 'staging_bad_geom')$$,
                  $$VALUES (0::bigint, 0::bigint, 3::bigint)$$,
                  'NaN, empty and missing staged geometries are counted as degenerate, not loaded');
CREATE TEMP TABLE staging_out_of_range (source text, tags jsonb, geom geometry);
INSERT INTO staging_out_of_range VALUES ('osm:way/13', '{"highway": "residential"}', 'SRID=4326;LINESTRING(2.37 48.86, 2.37 95)');
SELECT throws_ok($$SELECT * FROM streetgen.load_osm_ways('staged', 'staging_out_of_range')$$, '22023', NULL,
                 'a latitude of 95 degrees cannot be transformed: a clear 22023, not an internal error');

-- Street parking mapped as its own area (parking:<side>=separate): the bays lining at least half
-- of a side widen its roadway by their depth; other sides stay as they were.
SELECT streetgen.create_model('parked', 32631);
INSERT INTO parked.axis (id, geom, roadway_width, speed_kmh, road_class, tags) VALUES
  (1, 'SRID=32631;LINESTRING(0 0, 100 0)', 8, 30, 'residential', '{"parking:left": "lane", "parking:right": "separate"}'),
  (2, 'SRID=32631;LINESTRING(0 100, 100 100)', 8, 30, 'residential', '{"parking:both": "separate"}'),
  (3, 'SRID=32631;LINESTRING(0 200, 100 200)', 8, 30, 'residential', '{}');
-- a oneway=-1 way drawn eastwards, stored reversed: its left (north) is the axis' right
INSERT INTO parked.axis (id, geom, roadway_width, speed_kmh, road_class, oneway, tags) VALUES
  (4, 'SRID=32631;LINESTRING(100 300, 0 300)', 3, 30, 'residential', true, '{"oneway": "-1", "parking:left": "separate"}');
CREATE TEMP TABLE staging_parking (source text, tags jsonb, geom geometry);
INSERT INTO staging_parking VALUES
  -- axis 1, right (south): two 5 m deep bays along 60 % of it; left (north, a parking lane, not
  -- separate): a bay all along, which must not count
  ('osm:way/21', '{"amenity": "parking", "parking": "street_side"}', 'SRID=32631;POLYGON((0 -3, 30 -3, 30 -8, 0 -8, 0 -3))'),
  ('osm:way/22', '{"amenity": "parking", "parking": "street_side"}', 'SRID=32631;POLYGON((40 -3, 70 -3, 70 -8, 40 -8, 40 -3))'),
  ('osm:way/23', '{"amenity": "parking", "parking": "street_side"}', 'SRID=32631;POLYGON((0 4, 100 4, 100 9, 0 9, 0 4))'),
  -- axis 2: 2 m deep on the right along 60 %, on the left along 30 % only
  ('osm:way/24', '{"amenity": "parking", "parking": "street_side"}', 'SRID=32631;POLYGON((0 96, 60 96, 60 98, 0 98, 0 96))'),
  ('osm:way/25', '{"amenity": "parking", "parking": "street_side"}', 'SRID=32631;POLYGON((0 103, 30 103, 30 108, 0 108, 0 103))'),
  -- axis 3 has no parking:*=separate: its bay is not its roadway
  ('osm:way/26', '{"amenity": "parking", "parking": "street_side"}', 'SRID=32631;POLYGON((0 196, 100 196, 100 191, 0 191, 0 196))'),
  -- axis 4: bays north of it, all along
  ('osm:way/28', '{"amenity": "parking", "parking": "street_side"}', 'SRID=32631;POLYGON((0 301.5, 100 301.5, 100 306.5, 0 306.5, 0 301.5))'),
  -- not an area: ignored
  ('osm:way/27', '{"amenity": "parking", "parking": "street_side"}', 'SRID=32631;LINESTRING(0 -3, 100 -3)');
SELECT results_eq($$SELECT sides_widened, areas_used FROM streetgen.load_osm_street_parking('parked', 'staging_parking')$$,
                  $$VALUES (3::bigint, 4::bigint)$$, 'three sides widened, by four bays');
SELECT results_eq($$SELECT id, roadway_width, tags->>'parking:left:separate_width', tags->>'parking:right:separate_width'
                      FROM parked.axis ORDER BY id$$,
                  $$VALUES (1::bigint, 13::float8, NULL, '5.0'), (2, 10, NULL, '2.0'), (3, 8, NULL, NULL), (4, 8, '5.0', NULL)$$,
                  'the lined sides widen by the bays'' depth (the reversed way''s left by the bays on the axis'' right); a side lined along 30 %, a parking lane side and an untagged road do not');
SELECT results_eq($$SELECT sides_widened, areas_used FROM streetgen.load_osm_street_parking('parked', 'staging_parking')$$,
                  $$VALUES (0::bigint, 0::bigint)$$, 'loading again widens nothing twice');
SELECT is((SELECT roadway_width FROM parked.axis WHERE id = 1), 13::float8, 'the width after the second load');
-- A file without parking areas (most): nothing widened, nothing read twice; the model is still checked.
CREATE TEMP TABLE staging_no_parking_area (source text, tags jsonb, geom geometry);
INSERT INTO staging_no_parking_area VALUES
  ('osm:way/29', '{"amenity": "parking", "parking": "street_side"}', 'SRID=32631;LINESTRING(0 -3, 100 -3)');
SELECT results_eq($$SELECT sides_widened, areas_used FROM streetgen.load_osm_street_parking('parked', 'staging_no_parking_area')$$,
                  $$VALUES (0::bigint, 0::bigint)$$, 'no staged parking area: no side widened');
SELECT is((SELECT array_agg(roadway_width ORDER BY id) FROM parked.axis), ARRAY[13, 10, 8, 8]::float8[],
          'and every width as it was');
SELECT throws_ok($$SELECT * FROM streetgen.load_osm_street_parking('nope', 'staging_no_parking_area')$$, '42704', NULL,
                 'street parking into an unknown model, even with no parking area staged');
SELECT streetgen.generate('parked');
SELECT results_eq($$SELECT type, direction, width FROM parked.lane WHERE axis_id = 1 ORDER BY lane_index$$,
                  $$VALUES ('parking', 'backward', 2::float8), ('driving', 'backward', 3::float8),
                           ('driving', 'forward', 3::float8), ('parking', 'forward', 5::float8)$$,
                  'the engine draws the separate parking as a 5 m parking lane at the right curb');
SELECT cmp_ok((SELECT abs(ST_YMin(ST_Collect(geom)) + 8) FROM parked.section WHERE axis_id = 1), '<', 1e-6::float8,
              'the section reaches the far edge of the bays (3 m of traffic lane, then 5 m of bays)');
SELECT cmp_ok((SELECT abs(ST_YMax(ST_Collect(geom)) - 5) FROM parked.section WHERE axis_id = 1), '<', 1e-6::float8,
              'and the parking lane on the left still ends at 5 m');
SELECT results_eq($$SELECT type, direction, width FROM parked.lane WHERE axis_id = 4 ORDER BY lane_index$$,
                  $$VALUES ('driving', 'forward', 3::float8), ('parking', 'forward', 5::float8)$$,
                  'a reversed way''s parking:left is drawn at the stored axis'' right curb');
SELECT cmp_ok((SELECT abs(ST_YMax(ST_Collect(geom)) - 306.5) FROM parked.section WHERE axis_id = 4), '<', 1e-6::float8,
              'its section reaches the bays north of it');
SELECT throws_ok($$SELECT * FROM streetgen.load_osm_street_parking('parked', NULL)$$, '22004', NULL,
                 'street parking from a NULL staging table');
SELECT throws_ok($$SELECT * FROM streetgen.load_osm_street_parking('parked', 'no_such_table')$$, '42P01', NULL,
                 'street parking from a missing table');
SELECT throws_ok($$SELECT * FROM streetgen.load_osm_street_parking('nope', 'staging_parking')$$, '42704', NULL,
                 'street parking into an unknown model');

SELECT * FROM finish();
ROLLBACK;
