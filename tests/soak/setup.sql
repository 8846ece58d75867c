-- Before the soak: the axes as imported, and the audit log every edit script writes in the same
-- transaction as its edit. After the run, check.sql replays the log on the originals: a committed
-- edit whose effect is not in the axis table (a lost edit) breaks the replay.
-- psql variable: model.
CREATE TABLE soak_original AS SELECT id, geom, roadway_width, speed_kmh FROM :"model".axis;
ALTER TABLE soak_original ADD PRIMARY KEY (id);

-- Moves are logged as integer centimetres, widths and speeds as multiples of 0.5: sums are exact,
-- so the replay needs no tolerance beyond the float rounding of the coordinates themselves.
CREATE TABLE soak_log (
  seq bigserial PRIMARY KEY,
  kind text NOT NULL CHECK (kind IN ('move', 'vertex', 'width', 'speed', 'insert', 'delete')),
  axis_id bigint NOT NULL,
  vertex integer,              -- vertex: 0-based index of the moved point
  dx_cm integer, dy_cm integer, -- move, vertex
  d double precision,          -- width (m), speed (km/h)
  geom geometry, roadway_width double precision, speed_kmh double precision, -- insert: the new axis
  refresh bigint                -- the model's refresh count at commit: the order edits took effect
);
CREATE INDEX ON soak_log (axis_id);

-- The commit order, for replaying a failed soak in one session (a scope bug, if it fails again,
-- rather than a concurrency bug). At commit the edit's transaction still holds the refresh_state
-- row its recompute updated, so the count read then is its own; deferred, so the edit scripts
-- and their locking stay as they are.
CREATE FUNCTION soak_commit_order() RETURNS trigger LANGUAGE plpgsql AS $$
BEGIN
  EXECUTE format('UPDATE soak_log SET refresh = (SELECT refreshes FROM %I.refresh_state) WHERE seq = $1', TG_ARGV[0])
    USING NEW.seq;
  RETURN NULL;
END
$$;
CREATE CONSTRAINT TRIGGER commit_order AFTER INSERT ON soak_log DEFERRABLE INITIALLY DEFERRED
  FOR EACH ROW EXECUTE FUNCTION soak_commit_order(:'model');
