// Typed arrays from the base64 text of view/tile_X_Y.js (little-endian, as relief writes them).

export function bytes(b64) {
  const s = atob(b64);
  const out = new Uint8Array(s.length);
  for (let i = 0; i < s.length; i++) out[i] = s.charCodeAt(i);
  return out.buffer;
}

export function decodeLayer(raw) {
  const layer = {
    name: raw.layer,
    vertices: raw.vertices,
    triangles: raw.triangles,
    positions: new Float32Array(bytes(raw.positions)),
    indices: new Uint32Array(bytes(raw.indices)),
  };
  if (raw.owner) {
    layer.owner = new Int32Array(bytes(raw.owner));
    layer.grade = new Float32Array(bytes(raw.grade));
    layer.dz = new Float32Array(bytes(raw.dz));
  }
  if (layer.positions.length !== 3 * layer.vertices || layer.indices.length !== 3 * layer.triangles)
    throw new Error(`tile layer ${raw.layer}: array sizes do not match its counts`);
  return layer;
}
