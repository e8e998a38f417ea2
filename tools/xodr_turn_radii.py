#!/usr/bin/env python3
"""Counts the connecting roads of an OpenDRIVE file by their tightest radius in plan (arcs and
spirals exactly, paramPoly3 sampled at 200 parameters): how many are under 2, 3, 4, 5, 6 and 8 m,
and the eight tightest (radius, road, junction, length).

    python3 tools/xodr_turn_radii.py out/NAME.xodr
"""
import math
import sys
import xml.etree.ElementTree as ET

BANDS = [2, 3, 4, 5, 6, 8]


def param_poly3_curvature(geometry):
    p = geometry.find('paramPoly3')
    c = {k: float(p.get(k)) for k in ['bU', 'cU', 'dU', 'bV', 'cV', 'dV']}
    top = 1.0 if p.get('pRange', 'normalized') == 'normalized' else float(geometry.get('length'))
    worst = 0.0
    for i in range(200):
        t = top * i / 199
        du, dv = c['bU'] + 2 * c['cU'] * t + 3 * c['dU'] * t * t, c['bV'] + 2 * c['cV'] * t + 3 * c['dV'] * t * t
        ddu, ddv = 2 * c['cU'] + 6 * c['dU'] * t, 2 * c['cV'] + 6 * c['dV'] * t
        worst = max(worst, abs(du * ddv - dv * ddu) / max((du * du + dv * dv) ** 1.5, 1e-12))
    return worst


def main(path):
    rows = []
    for road in ET.parse(path).getroot().findall('road'):
        if road.get('junction', '-1') == '-1':
            continue
        curvature = 0.0
        for g in road.find('planView').findall('geometry'):
            kind = g[0]
            if kind.tag == 'arc':
                curvature = max(curvature, abs(float(kind.get('curvature'))))
            elif kind.tag == 'spiral':
                curvature = max(curvature, abs(float(kind.get('curvStart'))), abs(float(kind.get('curvEnd'))))
            elif kind.tag == 'paramPoly3':
                curvature = max(curvature, param_poly3_curvature(g))
        rows.append((1.0 / curvature if curvature > 0 else math.inf, road.get('id'), road.get('junction'),
                     float(road.get('length'))))
    rows.sort()
    print('%d connecting roads; ' % len(rows) + ' '.join('R<%g:%d' % (b, sum(r[0] < b for r in rows)) for b in BANDS))
    for r in rows[:8]:
        print('  R=%.2f road %s junction %s length %.2f' % r)


if __name__ == '__main__':
    main(sys.argv[1])
