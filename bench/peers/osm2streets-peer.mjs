// The osm2streets peer process: OSM XML -> osm2streets (Rust compiled to wasm,
// npm osm2streets-js) -> its own GeoJSON exports, written unchanged.
// Usage: node osm2streets-peer.mjs INPUT.osm OUT_PREFIX
// Writes OUT_PREFIX.plain.geojson (toGeojsonPlain: road + intersection polygons),
// OUT_PREFIX.lanes.geojson (toLanePolygonsGeojson), OUT_PREFIX.tags.json
// (highway tag of every OSM way used by a road) and OUT_PREFIX.stats.json.
// osm2streets logs with console.log, so stdout is only a log.
import fs from 'fs';
import {JsStreetNetwork, initSync} from './node_modules/osm2streets-js/osm2streets_js.js';

const [input, prefix] = process.argv.slice(2);
if (!input || !prefix) { console.error('usage: node osm2streets-peer.mjs INPUT.osm OUT_PREFIX'); process.exit(2); }
const now = () => Number(process.hrtime.bigint()) / 1e9;
const t0 = now();
initSync(fs.readFileSync(new URL('./node_modules/osm2streets-js/osm2streets_js_bg.wasm', import.meta.url)));
const xml = fs.readFileSync(input, 'utf8');
const t1 = now();
// Options as in the osm2streets Street Explorer defaults.
const options = {
  debug_each_step: false,
  dual_carriageway_experiment: false,
  cycletrack_snapping_experiment: false,
  inferred_sidewalks: true,
  osm2lanes: false,
};
const net = new JsStreetNetwork(xml, '', options);   // '' = no clip polygon: <bounds> or the data's extent
const t2 = now();
const plain = net.toGeojsonPlain();
const lanes = net.toLanePolygonsGeojson();
const t3 = now();
const tags = {};
for (const f of JSON.parse(plain).features) {
  if (f.properties.type !== 'road') continue;
  for (const id of f.properties.osm_way_ids) {
    if (id in tags) continue;
    try { tags[id] = JSON.parse(net.getOsmTagsForWay(BigInt(id))).highway ?? null; } catch { tags[id] = null; }
  }
}
const t4 = now();
fs.writeFileSync(prefix + '.plain.geojson', plain);
fs.writeFileSync(prefix + '.lanes.geojson', lanes);
fs.writeFileSync(prefix + '.tags.json', JSON.stringify(tags));
fs.writeFileSync(prefix + '.stats.json', JSON.stringify({
  load_s: t1 - t0, import_s: t2 - t1, export_s: t3 - t2, tags_s: t4 - t3, write_s: now() - t4,
}));
