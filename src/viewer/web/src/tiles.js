// The scene's plan tiles: loaded as <script> files (view/tile_X_Y.js, which call RELIEF_TILE)
// when they come into the camera's view, nearest first, two at a time. Big tiles have a coarse
// copy (tile_X_Y_lod.js) drawn while the camera is farther than FULL_NEAR tile sizes from them;
// the full tile loads nearer, replaces the copy, and is dropped again beyond three times that.
// A tile's marks come in a file of their own (tile_X_Y_marks.js), loaded only within
// MARKS_NEAR_M of the camera (afar a mark is under a pixel wide) and dropped beyond twice that;
// past the triangle budget the farthest tiles out of view are dropped.
import * as THREE from 'three';
import { decodeLayer } from './decode.js';

const MARKS_NEAR_M = 600;
const FULL_NEAR = 1.0;  // tile sizes

export class TileSet {
  constructor(index, onPart, { budgetTriangles = 6e6, concurrent = 2 } = {}) {
    this.onPart = onPart;
    this.base = window.RELIEF_VIEW_BASE || 'view';
    this.budget = budgetTriangles;
    this.concurrent = concurrent;
    this.fullNear = FULL_NEAR * (index.tile_size_m || 0);
    this.loading = 0;
    this.loadedTriangles = 0;
    this.failed = [];
    this.tiles = index.tiles.map((t) => {
      const tile = {
        ...t,
        key: `${t.x}_${t.y}`,
        // three.js axes: (x, z, -y).
        box: new THREE.Box3(
          new THREE.Vector3(t.bounds[0], t.z[0], -t.bounds[3]),
          new THREE.Vector3(t.bounds[2], t.z[1], -t.bounds[1]),
        ),
      };
      tile.parts = { base: { tile, kind: 'base', file: t.file, triangles: t.triangles, state: 'absent', objects: [] } };
      if (t.lod_file)
        tile.parts.lod = { tile, kind: 'lod', file: t.lod_file, triangles: t.lod_triangles, state: 'absent', objects: [] };
      if (t.marks_file)
        tile.parts.marks = { tile, kind: 'marks', file: t.marks_file, triangles: t.marks_triangles, state: 'absent', objects: [] };
      return tile;
    });
    this.byKey = new Map(this.tiles.map((t) => [t.key, t]));
    window.RELIEF_TILE = (raw) => this.receive(raw);
  }

  /// Parts to load for this view, nearest first.
  wanted(camera, frustum) {
    const eye = camera.position;
    const out = [];
    for (const t of this.tiles) {
      if (!frustum.intersectsBox(t.box)) continue;
      const d = t.box.distanceToPoint(eye);
      const lod = t.parts.lod;
      if (lod && d > this.fullNear) {
        if (lod.state === 'absent' && t.parts.base.state !== 'loaded') out.push({ part: lod, d });
      } else if (t.parts.base.state === 'absent') out.push({ part: t.parts.base, d });
      else if (t.parts.marks && t.parts.marks.state === 'absent' && t.parts.base.state === 'loaded' && d < MARKS_NEAR_M)
        out.push({ part: t.parts.marks, d: d + 1 });
    }
    return out.sort((a, b) => a.d - b.d).map((e) => e.part);
  }

  /// Starts loading what the camera sees; returns true when everything in view is loaded.
  update(camera) {
    const frustum = new THREE.Frustum().setFromProjectionMatrix(
      new THREE.Matrix4().multiplyMatrices(camera.projectionMatrix, camera.matrixWorldInverse),
    );
    const wanted = this.wanted(camera, frustum);
    for (const part of wanted) {
      if (this.loading >= this.concurrent) break;
      this.load(part);
    }
    for (const t of this.tiles) {
      const d = t.box.distanceToPoint(camera.position);
      if (t.parts.marks && t.parts.marks.state === 'loaded' && d > 2 * MARKS_NEAR_M) this.drop(t.parts.marks);
      const lod = t.parts.lod;
      if (lod && lod.state === 'loaded' && t.parts.base.state === 'loaded' && d > 3 * this.fullNear) this.drop(t.parts.base);
      // The coarse copy shows while its full tile is not there.
      if (lod) for (const o of lod.objects) o.visible = t.parts.base.state !== 'loaded';
    }
    if (this.loadedTriangles > this.budget) this.evict(camera, frustum);
    return wanted.length === 0 && this.loading === 0;
  }

  load(part) {
    part.state = 'loading';
    this.loading++;
    const script = document.createElement('script');
    script.src = `${this.base}/${part.file}`;
    script.onerror = () => {
      part.state = 'failed';
      this.loading--;
      this.failed.push(part.file);
      console.error(`relief view: cannot load ${this.base}/${part.file}`);
      script.remove();
      this.onPart(null);
    };
    script.onload = () => script.remove();
    document.head.appendChild(script);
  }

  receive(raw) {
    const tile = this.byKey.get(`${raw.x}_${raw.y}`);
    const part = tile && tile.parts[raw.part || 'base'];
    if (!part || part.state !== 'loading') return;
    this.loading--;
    part.state = 'loaded';
    this.loadedTriangles += part.triangles;
    this.onPart(part, raw.layers.map(decodeLayer));
  }

  drop(part) {
    for (const o of part.objects) {
      o.parent?.remove(o);
      o.geometry.dispose();
    }
    part.objects = [];
    part.state = 'absent';
    this.loadedTriangles -= part.triangles;
  }

  /// Drops the farthest loaded tiles outside the view until the budget holds.
  evict(camera, frustum) {
    const loaded = this.tiles
      .filter((t) => !frustum.intersectsBox(t.box))
      .sort((a, b) => b.box.distanceToPoint(camera.position) - a.box.distanceToPoint(camera.position));
    for (const t of loaded) {
      if (this.loadedTriangles <= this.budget) break;
      for (const part of Object.values(t.parts)) if (part.state === 'loaded') this.drop(part);
    }
  }

  /// Tiles drawn, in full or as their coarse copy.
  loaded() {
    return this.tiles.filter((t) => t.parts.base.state === 'loaded' || (t.parts.lod && t.parts.lod.state === 'loaded'));
  }
}
