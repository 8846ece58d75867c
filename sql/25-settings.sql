-- Street surface settings. One definition: this single-row table holds the defaults and the
-- checks; create_model copies it into each model (LIKE ... INCLUDING ALL), and the stateless
-- street_surfaces() reads its defaults from it.
CREATE TABLE streetgen.default_settings (
  singleton boolean PRIMARY KEY DEFAULT true CHECK (singleton),
  snap_tolerance double precision NOT NULL DEFAULT 0.5 CHECK (snap_tolerance >= 0 AND snap_tolerance <= 10),
  turn_speed_ratio double precision NOT NULL DEFAULT 0.35 CHECK (turn_speed_ratio > 0 AND turn_speed_ratio <= 1),
  lateral_acceleration double precision NOT NULL DEFAULT 3.0 CHECK (lateral_acceleration > 0 AND lateral_acceleration <= 20),
  min_radius double precision NOT NULL DEFAULT 0.15 CHECK (min_radius > 0 AND min_radius <= 50),
  max_radius double precision NOT NULL DEFAULT 25 CHECK (max_radius >= min_radius AND max_radius <= 500),
  misplaced_factor double precision NOT NULL DEFAULT 3 CHECK (misplaced_factor > 0 AND misplaced_factor <= 100),
  min_border_distance double precision NOT NULL DEFAULT 0.5 CHECK (min_border_distance >= 0 AND min_border_distance <= 50),
  transition_length_per_metre double precision NOT NULL DEFAULT 5 CHECK (transition_length_per_metre > 0 AND transition_length_per_metre <= 100),
  min_transition_length double precision NOT NULL DEFAULT 5 CHECK (min_transition_length >= 0 AND min_transition_length <= 500),
  max_transition_deflection_deg double precision NOT NULL DEFAULT 30 CHECK (max_transition_deflection_deg >= 0 AND max_transition_deflection_deg <= 90),
  crossing_width double precision NOT NULL DEFAULT 3 CHECK (crossing_width >= 0 AND crossing_width <= 10),
  crossing_max_speed_kmh double precision NOT NULL DEFAULT 50 CHECK (crossing_max_speed_kmh >= 0 AND crossing_max_speed_kmh <= 300),
  default_sidewalk_width double precision NOT NULL DEFAULT 2 CHECK (default_sidewalk_width >= 0 AND default_sidewalk_width <= 20),
  details boolean NOT NULL DEFAULT true
);
INSERT INTO streetgen.default_settings DEFAULT VALUES;
GRANT SELECT ON streetgen.default_settings TO PUBLIC;
COMMENT ON TABLE streetgen.default_settings IS 'Street surface settings: the defaults each new model copies into <model>.settings';
COMMENT ON COLUMN streetgen.default_settings.snap_tolerance IS 'm: axis ends (and vertices near other axes of the same layer) closer than this meet in one node';
COMMENT ON COLUMN streetgen.default_settings.turn_speed_ratio IS 'Corner radius rule: turning speed at a corner as a share of the street speed';
COMMENT ON COLUMN streetgen.default_settings.lateral_acceleration IS 'Corner radius rule: comfortable lateral acceleration, m/s2; radius = (ratio x speed)^2 / acceleration';
COMMENT ON COLUMN streetgen.default_settings.min_radius IS 'm: smallest corner radius, and the fallback for misplaced arcs (the paper: 0.15 m)';
COMMENT ON COLUMN streetgen.default_settings.max_radius IS 'm: largest corner radius';
COMMENT ON COLUMN streetgen.default_settings.misplaced_factor IS 'An arc farther from its node than this x (half width + radius) is misplaced and gets min_radius';
COMMENT ON COLUMN streetgen.default_settings.min_border_distance IS 'm: every junction surface reaches at least this far along its axes';
COMMENT ON COLUMN streetgen.default_settings.transition_length_per_metre IS 'Width transitions: length per metre of width change';
COMMENT ON COLUMN streetgen.default_settings.min_transition_length IS 'm: shortest width transition';
COMMENT ON COLUMN streetgen.default_settings.max_transition_deflection_deg IS 'A degree-2 node is a width transition (not a corner) when the axis bends less than this';
COMMENT ON COLUMN streetgen.default_settings.crossing_width IS 'm: pedestrian crossings along the axis (0: no crossings)';
COMMENT ON COLUMN streetgen.default_settings.crossing_max_speed_kmh IS 'Crossings only on streets this slow or slower (km/h)';
COMMENT ON COLUMN streetgen.default_settings.default_sidewalk_width IS 'm: the sidewalk of a street that has one by the class rule when neither sidewalk_width nor an OSM width tag says how wide (see streetgen.sidewalk_widths)';
COMMENT ON COLUMN streetgen.default_settings.details IS 'false: street surfaces only (nodes, sections, corners, intersections); no lanes, markings, crossings, sidewalks or blocks, which take most of a city''s time';

-- The settings as the C function takes them: a float8[] in the column order above (details as 1
-- or 0; default_sidewalk_width goes to streetgen.sidewalk_widths instead). `settings`
-- is a jsonb object of overrides (unknown keys are an error), applied over the defaults.
CREATE FUNCTION streetgen._settings_vector(settings jsonb)
  RETURNS double precision[]
  LANGUAGE plpgsql STABLE PARALLEL SAFE
  SET search_path FROM CURRENT
  AS $$
DECLARE
  s streetgen.default_settings;
  unknown text;
BEGIN
  IF settings IS NULL OR jsonb_typeof(settings) <> 'object' THEN
    RAISE EXCEPTION 'settings must be a jsonb object' USING ERRCODE = 'invalid_parameter_value';
  END IF;
  SELECT k INTO unknown FROM jsonb_object_keys(settings) AS k
   WHERE k NOT IN (SELECT a.attname FROM pg_attribute a
                    WHERE a.attrelid = 'streetgen.default_settings'::regclass AND a.attnum > 0 AND NOT a.attisdropped)
   LIMIT 1;
  IF unknown IS NOT NULL THEN
    RAISE EXCEPTION 'unknown setting "%"', unknown
      USING ERRCODE = 'invalid_parameter_value', HINT = 'The settings are the columns of streetgen.default_settings.';
  END IF;
  SELECT * INTO s FROM jsonb_populate_record((SELECT d FROM streetgen.default_settings d), settings);
  RETURN ARRAY[s.snap_tolerance, s.turn_speed_ratio, s.lateral_acceleration, s.min_radius, s.max_radius,
               s.misplaced_factor, s.min_border_distance, s.transition_length_per_metre, s.min_transition_length,
               s.max_transition_deflection_deg, s.crossing_width, s.crossing_max_speed_kmh,
               CASE WHEN s.details THEN 1 ELSE 0 END];
END
$$;

