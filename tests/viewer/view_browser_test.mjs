// view.html in a real browser: headless Chromium (Debian's) driven by puppeteer-core.
//   node view_browser_test.mjs --view OUT/view.html --road "NAME" --shots DIR [--replay 1]
// Checks: the page loads from file:// with the network off, with no console error and every tile in view; the canvas
// is not empty (pixels read back); a click on a road named NAME selects it and shows its
// profile (DEM drape, paper, fit); the terrain toggle and the colour mode change the picture;
// the findings list jumps to a finding; with --replay, a co-simulation's replay plays. Screenshots go to DIR. Prints one JSON line of figures.
import { createRequire } from 'node:module';
import { mkdirSync } from 'node:fs';
import path from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';

const here = path.dirname(fileURLToPath(import.meta.url));
const require = createRequire(path.join(here, '../../src/viewer/web/package.json'));
const puppeteer = require('puppeteer-core');

const args = {};
for (let i = 2; i < process.argv.length; i += 2) args[process.argv[i].replace(/^--/, '')] = process.argv[i + 1];
const failures = [];
const check = (ok, what) => {
  if (!ok) failures.push(what);
  console.log(`${ok ? 'ok  ' : 'FAIL'} ${what}`);
};

const shots = args.shots || 'view-shots';
mkdirSync(shots, { recursive: true });
const browser = await puppeteer.launch({
  executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
  headless: true,
  // WebGL through SwiftShader (software): the machine has no GPU.
  args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--window-size=1280,800'],
});
const figures = {};
try {
  const page = await browser.newPage();
  await page.setViewport({ width: 1280, height: 800 });
  const errors = [];
  page.on('console', (m) => m.type() === 'error' && errors.push(m.text()));
  page.on('pageerror', (e) => errors.push(String(e)));
  page.on('requestfailed', (r) => errors.push(`request failed: ${r.url()}`));
  // No network: everything the page needs is in the build's folder.
  await page.setOfflineMode(true);
  const start = Date.now();
  await page.goto(pathToFileURL(path.resolve(args.view)).href);
  await page.waitForFunction(() => window.reliefView && window.reliefView.ready, { timeout: 180000, polling: 200 });
  figures.load_s = (Date.now() - start) / 1000;
  const loaded = await page.evaluate(() => ({
    tiles: window.reliefView.tilesLoaded,
    of: window.reliefView.data.tiles.length,
    triangles: window.reliefView.trianglesLoaded,
    failed: window.reliefView.failedTiles.length,
  }));
  Object.assign(figures, { tiles: loaded.tiles, tiles_total: loaded.of, triangles: loaded.triangles });
  check(errors.length === 0, `no console error (${errors.slice(0, 3).join(' | ')})`);
  check(loaded.failed === 0 && loaded.tiles > 0, `tiles in view loaded: ${loaded.tiles} of ${loaded.of}`);

  const overview = await page.evaluate(() => window.reliefView.pixelStats());
  figures.overview_fraction = overview.fraction;
  check(overview.fraction > 0.2 && overview.colours > 20,
    `the canvas shows the scene: ${(100 * overview.fraction).toFixed(1)} % of pixels not background, ${overview.colours} colours`);
  await page.screenshot({ path: path.join(shots, 'overview.png') });

  // Frame time with everything in view (software WebGL: a GPU is far faster).
  figures.frame_ms = await page.evaluate(() => {
    const t0 = performance.now();
    for (let i = 0; i < 10; i++) window.reliefView.pixelStats();
    return (performance.now() - t0) / 10;
  });

  // A click on a known road shows its attributes and its profile.
  const target = await page.evaluate((name) => {
    const v = window.reliefView;
    const ids = Object.entries(v.data.roads)
      .filter(([, r]) => r.name === name && r.network_road >= 0)
      .sort((a, b) => b[1].length_m - a[1].length_m)
      .map(([id]) => Number(id));
    for (const id of ids) {
      const p = v.screenPointOf(id);
      if (p) return { id, ...p };
    }
    return { candidates: ids.length };
  }, args.road);
  check(target.id !== undefined, `a road named "${args.road}" is on the screen (${JSON.stringify(target)})`);
  if (target.id !== undefined) {
    await page.mouse.click(target.x, target.y);
    const shown = await page.evaluate(() => ({
      owner: document.getElementById('info').dataset.owner,
      title: document.querySelector('#info h2')?.textContent,
      series: [...document.querySelectorAll('#profile path.series')].map((p) => [p.dataset.series, p.getAttribute('d').length]),
    }));
    check(shown.owner === String(target.id), `the click selected road ${target.id} (panel: ${shown.owner}, "${shown.title}")`);
    const keys = shown.series.map((s) => s[0]).join(',');
    check(keys === 'raw,paper,fit' && shown.series.every((s) => s[1] > 20), `its profile shows the DEM drape, paper and fit (${keys})`);
    await page.screenshot({ path: path.join(shots, 'selected.png') });
  }

  // The terrain toggle hides the terrain: fewer pixels differ from the background.
  await page.click('input[name=layer][value=terrain]');
  const noTerrain = await page.evaluate(() => ({ visible: window.reliefView.layerVisible('terrain'), ...window.reliefView.pixelStats() }));
  check(!noTerrain.visible && noTerrain.fraction < overview.fraction - 0.05,
    `terrain toggle: hidden, scene pixels ${(100 * overview.fraction).toFixed(1)} % -> ${(100 * noTerrain.fraction).toFixed(1)} %`);
  await page.screenshot({ path: path.join(shots, 'no-terrain.png') });
  await page.click('input[name=layer][value=terrain]');

  // The colour mode: height over the DEM.
  const before = await page.evaluate(() => window.reliefView.pixelStats());
  await page.click('input[name=mode][value=dem]');
  const dem = await page.evaluate(() => ({ mode: window.reliefView.mode(), ...window.reliefView.pixelStats() }));
  check(dem.mode === 'dem' && dem.colours !== before.colours, `colour by height over the DEM: ${before.colours} -> ${dem.colours} colours`);
  await page.screenshot({ path: path.join(shots, 'dem.png') });

  // The findings list: one item per finding; a placed one moves the camera there.
  const findings = await page.evaluate(() => ({
    items: document.querySelectorAll('#finding-list li[data-i]').length,
    total: window.reliefView.data.findings.length,
    placed: window.reliefView.data.findings.findIndex((f) => Array.isArray(f.at)),
  }));
  figures.findings = findings.total;
  check(findings.items === findings.total, `findings listed: ${findings.items} of ${findings.total}`);
  if (findings.placed >= 0) {
    await page.click(`#finding-list li[data-i="${findings.placed}"]`);
    const moved = await page.evaluate((i) => {
      const f = window.reliefView.data.findings[i];
      const t = window.reliefView.target();
      return Math.hypot(t[0] - f.at[0], t[1] - f.at[1], t[2] - f.at[2]);
    }, findings.placed);
    check(moved < 0.01, `a click on a finding centres the view on it (${moved.toFixed(3)} m off)`);
    await page.waitForFunction(() => window.reliefView.ready, { timeout: 120000, polling: 200 });
    // 80 m from the finding: the tile there is drawn in full, with its marks.
    const near = await page.evaluate(() => ({ full: window.reliefView.fullTiles, marks: window.reliefView.marksTiles }));
    check(near.full > 0 && near.marks > 0, `zoomed in, tiles in full: ${near.full}, with their marks: ${near.marks}`);
    await page.screenshot({ path: path.join(shots, 'finding.png') });
  }
  // A co-simulation's page: its replay plays.
  if (args.replay) {
    const mid = await page.evaluate(() => {
      const r = window.reliefView.replay;
      if (!r) return null;
      const shown = r.setTime(r.end / 2);
      r.show();
      return { shown, end: r.end, vehicles: r.vehicles.length, panel: !document.getElementById('replay').hidden };
    });
    check(mid && mid.panel && mid.shown > 0,
      `the replay shows its vehicles: ${mid && mid.shown} of ${mid && mid.vehicles} at ${mid && (mid.end / 2).toFixed(1)} s`);
    figures.replay_vehicles = mid && mid.vehicles;
    await page.click('#play');
    await new Promise((r) => setTimeout(r, 1500));
    const played = await page.evaluate(() => ({ t: window.reliefView.replay.time, playing: window.reliefView.replay.playing() }));
    await page.click('#play');
    check(played.playing && played.t > (mid ? mid.end / 2 : 0) + 0.2, `play advances the replay (t = ${played.t.toFixed(2)} s)`);
    await page.screenshot({ path: path.join(shots, 'replay.png') });
  }
  check(errors.length === 0, `still no console error (${errors.slice(0, 3).join(' | ')})`);
} finally {
  await browser.close();
}
console.log(JSON.stringify(figures));
if (failures.length) {
  console.log(`${failures.length} check(s) failed`);
  process.exit(1);
}
