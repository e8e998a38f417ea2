// Colour ramps of the roads: by grade (percent) and by height over the DEM (metres).

const GRADE_STOPS = [
  [0, [26, 152, 80]],
  [5, [145, 207, 96]],
  [10, [254, 224, 139]],
  [15, [252, 141, 89]],
  [20, [215, 48, 39]],
  [30, [123, 50, 148]],
];
const DEM_STOPS = [
  [-10, [33, 102, 172]],
  [-2, [146, 197, 222]],
  [0, [247, 247, 247]],
  [2, [244, 165, 130]],
  [10, [178, 24, 43]],
];
const NO_VALUE = [150, 150, 150];

// Vertex colours are in three.js's linear working space: the ramps are sRGB, converted here
// (else they come out washed out through the sRGB output).
const TO_LINEAR = Array.from({ length: 256 }, (_, i) => {
  const v = i / 255;
  return Math.round(255 * (v <= 0.04045 ? v / 12.92 : ((v + 0.055) / 1.055) ** 2.4));
});

function ramp(stops, v) {
  if (!Number.isFinite(v)) return NO_VALUE;
  if (v <= stops[0][0]) return stops[0][1];
  for (let i = 1; i < stops.length; i++) {
    const [v1, c1] = stops[i];
    if (v <= v1) {
      const [v0, c0] = stops[i - 1];
      const f = (v - v0) / (v1 - v0);
      return [0, 1, 2].map((k) => Math.round(c0[k] + f * (c1[k] - c0[k])));
    }
  }
  return stops[stops.length - 1][1];
}

export const MODES = {
  grade: { label: 'grade %', stops: GRADE_STOPS, value: (layer, i) => layer.grade[i] },
  dem: { label: 'height over the DEM, m', stops: DEM_STOPS, value: (layer, i) => layer.dz[i] },
};

/// Writes the colours of every vertex of `layer` into `out` (Uint8, rgb), the selected owner in cyan.
export function colourLayer(layer, mode, selectedOwner, out) {
  const m = MODES[mode];
  for (let i = 0; i < layer.vertices; i++) {
    const c = layer.owner[i] === selectedOwner && selectedOwner >= 0 ? [0, 229, 255] : ramp(m.stops, m.value(layer, i));
    out[3 * i] = TO_LINEAR[c[0]];
    out[3 * i + 1] = TO_LINEAR[c[1]];
    out[3 * i + 2] = TO_LINEAR[c[2]];
  }
}

/// Terrain: a muted hypsometric tint between the scene's lowest and highest ground.
export function colourTerrain(positions, zMin, zMax, out) {
  const low = [120, 150, 100];
  const high = [190, 175, 150];
  const span = Math.max(1, zMax - zMin);
  for (let i = 0, n = positions.length / 3; i < n; i++) {
    const f = Math.min(1, Math.max(0, (positions[3 * i + 1] - zMin) / span));
    for (let k = 0; k < 3; k++) out[3 * i + k] = TO_LINEAR[Math.round(low[k] + f * (high[k] - low[k]))];
  }
}

/// The legend of a mode as HTML: a bar of the stops and their values.
export function legendHtml(mode) {
  const m = MODES[mode];
  const bar = m.stops.map(([, c]) => `<span style="flex:1;background:rgb(${c.join(',')})"></span>`).join('');
  const labels = m.stops.map(([v]) => `<span>${v}</span>`).join('');
  return `<div style="display:flex;height:12px">${bar}</div><div id="legend-labels">${labels}</div><div class="hint">${m.label}</div>`;
}
