// The scene's plan tiles: loaded as <script> files (view/tile_X_Y.js, which call RELIEF_TILE)
// when they come into the camera's view, nearest first, two at a time; the farthest dropped when
// the loaded triangles pass the budget.
import * as THREE from 'three';
import { decodeLayer } from './decode.js';

export class TileSet {
  constructor(index, onTile, { budgetTriangles = 6e6, concurrent = 2 } = {}) {
    this.onTile = onTile;
    this.base = window.RELIEF_VIEW_BASE || 'view';
    this.budget = budgetTriangles;
    this.concurrent = concurrent;
    this.loading = 0;
    this.loadedTriangles = 0;
    this.failed = [];
    this.tiles = index.tiles.map((t) => ({
      ...t,
      key: `${t.x}_${t.y}`,
      state: 'absent',
      // three.js axes: (x, z, -y).
      box: new THREE.Box3(
        new THREE.Vector3(t.bounds[0], t.z[0], -t.bounds[3]),
        new THREE.Vector3(t.bounds[2], t.z[1], -t.bounds[1]),
      ),
      objects: [],
    }));
    this.byKey = new Map(this.tiles.map((t) => [t.key, t]));
    window.RELIEF_TILE = (raw) => this.receive(raw);
  }

  /// Tiles in the camera's frustum that are not loaded yet, nearest first.
  wanted(camera, frustum) {
    const eye = camera.position;
    return this.tiles
      .filter((t) => t.state === 'absent' && frustum.intersectsBox(t.box))
      .map((t) => ({ t, d: t.box.distanceToPoint(eye) }))
      .sort((a, b) => a.d - b.d)
      .map((e) => e.t);
  }

  /// Starts loading what the camera sees; returns true when everything in view is loaded.
  update(camera) {
    const frustum = new THREE.Frustum().setFromProjectionMatrix(
      new THREE.Matrix4().multiplyMatrices(camera.projectionMatrix, camera.matrixWorldInverse),
    );
    const wanted = this.wanted(camera, frustum);
    for (const t of wanted) {
      if (this.loading >= this.concurrent) break;
      this.load(t);
    }
    if (this.loadedTriangles > this.budget) this.evict(camera, frustum);
    return wanted.length === 0 && this.loading === 0;
  }

  load(tile) {
    tile.state = 'loading';
    this.loading++;
    const script = document.createElement('script');
    script.src = `${this.base}/${tile.file}`;
    script.onerror = () => {
      tile.state = 'failed';
      this.loading--;
      this.failed.push(tile.file);
      console.error(`relief view: cannot load ${this.base}/${tile.file}`);
      script.remove();
      this.onTile(null);
    };
    script.onload = () => script.remove();
    document.head.appendChild(script);
  }

  receive(raw) {
    const tile = this.byKey.get(`${raw.x}_${raw.y}`);
    if (!tile || tile.state !== 'loading') return;
    this.loading--;
    tile.state = 'loaded';
    tile.layers = raw.layers.map(decodeLayer);
    this.loadedTriangles += tile.triangles;
    this.onTile(tile);
  }

  /// Drops the farthest loaded tiles outside the view until the budget holds.
  evict(camera, frustum) {
    const loaded = this.tiles
      .filter((t) => t.state === 'loaded' && !frustum.intersectsBox(t.box))
      .sort((a, b) => b.box.distanceToPoint(camera.position) - a.box.distanceToPoint(camera.position));
    for (const t of loaded) {
      if (this.loadedTriangles <= this.budget) break;
      for (const o of t.objects) {
        o.parent?.remove(o);
        o.geometry.dispose();
      }
      t.objects = [];
      t.layers = null;
      t.state = 'absent';
      this.loadedTriangles -= t.triangles;
    }
  }

  loaded() {
    return this.tiles.filter((t) => t.state === 'loaded');
  }
}
