-- Checks the models run-import.sh loaded, against the facts it gathered with osmium and python.
BEGIN;
SELECT * FROM no_plan();

-- Every axis of every imported model, with its model's facts.
CREATE FUNCTION pg_temp.all_axes() RETURNS TABLE (model text, srid integer, id bigint, geom geometry, roadway_width float8,
    speed_kmh float8, lanes smallint, road_class text, source text, tags jsonb, estimated text[])
  LANGUAGE plpgsql AS $$
DECLARE
  m record;
BEGIN
  FOR m IN SELECT f.model FROM import_fact f ORDER BY f.model LOOP
    RETURN QUERY EXECUTE format('SELECT %L::text, streetgen.model_srid(%L), a.id, a.geom, a.roadway_width, a.speed_kmh,
                                        a.lanes, a.road_class, a.source, a.tags, a.estimated FROM %I.axis a',
                                m.model, m.model, m.model);
  END LOOP;
END $$;
CREATE TEMP TABLE axes AS SELECT * FROM pg_temp.all_axes();

SELECT cmp_ok((SELECT count(*) FROM import_fact WHERE kind = 'osm'), '>=', 5::bigint, 'at least five OSM files imported');
SELECT is((SELECT count(DISTINCT file ~ '\.pbf$')::int + count(DISTINCT file ~ '\.gz$')::int FROM import_fact WHERE kind = 'osm'), 4,
          'pbf and non-pbf, gz and non-gz files are among them');
SELECT is_empty($$SELECT model FROM import_fact WHERE loaded < 10$$, 'every file gives at least ten axes');
SELECT is_empty($$SELECT f.model FROM import_fact f LEFT JOIN (SELECT model, count(*) n FROM axes GROUP BY model) a USING (model)
                   WHERE coalesce(a.n, 0) <> f.loaded$$,
                'each model holds exactly the number of axes the importer reported');

-- Against osmium: nothing invented, nothing duplicated, most driveable ways kept.
SELECT is_empty($$SELECT model FROM import_fact WHERE kind = 'osm' AND loaded + not_driveable + degenerate > highway_ways$$,
                'no more ways staged than osmium finds highway ways');
SELECT is_empty($$SELECT model FROM import_fact WHERE kind = 'osm' AND loaded > driveable_class_ways$$,
                'no more axes than osmium finds ways of driveable classes');
-- Extracts cut ways whose nodes lie outside them; osm2pgsql cannot build those. The rest stays.
SELECT is_empty($$SELECT model, loaded, driveable_class_ways FROM import_fact
                   WHERE kind = 'osm' AND loaded < 0.5 * driveable_class_ways$$,
                'at least half of the driveable-class ways osmium sees are loaded');
SELECT is_empty($$SELECT a.model, a.source FROM axes a
                   WHERE a.model <> 'gothenburg'
                     AND NOT EXISTS (SELECT 1 FROM import_source_id s WHERE s.model = a.model AND s.source = a.source)$$,
                'every axis comes from a highway way osmium knows');
SELECT is_empty($$SELECT model, source FROM axes GROUP BY model, source HAVING count(*) > 1$$, 'no way is loaded twice');
SELECT is((SELECT loaded + not_driveable + degenerate FROM import_fact WHERE model = 'gothenburg'),
          (SELECT highway_ways FROM import_fact WHERE model = 'gothenburg'),
          'GeoJSON: every feature is accounted for (loaded, not driveable or degenerate)');

-- The reader (streetgen-osm-stage) stages what osm2pgsql with the shipped flex style stages.
SELECT is((SELECT count(*) FROM stage_parity), (SELECT count(*) + 2 FROM import_fact WHERE kind = 'osm'),
          'every OSM file and the hand-made cases (out of order, and sorted by type) were staged by both');
SELECT is_empty($$SELECT * FROM stage_parity
                   WHERE osm2pgsql_lines <> reader_lines OR lines_only_osm2pgsql > 0 OR lines_only_reader > 0
                      OR osm2pgsql_areas <> reader_areas OR areas_differing > 0$$,
                'the reader stages the same lines (to the byte) and street parking areas as osm2pgsql');
SELECT results_eq($$SELECT reader_lines, reader_areas FROM stage_parity WHERE name IN ('cases', 'cases_by_type') ORDER BY name$$,
                  $$VALUES (5::bigint, 2::bigint), (5::bigint, 2::bigint)$$,
                  'hand-made cases: five highway lines (a missing node skipped, repeats once, a closed way, a highway with parking tags) and two street parking areas (a closed way, a multipolygon)');
SELECT is((SELECT string_agg(source, ' ' ORDER BY source) FROM oracle.s_cases),
          'osm:relation/30 osm:way/10 osm:way/11 osm:way/13 osm:way/14 osm:way/20 osm:way/22',
          'hand-made cases: which objects are staged');
SELECT is_empty($$SELECT kind, source, tags, ST_AsEWKB(geom) FROM oracle.s_cases
                  EXCEPT ALL SELECT kind, source, tags, ST_AsEWKB(geom) FROM oracle.s_cases_by_type$$,
                'the hand-made cases give the same rows in one pass (sorted by type) as in two (out of order)');
SELECT is((SELECT tags FROM oracle.s_cases WHERE source = 'osm:way/10'),
          jsonb_build_object('highway', 'residential', 'name', 'Straße "am" Back\slash',
                             'note', E'a tab\tand a new line\nin a value', 'name:ja', '通り'),
          'quotes, backslashes, tabs, new lines and non-Latin text in tags arrive as they are in the file');

-- The axes themselves.-- The axes themselves.
SELECT is_empty($$SELECT model, id FROM axes WHERE NOT (roadway_width > 0 AND speed_kmh > 0)$$,
                'every axis has a positive roadway width and speed');
SELECT is_empty($$SELECT model, id FROM axes WHERE NOT ST_IsValid(geom) OR ST_GeometryType(geom) <> 'ST_LineString'$$,
                'every axis is a valid LineString');
SELECT is_empty($$SELECT model, id FROM axes WHERE ST_SRID(geom) <> srid$$, 'every axis is in its model''s SRID');
SELECT is_empty($$SELECT f.model, streetgen.model_srid(f.model)
                    FROM import_fact f
                   WHERE f.model <> 'gothenburg'
                     AND streetgen.model_srid(f.model) <> CASE WHEN f.minlat + f.maxlat >= 0 THEN 32600 ELSE 32700 END
                                                          + floor(((f.minlon + f.maxlon) / 2 + 180) / 6)::int + 1$$,
                'each OSM model is in the UTM zone of its data''s centre');
SELECT is(streetgen.model_srid('gothenburg'), 32632, 'Gothenburg is in UTM 32N (the Norway exception)');
SELECT is_empty($$SELECT a.model, a.id FROM axes a JOIN import_fact f USING (model)
                   WHERE NOT ST_CoveredBy(ST_Transform(a.geom, 4326),
                                          ST_Expand(ST_MakeEnvelope(f.minlon, f.minlat, f.maxlon, f.maxlat, 4326), 1e-6))$$,
                'every axis lies inside its file''s bounding box (osmium) after the round trip through UTM');
SELECT is_empty($$SELECT model, id, tags->>'highway' FROM axes
                   WHERE tags->>'highway' IN ('footway', 'cycleway', 'path', 'steps', 'pedestrian', 'track', 'bridleway', 'platform', 'construction')$$,
                'no footway, cycleway, path, steps, pedestrian, track or construction way is an axis');

-- Tags are honoured on real data.
SELECT is_empty($$SELECT model, id, tags->>'maxspeed', speed_kmh FROM axes
                   WHERE tags->>'maxspeed' ~ '^[0-9]{1,3}$' AND (tags->>'maxspeed')::int BETWEEN 1 AND 300
                     AND speed_kmh <> (tags->>'maxspeed')::float8$$,
                'a numeric maxspeed tag is the axis speed');
SELECT is_empty($$SELECT model, id, tags->>'width', roadway_width FROM axes
                   WHERE tags->>'width' ~ '^[0-9]+(\.[0-9]+)?$' AND (tags->>'width')::float8 BETWEEN 2 AND 60
                     AND NOT tags ? 'width:carriageway' AND roadway_width <> (tags->>'width')::float8$$,
                'a plausible width tag is the roadway width');
SELECT is_empty($$SELECT model, id FROM axes
                   WHERE tags->>'lanes' ~ '^[1-9]$' AND lanes <> (tags->>'lanes')::int$$,
                'a lanes tag is the lane count');
SELECT is_empty($$SELECT model, id, tags->>'width', roadway_width FROM axes
                   WHERE NOT 'roadway_width' = ANY(estimated)
                     AND NOT EXISTS (
                       SELECT 1 FROM unnest(ARRAY[tags->>'width', tags->>'width:carriageway', tags->>'est_width', tags->>'est:width']) w(v),
                                     LATERAL (SELECT replace((regexp_match(v, '^\s*([0-9]+([.,][0-9]+)?)'))[1], ',', '.')::float8 AS n) p
                        WHERE abs(p.n - roadway_width) < 1e-9 OR abs(p.n * 0.3048 - roadway_width) < 0.3)$$,
                'a width not marked estimated is the number of a width tag (metres or feet)');

SELECT * FROM finish();
ROLLBACK;
