-- OSM tags -> axis attributes. The one definition of the mapping, used by both import paths
-- (osm2pgsql flex for OSM files, ogr2ogr for GeoJSON): the flex style only stages raw tags.

-- Per highway class: what to assume when tags are missing. The StreetGen paper estimates
-- roadway width and speed from the road's importance; these are our estimates, editable here.
--   width = lanes x lane_width, lanes from the `lanes` tag or the default for the direction;
--   speed = the maxspeed tag, else speed_kmh (typical urban limits, km/h).
CREATE TABLE streetgen.highway_class (
  highway text PRIMARY KEY,
  lane_width double precision NOT NULL CHECK (lane_width > 0 AND lane_width <= 10),
  lanes_two_way smallint NOT NULL CHECK (lanes_two_way BETWEEN 1 AND 20),
  lanes_one_way smallint NOT NULL CHECK (lanes_one_way BETWEEN 1 AND 20),
  speed_kmh double precision NOT NULL CHECK (speed_kmh > 0 AND speed_kmh <= 300),
  implied_oneway boolean NOT NULL DEFAULT false
);
COMMENT ON TABLE streetgen.highway_class IS
  'Driveable OSM highway classes and the defaults used when width, lanes or maxspeed are not tagged';
GRANT SELECT ON streetgen.highway_class TO PUBLIC;

INSERT INTO streetgen.highway_class (highway, lane_width, lanes_two_way, lanes_one_way, speed_kmh, implied_oneway) VALUES
  ('motorway',       3.50, 4, 2, 110, true),
  ('motorway_link',  3.50, 2, 1,  60, false),
  ('trunk',          3.50, 4, 2,  90, false),
  ('trunk_link',     3.50, 2, 1,  50, false),
  ('primary',        3.25, 2, 2,  50, false),
  ('primary_link',   3.25, 2, 1,  40, false),
  ('secondary',      3.25, 2, 1,  50, false),
  ('secondary_link', 3.25, 2, 1,  40, false),
  ('tertiary',       3.00, 2, 1,  50, false),
  ('tertiary_link',  3.00, 2, 1,  30, false),
  ('unclassified',   2.75, 2, 1,  40, false),
  ('residential',    2.75, 2, 1,  30, false),
  ('living_street',  2.50, 2, 1,  10, false),
  ('road',           2.75, 2, 1,  40, false),
  ('service',        3.00, 1, 1,  20, false);

-- The parsers and the mapping below are plain SQL without a SET clause so that PostgreSQL
-- inlines them into load_osm_ways' one INSERT ... SELECT (a SET clause, or plpgsql, would cost
-- a function call per tag per way: 2 s instead of a fraction for 7,000 ways). They name nothing
-- outside pg_catalog and streetgen, so the caller's search_path cannot change what they do.

-- A length in metres from an OSM value: "7", "7.5 m", "7,5", "24'", "12 ft", "8'6\"".
-- NULL when it cannot be read.
CREATE FUNCTION streetgen.osm_parse_length(value text)
  RETURNS double precision
  LANGUAGE sql IMMUTABLE PARALLEL SAFE
  AS $$
    SELECT CASE
      WHEN pg_catalog.replace(pg_catalog.lower(pg_catalog.btrim(value)), ',', '.') ~ '^[0-9]+(\.[0-9]+)?\s*(m|meters?|metres?)?$'
        THEN pg_catalog.substring(pg_catalog.replace(pg_catalog.btrim(value), ',', '.'), '^([0-9]+(?:\.[0-9]+)?)')::double precision
      WHEN pg_catalog.replace(pg_catalog.lower(pg_catalog.btrim(value)), ',', '.') ~ '^[0-9]+(\.[0-9]+)?\s*(''|ft|feet)$'
        THEN pg_catalog.substring(pg_catalog.replace(pg_catalog.btrim(value), ',', '.'), '^([0-9]+(?:\.[0-9]+)?)')::double precision * 0.3048
      WHEN pg_catalog.replace(pg_catalog.btrim(value), ',', '.') ~ '^[0-9]+''\s*[0-9]+(\.[0-9]+)?"$'
        THEN pg_catalog.substring(pg_catalog.btrim(value), '^([0-9]+)')::double precision * 0.3048
             + pg_catalog.substring(pg_catalog.replace(pg_catalog.btrim(value), ',', '.'), '''\s*([0-9]+(?:\.[0-9]+)?)"$')::double precision * 0.0254
    END
  $$;
COMMENT ON FUNCTION streetgen.osm_parse_length(text) IS 'Metres from an OSM width value (m, ft, feet-inches); NULL if unreadable';

-- A speed in km/h from an OSM maxspeed value: "50", "30 mph", "10 knots", "walk", and the
-- implicit country values ("DE:urban", "FR:rural", "RU:living_street", "DE:zone30", ...).
-- NULL when it cannot be read or means no limit ("none", "signals", "variable"); the first of
-- a list ("50;30") counts. In three functions of one expression each, none with a FROM: a SQL
-- function is inlined only then, and called otherwise (27 us a call: a FROM over the lowered
-- value made Reisterstown's 4,560 ways cost 1.2 s of the import, three calls a way).
CREATE FUNCTION streetgen._osm_speed_in_range(kmh double precision)
  RETURNS double precision
  LANGUAGE sql IMMUTABLE PARALLEL SAFE
  AS $$ SELECT CASE WHEN kmh > 0 AND kmh <= 300 THEN kmh END $$;
-- (v: the value lower-cased and trimmed, its first list item)
CREATE FUNCTION streetgen._osm_speed_of(v text)
  RETURNS double precision
  LANGUAGE sql IMMUTABLE PARALLEL SAFE
  AS $$
    SELECT CASE
      WHEN v ~ '^[0-9]+(\.[0-9]+)?\s*(km/h|kmh|kph)?$'
        THEN streetgen._osm_speed_in_range(pg_catalog.substring(v, '^([0-9]+(?:\.[0-9]+)?)')::double precision)
      WHEN v ~ '^[0-9]+(\.[0-9]+)?\s*mph$'
        THEN streetgen._osm_speed_in_range(pg_catalog.substring(v, '^([0-9]+(?:\.[0-9]+)?)')::double precision * 1.609344)
      WHEN v ~ '^[0-9]+(\.[0-9]+)?\s*knots$'
        THEN streetgen._osm_speed_in_range(pg_catalog.substring(v, '^([0-9]+(?:\.[0-9]+)?)')::double precision * 1.852)
      WHEN v ~ 'zone:?[0-9]+$' THEN streetgen._osm_speed_in_range(pg_catalog.substring(v, 'zone:?([0-9]+)$')::double precision)
      WHEN v = 'walk' OR v ~ ':walk$' THEN 7
      WHEN v ~ ':living_street$' THEN 20
      WHEN v ~ ':bicycle_road$' THEN 30
      WHEN v ~ ':urban$' THEN 50
      WHEN v ~ ':rural$' THEN 90
      WHEN v ~ ':trunk$' THEN 100
      WHEN v ~ ':motorway$' THEN 120
    END
  $$;
CREATE FUNCTION streetgen.osm_parse_speed(value text)
  RETURNS double precision
  LANGUAGE sql IMMUTABLE PARALLEL SAFE
  AS $$ SELECT streetgen._osm_speed_of(pg_catalog.lower(pg_catalog.btrim(pg_catalog.split_part(value, ';', 1)))) $$;
COMMENT ON FUNCTION streetgen.osm_parse_speed(text) IS 'km/h from an OSM maxspeed value (numbers, mph, knots, country zones); NULL if unreadable';

-- A positive lane count from an OSM value ("2", "2;3" takes the first); NULL for 0, junk, > 20.
CREATE FUNCTION streetgen.osm_parse_lanes(value text)
  RETURNS smallint
  LANGUAGE sql IMMUTABLE PARALLEL SAFE
  AS $$
    SELECT CASE WHEN pg_catalog.btrim(pg_catalog.split_part(value, ';', 1)) ~ '^[0-9]{1,3}$'
                 AND pg_catalog.btrim(pg_catalog.split_part(value, ';', 1))::integer BETWEEN 1 AND 20
                THEN pg_catalog.btrim(pg_catalog.split_part(value, ';', 1))::smallint END
  $$;
COMMENT ON FUNCTION streetgen.osm_parse_lanes(text) IS 'Lane count from an OSM lanes value; NULL for 0, junk or more than 20';

-- Is this OSM way a driveable road? Rules: highway class in streetgen.highway_class; not an
-- area; motor vehicles not forbidden; service roads except parking aisles, parking lots,
-- emergency access and private ones (the OSMnx "drive_service" rules).
-- The conditions of osm_is_driveable besides the class, for callers that join highway_class
-- themselves: one expression without a subquery, so PostgreSQL inlines it (osm_is_driveable's
-- EXISTS keeps it from being inlined: a call per way, about 10 µs each, most of a load's filter).
CREATE FUNCTION streetgen._osm_driveable_tags(tags jsonb)
  RETURNS boolean
  LANGUAGE sql IMMUTABLE PARALLEL SAFE
  AS $$
    SELECT coalesce(tags->>'area', 'no') <> 'yes'
       AND coalesce(tags->>'motor_vehicle', '') <> 'no'
       AND coalesce(tags->>'motorcar', '') <> 'no'
       AND NOT (tags->>'highway' = 'service'
                AND coalesce(tags->>'service', '') IN ('parking_aisle', 'parking', 'emergency_access', 'private'))
  $$;

CREATE FUNCTION streetgen.osm_is_driveable(tags jsonb)
  RETURNS boolean
  LANGUAGE sql STABLE PARALLEL SAFE
  AS $$
    SELECT EXISTS (SELECT 1 FROM streetgen.highway_class h WHERE h.highway = tags->>'highway')
       AND streetgen._osm_driveable_tags(tags)
  $$;
COMMENT ON FUNCTION streetgen.osm_is_driveable(jsonb) IS 'True for OSM ways that are driveable roads (see streetgen.highway_class)';

-- The roadway street parking takes on the left and the right (m), from "key=value" lines of
-- parking:* tags, by the engine's own rule (src/core/streets/lanes.cpp): an estimated roadway
-- width adds it to the traffic lanes.
CREATE FUNCTION streetgen._street_parking_widths(parking_tags text)
  RETURNS double precision[]
  LANGUAGE c IMMUTABLE PARALLEL SAFE
  AS 'MODULE_PATHNAME', '_streetgen_street_parking';

-- The mapping itself: axis attributes from the tags of a driveable way (no row for other
-- ways). reverse_geometry: oneway=-1 ways are stored in their direction of travel with oneway
-- = true. estimated lists what came from streetgen.highway_class rather than from tags.
CREATE FUNCTION streetgen._osm_axis_attributes(tags jsonb)
  RETURNS TABLE (roadway_width double precision, lanes smallint, speed_kmh double precision, road_class text,
                 oneway boolean, reverse_geometry boolean, layer smallint, structure text,
                 sidewalk_width double precision, estimated text[])
  LANGUAGE sql STABLE PARALLEL SAFE
  AS $$
    SELECT coalesce(w.tagged, l.lanes * h.lane_width + pk.widths[1] + pk.widths[2]),
           l.lanes,
           coalesce(sp.tagged, h.speed_kmh),
           h.highway,
           o.oneway,
           o.reverse_geometry,
           greatest(-5, least(5, coalesce(
             CASE WHEN pg_catalog.btrim(tags->>'layer') ~ '^[+-]?[0-9]{1,2}$' THEN pg_catalog.btrim(tags->>'layer')::integer END,
             -- OSM convention: a bridge without layer is above ground, a tunnel below (a
             -- building passage stays at ground level).
             CASE WHEN st.structure = 'bridge' THEN 1
                  WHEN st.structure = 'tunnel' AND tags->>'tunnel' <> 'building_passage' THEN -1
                  ELSE 0 END)))::smallint,
           st.structure,
           -- (the subqueries on the tags' values run only for ways that have one of their keys,
           -- few of them: without one the answer is NULL)
           CASE WHEN tags ?| ARRAY['sidewalk:both:width', 'sidewalk:width'] THEN
             (SELECT x FROM pg_catalog.unnest(ARRAY[streetgen.osm_parse_length(tags->>'sidewalk:both:width'),
                                                     streetgen.osm_parse_length(tags->>'sidewalk:width')]) AS x
               WHERE x > 0 AND x <= 20 LIMIT 1) END,
           pg_catalog.array_remove(ARRAY[CASE WHEN l.estimated THEN 'lanes' END,
                                         CASE WHEN w.tagged IS NULL THEN 'roadway_width' END,
                                         CASE WHEN sp.tagged IS NULL THEN 'speed_kmh' END], NULL)
      FROM streetgen.highway_class AS h,
           LATERAL (SELECT pg_catalog.lower(tags->>'oneway') AS tag) AS ot,
           LATERAL (SELECT CASE
                             WHEN ot.tag IN ('yes', 'true', '1', '-1', 'reverse') THEN true
                             WHEN ot.tag IN ('no', 'false', '0', 'reversible', 'alternating') THEN false
                             ELSE h.implied_oneway OR coalesce(tags->>'junction', '') IN ('roundabout', 'circular')
                           END AS oneway,
                           coalesce(ot.tag IN ('-1', 'reverse'), false) AS reverse_geometry) AS o,
           LATERAL (SELECT coalesce(streetgen.osm_parse_lanes(tags->>'lanes'),
                             CASE WHEN tags ? 'lanes:forward' OR tags ? 'lanes:backward' THEN
                               nullif(coalesce(streetgen.osm_parse_lanes(tags->>'lanes:forward'), 0)
                                                 + coalesce(streetgen.osm_parse_lanes(tags->>'lanes:backward'), 0)
                                                 + coalesce(streetgen.osm_parse_lanes(tags->>'lanes:both_ways'), 0), 0)::smallint
                             END) AS tagged) AS lt,
           LATERAL (SELECT coalesce(lt.tagged, CASE WHEN o.oneway THEN h.lanes_one_way ELSE h.lanes_two_way END) AS lanes,
                           lt.tagged IS NULL AS estimated) AS l,
           -- Widths under 2 m or over 60 m on a driveable road are tagging mistakes (a footway
           -- width, the whole corridor): estimated instead.
           LATERAL (SELECT CASE WHEN tags ?| ARRAY['width:carriageway', 'width', 'est_width', 'est:width'] THEN
                             (SELECT x FROM pg_catalog.unnest(ARRAY[streetgen.osm_parse_length(tags->>'width:carriageway'),
                                                                     streetgen.osm_parse_length(tags->>'width'),
                                                                     streetgen.osm_parse_length(tags->>'est_width'),
                                                                     streetgen.osm_parse_length(tags->>'est:width')])
                                                     WITH ORDINALITY AS u(x, i)
                               WHERE x BETWEEN 2 AND 60 ORDER BY i LIMIT 1) END AS tagged) AS w,
           -- (most ways have no parking:* key: a look at the tags' text first spares them the
           -- listing of every tag; without one the widths are those of no tags, a constant)
           LATERAL (SELECT CASE WHEN tags::text LIKE '%"parking:%'
                                THEN streetgen._street_parking_widths(
                                       (SELECT pg_catalog.string_agg(t.key || '=' || t.value, E'\n')
                                          FROM pg_catalog.jsonb_each_text(tags) AS t WHERE t.key LIKE 'parking:%'))
                                ELSE streetgen._street_parking_widths(NULL) END AS widths) AS pk,
           LATERAL (SELECT coalesce(streetgen.osm_parse_speed(tags->>'maxspeed'),
                             CASE WHEN tags ?| ARRAY['maxspeed:forward', 'maxspeed:backward'] THEN
                               least(streetgen.osm_parse_speed(tags->>'maxspeed:forward'),
                                     streetgen.osm_parse_speed(tags->>'maxspeed:backward')) END) AS tagged) AS sp,
           LATERAL (SELECT CASE WHEN coalesce(tags->>'bridge', 'no') <> 'no' THEN 'bridge'
                                WHEN coalesce(tags->>'tunnel', 'no') <> 'no' THEN 'tunnel' END AS structure) AS st
     WHERE h.highway = tags->>'highway'
  $$;

-- The mapping for one way, with clear errors for what it cannot map.
CREATE FUNCTION streetgen.osm_axis_attributes(tags jsonb,
    OUT roadway_width double precision, OUT lanes smallint, OUT speed_kmh double precision,
    OUT road_class text, OUT oneway boolean, OUT reverse_geometry boolean, OUT layer smallint,
    OUT structure text, OUT sidewalk_width double precision, OUT estimated text[])
  RETURNS record
  LANGUAGE plpgsql STABLE PARALLEL SAFE
  SET search_path FROM CURRENT
  AS $$
BEGIN
  IF tags IS NULL THEN
    RAISE EXCEPTION 'tags must not be null' USING ERRCODE = 'null_value_not_allowed';
  END IF;
  SELECT * INTO roadway_width, lanes, speed_kmh, road_class, oneway, reverse_geometry, layer, structure,
                sidewalk_width, estimated
    FROM streetgen._osm_axis_attributes(tags);
  IF NOT FOUND THEN
    RAISE EXCEPTION 'highway=% is not a driveable class', coalesce(tags->>'highway', '(missing)')
      USING ERRCODE = 'invalid_parameter_value',
            HINT = 'Filter with streetgen.osm_is_driveable(tags); the classes are in streetgen.highway_class.';
  END IF;
END
$$;
COMMENT ON FUNCTION streetgen.osm_axis_attributes(jsonb) IS
  'Axis attributes (width, lanes, speed, class, one-way, layer, structure) from the tags of a driveable OSM way, estimating what is missing';

-- The EPSG code of the WGS 84 / UTM zone holding the centre of GEOM's bounding box, with the
-- Norway and Svalbard exceptions.
CREATE FUNCTION streetgen.utm_srid(geom geometry)
  RETURNS integer
  LANGUAGE plpgsql STABLE PARALLEL SAFE
  SET search_path FROM CURRENT
  AS $$
DECLARE
  centre geometry;
  lon double precision;
  lat double precision;
  zone integer;
BEGIN
  IF geom IS NULL THEN
    RAISE EXCEPTION 'geom must not be null' USING ERRCODE = 'null_value_not_allowed';
  END IF;
  IF ST_IsEmpty(geom) THEN
    RAISE EXCEPTION 'geom is empty' USING ERRCODE = 'invalid_parameter_value';
  END IF;
  IF ST_SRID(geom) = 0 THEN
    RAISE EXCEPTION 'geom has no SRID, so its place on Earth is unknown'
      USING ERRCODE = 'invalid_parameter_value', HINT = 'Set one with ST_SetSRID.';
  END IF;
  centre := ST_Transform(ST_Centroid(ST_Envelope(geom)), 4326);
  lon := ST_X(centre);
  lat := ST_Y(centre);
  -- NULL when the centre is empty, as for NaN coordinates.
  IF lon IS NULL OR lat IS NULL OR NOT (lon BETWEEN -180 AND 180) OR NOT (lat BETWEEN -80 AND 84) THEN
    RAISE EXCEPTION 'no UTM zone at longitude %, latitude %', lon, lat
      USING ERRCODE = 'invalid_parameter_value',
            DETAIL = 'UTM covers latitudes 80 S to 84 N; the coordinates may be non-finite or out of range.';
  END IF;
  zone := least(60, floor((lon + 180) / 6)::integer + 1);
  IF lat >= 56 AND lat < 64 AND lon >= 3 AND lon < 12 THEN
    zone := 32;
  ELSIF lat >= 72 THEN
    zone := CASE WHEN lon >= 0 AND lon < 9 THEN 31 WHEN lon >= 9 AND lon < 21 THEN 33
                 WHEN lon >= 21 AND lon < 33 THEN 35 WHEN lon >= 33 AND lon < 42 THEN 37 ELSE zone END;
  END IF;
  RETURN CASE WHEN lat >= 0 THEN 32600 ELSE 32700 END + zone;
END
$$;
COMMENT ON FUNCTION streetgen.utm_srid(geometry) IS 'EPSG code of the WGS 84 UTM zone at the centre of geom''s bounding box';

-- Loads staged OSM ways into MODEL's axis table. STAGING is any table or view with columns
-- source text (e.g. 'osm:way/42'), tags jsonb, geom geometry (LineStrings in any SRID with a
-- known transformation; other geometry types are counted as degenerate).
-- Keeps driveable ways, maps tags with osm_axis_attributes, transforms to the model's SRID.
CREATE FUNCTION streetgen.load_osm_ways(model text, staging regclass,
    OUT loaded bigint, OUT not_driveable bigint, OUT degenerate bigint)
  RETURNS record
  LANGUAGE plpgsql VOLATILE
  SET search_path FROM CURRENT
  SET jit = off
  AS $$
DECLARE
  model_srid integer := streetgen.model_srid(model);
  staged bigint;
  driveable bigint;
  without_srid bigint;
  deferred text[];
  insert_trigger text;
BEGIN
  IF staging IS NULL THEN
    RAISE EXCEPTION 'staging must not be null' USING ERRCODE = 'null_value_not_allowed';
  END IF;
  -- (osm_is_driveable spelt out: its class test as a join, the rest inlined)
  EXECUTE format('SELECT count(*), count(*) FILTER (WHERE h.highway IS NOT NULL AND streetgen._osm_driveable_tags(s.tags)),
                         count(*) FILTER (WHERE ST_SRID(s.geom) = 0)
                    FROM %s AS s LEFT JOIN streetgen.highway_class AS h ON h.highway = s.tags->>''highway''', staging)
    INTO staged, driveable, without_srid;
  IF without_srid > 0 THEN
    RAISE EXCEPTION 'staging table % has % geometries without SRID', staging, without_srid
      USING ERRCODE = 'invalid_parameter_value',
            HINT = 'Staged geometries need an SRID to be transformed to the model''s (osm2pgsql and ogr2ogr stage in 4326).';
  END IF;
  -- Into a model without axes, a bulk load: its foreign keys are made again after it, and its
  -- insert trigger's recompute (the whole model, as the trigger would have run it) comes after the
  -- INSERT, in a statement of its own: the INSERT's memory (its transformed rows) is freed before
  -- the engine runs. The trigger is dropped for the INSERT and made again from its own definition
  -- after it, not disabled: PostgreSQL fills a transition table for every trigger that declares
  -- one, enabled or not, and that table's rows stay in the transaction's memory to its end (4 MB
  -- of Reisterstown's backend under the engine's and the blocks' peaks).
  deferred := streetgen._defer_foreign_keys(model);
  IF deferred IS NOT NULL THEN
    SELECT pg_catalog.pg_get_triggerdef(t.oid) INTO STRICT insert_trigger
      FROM pg_catalog.pg_trigger t
     WHERE t.tgrelid = format('%I.axis', model)::regclass AND t.tgname = 'axis_refresh_insert';
    EXECUTE format('DROP TRIGGER axis_refresh_insert ON %I.axis', model);
  END IF;
  EXECUTE format($q$
    -- MATERIALIZED: the transformed geometry is used four times below; inlined, PostgreSQL
    -- would transform it four times.
    WITH candidate AS MATERIALIZED (
      SELECT s.source, s.tags, ST_Transform(s.geom, %2$s) AS geom, a.*
        FROM %3$s AS s,
             LATERAL streetgen._osm_axis_attributes(s.tags) AS a
       -- (osm_is_driveable without its class test: _osm_axis_attributes joins the class)
       WHERE streetgen._osm_driveable_tags(s.tags)
         AND ST_GeometryType(s.geom) = 'ST_LineString'
         -- NaN/Inf coordinates and zero-length lines are degenerate; filter them before the
         -- transformation, which would fail on them.
         AND ST_Length(s.geom) > 0 AND ST_Length(s.geom) < 'Infinity'::double precision
    )
    INSERT INTO %1$I.axis (geom, roadway_width, lanes, speed_kmh, road_class, oneway, sidewalk_width,
                           layer, structure, source, tags, estimated)
    SELECT CASE WHEN c.reverse_geometry THEN ST_Reverse(c.geom) ELSE c.geom END,
           c.roadway_width, c.lanes, c.speed_kmh, c.road_class, c.oneway, c.sidewalk_width, c.layer,
           c.structure, c.source, c.tags, c.estimated
      FROM candidate AS c
     WHERE NOT ST_IsEmpty(c.geom) AND ST_Length(c.geom) > 0 AND ST_Length(c.geom) < 'Infinity'::double precision
  $q$, model, model_srid, staging);
  GET DIAGNOSTICS loaded = ROW_COUNT;
  IF deferred IS NOT NULL THEN
    EXECUTE insert_trigger;
    -- (every axis is new: the model had none)
    EXECUTE format('SELECT streetgen._refresh(%L, (SELECT array_agg(a.id) FROM %I.axis a), ''{}'')', model, model);
  END IF;
  PERFORM streetgen._restore_foreign_keys(deferred);
  not_driveable := staged - driveable;
  degenerate := driveable - loaded;
EXCEPTION WHEN internal_error THEN
  -- PostGIS reports coordinates outside the source CRS's domain as an internal error.
  IF SQLERRM LIKE 'transform:%' THEN
    RAISE EXCEPTION 'staged geometries of % cannot be transformed to SRID %', staging, model_srid
      USING ERRCODE = 'invalid_parameter_value', DETAIL = format('PostGIS said: %s', SQLERRM),
            HINT = 'Check the SRID and coordinate ranges of the staged geometries.';
  END IF;
  RAISE;
END
$$;
COMMENT ON FUNCTION streetgen.load_osm_ways(text, regclass) IS
  'Loads staged OSM ways (source, tags, geom) into a model''s axes; returns counts loaded, not driveable, degenerate';

-- Street parking mapped as its own area. OSM's parking:<side>=separate says a road's parking is
-- drawn as separate objects: street-side bays (amenity=parking, parking=street_side) along the
-- curb, which a city's carriageway includes. Those areas are not axes, so their depth becomes the
-- roadway's: for each axis side tagged separate (parking:<side> or parking:both), the staged
-- areas reaching within 2 m of that side's half roadway are clipped to the side (a one-sided,
-- flat-ended buffer) and measured along the axis. When they line at least half of the side,
-- the side gets tag parking:<side>:separate_width (a streetgen key, not OSM's: the mean depth,
-- area over length lined, 1 to 10 m) and the roadway widens by it, so the engine draws a
-- parking lane there (src/core/streets/lanes.cpp). Sides lined less are left alone: a lane along
-- the whole side would be mostly where no bay is. Sides are the way's, as its tags say (a
-- oneway=-1 way is stored reversed: its right is the axis' left). Sides that already carry the
-- key are left alone (loading twice does not widen twice).
-- STAGING: source text, tags jsonb, geom (multi)polygons in any SRID with a known transformation.
CREATE FUNCTION streetgen.load_osm_street_parking(model text, staging regclass,
    OUT sides_widened bigint, OUT areas_used bigint)
  RETURNS record
  LANGUAGE plpgsql VOLATILE
  SET search_path FROM CURRENT
  AS $$
DECLARE
  model_srid integer := streetgen.model_srid(model);
  any_area boolean;
BEGIN
  IF staging IS NULL THEN
    RAISE EXCEPTION 'staging must not be null' USING ERRCODE = 'null_value_not_allowed';
  END IF;
  -- Nothing to do without a staged area (most files): the temporary table, its index and the
  -- query below are 15-20 ms of a new session, a twelfth of a small file's import.
  EXECUTE format('SELECT EXISTS (SELECT 1 FROM %s AS s WHERE ST_Dimension(s.geom) = 2)', staging) INTO any_area;
  IF NOT any_area THEN
    sides_widened := 0;
    areas_used := 0;
    RETURN;
  END IF;
  -- The areas in the model's SRID, indexed: each side then finds the few near it (a city has
  -- thousands of both).
  DROP TABLE IF EXISTS pg_temp._streetgen_parking_area;
  EXECUTE format($q$
    CREATE TEMP TABLE _streetgen_parking_area ON COMMIT DROP AS
      SELECT s.source, ST_CollectionExtract(ST_MakeValid(ST_Transform(s.geom, %1$s)), 3) AS geom
        FROM %2$s AS s
       WHERE ST_Dimension(s.geom) = 2 AND ST_SRID(s.geom) <> 0 AND NOT ST_IsEmpty(s.geom)
  $q$, model_srid, staging);
  CREATE INDEX ON pg_temp._streetgen_parking_area USING gist (geom);
  ANALYZE pg_temp._streetgen_parking_area;
  EXECUTE format($q$
    WITH side AS (
      -- side: as the way's tags say it; geom_side: of the stored axis (oneway=-1 ways are stored
      -- reversed, see streetgen._lane_tags)
      SELECT a.id, a.geom, a.roadway_width, s.side,
             CASE WHEN lower(a.tags->>'oneway') IN ('-1', 'reverse')
                  THEN CASE s.side WHEN 'left' THEN 'right' ELSE 'left' END ELSE s.side END AS geom_side
        FROM %1$I.axis AS a, (VALUES ('left'), ('right')) AS s(side)
       WHERE coalesce(a.tags->>('parking:' || s.side), a.tags->>'parking:both') = 'separate'
         AND NOT a.tags ? ('parking:' || s.side || ':separate_width')
    ), lining AS (
      SELECT d.id, d.side, d.geom AS axis_geom, a.source, c.part
        FROM side AS d
        JOIN pg_temp._streetgen_parking_area AS a ON ST_DWithin(a.geom, d.geom, d.roadway_width / 2 + 2)
        CROSS JOIN LATERAL (SELECT ST_CollectionExtract(ST_Intersection(a.geom,
                              ST_Buffer(d.geom, d.roadway_width / 2 + 12, 'side=' || d.geom_side || ' endcap=flat')), 3) AS part) AS c
       WHERE ST_Area(c.part) > 0.5
    ), span AS (
      SELECT l.id, l.side, l.source, ST_Area(l.part) AS area, ST_Length(l.axis_geom) AS axis_length,
             (SELECT numrange(min(f)::numeric, max(f)::numeric)
                FROM (SELECT ST_LineLocatePoint(l.axis_geom, p.geom) AS f FROM ST_DumpPoints(l.part) AS p) AS x) AS along
        FROM lining AS l
    ), measured AS (
      SELECT id, side, array_agg(source) AS sources,
             (SELECT sum(upper(r) - lower(r)) FROM unnest(range_agg(along)) AS r)::double precision AS lined,
             sum(area) / nullif(sum(upper(along) - lower(along))::double precision * min(axis_length), 0) AS depth
        FROM span GROUP BY id, side
    ), kept AS (
      SELECT id, side, sources, round(depth::numeric, 1) AS depth
        FROM measured WHERE lined >= 0.5 AND depth BETWEEN 1 AND 10
    ), widened AS (
      SELECT id, jsonb_object_agg('parking:' || side || ':separate_width', depth::text) AS tags,
             sum(depth)::double precision AS extra
        FROM kept GROUP BY id
    ), updated AS (
      UPDATE %1$I.axis AS a SET tags = a.tags || w.tags, roadway_width = least(200, a.roadway_width + w.extra)
        FROM widened AS w WHERE a.id = w.id
      RETURNING a.id
    )
    SELECT (SELECT count(*) FROM kept WHERE id IN (SELECT id FROM updated)),
           (SELECT count(DISTINCT s) FROM kept, unnest(sources) AS s WHERE id IN (SELECT id FROM updated))
  $q$, model) INTO sides_widened, areas_used;
  DROP TABLE pg_temp._streetgen_parking_area;
END
$$;
COMMENT ON FUNCTION streetgen.load_osm_street_parking(text, regclass) IS
  'Widens the roadway of axis sides tagged parking:<side>=separate by the depth of the staged street-side parking areas lining at least half of the side; returns sides widened and areas used';
