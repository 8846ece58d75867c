-- Models: one schema per model holding its input axes (and, in later versions, the generated
-- outputs). Model tables are ordinary user tables: pg_dump keeps them, GRANTs work per schema.

CREATE TABLE streetgen.model (
  name text PRIMARY KEY,
  srid integer NOT NULL,
  created_at timestamptz NOT NULL DEFAULT now(),
  created_by name NOT NULL DEFAULT current_user
);
COMMENT ON TABLE streetgen.model IS 'Registry of streetgen models: one schema each (create_model / drop_model)';
-- The registry rows are user data: pg_dump must keep them with the model schemas.
SELECT pg_catalog.pg_extension_config_dump('streetgen.model', '');

-- create_model and drop_model run with the caller's rights, so everyone may write the registry;
-- row security keeps a user from registering in someone else's name or removing a model
-- whose schema they do not own (superusers bypass it).
GRANT SELECT, INSERT, DELETE ON streetgen.model TO PUBLIC;
ALTER TABLE streetgen.model ENABLE ROW LEVEL SECURITY;
CREATE POLICY model_read ON streetgen.model FOR SELECT USING (true);
CREATE POLICY model_register ON streetgen.model FOR INSERT WITH CHECK (created_by = current_user);
CREATE POLICY model_unregister ON streetgen.model FOR DELETE
  USING (NOT EXISTS (SELECT 1 FROM pg_catalog.pg_namespace n WHERE n.nspname = name)
         OR EXISTS (SELECT 1 FROM pg_catalog.pg_namespace n
                     WHERE n.nspname = name AND pg_catalog.pg_has_role(current_user, n.nspowner, 'USAGE')));

-- Serialises create_model/drop_model of one name across sessions (first key: streetgen's
-- models; second: the name), so a concurrent duplicate waits and then gets a clean 42P06.
CREATE FUNCTION streetgen._lock_model_name(name text)
  RETURNS void
  LANGUAGE sql VOLATILE
  SET search_path FROM CURRENT
  AS $$ SELECT pg_advisory_xact_lock(hashtext('streetgen.model'), hashtext(name)) $$;

-- The generated tables of a model: settings, node, section, corner, intersection, lane, marking,
-- sidewalk, crossing, block, issue. Every
-- row is keyed so that regenerating the same axes gives the same keys, and points to the axes
-- or nodes it came from (deleting an axis deletes its sections and corners).
CREATE FUNCTION streetgen._create_output_tables(name text, srid integer)
  RETURNS void
  LANGUAGE plpgsql VOLATILE
  SET search_path FROM CURRENT
  AS $$
BEGIN
  EXECUTE format($ddl$
    CREATE TABLE %1$I.settings (LIKE streetgen.default_settings INCLUDING ALL);
    INSERT INTO %1$I.settings SELECT * FROM streetgen.default_settings;
    COMMENT ON TABLE %1$I.settings IS 'Street surface settings of this model (one row; see streetgen.default_settings)';

    CREATE TABLE %1$I.node (
      id bigint PRIMARY KEY,
      geom geometry(Point, %2$s) NOT NULL,
      degree integer NOT NULL,
      layer smallint NOT NULL,
      axis_ids bigint[] NOT NULL
    );
    CREATE INDEX node_geom_idx ON %1$I.node USING gist (geom);
    COMMENT ON TABLE %1$I.node IS 'Junctions and dead ends of the axis network (id: stable hash of position and layer)';

    CREATE TABLE %1$I.section (
      axis_id bigint NOT NULL REFERENCES %1$I.axis (id) ON DELETE CASCADE,
      part bigint NOT NULL,
      from_node bigint NOT NULL REFERENCES %1$I.node (id) ON DELETE CASCADE,
      to_node bigint NOT NULL REFERENCES %1$I.node (id) ON DELETE CASCADE,
      status text NOT NULL,
      start_border double precision NOT NULL,
      end_border double precision NOT NULL,
      centre_line geometry(LineString, %2$s) NOT NULL,
      geom geometry(Polygon, %2$s),
      PRIMARY KEY (axis_id, part)
    );
    CREATE INDEX section_geom_idx ON %1$I.section USING gist (geom);
    COMMENT ON TABLE %1$I.section IS 'Constant part of each axis part between its border lines (geom NULL when the junctions take it all)';
    COMMENT ON COLUMN %1$I.section.part IS 'Which part of the axis (between two nodes): where it starts along the axis, in mm of curvilinear abscissa';

    CREATE TABLE %1$I.corner (
      node_id bigint NOT NULL REFERENCES %1$I.node (id) ON DELETE CASCADE,
      axis_a bigint NOT NULL REFERENCES %1$I.axis (id) ON DELETE CASCADE,
      part_a bigint NOT NULL,
      end_a boolean NOT NULL,
      axis_b bigint NOT NULL REFERENCES %1$I.axis (id) ON DELETE CASCADE,
      part_b bigint NOT NULL,
      end_b boolean NOT NULL,
      status text NOT NULL,
      radius_wanted double precision,
      radius double precision,
      radius_override double precision CHECK (radius_override > 0 AND radius_override <= 500),
      centre geometry(Point, %2$s),
      arc geometry(CircularString, %2$s),
      arc_segmentized geometry(LineString, %2$s),
      PRIMARY KEY (node_id, axis_a, part_a, end_a, axis_b, part_b, end_b)
    );
    COMMENT ON TABLE %1$I.corner IS 'Curb corner between two consecutive axes around a node (counter-clockwise from a to b): arc, radius, status';
    COMMENT ON COLUMN %1$I.corner.radius_override IS 'Set by you: the radius of this corner at the next generate (kept across runs)';

    CREATE TABLE %1$I.intersection (
      node_id bigint PRIMARY KEY REFERENCES %1$I.node (id) ON DELETE CASCADE,
      status text NOT NULL,
      axis_ids bigint[] NOT NULL,
      geom geometry(Polygon, %2$s) NOT NULL
    );
    CREATE INDEX intersection_geom_idx ON %1$I.intersection USING gist (geom);
    COMMENT ON TABLE %1$I.intersection IS 'Junction surface of each node of degree 2 or more';

    CREATE TABLE %1$I.lane (
      axis_id bigint NOT NULL,
      part bigint NOT NULL,
      lane_index smallint NOT NULL,
      type text NOT NULL,
      direction text NOT NULL,
      width double precision NOT NULL,
      turn text,
      geom geometry(MultiPolygon, %2$s) NOT NULL,
      PRIMARY KEY (axis_id, part, lane_index),
      FOREIGN KEY (axis_id, part) REFERENCES %1$I.section (axis_id, part) ON DELETE CASCADE
    );
    CREATE INDEX lane_geom_idx ON %1$I.lane USING gist (geom);
    COMMENT ON TABLE %1$I.lane IS 'Lanes of each section, left to right looking along the axis: type (driving, bus, cycle), direction (forward, backward, both), width, turn; they tile the section surface';
    COMMENT ON COLUMN %1$I.lane.lane_index IS 'From 1 at the left edge of the roadway, looking along the axis';

    CREATE TABLE %1$I.marking (
      axis_id bigint NOT NULL,
      part bigint NOT NULL,
      kind text NOT NULL,
      position smallint NOT NULL,
      style text NOT NULL,
      geom geometry(MultiLineString, %2$s) NOT NULL,
      PRIMARY KEY (axis_id, part, kind, position),
      FOREIGN KEY (axis_id, part) REFERENCES %1$I.section (axis_id, part) ON DELETE CASCADE
    );
    CREATE INDEX marking_geom_idx ON %1$I.marking USING gist (geom);
    COMMENT ON TABLE %1$I.marking IS 'Road markings of each section: centre_line, lane_separator (position: between lanes position and position + 1), stop_line (position 0 at the start border, 1 at the end); style solid or dashed';

    -- A section's sidewalks are keyed (axis_id, part, side), a junction's by node_id: one of the
    -- two, each with its foreign key (the partial unique indexes are the upserts' keys).
    CREATE TABLE %1$I.sidewalk (
      axis_id bigint,
      part bigint,
      node_id bigint REFERENCES %1$I.intersection (node_id) ON DELETE CASCADE,
      side text NOT NULL,
      width double precision NOT NULL,
      geom geometry(MultiPolygon, %2$s) NOT NULL,
      FOREIGN KEY (axis_id, part) REFERENCES %1$I.section (axis_id, part) ON DELETE CASCADE,
      CONSTRAINT sidewalk_one_owner CHECK ((node_id IS NULL) = (axis_id IS NOT NULL AND part IS NOT NULL)),
      CONSTRAINT sidewalk_side CHECK (side IN ('left', 'right', 'around') AND (side = 'around') = (node_id IS NOT NULL))
    );
    CREATE UNIQUE INDEX sidewalk_section_key ON %1$I.sidewalk (axis_id, part, side) WHERE node_id IS NULL;
    CREATE UNIQUE INDEX sidewalk_junction_key ON %1$I.sidewalk (node_id) WHERE node_id IS NOT NULL;
    CREATE INDEX sidewalk_geom_idx ON %1$I.sidewalk USING gist (geom);
    CREATE INDEX sidewalk_width_idx ON %1$I.sidewalk (width);
    COMMENT ON TABLE %1$I.sidewalk IS 'Sidewalks: beside each section (side left or right, looking along the axis) and around each junction (side around, node_id), outside every roadway, never overlapping each other';

    CREATE TABLE %1$I.crossing (
      axis_id bigint NOT NULL,
      part bigint NOT NULL,
      position smallint NOT NULL,
      node_id bigint NOT NULL REFERENCES %1$I.node (id) ON DELETE CASCADE,
      width double precision NOT NULL,
      geom geometry(MultiPolygon, %2$s) NOT NULL,
      PRIMARY KEY (axis_id, part, position),
      FOREIGN KEY (axis_id, part) REFERENCES %1$I.section (axis_id, part) ON DELETE CASCADE
    );
    CREATE INDEX crossing_geom_idx ON %1$I.crossing USING gist (geom);
    COMMENT ON TABLE %1$I.crossing IS 'Pedestrian crossings (zebra areas) across a section at its border line with junction node_id: position 0 at the section''s start, 1 at its end';

    -- Blocks: the bounded faces of the ground-level axis network (layer 0) minus its street
    -- surfaces, sidewalks included. Keyed by a hash of the face (stable while the face stays).
    CREATE TABLE %1$I.block (
      id bigint PRIMARY KEY,
      face geometry(Polygon, %2$s) NOT NULL,
      geom geometry(MultiPolygon, %2$s),
      axis_ids bigint[] NOT NULL,
      kind text NOT NULL CHECK (kind IN ('block', 'island'))
    );
    CREATE INDEX block_face_idx ON %1$I.block USING gist (face);
    COMMENT ON TABLE %1$I.block IS 'City blocks: each bounded face of the ground-level axis network (face) minus street surfaces and sidewalks (geom, NULL when the streets fill it); axis_ids: the axes around it; kind: block, or island (a traffic island between one-way carriageways or links)';

    CREATE TABLE %1$I.issue (
      axis_id bigint REFERENCES %1$I.axis (id) ON DELETE CASCADE,
      part bigint,
      kind text NOT NULL,
      detail text,
      node_id bigint  -- where it happens, when the part has no section (a dropped loop, a duplicate)
    );
    CREATE INDEX issue_axis_idx ON %1$I.issue (axis_id);
    COMMENT ON TABLE %1$I.issue IS 'What the last generate could not use as given (duplicate or degenerate axes, ...)';

    -- What the incremental refresh walks: the graph of the last result.
    CREATE INDEX section_from_idx ON %1$I.section (from_node);
    CREATE INDEX section_centre_line_idx ON %1$I.section USING gist (centre_line);
    CREATE INDEX corner_override_idx ON %1$I.corner (node_id) WHERE radius_override IS NOT NULL;
    CREATE INDEX section_to_idx ON %1$I.section (to_node);
    CREATE INDEX node_axes_idx ON %1$I.node USING gin (axis_ids);
    CREATE INDEX axis_width_idx ON %1$I.axis (roadway_width);

    -- One row that every recompute of the model updates first: concurrent recomputes of one
    -- model queue on its row lock (READ COMMITTED), or fail with 40001 under REPEATABLE READ and
    -- SERIALIZABLE, where a recompute could not see the other's result.
    CREATE TABLE %1$I.refresh_state (
      singleton boolean PRIMARY KEY DEFAULT true CHECK (singleton),
      refreshes bigint NOT NULL DEFAULT 0,
      refreshed_at timestamptz
    );
    INSERT INTO %1$I.refresh_state DEFAULT VALUES;
    COMMENT ON TABLE %1$I.refresh_state IS 'Serialises the recomputes of this model (generate and the axis triggers)';
  $ddl$, name, srid);
END
$$;

CREATE FUNCTION streetgen.create_model(name text, srid integer)
  RETURNS void
  LANGUAGE plpgsql VOLATILE
  SET search_path FROM CURRENT
  AS $$
BEGIN
  PERFORM streetgen._require_model_name(name);
  -- Schemas a model must not take over (dropping the model would drop them).
  IF name IN ('public', 'streetgen', 'information_schema', 'topology', 'tiger', 'tiger_data')
     OR name LIKE 'pg\_%'
     OR EXISTS (SELECT 1 FROM pg_extension e JOIN pg_namespace n ON n.oid = e.extnamespace WHERE n.nspname = name)
     OR EXISTS (SELECT 1 FROM pg_get_keywords() k WHERE k.word = name AND k.catcode IN ('R', 'T')) THEN
    RAISE EXCEPTION 'model name % is reserved', quote_literal(name)
      USING ERRCODE = 'reserved_name',
            DETAIL = 'It names a system or extension schema, or is an SQL reserved word.';
  END IF;
  PERFORM streetgen._require_metric_srid(srid, 'srid');
  PERFORM streetgen._lock_model_name(name);
  IF EXISTS (SELECT 1 FROM streetgen.model m WHERE m.name = create_model.name) THEN
    RAISE EXCEPTION 'model "%" already exists', name USING ERRCODE = 'duplicate_schema';
  END IF;
  -- Raises 42P06 itself if an unrelated schema has that name.
  EXECUTE format('CREATE SCHEMA %I', name);

  EXECUTE format($ddl$
    CREATE TABLE %1$I.axis (
      id bigint GENERATED BY DEFAULT AS IDENTITY PRIMARY KEY,
      geom geometry(LineString, %2$s) NOT NULL,
      roadway_width double precision NOT NULL,
      lanes smallint,
      speed_kmh double precision NOT NULL,
      road_class text NOT NULL DEFAULT 'unclassified',
      oneway boolean NOT NULL DEFAULT false,
      sidewalk_width double precision,
      layer smallint NOT NULL DEFAULT 0,
      structure text,
      source text,
      radius_override double precision,
      tags jsonb NOT NULL DEFAULT '{}',
      estimated text[] NOT NULL DEFAULT '{}',
      CONSTRAINT axis_geom_not_empty CHECK (NOT ST_IsEmpty(geom)),
      -- A NaN or infinite coordinate makes the length NaN or infinite, and PostgreSQL orders
      -- NaN above Infinity: this one comparison rejects both.
      CONSTRAINT axis_geom_finite CHECK (ST_Length(geom) < 'Infinity'::double precision),
      CONSTRAINT axis_geom_positive_length CHECK (ST_Length(geom) > 0),
      -- Upper bounds make the ranges reject NaN as well (NaN > 0 is true in PostgreSQL).
      CONSTRAINT axis_roadway_width_range CHECK (roadway_width > 0 AND roadway_width <= 200),
      CONSTRAINT axis_lanes_range CHECK (lanes BETWEEN 1 AND 20),
      CONSTRAINT axis_speed_range CHECK (speed_kmh > 0 AND speed_kmh <= 300),
      CONSTRAINT axis_road_class_not_blank CHECK (btrim(road_class) <> ''),
      CONSTRAINT axis_sidewalk_width_range CHECK (sidewalk_width >= 0 AND sidewalk_width <= 50),
      CONSTRAINT axis_layer_range CHECK (layer BETWEEN -5 AND 5),
      CONSTRAINT axis_structure_kind CHECK (structure IN ('bridge', 'tunnel')),
      CONSTRAINT axis_radius_override_range CHECK (radius_override > 0 AND radius_override <= 500),
      CONSTRAINT axis_tags_object CHECK (jsonb_typeof(tags) = 'object')
    )$ddl$, name, srid);
  EXECUTE format('CREATE INDEX axis_geom_idx ON %I.axis USING gist (geom)', name);
  PERFORM streetgen._create_output_tables(name, srid);
  PERFORM streetgen._create_triggers(name);
  EXECUTE format($c$COMMENT ON TABLE %I.axis IS
    'Road axes (input): centre lines with roadway width (m), lanes, speed (km/h), class, one-way, layer (bridges/tunnels), source'$c$, name);
  EXECUTE format($c$COMMENT ON COLUMN %I.axis.estimated IS
    'Attributes an importer estimated rather than read from tags (roadway_width, lanes, speed_kmh)'$c$, name);

  INSERT INTO streetgen.model (name, srid) VALUES (name, srid);
END
$$;
COMMENT ON FUNCTION streetgen.create_model(text, integer) IS
  'Creates model NAME: a schema with the axis table in the given projected SRID (metres; 0 for local coordinates)';

CREATE FUNCTION streetgen.drop_model(name text)
  RETURNS void
  LANGUAGE plpgsql VOLATILE
  SET search_path FROM CURRENT
  AS $$
BEGIN
  PERFORM streetgen._require_model_name(name);
  PERFORM streetgen._lock_model_name(name);
  IF NOT EXISTS (SELECT 1 FROM streetgen.model m WHERE m.name = drop_model.name) THEN
    RAISE EXCEPTION 'model "%" does not exist', name
      USING ERRCODE = 'undefined_object',
            HINT = 'SELECT name FROM streetgen.model lists the models.';
  END IF;
  -- Never drops a schema that is not a registered model; ownership is checked by DROP itself.
  EXECUTE format('DROP SCHEMA IF EXISTS %I CASCADE', name);
  DELETE FROM streetgen.model m WHERE m.name = drop_model.name;
END
$$;
COMMENT ON FUNCTION streetgen.drop_model(text) IS 'Drops model NAME: its schema with every table in it';

-- The model's SRID, or 42704 if NAME is not a model. Used by importers.
CREATE FUNCTION streetgen.model_srid(name text)
  RETURNS integer
  LANGUAGE plpgsql STABLE PARALLEL SAFE
  SET search_path FROM CURRENT
  AS $$
DECLARE
  result integer;
BEGIN
  PERFORM streetgen._require_model_name(name);
  SELECT m.srid INTO result FROM streetgen.model m WHERE m.name = model_srid.name;
  IF NOT FOUND THEN
    RAISE EXCEPTION 'model "%" does not exist', name USING ERRCODE = 'undefined_object';
  END IF;
  RETURN result;
END
$$;
COMMENT ON FUNCTION streetgen.model_srid(text) IS 'The SRID of model NAME';

-- Bulk loading into a model without axes, the way pg_restore loads a table: the model's foreign
-- keys are dropped before the load and made again after it. Row by row, the stored sections,
-- corners and junctions cost a lookup and a row lock in their referenced tables for each of their
-- foreign keys (about a fifth of a surfaces-only import's time); ADD FOREIGN KEY checks a whole
-- table in one join. (The indexes stay: dropped too, the details' phases, which search the
-- model's tables during the load, took twice as long.)
--
-- _defer_foreign_keys, if MODEL has no axes and the caller owns all of its tables, takes them
-- all in ACCESS EXCLUSIVE mode (so two loads into one empty model queue instead of deadlocking
-- on the lock upgrade), drops the foreign keys and returns the statements that make them again;
-- otherwise NULL, and the load checks them row by row as before, with no exclusive lock. The
-- caller passes them to _restore_foreign_keys in the same function: an error between the two
-- rolls back the whole load, so no model is ever left without its foreign keys.
CREATE FUNCTION streetgen._defer_foreign_keys(model text)
  RETURNS text[]
  LANGUAGE plpgsql VOLATILE
  SET search_path FROM CURRENT
  AS $$
DECLARE
  schema_oid oid := (SELECT n.oid FROM pg_catalog.pg_namespace n WHERE n.nspname = model);
  tables text;
  owned boolean;
  has_axes boolean;
  restore text[];
  drops text[];
  statement text;
BEGIN
  SELECT string_agg(c.oid::regclass::text, ', ' ORDER BY c.relname),
         bool_and(pg_catalog.pg_has_role(current_user, c.relowner, 'USAGE'))
    INTO tables, owned
    FROM pg_catalog.pg_class c WHERE c.relnamespace = schema_oid AND c.relkind = 'r';
  IF tables IS NULL OR NOT owned THEN
    RETURN NULL;
  END IF;
  EXECUTE format('SELECT EXISTS (SELECT 1 FROM %I.axis)', model) INTO STRICT has_axes;
  IF has_axes THEN
    RETURN NULL;
  END IF;
  EXECUTE format('LOCK TABLE %s IN ACCESS EXCLUSIVE MODE', tables);
  -- (again under the lock: a load that held it may have committed axes meanwhile)
  EXECUTE format('SELECT EXISTS (SELECT 1 FROM %I.axis)', model) INTO STRICT has_axes;
  IF has_axes THEN
    RETURN NULL;
  END IF;
  SELECT array_agg(format('ALTER TABLE %s ADD CONSTRAINT %I %s', k.conrelid::regclass, k.conname,
                          pg_catalog.pg_get_constraintdef(k.oid)) ORDER BY k.conname),
         array_agg(format('ALTER TABLE %s DROP CONSTRAINT %I', k.conrelid::regclass, k.conname) ORDER BY k.conname)
    INTO restore, drops
    FROM pg_catalog.pg_constraint k JOIN pg_catalog.pg_class c ON c.oid = k.conrelid
   WHERE c.relnamespace = schema_oid AND k.contype = 'f';
  FOREACH statement IN ARRAY coalesce(drops, '{}') LOOP
    EXECUTE statement;
  END LOOP;
  RETURN coalesce(restore, '{}');
END
$$;

CREATE FUNCTION streetgen._restore_foreign_keys(restore text[])
  RETURNS void
  LANGUAGE plpgsql VOLATILE
  SET search_path FROM CURRENT
  AS $$
DECLARE
  statement text;
BEGIN
  FOREACH statement IN ARRAY coalesce(restore, '{}') LOOP
    EXECUTE statement;
  END LOOP;
END
$$;
