// A co-simulation's replay (relief cosim writes replay.js beside its view.html): every vehicle
// as a box of its size, posed between its keys (linear position, shortest-way heading, pitch
// and roll), shown from its first key until it leaves.
import * as THREE from 'three';
import { bytes } from './decode.js';

const FIELDS = 7;  // t, x, y, z, heading, pitch, roll (local frame, radians)

export class Replay {
  constructor(raw, scene) {
    this.end = raw.end_s;
    this.vehicles = raw.vehicles.map((v) => ({ ...v, keys: new Float32Array(bytes(v.keys)) }));
    const box = new THREE.BoxGeometry(1, 1, 1).translate(0, 0.5, 0);
    this.mesh = new THREE.InstancedMesh(box, new THREE.MeshLambertMaterial({ color: 0x2050d0 }), this.vehicles.length);
    this.mesh.name = 'replay';
    this.mesh.frustumCulled = false;
    scene.add(this.mesh);
    this.time = 0;
    this.shown = 0;
    this.setTime(0);
  }

  /// Poses every vehicle at time t (seconds); returns how many are on the road.
  setTime(t) {
    this.time = Math.max(0, Math.min(this.end, t));
    const m = new THREE.Matrix4(), q = new THREE.Quaternion(), e = new THREE.Euler(0, 0, 0, 'YZX');
    const p = new THREE.Vector3(), s = new THREE.Vector3();
    let shown = 0;
    this.vehicles.forEach((v, i) => {
      const k = v.keys, n = k.length / FIELDS;
      if (n === 0 || this.time < k[0] || this.time > v.hide_s) {
        this.mesh.setMatrixAt(i, m.makeScale(0, 0, 0));
        return;
      }
      // The last key at or before t (binary search), and the next one.
      let lo = 0, hi = n - 1;
      while (lo < hi) {
        const mid = (lo + hi + 1) >> 1;
        if (k[mid * FIELDS] <= this.time) lo = mid;
        else hi = mid - 1;
      }
      const a = lo * FIELDS, b = Math.min(lo + 1, n - 1) * FIELDS;
      const f = b > a ? Math.min(1, (this.time - k[a]) / (k[b] - k[a])) : 0;
      const lerp = (j) => k[a + j] + f * (k[b + j] - k[a + j]);
      let dh = k[b + 4] - k[a + 4];
      dh -= 2 * Math.PI * Math.round(dh / (2 * Math.PI));
      const heading = k[a + 4] + f * dh;
      // three.js axes (x, z, -y): heading about +y (counter-clockwise from +x seen from above),
      // pitch nose up about the body's lateral axis, roll right side down about its length.
      e.set(lerp(6), heading, lerp(5), 'YZX');
      q.setFromEuler(e);
      p.set(lerp(1), lerp(3), -lerp(2));
      s.set(v.size[0], v.size[2], v.size[1]);
      this.mesh.setMatrixAt(i, m.compose(p, q, s));
      shown++;
    });
    this.mesh.instanceMatrix.needsUpdate = true;
    this.shown = shown;
    return shown;
  }
}
