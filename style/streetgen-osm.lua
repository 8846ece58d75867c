-- osm2pgsql flex style for streetgen: stages every highway=* way with all its tags (jsonb) and
-- its line in WGS 84, with source = 'osm:way/<id>'. Which ways are roads and what their tags
-- mean is decided in SQL (streetgen.load_osm_ways), so the OSM and GeoJSON import paths share one
-- mapping.
--
-- Environment: STREETGEN_STAGING_SCHEMA (default public), STREETGEN_STAGING_TABLE (default
-- streetgen_osm_staging). scripts/streetgen-import sets both.

local staging = osm2pgsql.define_table({
    name = os.getenv('STREETGEN_STAGING_TABLE') or 'streetgen_osm_staging',
    schema = os.getenv('STREETGEN_STAGING_SCHEMA') or 'public',
    ids = { type = 'way', id_column = 'osm_id' },
    columns = {
        { column = 'source', type = 'text', not_null = true },
        { column = 'tags', type = 'jsonb', not_null = true },
        { column = 'geom', type = 'linestring', projection = 4326, not_null = true },
    },
})

function osm2pgsql.process_way(object)
    if object.tags.highway == nil then
        return
    end
    -- Ways whose nodes are missing from the extract have no geometry: osm2pgsql skips them
    -- because of not_null; load_osm_ways reports the difference.
    staging:insert({ source = 'osm:way/' .. object.id, tags = object.tags, geom = object:as_linestring() })
end
