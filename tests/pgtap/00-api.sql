-- The public API, as shipped: every function's signature, result, volatility and strictness,
-- and the habits every function must keep (search_path pinned, no SECURITY DEFINER, comments).
BEGIN;
SELECT * FROM no_plan();

CREATE TEMP VIEW streetgen_functions AS
SELECT p.oid::regprocedure::text AS signature,
       pg_get_function_result(p.oid) AS result,
       p.provolatile AS volatility,
       p.proisstrict AS strict,
       p.prosecdef AS security_definer,
       l.lanname AS language,
       p.proconfig AS config,
       obj_description(p.oid, 'pg_proc') AS comment
  FROM pg_proc p
  JOIN pg_language l ON l.oid = p.prolang
  JOIN pg_depend d ON d.classid = 'pg_proc'::regclass AND d.objid = p.oid AND d.deptype = 'e'
  JOIN pg_extension e ON e.oid = d.refobjid AND e.extname = 'streetgen';

SELECT set_eq(
  'SELECT signature, result, volatility::text, strict FROM streetgen_functions',
  $$VALUES
    ('streetgen._streetgen_version()', 'record', 'i', true),
    ('streetgen.version()', 'record', 's', false),
    ('streetgen._require_model_name(text)', 'void', 'i', false),
    ('streetgen._require_params(jsonb,text[])', 'void', 'i', false),
    ('streetgen._require_metric_srid(integer,text)', 'void', 's', false),
    ('streetgen._lock_model_name(text)', 'void', 'v', false),
    ('streetgen.create_model(text,integer)', 'void', 'v', false),
    ('streetgen.drop_model(text)', 'void', 'v', false),
    ('streetgen.model_srid(text)', 'integer', 's', false),
    ('streetgen._streetgen_roadway_borders(bytea,double precision)', 'SETOF record', 'i', false),
    ('streetgen.roadway_borders(geometry,double precision)', 'SETOF record', 's', false),
    ('streetgen.osm_parse_length(text)', 'double precision', 'i', false),
    ('streetgen.osm_parse_speed(text)', 'double precision', 'i', false),
    ('streetgen._osm_speed_of(text)', 'double precision', 'i', false),
    ('streetgen._osm_speed_in_range(double precision)', 'double precision', 'i', false),
    ('streetgen.osm_parse_lanes(text)', 'smallint', 'i', false),
    ('streetgen.osm_is_driveable(jsonb)', 'boolean', 's', false),
    ('streetgen.osm_axis_attributes(jsonb)', 'record', 's', false),
    ('streetgen._osm_driveable_tags(jsonb)', 'boolean', 'i', false),
    ('streetgen._osm_axis_attributes(jsonb)', 'TABLE(roadway_width double precision, lanes smallint, speed_kmh double precision, road_class text, oneway boolean, reverse_geometry boolean, layer smallint, structure text, sidewalk_width double precision, estimated text[])', 's', false),
    ('streetgen.utm_srid(geometry)', 'integer', 's', false),
    ('streetgen._streetgen_network_stats(bytea[],double precision,bytea,boolean,boolean,boolean,integer[])', 'streetgen.network_metrics', 'i', false),
    ('streetgen._streetgen_compare_networks(streetgen.network_metrics,streetgen.network_metrics)', 'SETOF record', 'i', false),
    ('streetgen._network_stats(bytea[],integer,double precision,geometry,boolean,boolean,boolean,integer[])', 'streetgen.network_metrics', 's', false),
    ('streetgen.network_stats(geometry,double precision,geometry,boolean,boolean,boolean)', 'streetgen.network_metrics', 's', false),
    ('streetgen.network_stats(text,double precision,geometry,boolean,boolean,boolean)', 'streetgen.network_metrics', 'v', false),
    ('streetgen.model_network_stats(text,double precision,geometry,boolean,boolean)', 'streetgen.network_metrics', 's', false),
    ('streetgen.compare_networks(streetgen.network_metrics,streetgen.network_metrics)', 'SETOF record', 'i', false),
    ('streetgen.load_osm_ways(text,regclass)', 'record', 'v', false),
    ('streetgen.load_osm_street_parking(text,regclass)', 'record', 'v', false),
    ('streetgen._settings_vector(jsonb)', 'double precision[]', 's', false),
    ('streetgen._create_output_tables(text,integer)', 'void', 'v', false),
    ('streetgen._streetgen_street_surfaces(bigint[],bytea[],double precision[],double precision[],integer[],double precision[],double precision[],bigint[],bigint[],double precision[],integer[],boolean[],text[],double precision[],double precision[])', 'SETOF record', 'i', false),
    ('streetgen._lane_tags(jsonb)', 'text', 'i', false),
    ('streetgen._lane_tags_listed(jsonb)', 'text', 'i', false),
    ('streetgen.sidewalk_widths(text,double precision,jsonb,double precision)', 'double precision[]', 'i', false),
    ('streetgen._sidewalk_tags(jsonb)', 'text', 'i', false),
    ('streetgen._compute_blocks(text,geometry,geometry)', 'void', 'v', false),
    ('streetgen._streetgen_faces_minus(bytea[],bytea[],bytea[],bytea[],double precision)', 'SETOF record', 'i', false),
    ('streetgen._store_blocks(text,geometry)', 'void', 'v', false),
    ('streetgen._scope_extent(text)', 'geometry', 'v', false),
    ('streetgen.detail_quality(text)', 'record', 's', false),
    ('streetgen._street_parking_widths(text)', 'double precision[]', 'i', false),
    ('streetgen._compute_model(text,bigint[])', 'void', 'v', false),
    ('streetgen._store(text,boolean)', 'void', 'v', false),
    ('streetgen._defer_foreign_keys(text)', 'text[]', 'v', false),
    ('streetgen._restore_foreign_keys(text[])', 'void', 'v', false),
    ('streetgen._lock_outputs(text)', 'void', 'v', false),
    ('streetgen._lock_outputs_first()', 'trigger', 'v', false),
    ('streetgen._axes_of_overlapping_outputs(text)', 'bigint[]', 's', false),
    ('streetgen._refresh(text,bigint[],geometry[],boolean)', 'void', 'v', false),
    ('streetgen._axis_inserted()', 'trigger', 'v', false),
    ('streetgen._axis_updated()', 'trigger', 'v', false),
    ('streetgen._axis_deleted()', 'trigger', 'v', false),
    ('streetgen._corner_override_changed()', 'trigger', 'v', false),
    ('streetgen._settings_changed()', 'trigger', 'v', false),
    ('streetgen._create_triggers(text)', 'void', 'v', false),
    ('streetgen._apart(geometry,geometry)', 'text', 'i', false),
    ('streetgen.outdated(text)', 'SETOF record', 'v', false),
    ('streetgen._work_tables(text[])', 'void', 'v', false),
    ('streetgen._empty_work_tables()', 'void', 'v', false),
    ('streetgen.generate(text)', 'SETOF record', 'v', false),
    ('streetgen.street_surfaces(text,jsonb)', 'SETOF record', 'v', false),
    ('streetgen.surface_quality(text)', 'record', 's', false),
    ('streetgen.lane_quality(text)', 'record', 's', false),
    ('streetgen._streetgen_grow_example(bytea[],text[],bigint[],integer[],bytea,double precision[],double precision[],bytea[],double precision,double precision,boolean,bigint,integer,boolean,double precision,double precision,integer,bytea[],boolean,boolean,boolean,double precision,double precision,boolean,double precision,double precision,double precision,integer,integer,double precision,text,bytea,double precision,text,double precision,double precision[],double precision[],double precision,double precision[],double precision[],double precision[],double precision[])', 'SETOF record', 'i', false),
    ('streetgen._control_raster(raster,text,geometry)', 'record', 's', false),
    ('streetgen._grow(text[],geometry,geometry,geometry,jsonb,text,geometry,raster,raster)', 'SETOF record', 'v', false),
    ('streetgen.grow_example(text,geometry,geometry,geometry,jsonb,text,geometry,raster)', 'SETOF record', 'v', false),
    ('streetgen.grow_example(text[],geometry,geometry,geometry,jsonb,text,geometry,raster,raster)', 'SETOF record', 'v', false),
    ('streetgen.grow_parametric(geometry,geometry,geometry,jsonb,text,geometry,raster)', 'SETOF record', 'v', false),
    ('streetgen._streetgen_extract_patches(bytea[],text[],bigint[],boolean[],double precision,double precision,boolean,double precision,double precision,double precision,double precision,boolean)', 'SETOF record', 'i', false),
    ('streetgen._streetgen_grow_patches(bigint[],text[],text[],bytea[],integer[],bytea,double precision[],double precision[],bytea[],bigint,integer,double precision,double precision,double precision,double precision,double precision,integer,integer,double precision,boolean,double precision,boolean[],boolean,bytea[],double precision[],double precision[],double precision,double precision,double precision,bytea,double precision,bigint[],text[],text[],bytea[],integer[],boolean[],double precision,text,double precision,double precision[],double precision[],double precision,boolean,double precision[],double precision[],boolean,boolean,double precision,boolean,boolean[],boolean,text,double precision,double precision,boolean,double precision,boolean[])', 'SETOF record', 'i', false),
    ('streetgen._rows_with_geom(text,text)', 'TABLE(j jsonb, geom geometry, n bigint)', 'v', false),
    ('streetgen.extract_patches(text,jsonb)', 'SETOF record', 'v', false),
    ('streetgen._patch_arrays(text,text)', 'record', 'v', false),
    ('streetgen.grow_patches(text,geometry,geometry,geometry,jsonb,geometry,raster,geometry,raster)', 'SETOF record', 'v', false),
    ('streetgen.rasterise_network(text,double precision,integer,geometry)', 'raster', 'v', false),
    ('streetgen._streetgen_raster_to_network(bytea,double precision,integer,integer,double precision,double precision,integer,double precision,double precision,double precision)', 'SETOF record', 'i', false),
    ('streetgen.raster_to_network(raster,jsonb)', 'SETOF record', 'i', false),
    ('streetgen._streetgen_gan_sample(bytea,integer,integer,bigint,boolean,double precision,double precision,integer)', 'bytea', 'i', false),
    ('streetgen._streetgen_gan_generator_info(bytea)', 'record', 'i', false),
    ('streetgen._gan_generator_check()', 'trigger', 'v', false),
    ('streetgen.gan_load_generator(text,bytea,text,boolean)', 'record', 'v', false),
    ('streetgen.gan_sample(bytea,integer,integer,bigint,geometry,boolean)', 'raster', 'i', false),
    ('streetgen.gan_sample(text,integer,integer,bigint,geometry,boolean)', 'raster', 's', false)
  $$,
  'the extension ships exactly the documented functions, with these results and volatilities');

-- OUT parameters are part of the contract too.
SELECT is(pg_get_function_result('streetgen.version()'::regprocedure), 'record', 'version() returns a record');
CREATE FUNCTION pg_temp.argument_names(f regprocedure) RETURNS text LANGUAGE sql AS $$
  SELECT array_to_string(proargnames, ',') COLLATE "C" FROM pg_proc WHERE oid = f
$$;
SELECT is(pg_temp.argument_names('streetgen.version()'), 'extension,geos,cgal,postgis,postgresql', 'version() columns');
SELECT is(pg_temp.argument_names('streetgen.roadway_borders(geometry,double precision)'), 'axis,roadway_width,side,geom',
          'roadway_borders(axis, roadway_width) -> (side, geom)');
SELECT is(pg_temp.argument_names('streetgen.load_osm_ways(text,regclass)'), 'model,staging,loaded,not_driveable,degenerate',
          'load_osm_ways(model, staging) -> (loaded, not_driveable, degenerate)');
SELECT is(pg_temp.argument_names('streetgen.load_osm_street_parking(text,regclass)'), 'model,staging,sides_widened,areas_used',
          'load_osm_street_parking(model, staging) -> (sides_widened, areas_used)');
SELECT is(pg_temp.argument_names('streetgen.create_model(text,integer)'), 'name,srid', 'create_model(name, srid)');
SELECT is(pg_temp.argument_names('streetgen.compare_networks(streetgen.network_metrics,streetgen.network_metrics)'),
          'reference,candidate,metric,kind,reference_value,candidate_value,relative_difference,ks,wasserstein,score',
          'compare_networks(reference, candidate) -> (metric, kind, reference_value, candidate_value, relative_difference, ks, wasserstein, score)');
SELECT is(pg_temp.argument_names('streetgen.generate(text)'), 'model,kind,status,count', 'generate(model) -> (kind, status, count)');
SELECT is(pg_temp.argument_names('streetgen.street_surfaces(text,jsonb)'), 'axes,settings,kind,node_id,axis_id,part,status,geom,item,detail',
          'street_surfaces(axes, settings) -> (kind, node_id, axis_id, part, status, geom, item, detail)');
SELECT is(pg_temp.argument_names('streetgen.lane_quality(text)'),
          'model,sections,sections_without_lanes,lanes,markings,invalid_geometries,max_coverage_difference,sections_over_tolerance,lane_overlap_area,outside_section_area,foreign_overlap_area',
          'lane_quality(model) -> (sections, sections_without_lanes, lanes, markings, invalid_geometries, max_coverage_difference, sections_over_tolerance, lane_overlap_area, outside_section_area, foreign_overlap_area)');

SELECT is(pg_temp.argument_names('streetgen.detail_quality(text)'),
          'model,sidewalks,crossings,blocks,invalid_geometries,sidewalk_area,sidewalk_roadway_overlap_area,sidewalk_overlap_area,crossing_outside_area,face_area,overlap_area,roadway_overlap_area,gap_area',
          'detail_quality(model) -> (sidewalks, crossings, blocks, invalid_geometries, sidewalk_area, sidewalk_roadway_overlap_area, sidewalk_overlap_area, crossing_outside_area, face_area, overlap_area, roadway_overlap_area, gap_area)');
SELECT is(pg_temp.argument_names('streetgen.grow_example(text,geometry,geometry,geometry,jsonb,text,geometry,raster)'),
          'example,region,seeds,obstacles,params,existing,guide,direction,id,from_node,to_node,road_class,origin,geom',
          'grow_example(example, region, seeds, obstacles, params, existing, guide, direction) -> (id, from_node, to_node, road_class, origin, geom)');
SELECT is(pg_temp.argument_names('streetgen.grow_example(text[],geometry,geometry,geometry,jsonb,text,geometry,raster,raster)'),
          'examples,region,seeds,obstacles,params,existing,guide,direction,weights,id,from_node,to_node,road_class,origin,geom',
          'grow_example(examples, region, seeds, obstacles, params, existing, guide, direction, weights) -> (id, from_node, to_node, road_class, origin, geom)');
SELECT is(pg_temp.argument_names('streetgen.grow_parametric(geometry,geometry,geometry,jsonb,text,geometry,raster)'),
          'region,seeds,obstacles,params,existing,guide,direction,id,from_node,to_node,road_class,origin,geom',
          'grow_parametric(region, seeds, obstacles, params, existing, guide, direction) -> (id, from_node, to_node, road_class, origin, geom)');

SELECT is(pg_temp.argument_names('streetgen.extract_patches(text,jsonb)'),
          'example,params,patch_id,edge_index,role,road_class,tags,edge_tags,start_tags,end_tags,max_uses,example_id,geom',
          'extract_patches(example, params) -> (patch_id, edge_index, role, road_class, tags, edge_tags, start_tags, end_tags, max_uses, example_id, geom)');
SELECT is(pg_temp.argument_names('streetgen.grow_patches(text,geometry,geometry,geometry,jsonb,geometry,raster,geometry,raster)'),
          'patches,region,seeds,obstacles,params,water,dem,guide,direction,id,from_node,to_node,road_class,origin,geom',
          'grow_patches(patches, region, seeds, obstacles, params, water, dem, guide, direction) -> (id, from_node, to_node, road_class, origin, geom)');

SELECT is(pg_temp.argument_names('streetgen.rasterise_network(text,double precision,integer,geometry)'),
          'edges,pixel_size,road_width_px,extent', 'rasterise_network(edges, pixel_size, road_width_px, extent)');
SELECT is(pg_temp.argument_names('streetgen.raster_to_network(raster,jsonb)'), 'rast,params,id,from_node,to_node,geom',
          'raster_to_network(rast, params) -> (id, from_node, to_node, geom)');

SELECT is(pg_temp.argument_names('streetgen.gan_sample(text,integer,integer,bigint,geometry,boolean)'),
          'generator,width_px,height_px,seed,upper_left,raw', 'gan_sample(generator, width_px, height_px, seed, upper_left, raw)');
SELECT is(pg_temp.argument_names('streetgen.gan_load_generator(text,bytea,text,boolean)'),
          'name,weights,source,replace,noise_channels,layer_count,parameter_count,metres_per_pixel,bytes',
          'gan_load_generator(name, weights, source, replace) -> (noise_channels, layer_count, parameter_count, metres_per_pixel, bytes)');

SELECT is_empty(
  'SELECT signature FROM streetgen_functions WHERE security_definer',
  'no function is SECURITY DEFINER');
-- The tag parsers and the OSM mapping are inlinable SQL (no SET clause, so PostgreSQL can
-- inline them into the import query); they name only pg_catalog and streetgen objects.
SELECT is_empty(
  $$SELECT signature FROM streetgen_functions
     WHERE language <> 'c'
       AND signature NOT IN ('streetgen.osm_parse_length(text)', 'streetgen.osm_parse_speed(text)',
                             'streetgen._osm_speed_of(text)', 'streetgen._osm_speed_in_range(double precision)',
                             'streetgen.osm_parse_lanes(text)', 'streetgen.osm_is_driveable(jsonb)',
                             'streetgen._osm_driveable_tags(jsonb)', 'streetgen._osm_axis_attributes(jsonb)', 'streetgen._lane_tags(jsonb)')
       AND NOT EXISTS (SELECT 1 FROM unnest(config) c
                        WHERE c LIKE 'search_path=pg_catalog, streetgen, %, pg_temp')$$,
  'every other SQL-level function pins search_path to pg_catalog, streetgen, postgis, pg_temp');
SELECT is_empty(
  $$SELECT signature FROM streetgen_functions
     WHERE signature IN ('streetgen.osm_parse_length(text)', 'streetgen.osm_parse_speed(text)',
                         'streetgen._osm_speed_of(text)', 'streetgen._osm_speed_in_range(double precision)',
                         'streetgen.osm_parse_lanes(text)', 'streetgen.osm_is_driveable(jsonb)',
                         'streetgen._osm_driveable_tags(jsonb)', 'streetgen._osm_axis_attributes(jsonb)', 'streetgen._lane_tags(jsonb)')
       AND (language <> 'sql' OR config IS NOT NULL)$$,
  'the inlinable mapping functions are plain SQL without a SET clause');
-- And PostgreSQL does inline the tag parsers: the plan of a query calling them names none of
-- them, only what they are made of (a parser that is called instead costs a function call per
-- tag per way: osm_parse_speed with a FROM was a second of Reisterstown's import).
CREATE FUNCTION pg_temp.plan_of(query text) RETURNS text LANGUAGE plpgsql AS $f$
DECLARE
  line text;
  plan text := '';
BEGIN
  FOR line IN EXECUTE 'EXPLAIN (VERBOSE, COSTS OFF) ' || query LOOP
    plan := plan || line || E'\n';
  END LOOP;
  RETURN plan;
END $f$;
CREATE TEMP TABLE tag_values (v text);  -- (a column, not constants, which the planner would fold)
SELECT doesnt_match(pg_temp.plan_of($$SELECT streetgen.osm_parse_speed(v), streetgen.osm_parse_length(v), streetgen.osm_parse_lanes(v)
                                 FROM tag_values$$),
                    'osm_', 'the tag parsers are inlined into the query that calls them');
SELECT matches(pg_temp.plan_of($$SELECT streetgen.osm_parse_speed(v) FROM tag_values$$),
               'split_part', 'osm_parse_speed''s own expression is in the plan');
-- _lane_tags too: its look at the tags' text is in the plan, and only the ways it lets through
-- call _lane_tags_listed (a query each: 28 us a way, on every way before).
SELECT matches(pg_temp.plan_of($$SELECT streetgen._lane_tags(v::jsonb) FROM tag_values$$),
               'CASE WHEN .*~.*_lane_tags_listed', '_lane_tags is inlined: its text test decides whether to list the tags');
-- The loader's driveable filter: _osm_driveable_tags is inlined (osm_is_driveable's EXISTS
-- cannot be: a function call per way), and with the class join it says what osm_is_driveable says.
SELECT doesnt_match(pg_temp.plan_of($$SELECT streetgen._osm_driveable_tags(v::jsonb) FROM tag_values$$),
                    '_osm_driveable_tags', '_osm_driveable_tags is inlined into the query that calls it');
SELECT is_empty(
  $$SELECT t FROM (VALUES ('{"highway": "residential"}'::jsonb), ('{"highway": "service", "service": "alley"}'),
                          ('{"highway": "service", "service": "parking_aisle"}'), ('{"highway": "service"}'),
                          ('{"highway": "footway"}'), ('{"highway": "pedestrian", "area": "yes"}'),
                          ('{"highway": "primary", "area": "no"}'), ('{"highway": "residential", "motor_vehicle": "no"}'),
                          ('{"highway": "residential", "motorcar": "no"}'), ('{"building": "yes"}'), ('{}')) AS v(t)
              LEFT JOIN streetgen.highway_class h ON h.highway = t->>'highway'
     WHERE (h.highway IS NOT NULL AND streetgen._osm_driveable_tags(t)) IS DISTINCT FROM streetgen.osm_is_driveable(t)$$,
  'the class join and _osm_driveable_tags say what osm_is_driveable says');
SELECT is_empty(
  $$SELECT t FROM (VALUES ('{"lanes": "2"}'::jsonb), ('{"parking:left": "lane", "highway": "residential"}'),
                          ('{"turn:lanes:forward": "left|through"}'), ('{"cycleway": "lane"}'), ('{"busway:right": "lane"}'),
                          ('{"placement": "right_of:1"}'), ('{"oneway": "-1", "lanes:forward": "2", "parking:both": "no"}'),
                          ('{"name": "parking", "highway": "service"}'), ('{"lanesx": "2", "xlanes": "3"}'),
                          ('{"lanes\"": "2"}'), ('["lanes"]'), ('"lanes"'), ('{}'), (NULL)) AS v(t)
     WHERE streetgen._lane_tags(t) IS DISTINCT FROM streetgen._lane_tags_listed(t)$$,
  '_lane_tags lists the same tags as _lane_tags_listed: its text test lets every such key through');
SELECT is_empty(
  $$SELECT signature FROM streetgen_functions WHERE signature NOT LIKE 'streetgen.\_%' AND comment IS NULL$$,
  'every public function has a comment');
SELECT is_empty(
  $$SELECT c.relname FROM pg_class c
      JOIN pg_depend d ON d.classid = 'pg_class'::regclass AND d.objid = c.oid AND d.deptype = 'e'
      JOIN pg_extension e ON e.oid = d.refobjid AND e.extname = 'streetgen'
     WHERE c.relkind = 'r' AND obj_description(c.oid, 'pg_class') IS NULL$$,
  'every extension table has a comment');

SELECT * FROM finish();
ROLLBACK;
