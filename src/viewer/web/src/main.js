// relief's view.html: the scene of a build in three.js, roads coloured by grade or by height
// over the DEM, a road's attributes and profile on click, the findings marked and listed.
// Renders on demand (after a change), so an idle page costs nothing.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { TileSet } from './tiles.js';
import { colourLayer, colourTerrain, legendHtml } from './colors.js';
import { profileSvg, escape } from './profile.js';
import { Replay } from './replay.js';

const KIND_COLOURS = {
  gate: '#aa0000',
  self_intersection: '#e7298a',
  hole: '#7570b3',
  junction_open: '#d95f02',
  sight: '#1b9e77',
};
const PAVED = new Set(['road', 'structure', 'sidewalk']);

function main() {
  const data = window.RELIEF_VIEW;
  const status = document.getElementById('status');
  if (!data) {
    status.textContent = 'view/index.js is missing: open view.html inside the build folder';
    throw new Error('relief view: window.RELIEF_VIEW is not defined (view/index.js not loaded)');
  }
  const canvas = document.getElementById('view');
  const stage = document.getElementById('stage');
  const renderer = new THREE.WebGLRenderer({ canvas, antialias: true });
  renderer.setPixelRatio(window.devicePixelRatio);
  const background = new THREE.Color(0xcfd8e3);
  renderer.setClearColor(background);
  const scene = new THREE.Scene();
  scene.add(new THREE.HemisphereLight(0xffffff, 0x667755, 1.6));
  const sun = new THREE.DirectionalLight(0xffffff, 1.6);
  sun.position.set(-0.5, 1, 0.3);
  scene.add(sun);

  // The whole scene's box, from the tiles' bounds.
  const all = new THREE.Box3();
  for (const t of data.tiles)
    all.union(
      new THREE.Box3(new THREE.Vector3(t.bounds[0], t.z[0], -t.bounds[3]), new THREE.Vector3(t.bounds[2], t.z[1], -t.bounds[1])),
    );
  const size = all.isEmpty() ? 100 : Math.max(50, all.getSize(new THREE.Vector3()).length());
  const centre = all.isEmpty() ? new THREE.Vector3() : all.getCenter(new THREE.Vector3());
  const camera = new THREE.PerspectiveCamera(45, 1, size / 1e4, size * 20);
  camera.position.copy(centre).add(new THREE.Vector3(0, size * 0.55, size * 0.6));
  const controls = new OrbitControls(camera, canvas);
  controls.target.copy(centre);
  controls.screenSpacePanning = false;
  controls.maxPolarAngle = Math.PI * 0.495;
  controls.update();

  const state = { mode: 'grade', selected: null };
  const groups = {};
  for (const name of ['road', 'structure', 'sidewalk', 'marking', 'terrain', 'other']) {
    groups[name] = new THREE.Group();
    groups[name].name = name;
    scene.add(groups[name]);
  }
  const materials = {
    paved: new THREE.MeshLambertMaterial({ vertexColors: true, side: THREE.DoubleSide }),
    marking: new THREE.MeshLambertMaterial({ color: 0xf4f4f4, polygonOffset: true, polygonOffsetFactor: -2, polygonOffsetUnits: -2 }),
    terrain: new THREE.MeshLambertMaterial({ vertexColors: true, polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1 }),
    other: new THREE.MeshLambertMaterial({ color: 0xbbbbbb }),
  };

  let pending = false;
  const render = () => {
    pending = false;
    // The near plane follows the distance to what is looked at: centimetres close up, metres afar.
    camera.near = Math.max(0.05, camera.position.distanceTo(controls.target) / 2000);
    camera.updateProjectionMatrix();
    renderer.render(scene, camera);
  };
  const requestRender = () => {
    if (!pending) {
      pending = true;
      requestAnimationFrame(() => {
        render();
        refreshTiles();
      });
    }
  };

  const paint = (mesh) => {
    const layer = mesh.userData.layer;
    const colours = mesh.geometry.getAttribute('color');
    colourLayer(layer, state.mode, state.selected === null ? -1 : data.owners.indexOf(state.selected), colours.array);
    colours.needsUpdate = true;
  };
  const tiles = new TileSet(data, (part, layers) => {
    if (part) {
      for (const layer of layers) {
        const g = new THREE.BufferGeometry();
        g.setAttribute('position', new THREE.BufferAttribute(layer.positions, 3));
        g.setIndex(new THREE.BufferAttribute(layer.indices, 1));
        let material = materials.other;
        if (PAVED.has(layer.name) && layer.owner) {
          g.setAttribute('color', new THREE.BufferAttribute(new Uint8Array(3 * layer.vertices), 3, true));
          material = materials.paved;
        } else if (layer.name === 'terrain') {
          const c = new Uint8Array(3 * layer.vertices);
          colourTerrain(layer.positions, all.min.y, all.max.y, c);
          g.setAttribute('color', new THREE.BufferAttribute(c, 3, true));
          material = materials.terrain;
        } else if (layer.name === 'marking') {
          material = materials.marking;
        }
        g.computeVertexNormals();
        g.computeBoundingSphere();
        const mesh = new THREE.Mesh(g, material);
        mesh.name = `${layer.name} ${part.tile.key}`;
        mesh.userData = { layer, tile: part.tile.key };
        if (layer.owner) paint(mesh);
        (groups[layer.name] || groups.other).add(mesh);
        part.objects.push(mesh);
      }
    }
    // Ask for the next tiles now, not after the next frame: in software rendering a frame of a
    // city takes a second or more, and the loads would wait for each.
    refreshTiles();
    requestRender();
  });

  // Findings: a marker of constant size at each placed one (defects larger than the many sight
  // deficits, drawn over them), and the list.
  const placed = data.findings.filter((f) => Array.isArray(f.at));
  const markers = new THREE.Group();
  markers.name = 'findings';
  for (const [sight, size] of [[true, 6], [false, 11]]) {
    const some = placed.filter((f) => (f.kind === 'sight') === sight);
    const g = new THREE.BufferGeometry();
    g.setAttribute('position', new THREE.Float32BufferAttribute(some.flatMap((f) => [f.at[0], f.at[2] + 1.0, -f.at[1]]), 3));
    g.setAttribute(
      'color',
      new THREE.Float32BufferAttribute(some.flatMap((f) => new THREE.Color(KIND_COLOURS[f.kind] || '#000').toArray()), 3),
    );
    const points = new THREE.Points(g, new THREE.PointsMaterial({ size, sizeAttenuation: false, vertexColors: true, depthTest: false }));
    points.renderOrder = sight ? 10 : 11;
    markers.add(points);
  }
  scene.add(markers);
  const list = document.getElementById('finding-list');
  list.innerHTML = data.findings.length
    ? data.findings
        .map(
          (f, i) =>
            `<li data-i="${i}" class="${f.at ? '' : 'unplaced'}"><span class="kind" style="background:${KIND_COLOURS[f.kind] || '#000'}"></span>${escape(f.text)}</li>`,
        )
        .join('')
    : '<li class="unplaced">none: every gate passed and no finding has a place</li>';
  list.addEventListener('click', (e) => {
    const li = e.target.closest('li[data-i]');
    const f = li && data.findings[Number(li.dataset.i)];
    if (f && f.at) focus(f.at[0], f.at[1], f.at[2], 80);
    if (f && f.road) select(f.road);
  });

  function focus(x, y, z, distance) {
    api.ready = false;  // until the tiles of the new view are in
    const target = new THREE.Vector3(x, z, -y);
    const offset = camera.position.clone().sub(controls.target).setLength(distance);
    controls.target.copy(target);
    camera.position.copy(target).add(offset);
    controls.update();
    requestRender();
  }

  // Selection: a road's attributes and profile, or a junction's.
  const info = document.getElementById('info');
  function select(owner) {
    state.selected = owner;
    for (const name of ['road', 'structure', 'sidewalk']) for (const m of groups[name].children) paint(m);
    info.dataset.owner = owner === null ? '' : String(owner);
    if (owner === null) {
      info.innerHTML = '';
    } else if (owner < 0) {
      const id = -1 - owner;
      const j = data.junctions[String(id)] || {};
      info.innerHTML = `<h2>junction ${id}</h2><table><tr><td>name</td><td>${escape(j.name || '')}</td></tr></table>`;
    } else {
      const r = data.roads[String(owner)] || {};
      const rows = [
        ['OpenDRIVE road', owner],
        ['name', r.name || ''],
        ['class', r.class || ''],
        ['junction', r.junction >= 0 ? r.junction : ''],
        ['length', `${r.length_m} m`],
        ['steepest grade', `${r.max_grade_percent} %`],
        ['lanes', r.lanes ?? ''],
        ['speed', r.speed_kmh ? `${r.speed_kmh} km/h` : ''],
        ['bridge / tunnel', `${r.bridge ? 'bridge' : ''}${r.tunnel ? 'tunnel' : ''}` || 'no'],
        ['OSM ways', (r.osm_way_ids || []).map((w) => `<a href="https://www.openstreetmap.org/way/${w}">${w}</a>`).join(' ')],
      ];
      const profile = r.network_road >= 0 ? data.profiles[String(r.network_road)] : null;
      info.innerHTML =
        `<h2>${escape(r.name || `road ${owner}`)}</h2><table>${rows
          .map(([k, v]) => `<tr><td>${k}</td><td>${k === 'OSM ways' ? v : escape(v)}</td></tr>`)
          .join('')}</table>` +
        (profile ? `<h2>profile of the OSM road</h2><div id="profile">${profileSvg(profile, r.profile_s)}</div>` : '<p class="hint">a connecting road inside a junction: its profile is the junction\'s</p>');
    }
    requestRender();
  }

  const raycaster = new THREE.Raycaster();
  function pickAt(clientX, clientY) {
    const rect = canvas.getBoundingClientRect();
    const ndc = new THREE.Vector2(((clientX - rect.left) / rect.width) * 2 - 1, -((clientY - rect.top) / rect.height) * 2 + 1);
    raycaster.setFromCamera(ndc, camera);
    const targets = ['road', 'structure', 'sidewalk', 'terrain']
      .filter((n) => groups[n].visible)
      .flatMap((n) => groups[n].children)
      .filter((o) => o.visible);  // a coarse copy hidden behind its full tile is not picked
    const hit = raycaster.intersectObjects(targets, false)[0];
    if (!hit) return null;
    const layer = hit.object.userData.layer;
    if (!layer.owner) return { layer: layer.name };
    return { layer: layer.name, owner: data.owners[layer.owner[hit.face.a]], point: hit.point };
  }
  let down = null;
  canvas.addEventListener('pointerdown', (e) => (down = [e.clientX, e.clientY]));
  canvas.addEventListener('pointerup', (e) => {
    if (!down || Math.hypot(e.clientX - down[0], e.clientY - down[1]) > 4) return;
    const hit = pickAt(e.clientX, e.clientY);
    select(hit && hit.owner !== undefined ? hit.owner : null);
  });

  // Controls of the panel.
  const legend = document.getElementById('legend');
  legend.innerHTML = legendHtml(state.mode);
  function setMode(mode) {
    state.mode = mode;
    legend.innerHTML = legendHtml(mode);
    for (const name of ['road', 'structure', 'sidewalk']) for (const m of groups[name].children) paint(m);
    for (const input of document.querySelectorAll('input[name=mode]')) input.checked = input.value === mode;
    requestRender();
  }
  function setLayer(name, visible) {
    (name === 'findings' ? markers : groups[name]).visible = visible;
    const box = document.querySelector(`input[name=layer][value=${name}]`);
    if (box) box.checked = visible;
    requestRender();
  }
  for (const input of document.querySelectorAll('input[name=mode]')) input.addEventListener('change', () => setMode(input.value));
  for (const input of document.querySelectorAll('input[name=layer]'))
    input.addEventListener('change', () => setLayer(input.value, input.checked));

  const resize = () => {
    const w = stage.clientWidth, h = stage.clientHeight;
    renderer.setSize(w, h, false);
    camera.aspect = w / Math.max(1, h);
    camera.updateProjectionMatrix();
    requestRender();
  };
  new ResizeObserver(resize).observe(stage);
  controls.addEventListener('change', requestRender);

  // The co-simulation's replay, when this page is a cosim's (replay.js loaded before the bundle).
  let replay = null;
  if (window.RELIEF_REPLAY) {
    replay = new Replay(window.RELIEF_REPLAY, scene);
    const panel = document.getElementById('replay');
    const button = document.getElementById('play');
    const slider = document.getElementById('time');
    const clock = document.getElementById('clock');
    panel.hidden = false;
    slider.max = String(replay.end);
    let playing = false, last = 0;
    const show = () => {
      slider.value = String(replay.time);
      clock.textContent = `${replay.time.toFixed(1)} s, ${replay.shown} vehicles`;
      requestRender();
    };
    const tick = (now) => {
      if (!playing) return;
      replay.setTime(replay.time + (now - last) / 1000);
      last = now;
      show();
      if (replay.time >= replay.end) setPlaying(false);
      else requestAnimationFrame(tick);
    };
    const setPlaying = (on) => {
      playing = on;
      button.textContent = on ? 'pause' : 'play';
      if (on) {
        if (replay.time >= replay.end) replay.setTime(0);
        last = performance.now();
        requestAnimationFrame(tick);
      }
    };
    button.addEventListener('click', () => setPlaying(!playing));
    slider.addEventListener('input', () => {
      replay.setTime(Number(slider.value));
      show();
    });
    replay.playing = () => playing;
    replay.show = show;
    show();
  }

  const api = {
    replay,
    ready: false,
    data,
    get tilesLoaded() {
      return tiles.loaded().length;
    },
    get trianglesLoaded() {
      return tiles.loadedTriangles;
    },
    /// Tiles drawn in full (not as their coarse copy), and those with their marks.
    get fullTiles() {
      return tiles.tiles.filter((t) => t.parts.base.state === 'loaded').length;
    },
    get marksTiles() {
      return tiles.tiles.filter((t) => t.parts.marks && t.parts.marks.state === 'loaded').length;
    },
    failedTiles: tiles.failed,
    selected: () => state.selected,
    mode: () => state.mode,
    setMode,
    setLayer,
    layerVisible: (name) => (name === 'findings' ? markers : groups[name]).visible,
    focus,
    /// The point the camera orbits, in the local frame (x, y, z).
    target: () => [controls.target.x, -controls.target.z, controls.target.y],
    select,
    pickAt,
    /// Renders now and counts the canvas pixels that are not the background.
    pixelStats() {
      render();
      const gl = renderer.getContext();
      const w = gl.drawingBufferWidth, h = gl.drawingBufferHeight;
      const px = new Uint8Array(4 * w * h);
      gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, px);
      const hex = background.getHex();  // sRGB, as the canvas holds it
      const bg = [(hex >> 16) & 255, (hex >> 8) & 255, hex & 255];
      let other = 0;
      const colours = new Set();
      for (let i = 0; i < w * h; i++) {
        const r = px[4 * i], g = px[4 * i + 1], b = px[4 * i + 2];
        if (Math.abs(r - bg[0]) + Math.abs(g - bg[1]) + Math.abs(b - bg[2]) > 6) other++;
        if (i % 7 === 0) colours.add((r >> 3) * 1024 + (g >> 3) * 32 + (b >> 3));
      }
      return { width: w, height: h, nonBackground: other, fraction: other / (w * h), colours: colours.size };
    },
    /// A point on the screen (client pixels) where a click picks road `owner`, or null.
    screenPointOf(owner) {
      render();
      const index = data.owners.indexOf(owner);
      const rect = canvas.getBoundingClientRect();
      for (const name of ['road', 'structure']) {
        for (const m of groups[name].children) {
          if (!m.visible) continue;
          const l = m.userData.layer;
          for (let t = 0; t < l.triangles; t += 1) {
            const a = l.indices[3 * t];
            if (l.owner[a] !== index) continue;
            const p = new THREE.Vector3();
            for (let k = 0; k < 3; k++) {
              const v = l.indices[3 * t + k];
              p.add(new THREE.Vector3(l.positions[3 * v], l.positions[3 * v + 1], l.positions[3 * v + 2]));
            }
            p.divideScalar(3).project(camera);
            if (Math.abs(p.x) > 0.95 || Math.abs(p.y) > 0.95 || p.z > 1) continue;
            const x = rect.left + ((p.x + 1) / 2) * rect.width, y = rect.top + ((1 - p.y) / 2) * rect.height;
            const hit = pickAt(x, y);
            if (hit && hit.owner === owner) return { x, y };
          }
        }
      }
      return null;
    },
  };
  window.reliefView = api;

  let wasReady = false;
  function refreshTiles() {
    camera.updateMatrixWorld();
    const done = tiles.update(camera);
    const loaded = tiles.loaded();
    status.textContent = `${loaded.length} of ${data.tiles.length} tiles, ${(tiles.loadedTriangles / 1e6).toFixed(2)} M triangles${done ? '' : ', loading…'}${tiles.failed.length ? `, ${tiles.failed.length} failed` : ''}`;
    api.ready = done;
    if (done && !wasReady) canvas.dispatchEvent(new Event('relief-ready'));
    wasReady = done;
  }
  resize();
}

main();
