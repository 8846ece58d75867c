-- StreetGAN sampling from SQL: gan_load_generator, the gan_generator table and gan_sample, on a
-- tiny generator written here byte by byte after the documented file format (README.md, "StreetGAN"),
-- and every bad input by SQLSTATE: missing or corrupt generators, bad sizes, NULLs. The gan CTest
-- layer (tests/run-gan.sh) does the same with a generator trained by tools/sgan/train.py and checks
-- parity with PyTorch.
BEGIN;
SELECT * FROM no_plan();

CREATE SCHEMA gan_test;
-- Little-endian encodings of the format's fields.
CREATE FUNCTION gan_test.reversed(b bytea) RETURNS bytea LANGUAGE sql IMMUTABLE AS $$
  SELECT string_agg(substr(b, i, 1), ''::bytea ORDER BY i DESC) FROM generate_series(1, length(b)) AS i
$$;
CREATE FUNCTION gan_test.u32(v bigint) RETURNS bytea LANGUAGE sql IMMUTABLE AS $$
  SELECT gan_test.reversed(decode(lpad(to_hex(v), 8, '0'), 'hex'))
$$;
CREATE FUNCTION gan_test.f32(v real) RETURNS bytea LANGUAGE sql IMMUTABLE AS $$
  SELECT gan_test.reversed(float4send(v))
$$;
CREATE FUNCTION gan_test.f64(v double precision) RETURNS bytea LANGUAGE sql IMMUTABLE AS $$
  SELECT gan_test.reversed(float8send(v))
$$;
-- CRC-32 as zlib computes it (reflected, polynomial 0xEDB88320).
CREATE FUNCTION gan_test.crc32(data bytea) RETURNS bigint LANGUAGE plpgsql IMMUTABLE AS $$
DECLARE
  crc bigint := 4294967295;
BEGIN
  FOR i IN 0 .. length(data) - 1 LOOP
    crc := crc # get_byte(data, i);
    FOR j IN 1 .. 8 LOOP
      crc := CASE WHEN crc & 1 = 1 THEN (crc >> 1) # 3988292384 ELSE crc >> 1 END;
    END LOOP;
  END LOOP;
  RETURN crc # 4294967295;
END
$$;
-- A generator file: noise_channels -> widths[1] -> ... -> widths[n] channels, kernel 5, stride 2,
-- padding 2, ReLU then tanh on the last layer, weights from a fixed formula; in_override replaces
-- layer 2's declared input channels (for a shape error under a valid CRC).
CREATE FUNCTION gan_test.generator(noise_channels integer, widths integer[], version integer DEFAULT 1,
                                   in_override integer DEFAULT NULL, with_crc boolean DEFAULT true)
  RETURNS bytea LANGUAGE plpgsql IMMUTABLE AS $$
DECLARE
  body bytea := 'SGANGEN\000'::bytea || gan_test.u32(version) || gan_test.u32(noise_channels)
                || gan_test.u32(cardinality(widths)) || gan_test.u32(5) || gan_test.u32(2) || gan_test.u32(2)
                || gan_test.f64(3.0);
  cin integer := noise_channels;
  n integer := 0;
BEGIN
  FOR l IN 1 .. cardinality(widths) LOOP
    body := body || gan_test.u32(CASE WHEN l = 2 AND in_override IS NOT NULL THEN in_override ELSE cin END)
                 || gan_test.u32(widths[l]) || gan_test.u32(CASE WHEN l = cardinality(widths) THEN 2 ELSE 1 END);
    FOR i IN 1 .. cin * widths[l] * 25 LOOP
      n := n + 1;
      body := body || gan_test.f32((0.4 * sin(n * 1.7))::real);
    END LOOP;
    FOR i IN 1 .. widths[l] LOOP body := body || gan_test.f32(1.0); END LOOP;
    FOR i IN 1 .. widths[l] LOOP body := body || gan_test.f32((0.1 * cos(i))::real); END LOOP;
    cin := widths[l];
  END LOOP;
  RETURN CASE WHEN with_crc THEN body || gan_test.u32(gan_test.crc32(body)) ELSE body END;
END
$$;
CREATE TABLE gan_test.files AS
SELECT gan_test.generator(2, '{3,1}') AS good,
       gan_test.generator(2, '{3,1}', version => 2) AS version2,
       gan_test.generator(2, '{3,1}', in_override => 4) AS bad_shape,
       gan_test.generator(2, '{3,2}') AS two_channels,
       gan_test.generator(3, '{2,1}') AS other;

-- ---- loading
SELECT is((SELECT (g.noise_channels, g.layer_count, g.parameter_count, g.metres_per_pixel, g.bytes = length(f.good))::text
             FROM gan_test.files f, streetgen.gan_load_generator('tiny', f.good, 'pgTAP fixture') AS g),
          (2, 2, (2 * 3 + 3 * 1) * 25 + 2 * (3 + 1), 3.0::double precision, true)::text,
          'gan_load_generator stores a generator and reports its metadata');
SELECT is((SELECT (noise_channels, layer_count, source, loaded_by)::text FROM streetgen.gan_generator WHERE name = 'tiny'),
          (2, 2, 'pgTAP fixture', current_user)::text, 'the row holds the metadata, the source and who loaded it');
SELECT throws_ok($$SELECT streetgen.gan_load_generator('tiny', good) FROM gan_test.files$$, '42710',
                 'generator "tiny" already exists', 'loading a taken name fails');
SELECT is((SELECT g.noise_channels FROM gan_test.files f,
                   streetgen.gan_load_generator('tiny', f.other, 'again', replace => true) AS g), 3,
          'replace => true replaces it');
SELECT is((SELECT (noise_channels, source)::text FROM streetgen.gan_generator WHERE name = 'tiny'), '(3,again)',
          'and the row follows');
SELECT lives_ok($$SELECT streetgen.gan_load_generator('tiny', good, 'pgTAP fixture', true) FROM gan_test.files$$,
                'and back');
INSERT INTO streetgen.gan_generator (name, weights) SELECT 'from_client', good FROM gan_test.files;
SELECT is((SELECT (noise_channels, layer_count) FROM streetgen.gan_generator WHERE name = 'from_client')::text,
          '(2,2)', 'a plain INSERT from a client is checked and gets its metadata');
UPDATE streetgen.gan_generator SET noise_channels = 7 WHERE name = 'from_client';
SELECT is((SELECT noise_channels FROM streetgen.gan_generator WHERE name = 'from_client'), 2,
          'metadata edited by hand is recomputed from the weights');

-- ---- sampling
CREATE TABLE gan_test.s AS
SELECT streetgen.gan_sample('tiny', 37, 23, 42) AS a,
       streetgen.gan_sample('tiny', 37, 23, 42) AS a_again,
       (SELECT streetgen.gan_sample(good, 37, 23, 42) FROM gan_test.files) AS a_bytea,
       streetgen.gan_sample('tiny', 37, 23, 43) AS b,
       streetgen.gan_sample('tiny', 37, 23, 42, raw => true) AS a_raw,
       streetgen.gan_sample('tiny', 80, 60, 42) AS big,
       streetgen.gan_sample('tiny', 37, 23, 42, ST_SetSRID(ST_MakePoint(1000, 5000), 3857)) AS placed,
       streetgen.gan_sample('tiny', 1, 1, -1) AS one;
SELECT is((SELECT (ST_Width(a), ST_Height(a), ST_NumBands(a), ST_BandPixelType(a), ST_PixelWidth(a), ST_PixelHeight(a),
                   ST_UpperLeftX(a), ST_UpperLeftY(a), ST_SRID(a))::text FROM gan_test.s),
          '(37,23,1,8BUI,3,3,0,0,0)', 'gan_sample returns a 37 x 23 8BUI raster at the generator''s 3 m per pixel');
SELECT is((SELECT array_agg(value ORDER BY value) FROM gan_test.s, ST_ValueCount(a) AS v), '{0,1}'::double precision[],
          'road raster: values 0 and 1 only, both present');
SELECT ok((SELECT ST_AsBinary(a) = ST_AsBinary(a_again) AND ST_AsBinary(a) = ST_AsBinary(a_bytea) FROM gan_test.s),
          'deterministic for a seed, and the same by name or by bytea');
SELECT ok((SELECT ST_AsBinary(a) <> ST_AsBinary(b) FROM gan_test.s), 'another seed gives another raster');
SELECT is((SELECT (ST_BandPixelType(a_raw), (ST_SummaryStats(a_raw)).min >= -1, (ST_SummaryStats(a_raw)).max <= 1)::text
             FROM gan_test.s), '(32BF,t,t)', 'raw => true returns the tanh output as 32BF in [-1, 1]');
SELECT is((SELECT count(*) FROM gan_test.s, ST_PixelAsPoints(a) p, ST_PixelAsPoints(a_raw) r
            WHERE p.x = r.x AND p.y = r.y AND (p.val = 1) <> (r.val > 0)), 0::bigint,
          'the road raster is the raw output thresholded at 0');
SELECT is((SELECT count(*) FROM gan_test.s, ST_PixelAsPoints(a) p, ST_PixelAsPoints(big) q
            WHERE p.x = q.x AND p.y = q.y AND p.x <= 20 AND p.y <= 10 AND p.val <> q.val), 0::bigint,
          'a larger sample of the same seed extends the smaller one (away from its right and bottom edge)');
SELECT is((SELECT (ST_UpperLeftX(placed), ST_UpperLeftY(placed), ST_SRID(placed), ST_ScaleY(placed))::text FROM gan_test.s),
          '(1000,5000,3857,-3)', 'upper_left places the raster (its SRID, rows going south)');
SELECT is((SELECT (ST_Width(one), ST_Height(one))::text FROM gan_test.s), '(1,1)', 'a 1 x 1 sample works');
SELECT is((SELECT ST_Width(streetgen.gan_sample('tiny', 2048, 1, 1))), 2048, 'the documented maximum side is accepted');

-- ---- bad input
SELECT throws_ok($$SELECT streetgen.gan_sample('nope', 10, 10, 1)$$, '42704', 'generator "nope" does not exist',
                 'a missing generator');
SELECT throws_ok($$SELECT streetgen.gan_sample(NULL::text, 10, 10, 1)$$, '22004', 'generator must not be null',
                 'NULL generator name');
SELECT throws_ok($$SELECT streetgen.gan_sample(NULL::bytea, 10, 10, 1)$$, '22004', 'generator must not be null',
                 'NULL generator bytes');
SELECT throws_ok($$SELECT streetgen.gan_sample('tiny', 10, 10, NULL)$$, '22004', 'seed must not be null', 'NULL seed');
SELECT throws_ok($$SELECT streetgen.gan_sample('tiny', NULL, 10, 1)$$, '22004', 'width_px must not be null',
                 'NULL width_px');
SELECT throws_ok($$SELECT streetgen.gan_sample('tiny', 10, NULL, 1)$$, '22004', 'height_px must not be null',
                 'NULL height_px');
SELECT throws_ok($$SELECT streetgen.gan_sample('tiny', 0, 10, 1)$$, '22023', 'width_px must be between 1 and 2048',
                 'zero width_px');
SELECT throws_ok($$SELECT streetgen.gan_sample('tiny', -5, 10, 1)$$, '22023', 'width_px must be between 1 and 2048',
                 'negative width_px');
SELECT throws_ok($$SELECT streetgen.gan_sample('tiny', 10, 2049, 1)$$, '22023', 'height_px must be between 1 and 2048',
                 'height_px over the maximum');
SELECT throws_ok($$SELECT streetgen.gan_sample('tiny', 100000, 100000, 1)$$, '22023',
                 'width_px must be between 1 and 2048', 'a huge sample');
SELECT throws_ok($$SELECT streetgen.gan_sample('tiny', 10, 10, 1, 'LINESTRING(0 0, 1 1)'::geometry)$$, '22023',
                 'upper_left must be a point', 'upper_left that is not a point');
SELECT throws_ok($$SELECT streetgen.gan_sample(substr(good, 1, length(good) - 10), 10, 10, 1) FROM gan_test.files$$,
                 '22000', 'generator is truncated', 'truncated weights');
SELECT throws_ok($$SELECT streetgen.gan_sample(''::bytea, 10, 10, 1)$$, '22000', 'generator is truncated',
                 'empty weights');
SELECT throws_ok($$SELECT streetgen.gan_sample(overlay(good placing 'X'::bytea from 1), 10, 10, 1) FROM gan_test.files$$,
                 '22000', 'generator is not a streetgen generator file', 'wrong magic number');
SELECT throws_ok($$SELECT streetgen.gan_sample(version2, 10, 10, 1) FROM gan_test.files$$,
                 '22000', 'generator has an unsupported format version', 'wrong format version');
SELECT throws_ok($$SELECT streetgen.gan_sample(bad_shape, 10, 10, 1) FROM gan_test.files$$,
                 '22000', 'generator has inconsistent layer shapes', 'a layer whose input does not match (valid CRC)');
SELECT throws_ok($$SELECT streetgen.gan_sample(two_channels, 10, 10, 1) FROM gan_test.files$$,
                 '22000', 'generator has inconsistent layer shapes', 'a generator giving two channels');
SELECT throws_ok($$SELECT streetgen.gan_sample(set_byte(good, 100, get_byte(good, 100) # 1), 10, 10, 1) FROM gan_test.files$$,
                 '22000', 'generator is corrupt (CRC-32 mismatch)', 'one flipped bit in the weights');
SELECT throws_ok($$SELECT streetgen.gan_sample(good || '\x00'::bytea, 10, 10, 1) FROM gan_test.files$$,
                 '22000', 'generator has trailing bytes', 'trailing bytes');
SELECT throws_ok($$SELECT streetgen.gan_load_generator('broken', substr(good, 1, 200)) FROM gan_test.files$$,
                 '22000', 'generator is truncated', 'the loader refuses a corrupt file');
SELECT throws_ok($$INSERT INTO streetgen.gan_generator (name, weights) SELECT 'broken', version2 FROM gan_test.files$$,
                 '22000', 'generator has an unsupported format version', 'so does a plain INSERT');
SELECT is((SELECT count(*) FROM streetgen.gan_generator WHERE name = 'broken'), 0::bigint, 'and nothing was stored');
SELECT throws_ok($$SELECT streetgen.gan_load_generator(NULL, good) FROM gan_test.files$$, '22004',
                 'name must not be null', 'NULL name');
SELECT throws_ok($$SELECT streetgen.gan_load_generator('x', NULL)$$, '22004', 'weights must not be null',
                 'NULL weights');
SELECT ok((SELECT ST_Width(streetgen.gan_sample('tiny', 5, 5, 7)) = 5), 'and the session still samples');

SELECT * FROM finish();
ROLLBACK;
