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

-- A length in metres from an OSM value: "7", "7.5 m", "7,5", "24'", "12 ft", "8'6\"".
-- NULL when it cannot be read.
CREATE FUNCTION streetgen.osm_parse_length(value text)
  RETURNS double precision
  LANGUAGE plpgsql IMMUTABLE PARALLEL SAFE
  SET search_path FROM CURRENT
  AS $$
DECLARE
  v text := replace(lower(btrim(value)), ',', '.');
  m text[];
BEGIN
  IF v IS NULL THEN RETURN NULL; END IF;
  m := regexp_match(v, '^([0-9]+(?:\.[0-9]+)?)\s*(m|meters?|metres?)?$');
  IF m IS NOT NULL THEN RETURN m[1]::double precision; END IF;
  m := regexp_match(v, '^([0-9]+(?:\.[0-9]+)?)\s*(''|ft|feet)$');
  IF m IS NOT NULL THEN RETURN m[1]::double precision * 0.3048; END IF;
  m := regexp_match(v, '^([0-9]+)''\s*([0-9]+(?:\.[0-9]+)?)"$');
  IF m IS NOT NULL THEN RETURN m[1]::double precision * 0.3048 + m[2]::double precision * 0.0254; END IF;
  RETURN NULL;
END
$$;
COMMENT ON FUNCTION streetgen.osm_parse_length(text) IS 'Metres from an OSM width value (m, ft, feet-inches); NULL if unreadable';

-- A speed in km/h from an OSM maxspeed value: "50", "30 mph", "10 knots", "walk", and the
-- implicit country values ("DE:urban", "FR:rural", "RU:living_street", "DE:zone30", ...).
-- NULL when it cannot be read or means no limit ("none", "signals", "variable").
CREATE FUNCTION streetgen.osm_parse_speed(value text)
  RETURNS double precision
  LANGUAGE plpgsql IMMUTABLE PARALLEL SAFE
  SET search_path FROM CURRENT
  AS $$
DECLARE
  v text := lower(btrim(split_part(value, ';', 1)));
  m text[];
  kmh double precision;
BEGIN
  IF v IS NULL OR v = '' THEN RETURN NULL; END IF;
  m := regexp_match(v, '^([0-9]+(?:\.[0-9]+)?)\s*(km/h|kmh|kph)?$');
  IF m IS NOT NULL THEN kmh := m[1]::double precision;
  ELSE
    m := regexp_match(v, '^([0-9]+(?:\.[0-9]+)?)\s*mph$');
    IF m IS NOT NULL THEN kmh := m[1]::double precision * 1.609344;
    ELSE
      m := regexp_match(v, '^([0-9]+(?:\.[0-9]+)?)\s*knots$');
      IF m IS NOT NULL THEN kmh := m[1]::double precision * 1.852;
      ELSE
        m := regexp_match(v, 'zone:?([0-9]+)$');
        IF m IS NOT NULL THEN kmh := m[1]::double precision;
        ELSE
          kmh := CASE
            WHEN v = 'walk' OR v ~ ':walk$' THEN 7
            WHEN v ~ ':living_street$' THEN 20
            WHEN v ~ ':bicycle_road$' THEN 30
            WHEN v ~ ':urban$' THEN 50
            WHEN v ~ ':rural$' THEN 90
            WHEN v ~ ':trunk$' THEN 100
            WHEN v ~ ':motorway$' THEN 120
          END;
        END IF;
      END IF;
    END IF;
  END IF;
  IF kmh IS NULL OR kmh <= 0 OR kmh > 300 THEN RETURN NULL; END IF;
  RETURN kmh;
END
$$;
COMMENT ON FUNCTION streetgen.osm_parse_speed(text) IS 'km/h from an OSM maxspeed value (numbers, mph, knots, country zones); NULL if unreadable';

-- A positive lane count from an OSM value ("2", "2;3" takes the first); NULL for 0, junk, > 20.
CREATE FUNCTION streetgen.osm_parse_lanes(value text)
  RETURNS smallint
  LANGUAGE sql IMMUTABLE PARALLEL SAFE
  SET search_path FROM CURRENT
  AS $$
    SELECT CASE WHEN n BETWEEN 1 AND 20 THEN n::smallint END
      FROM (SELECT (regexp_match(btrim(split_part(value, ';', 1)), '^([0-9]{1,3})$'))[1]::integer AS n) AS p
  $$;
COMMENT ON FUNCTION streetgen.osm_parse_lanes(text) IS 'Lane count from an OSM lanes value; NULL for 0, junk or more than 20';

-- Is this OSM way a driveable road? Rules: highway class in streetgen.highway_class; not an
-- area; motor vehicles not forbidden; service roads except parking aisles, parking lots,
-- emergency access and private ones (the OSMnx "drive_service" rules).
CREATE FUNCTION streetgen.osm_is_driveable(tags jsonb)
  RETURNS boolean
  LANGUAGE sql STABLE PARALLEL SAFE
  SET search_path FROM CURRENT
  AS $$
    SELECT EXISTS (SELECT 1 FROM streetgen.highway_class h WHERE h.highway = tags->>'highway')
       AND coalesce(tags->>'area', 'no') <> 'yes'
       AND coalesce(tags->>'motor_vehicle', '') <> 'no'
       AND coalesce(tags->>'motorcar', '') <> 'no'
       AND NOT (tags->>'highway' = 'service'
                AND coalesce(tags->>'service', '') IN ('parking_aisle', 'parking', 'emergency_access', 'private'))
  $$;
COMMENT ON FUNCTION streetgen.osm_is_driveable(jsonb) IS 'True for OSM ways that are driveable roads (see streetgen.highway_class)';

-- Axis attributes from the tags of a driveable way; NULL fields only where the axis allows it.
-- reverse_geometry: oneway=-1 ways are stored in their direction of travel with oneway = true.
-- estimated lists what came from streetgen.highway_class rather than from tags.
CREATE FUNCTION streetgen.osm_axis_attributes(tags jsonb,
    OUT roadway_width double precision, OUT lanes smallint, OUT speed_kmh double precision,
    OUT road_class text, OUT oneway boolean, OUT reverse_geometry boolean, OUT layer smallint,
    OUT structure text, OUT sidewalk_width double precision, OUT estimated text[])
  RETURNS record
  LANGUAGE plpgsql STABLE PARALLEL SAFE
  SET search_path FROM CURRENT
  AS $$
DECLARE
  cls streetgen.highway_class%ROWTYPE;
  oneway_tag text := lower(tags->>'oneway');
  tagged_width double precision;
  tagged_speed double precision;
  tagged_layer integer;
BEGIN
  IF tags IS NULL THEN
    RAISE EXCEPTION 'tags must not be null' USING ERRCODE = 'null_value_not_allowed';
  END IF;
  SELECT * INTO cls FROM streetgen.highway_class h WHERE h.highway = tags->>'highway';
  IF NOT FOUND THEN
    RAISE EXCEPTION 'highway=% is not a driveable class', coalesce(tags->>'highway', '(missing)')
      USING ERRCODE = 'invalid_parameter_value',
            HINT = 'Filter with streetgen.osm_is_driveable(tags); the classes are in streetgen.highway_class.';
  END IF;
  road_class := cls.highway;
  estimated := '{}';

  reverse_geometry := coalesce(oneway_tag IN ('-1', 'reverse'), false);
  oneway := CASE
    WHEN oneway_tag IN ('yes', 'true', '1', '-1', 'reverse') THEN true
    WHEN oneway_tag IN ('no', 'false', '0', 'reversible', 'alternating') THEN false
    ELSE cls.implied_oneway OR coalesce(tags->>'junction', '') IN ('roundabout', 'circular')
  END;

  lanes := streetgen.osm_parse_lanes(tags->>'lanes');
  IF lanes IS NULL AND (tags ? 'lanes:forward' OR tags ? 'lanes:backward') THEN
    lanes := nullif(coalesce(streetgen.osm_parse_lanes(tags->>'lanes:forward'), 0)
                    + coalesce(streetgen.osm_parse_lanes(tags->>'lanes:backward'), 0)
                    + coalesce(streetgen.osm_parse_lanes(tags->>'lanes:both_ways'), 0), 0);
  END IF;
  IF lanes IS NULL THEN
    lanes := CASE WHEN oneway THEN cls.lanes_one_way ELSE cls.lanes_two_way END;
    estimated := estimated || 'lanes'::text;
  END IF;

  -- Widths under 2 m or over 60 m on a driveable road are tagging mistakes (a footway width,
  -- the whole corridor): estimate instead.
  SELECT w INTO tagged_width
    FROM unnest(ARRAY[streetgen.osm_parse_length(tags->>'width:carriageway'),
                      streetgen.osm_parse_length(tags->>'width'),
                      streetgen.osm_parse_length(tags->>'est_width'),
                      streetgen.osm_parse_length(tags->>'est:width')]) WITH ORDINALITY AS t(w, i)
   WHERE w BETWEEN 2 AND 60
   ORDER BY i LIMIT 1;
  IF tagged_width IS NOT NULL THEN
    roadway_width := tagged_width;
  ELSE
    roadway_width := lanes * cls.lane_width;
    estimated := estimated || 'roadway_width'::text;
  END IF;

  tagged_speed := coalesce(streetgen.osm_parse_speed(tags->>'maxspeed'),
                           least(streetgen.osm_parse_speed(tags->>'maxspeed:forward'),
                                 streetgen.osm_parse_speed(tags->>'maxspeed:backward')));
  IF tagged_speed IS NOT NULL THEN
    speed_kmh := tagged_speed;
  ELSE
    speed_kmh := cls.speed_kmh;
    estimated := estimated || 'speed_kmh'::text;
  END IF;

  structure := CASE
    WHEN coalesce(tags->>'bridge', 'no') <> 'no' THEN 'bridge'
    WHEN coalesce(tags->>'tunnel', 'no') <> 'no' THEN 'tunnel'
  END;
  tagged_layer := (regexp_match(btrim(tags->>'layer'), '^([+-]?[0-9]{1,2})$'))[1]::integer;
  -- OSM convention: a bridge without layer is above ground, a tunnel below (a building
  -- passage stays at ground level).
  layer := greatest(-5, least(5, coalesce(tagged_layer, CASE
    WHEN structure = 'bridge' THEN 1
    WHEN structure = 'tunnel' AND tags->>'tunnel' <> 'building_passage' THEN -1
    ELSE 0 END)));

  sidewalk_width := (SELECT w FROM unnest(ARRAY[streetgen.osm_parse_length(tags->>'sidewalk:both:width'),
                                                streetgen.osm_parse_length(tags->>'sidewalk:width')]) AS t(w)
                      WHERE w > 0 AND w <= 20 LIMIT 1);
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
  AS $$
DECLARE
  model_srid integer := streetgen.model_srid(model);
  staged bigint;
  driveable bigint;
  without_srid bigint;
BEGIN
  IF staging IS NULL THEN
    RAISE EXCEPTION 'staging must not be null' USING ERRCODE = 'null_value_not_allowed';
  END IF;
  EXECUTE format('SELECT count(*), count(*) FILTER (WHERE streetgen.osm_is_driveable(tags)),
                         count(*) FILTER (WHERE ST_SRID(geom) = 0) FROM %s', staging)
    INTO staged, driveable, without_srid;
  IF without_srid > 0 THEN
    RAISE EXCEPTION 'staging table % has % geometries without SRID', staging, without_srid
      USING ERRCODE = 'invalid_parameter_value',
            HINT = 'Staged geometries need an SRID to be transformed to the model''s (osm2pgsql and ogr2ogr stage in 4326).';
  END IF;
  EXECUTE format($q$
    WITH candidate AS (
      SELECT s.source, s.tags, ST_Transform(s.geom, %2$s) AS geom, streetgen.osm_axis_attributes(s.tags) AS a
        FROM %3$s AS s
       WHERE streetgen.osm_is_driveable(s.tags)
         AND ST_GeometryType(s.geom) = 'ST_LineString'
         -- NaN/Inf coordinates and zero-length lines are degenerate; filter them before the
         -- transformation, which would fail on them.
         AND ST_Length(s.geom) > 0 AND ST_Length(s.geom) < 'Infinity'::double precision
    )
    INSERT INTO %1$I.axis (geom, roadway_width, lanes, speed_kmh, road_class, oneway, sidewalk_width,
                           layer, structure, source, tags, estimated)
    SELECT CASE WHEN (c.a).reverse_geometry THEN ST_Reverse(c.geom) ELSE c.geom END,
           (c.a).roadway_width, (c.a).lanes, (c.a).speed_kmh, (c.a).road_class, (c.a).oneway,
           (c.a).sidewalk_width, (c.a).layer, (c.a).structure,
           c.source, c.tags, (c.a).estimated
      FROM candidate AS c
     WHERE NOT ST_IsEmpty(c.geom) AND ST_Length(c.geom) > 0 AND ST_Length(c.geom) < 'Infinity'::double precision
  $q$, model, model_srid, staging);
  GET DIAGNOSTICS loaded = ROW_COUNT;
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
