BEGIN;
SELECT * FROM no_plan();

SELECT is((SELECT extension FROM streetgen.version()),
          (SELECT extversion FROM pg_extension WHERE extname = 'streetgen'),
          'the loaded module is the installed extension version');
-- PostGIS and streetgen load the same libgeos_c: both must report the same runtime version.
SELECT is(split_part((SELECT geos FROM streetgen.version()), '-', 1),
          split_part(postgis_geos_version(), '-', 1),
          'GEOS version seen by streetgen equals the one PostGIS reports');
SELECT matches((SELECT cgal FROM streetgen.version()), '^[5-9]\.[0-9]+', 'CGAL 5 or later is compiled in');
SELECT is((SELECT postgis FROM streetgen.version()), postgis_lib_version(), 'PostGIS version');
SELECT is((SELECT postgresql FROM streetgen.version()), current_setting('server_version'), 'PostgreSQL version');

SELECT * FROM finish();
ROLLBACK;
