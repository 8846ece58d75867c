-- osm2pgsql flex style for streetgen: stages every highway=* way with all its tags (jsonb) and
-- its line in WGS 84, with source = 'osm:way/<id>'. Which ways are roads and what their tags
-- mean is decided in SQL (streetgen.load_osm_ways), so the OSM and GeoJSON import paths share one
-- mapping.
--
-- Street parking mapped as its own area (amenity=parking with parking=street_side|lane|layby, the
-- areas a road's parking:<side>=separate points to) is staged too, as (multi)polygons in a second
-- table, <staging>_parking: streetgen.load_osm_street_parking gives the roadway that depth.
--
-- Environment: STREETGEN_STAGING_SCHEMA (default public), STREETGEN_STAGING_TABLE (default
-- streetgen_osm_staging). scripts/streetgen-import sets both.

local staging_name = os.getenv('STREETGEN_STAGING_TABLE') or 'streetgen_osm_staging'
local staging_schema = os.getenv('STREETGEN_STAGING_SCHEMA') or 'public'

local staging = osm2pgsql.define_table({
    name = staging_name,
    schema = staging_schema,
    ids = { type = 'way', id_column = 'osm_id' },
    -- A staging table is read once, whole: no index and no clustering by geometry (osm2pgsql's
    -- defaults copy and sort the table, then build a GiST index nothing uses).
    indexes = {},
    cluster = 'no',
    columns = {
        { column = 'source', type = 'text', not_null = true },
        { column = 'tags', type = 'jsonb', not_null = true },
        { column = 'geom', type = 'linestring', projection = 4326, not_null = true },
    },
})

local parking = osm2pgsql.define_table({
    name = staging_name .. '_parking',
    schema = staging_schema,
    ids = { type = 'area', id_column = 'osm_id' },
    indexes = {},
    cluster = 'no',
    columns = {
        { column = 'source', type = 'text', not_null = true },
        { column = 'tags', type = 'jsonb', not_null = true },
        { column = 'geom', type = 'multipolygon', projection = 4326, not_null = true },
    },
})

local street_parking = { street_side = true, lane = true, layby = true }

local function is_street_parking(tags)
    return tags.amenity == 'parking' and street_parking[tags.parking] == true
end

function osm2pgsql.process_way(object)
    if object.tags.highway ~= nil then
        -- Ways whose nodes are missing from the extract have no geometry: osm2pgsql skips them
        -- because of not_null; load_osm_ways reports the difference.
        staging:insert({ source = 'osm:way/' .. object.id, tags = object.tags, geom = object:as_linestring() })
    elseif object.is_closed and is_street_parking(object.tags) then
        parking:insert({ source = 'osm:way/' .. object.id, tags = object.tags, geom = object:as_multipolygon() })
    end
end

function osm2pgsql.process_relation(object)
    if object.tags.type == 'multipolygon' and is_street_parking(object.tags) then
        parking:insert({ source = 'osm:relation/' .. object.id, tags = object.tags, geom = object:as_multipolygon() })
    end
end
