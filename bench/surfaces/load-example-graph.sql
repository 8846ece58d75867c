-- Loads an example road graph (Nishida et al.'s GeoJSON: local metres, properties type, lanes,
-- oneway) from staging table :staging into model :model (SRID 0). Widths from lanes and type:
-- lanes per direction x lane width (highway 3.5 m, avenue 3.25 m, street 3.0 m), doubled for
-- two-way edges; speed by type (highway 90, avenue 50, street 30 km/h).
INSERT INTO :"model".axis (geom, roadway_width, lanes, speed_kmh, road_class, oneway, source, tags)
SELECT ST_SetSRID(g.geom, 0),
       greatest(1, coalesce(nullif(g.lanes, '')::int, 1)) * CASE WHEN g.oneway = 'true' THEN 1 ELSE 2 END
         * CASE g.type WHEN 'highway' THEN 3.5 WHEN 'avenue' THEN 3.25 ELSE 3.0 END,
       least(20, greatest(1, coalesce(nullif(g.lanes, '')::int, 1)) * CASE WHEN g.oneway = 'true' THEN 1 ELSE 2 END),
       CASE g.type WHEN 'highway' THEN 90 WHEN 'avenue' THEN 50 ELSE 30 END,
       coalesce(g.type, 'street'),
       g.oneway = 'true',
       'example:' || g.src || '-' || g.tgt,
       jsonb_build_object('type', g.type, 'lanes', g.lanes, 'oneway', g.oneway)
  FROM (SELECT (ST_Dump(geom)).geom AS geom, type::text, lanes::text, oneway::text, src::text, tgt::text
          FROM :staging) AS g
 WHERE ST_Length(g.geom) > 0;
