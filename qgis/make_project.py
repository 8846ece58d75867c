#!/usr/bin/env python3
"""Write a QGIS project (.qgs) showing one streetgen model.

    QT_QPA_PLATFORM=offscreen /usr/bin/python3 qgis/make_project.py CONNINFO MODEL [OUT.qgs]

(the Python that has PyQGIS: on Debian, the system one with python3-qgis).

CONNINFO is a libpq connection string as QGIS stores it, e.g. "service=streetgen" (shareable: each
user's pg_service.conf says where the database is) or "dbname=city host=localhost port=5432
user=me". No password is written. OUT defaults to MODEL.qgs.

The project is generated with PyQGIS rather than shipped as a template so that it always matches
the QGIS that reads it and the model's CRS. Every layer repaints on NOTIFY qgis, 'MODEL', which
the model's triggers send when an axis edit commits: edit the axis layer, save, and the surfaces,
lanes and markings follow.
"""
import sys

from qgis.core import (QgsApplication, QgsCategorizedSymbolRenderer, QgsDataSourceUri, QgsFillSymbol,
                       QgsLineSymbol, QgsMarkerSymbol, QgsProject, QgsRendererCategory, QgsSingleSymbolRenderer,
                       QgsVectorLayer)

# (table, geometry column, key), drawn top first. corner, section, lane and marking have composite
# primary keys, which QGIS takes as a quoted list.
LAYERS = [
    ('node', 'geom', 'id'),
    ('axis', 'geom', 'id'),
    ('corner', 'arc_segmentized', '"node_id","axis_a","part_a","end_a","axis_b","part_b","end_b"'),
    ('marking', 'geom', '"axis_id","part","kind","position"'),
    ('lane', 'geom', '"axis_id","part","lane_index"'),
    ('intersection', 'geom', 'node_id'),
    ('section', 'geom', '"axis_id","part"'),
]


def renderer(table):
    """Lanes by type (driving grey, bus red, cycle green); markings white, in metres on the map:
    lines 0.15 m, solid or dashed by style, stop lines 0.5 m."""
    if table == 'lane':
        colours = {'driving': '#b0b0b0', 'bus': '#d9837a', 'cycle': '#7fbf7f'}
        return QgsCategorizedSymbolRenderer('type', [
            QgsRendererCategory(t, QgsFillSymbol.createSimple({'color': c, 'outline_style': 'no'}), t)
            for t, c in colours.items()])
    if table == 'marking':
        def line(width, style):
            return QgsLineSymbol.createSimple({'line_color': '#ffffff', 'line_width': str(width),
                                               'line_width_unit': 'MapUnit', 'line_style': style})
        return QgsCategorizedSymbolRenderer('kind || \' \' || style', [
            QgsRendererCategory('centre_line solid', line(0.15, 'solid'), 'centre line'),
            QgsRendererCategory('centre_line dashed', line(0.15, 'dash'), 'centre line (dashed)'),
            QgsRendererCategory('lane_separator solid', line(0.15, 'solid'), 'lane line'),
            QgsRendererCategory('lane_separator dashed', line(0.15, 'dash'), 'lane line (dashed)'),
            QgsRendererCategory('stop_line solid', line(0.5, 'solid'), 'stop line')])
    return QgsSingleSymbolRenderer(symbol(table))


def symbol(table):
    """Grey surfaces (junctions a little darker), dark axes and nodes, red curb arcs."""
    if table == 'node':
        return QgsMarkerSymbol.createSimple({'name': 'circle', 'color': '#303030', 'size': '1.2',
                                             'outline_style': 'no'})
    if table == 'axis':
        return QgsLineSymbol.createSimple({'line_color': '#303030', 'line_width': '0.3'})
    if table == 'corner':
        return QgsLineSymbol.createSimple({'line_color': '#e31a1c', 'line_width': '0.4'})
    grey = '#a0a0a0' if table == 'intersection' else '#c0c0c0'
    return QgsFillSymbol.createSimple({'color': grey, 'outline_style': 'no'})


def make_project(conninfo, model, out):
    """Writes the project; returns the names of the layers QGIS could not open (then writes nothing)."""
    project = QgsProject()
    layers = []
    for table, geom, key in LAYERS:
        uri = QgsDataSourceUri(conninfo)
        uri.setDataSource(model, table, geom, '', key)
        layer = QgsVectorLayer(uri.uri(False), f'{model} {table}', 'postgres')
        layer.setRenderer(renderer(table))
        # The message filter keeps the layers of other models in the same database still.
        layer.setRefreshOnNotifyEnabled(True)
        layer.setRefreshOnNofifyMessage(model)  # sic: the QGIS 3 API spells it so
        layers.append(layer)
    bad = [layer.name() for layer in layers if not layer.isValid()]
    if bad:
        return bad
    project.addMapLayers(layers)
    project.setCrs(layers[1].crs())
    if not project.write(out):
        raise RuntimeError(f'cannot write {out}: {project.error()}')
    return []


if __name__ == '__main__':
    if len(sys.argv) not in (3, 4):
        sys.exit(__doc__)
    conninfo, model = sys.argv[1], sys.argv[2]
    out = sys.argv[3] if len(sys.argv) == 4 else f'{model}.qgs'
    app = QgsApplication([], False)
    app.initQgis()
    bad = make_project(conninfo, model, out)
    print(f'make_project: cannot open {", ".join(bad)}' if bad else f'make_project: wrote {out}')
    app.exitQgis()
    sys.exit(1 if bad else 0)
