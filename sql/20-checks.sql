-- Argument checks shared by the plpgsql API. Each raises a documented SQLSTATE naming the
-- parameter it rejects.

-- A model name becomes a schema name: a plain lower-case identifier, so users can type it
-- unquoted, and nothing that could smuggle SQL into the dynamic DDL.
CREATE FUNCTION streetgen._require_model_name(name text)
  RETURNS void
  LANGUAGE plpgsql IMMUTABLE PARALLEL SAFE
  SET search_path FROM CURRENT
  AS $$
BEGIN
  IF name IS NULL THEN
    RAISE EXCEPTION 'model name must not be null' USING ERRCODE = 'null_value_not_allowed';
  END IF;
  IF name !~ '^[a-z_][a-z0-9_]*$' OR octet_length(name) > 63 THEN
    RAISE EXCEPTION 'invalid model name: %', quote_literal(name)
      USING ERRCODE = 'invalid_name',
            DETAIL = 'A model name is a lower-case SQL identifier: a letter or _, then letters, digits or _, at most 63 bytes.',
            HINT = 'For example streetgen.create_model(''paris_11e'', 32631).';
  END IF;
END
$$;

-- A params jsonb: an object whose keys are all KNOWN (a misspelt key is an error, not a default).
CREATE FUNCTION streetgen._require_params(params jsonb, known text[])
  RETURNS void
  LANGUAGE plpgsql IMMUTABLE PARALLEL SAFE
  SET search_path FROM CURRENT
  AS $$
DECLARE
  unknown text[];
BEGIN
  IF jsonb_typeof(params) <> 'object' THEN
    RAISE EXCEPTION 'params must be a json object' USING ERRCODE = 'invalid_parameter_value',
      DETAIL = format('It is a json %s.', jsonb_typeof(params));
  END IF;
  SELECT array_agg(k ORDER BY k) INTO unknown FROM jsonb_object_keys(params) AS k WHERE k <> ALL (known);
  IF unknown IS NOT NULL THEN
    RAISE EXCEPTION 'unknown params key: %', array_to_string(unknown, ', ') USING ERRCODE = 'invalid_parameter_value',
      DETAIL = format('Known keys: %s.', array_to_string(ARRAY(SELECT unnest(known) ORDER BY 1), ', '));
  END IF;
END
$$;

-- Widths, radii and speeds are in metres: a model's CRS must be projected in metres. SRID 0
-- means local coordinates and is taken to be in metres (the growth examples use it).
CREATE FUNCTION streetgen._require_metric_srid(srid integer, parameter text)
  RETURNS void
  LANGUAGE plpgsql STABLE PARALLEL SAFE
  SET search_path FROM CURRENT
  AS $$
DECLARE
  proj text;
BEGIN
  IF srid IS NULL THEN
    RAISE EXCEPTION '% must not be null', parameter USING ERRCODE = 'null_value_not_allowed';
  END IF;
  IF srid = 0 THEN
    RETURN;
  END IF;
  SELECT s.proj4text INTO proj FROM spatial_ref_sys s WHERE s.srid = _require_metric_srid.srid;
  IF NOT FOUND THEN
    RAISE EXCEPTION '% % is not a known SRID', parameter, srid
      USING ERRCODE = 'invalid_parameter_value',
            DETAIL = 'It is not in spatial_ref_sys.';
  END IF;
  IF proj ~ '\+proj=(longlat|latlong|lonlat|latlon|geocent)' THEN
    RAISE EXCEPTION '% % is a geographic CRS, not a projected one in metres', parameter, srid
      USING ERRCODE = 'invalid_parameter_value',
            DETAIL = 'streetgen measures widths, radii and lengths in metres.',
            HINT = 'Use a projected CRS, e.g. the UTM zone given by streetgen.utm_srid(geom).';
  END IF;
  IF (proj ~ '\+units=' AND proj !~ '\+units=m(\s|$)') OR proj ~ '\+to_meter=' THEN
    RAISE EXCEPTION '% % is not in metres', parameter, srid
      USING ERRCODE = 'invalid_parameter_value',
            DETAIL = format('Its definition is: %s', proj),
            HINT = 'Use a projected CRS in metres, e.g. the UTM zone given by streetgen.utm_srid(geom).';
  END IF;
END
$$;
