-- StreetGAN (Hartmann et al. 2017): sampling road rasters from a trained spatial GAN generator.
-- Training happens offline (tools/sgan/train.py); the generator file it writes is stored in
-- streetgen.gan_generator and sampled here by a C++ forward pass (src/core/gan/generator.hpp says
-- why not libtorch). Road rasters follow the project's convention: one 8BUI band, 1 = road,
-- 0 = background, the generator's pixel size (3 m for the shipped trainings).

-- The raster type and ST_RastFromWKB live in postgis_raster's schema: the functions below capture
-- it in their path too, before pg_temp (00-header.sql explains the path).
SELECT pg_catalog.set_config('search_path',
  (SELECT pg_catalog.format('pg_catalog, streetgen, %s, pg_temp',
                            pg_catalog.string_agg(DISTINCT pg_catalog.quote_ident(n.nspname), ', '))
     FROM pg_catalog.pg_extension e
     JOIN pg_catalog.pg_namespace n ON n.oid = e.extnamespace
    WHERE e.extname IN ('postgis', 'postgis_raster')),
  true);

CREATE FUNCTION streetgen._streetgen_gan_sample(generator bytea, width_px integer, height_px integer, seed bigint,
                                                raw boolean, upper_left_x double precision,
                                                upper_left_y double precision, srid integer)
  RETURNS bytea
  LANGUAGE c IMMUTABLE PARALLEL SAFE
  COST 100000
  AS 'MODULE_PATHNAME', '_streetgen_gan_sample';

CREATE FUNCTION streetgen._streetgen_gan_generator_info(weights bytea,
    OUT noise_channels integer, OUT layer_count integer, OUT parameter_count bigint,
    OUT metres_per_pixel double precision, OUT kernel integer, OUT stride integer, OUT padding integer)
  RETURNS record
  LANGUAGE c IMMUTABLE PARALLEL SAFE
  COST 1000
  AS 'MODULE_PATHNAME', '_streetgen_gan_generator_info';

CREATE TABLE streetgen.gan_generator (
  name text PRIMARY KEY,
  weights bytea NOT NULL,
  noise_channels integer NOT NULL,
  layer_count integer NOT NULL,
  parameter_count bigint NOT NULL,
  metres_per_pixel double precision NOT NULL,
  source text,
  loaded_at timestamptz NOT NULL DEFAULT now(),
  loaded_by name NOT NULL DEFAULT current_user
);
COMMENT ON TABLE streetgen.gan_generator IS
  'Trained StreetGAN generators by name (weights: the file tools/sgan/train.py writes); every insert or update is checked and fills the metadata columns';
-- Trained generators are user data: pg_dump keeps them.
SELECT pg_catalog.pg_extension_config_dump('streetgen.gan_generator', '');
GRANT SELECT, INSERT, UPDATE, DELETE ON streetgen.gan_generator TO PUBLIC;
ALTER TABLE streetgen.gan_generator ENABLE ROW LEVEL SECURITY;
CREATE POLICY gan_generator_read ON streetgen.gan_generator FOR SELECT USING (true);
CREATE POLICY gan_generator_load ON streetgen.gan_generator FOR INSERT WITH CHECK (loaded_by = current_user);
CREATE POLICY gan_generator_replace ON streetgen.gan_generator FOR UPDATE
  USING (loaded_by = current_user) WITH CHECK (loaded_by = current_user);
CREATE POLICY gan_generator_remove ON streetgen.gan_generator FOR DELETE USING (loaded_by = current_user);

-- Rows loaded from a client (INSERT INTO streetgen.gan_generator (name, weights) VALUES ('ny', $1))
-- are checked like the loader's: a corrupt file never gets in, and the metadata columns always
-- describe the weights (BEFORE triggers run before the NOT NULL checks, so they may be omitted).
CREATE FUNCTION streetgen._gan_generator_check()
  RETURNS trigger
  LANGUAGE plpgsql
  SET search_path FROM CURRENT
  AS $$
DECLARE
  info record;
BEGIN
  IF NEW.weights IS NULL THEN
    RAISE EXCEPTION 'weights must not be null' USING ERRCODE = 'null_value_not_allowed';
  END IF;
  info := streetgen._streetgen_gan_generator_info(NEW.weights);
  NEW.noise_channels := info.noise_channels;
  NEW.layer_count := info.layer_count;
  NEW.parameter_count := info.parameter_count;
  NEW.metres_per_pixel := info.metres_per_pixel;
  RETURN NEW;
END
$$;
CREATE TRIGGER gan_generator_check BEFORE INSERT OR UPDATE ON streetgen.gan_generator
  FOR EACH ROW EXECUTE FUNCTION streetgen._gan_generator_check();

-- Returns the stored row's metadata, not its weights (a psql user would get megabytes of hex).
CREATE FUNCTION streetgen.gan_load_generator(name text, weights bytea, source text DEFAULT NULL,
    replace boolean DEFAULT false, OUT noise_channels integer, OUT layer_count integer,
    OUT parameter_count bigint, OUT metres_per_pixel double precision, OUT bytes integer)
  RETURNS record
  LANGUAGE plpgsql VOLATILE
  SET search_path FROM CURRENT
  AS $$
DECLARE
  loaded streetgen.gan_generator;
BEGIN
  IF name IS NULL THEN
    RAISE EXCEPTION 'name must not be null' USING ERRCODE = 'null_value_not_allowed';
  END IF;
  IF weights IS NULL THEN
    RAISE EXCEPTION 'weights must not be null' USING ERRCODE = 'null_value_not_allowed';
  END IF;
  IF coalesce(replace, false) THEN
    INSERT INTO streetgen.gan_generator AS g (name, weights, source)
      VALUES (gan_load_generator.name, gan_load_generator.weights, gan_load_generator.source)
      ON CONFLICT ON CONSTRAINT gan_generator_pkey DO UPDATE
        SET weights = EXCLUDED.weights, source = EXCLUDED.source, loaded_at = now(), loaded_by = current_user
      RETURNING * INTO loaded;
  ELSE
    BEGIN
      INSERT INTO streetgen.gan_generator (name, weights, source)
        VALUES (gan_load_generator.name, gan_load_generator.weights, gan_load_generator.source)
        RETURNING * INTO loaded;
    EXCEPTION WHEN unique_violation THEN
      RAISE EXCEPTION 'generator "%" already exists', gan_load_generator.name
        USING ERRCODE = 'duplicate_object', HINT = 'Pass replace => true to replace it.';
    END;
  END IF;
  noise_channels := loaded.noise_channels;
  layer_count := loaded.layer_count;
  parameter_count := loaded.parameter_count;
  metres_per_pixel := loaded.metres_per_pixel;
  bytes := length(loaded.weights);
END
$$;
COMMENT ON FUNCTION streetgen.gan_load_generator(text, bytea, text, boolean) IS
  'Stores a generator file (tools/sgan/train.py writes generator.sgan) under a name after checking it; replace => true overwrites one of the same name. From psql: SELECT streetgen.gan_load_generator(''ny'', pg_read_binary_file(''/path/generator.sgan'')) as superuser, or pass the bytes as a bytea parameter from any client';

-- The sampler's contract (also tools/sgan/sgan.py sample()): noise of the seed (counter-based
-- SplitMix64) for the smallest noise size whose output covers the raster, the generator's forward
-- pass, cropped to width_px x height_px from the top-left.
CREATE FUNCTION streetgen.gan_sample(generator bytea, width_px integer, height_px integer, seed bigint,
                                     upper_left geometry DEFAULT NULL, raw boolean DEFAULT false)
  RETURNS raster
  LANGUAGE plpgsql IMMUTABLE PARALLEL SAFE
  COST 100000
  SET search_path FROM CURRENT
  AS $$
BEGIN
  IF generator IS NULL THEN
    RAISE EXCEPTION 'generator must not be null' USING ERRCODE = 'null_value_not_allowed';
  END IF;
  IF upper_left IS NOT NULL AND GeometryType(upper_left) <> 'POINT' THEN
    RAISE EXCEPTION 'upper_left must be a point' USING ERRCODE = 'invalid_parameter_value',
      DETAIL = format('upper_left is a %s.', GeometryType(upper_left));
  END IF;
  RETURN ST_RastFromWKB(streetgen._streetgen_gan_sample(generator, width_px, height_px, seed,
                                                         coalesce(raw, false),
                                                         coalesce(ST_X(upper_left), 0), coalesce(ST_Y(upper_left), 0),
                                                         coalesce(ST_SRID(upper_left), 0)));
END
$$;
COMMENT ON FUNCTION streetgen.gan_sample(bytea, integer, integer, bigint, geometry, boolean) IS
  'A road raster sampled from a StreetGAN generator file: width_px x height_px (each 1..2048), deterministic for seed; 8BUI with 1 = road, or with raw => true the generator''s 32BF output in [-1, 1]; pixel size from the generator, upper-left corner at upper_left (its SRID) or (0, 0) SRID 0';

CREATE FUNCTION streetgen.gan_sample(generator text, width_px integer, height_px integer, seed bigint,
                                     upper_left geometry DEFAULT NULL, raw boolean DEFAULT false)
  RETURNS raster
  LANGUAGE plpgsql STABLE PARALLEL SAFE
  COST 100000
  SET search_path FROM CURRENT
  AS $$
DECLARE
  stored bytea;
BEGIN
  IF generator IS NULL THEN
    RAISE EXCEPTION 'generator must not be null' USING ERRCODE = 'null_value_not_allowed';
  END IF;
  SELECT g.weights INTO stored FROM streetgen.gan_generator g WHERE g.name = generator;
  IF NOT FOUND THEN
    RAISE EXCEPTION 'generator "%" does not exist', generator USING ERRCODE = 'undefined_object',
      HINT = 'Load it with streetgen.gan_load_generator(name, weights); streetgen.gan_generator lists the loaded ones.';
  END IF;
  RETURN streetgen.gan_sample(stored, width_px, height_px, seed, upper_left, raw);
END
$$;
COMMENT ON FUNCTION streetgen.gan_sample(text, integer, integer, bigint, geometry, boolean) IS
  'A road raster sampled from the generator of that name in streetgen.gan_generator; see gan_sample(bytea, ...)';
