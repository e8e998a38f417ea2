// A road's elevation profile as SVG: the DEM drape, the seed paper's smoothing and relief's fit.

export const SERIES = [
  { key: 'raw', label: 'DEM drape', colour: '#999999', width: 1 },
  { key: 'paper', label: 'paper', colour: '#e6851e', width: 1.2 },
  { key: 'fit', label: 'relief fit', colour: '#1f5fbf', width: 1.8 },
];

const escape = (t) => String(t).replace(/[&<>"]/g, (c) => ({ '&': '&amp;', '<': '&lt;', '>': '&gt;', '"': '&quot;' })[c]);

/// `range`: [s0, s1] of the piece clicked, shaded (optional).
export function profileSvg(profile, range) {
  const W = 340, H = 170, L = 40, R = 8, T = 8, B = 24;
  const s = profile.s;
  const series = SERIES.filter((k) => Array.isArray(profile[k.key]));
  let zMin = Infinity, zMax = -Infinity;
  for (const k of series)
    for (const z of profile[k.key])
      if (z !== null) {
        zMin = Math.min(zMin, z);
        zMax = Math.max(zMax, z);
      }
  if (!(zMax >= zMin) || s.length < 2) return '<p class="hint">no profile</p>';
  if (zMax - zMin < 2) {
    const mid = (zMax + zMin) / 2;
    zMin = mid - 1;
    zMax = mid + 1;
  }
  const sMax = s[s.length - 1] || 1;
  const x = (v) => (L + (v / sMax) * (W - L - R)).toFixed(1);
  const y = (z) => (T + (1 - (z - zMin) / (zMax - zMin)) * (H - T - B)).toFixed(1);
  const lines = series.map((k) => {
    let d = '';
    profile[k.key].forEach((z, i) => {
      if (z === null) return;
      d += `${d ? 'L' : 'M'}${x(s[i])},${y(z)}`;
    });
    return `<path class="series" data-series="${k.key}" d="${d}" fill="none" stroke="${k.colour}" stroke-width="${k.width}"/>`;
  });
  const band =
    Array.isArray(range) && range[1] > range[0]
      ? `<rect class="piece" x="${x(range[0])}" y="${T}" width="${(x(range[1]) - x(range[0])).toFixed(1)}" height="${H - T - B}" fill="#00e5ff" fill-opacity="0.15"/>`
      : '';
  const axis = [
    `<line x1="${L}" y1="${H - B}" x2="${W - R}" y2="${H - B}" stroke="#888"/>`,
    `<line x1="${L}" y1="${T}" x2="${L}" y2="${H - B}" stroke="#888"/>`,
    `<text x="${L - 3}" y="${T + 8}" font-size="10" text-anchor="end">${zMax.toFixed(0)}</text>`,
    `<text x="${L - 3}" y="${H - B}" font-size="10" text-anchor="end">${zMin.toFixed(0)}</text>`,
    `<text x="${W - R}" y="${H - 6}" font-size="10" text-anchor="end">${sMax.toFixed(0)} m</text>`,
    `<text x="${L}" y="${H - 6}" font-size="10">0</text>`,
  ];
  const key = series
    .map((k) => `<span class="swatch" style="background:${k.colour}"></span>${escape(k.label)}`)
    .join('');
  return `<svg viewBox="0 0 ${W} ${H}" role="img" aria-label="elevation profile">${band}${axis.join('')}${lines.join('')}</svg><div>${key}${band ? '<span class="swatch" style="background:#00e5ff;opacity:.4;height:8px"></span>this road' : ''}</div>`;
}

export { escape };
