// The web app in headless Chromium (Debian's, driven by playwright-core) against native
// build/rtk: render hashes, debugged pixels, the comparison, a user's folder, bad input,
// a too-big scene, Cancel, Save PNG; screenshots of the three views in build/web-test/.
//   node web/test/browser.mjs URL        (make check-web starts the server and runs this)
import { chromium } from 'playwright-core';
import { execFileSync, spawnSync } from 'node:child_process';
import { mkdirSync, mkdtempSync, writeFileSync, copyFileSync, readFileSync, rmSync } from 'node:fs';
import { deflateSync, crc32 } from 'node:zlib';
import { tmpdir } from 'node:os';
import { join, resolve } from 'node:path';

const url = process.argv[2];
const root = resolve(new URL('../..', import.meta.url).pathname);
const rtkBin = join(root, 'build/rtk');
const shared = resolve(process.env.RTK_SHARED || join(root, '../shared'));
const corpusDir = join(shared, 'cse457');
const shots = join(root, 'build/web-test');
mkdirSync(shots, { recursive: true });
const work = mkdtempSync(join(tmpdir(), 'rtk-web-test-'));

let passed = 0, failed = 0;
function check(name, ok, detail = '') {
  if (ok) passed++;
  else failed++;
  console.log(`${ok ? 'ok  ' : 'FAIL'}  ${name}${!ok && detail ? `\n      ${detail}` : ''}`);
}
const same = (a, b) => JSON.stringify(a) === JSON.stringify(b);

// A black 8-bit RGB PNG (it compresses to almost nothing, but decodes to w * h * 3 bytes).
function blackPng(w, h) {
  const chunk = (type, data) => {
    const head = Buffer.alloc(8);
    head.writeUInt32BE(data.length);
    head.write(type, 4);
    const crc = Buffer.alloc(4);
    crc.writeUInt32BE(crc32(Buffer.concat([head.subarray(4), data])));
    return Buffer.concat([head, data, crc]);
  };
  const ihdr = Buffer.alloc(13);
  ihdr.writeUInt32BE(w, 0);
  ihdr.writeUInt32BE(h, 4);
  ihdr[8] = 8;
  ihdr[9] = 2;
  return Buffer.concat([Buffer.from([137, 80, 78, 71, 13, 10, 26, 10]), chunk('IHDR', ihdr),
    chunk('IDAT', deflateSync(Buffer.alloc((w * 3 + 1) * h), { level: 9 })), chunk('IEND', Buffer.alloc(0))]);
}

function rtk(args, cwd = root) {
  const r = spawnSync(rtkBin, args, { cwd, encoding: 'utf8', maxBuffer: 1 << 28 });
  return { rc: r.status, out: r.stdout, err: r.stderr.trim() };
}
// Option flags of `rtk render` for the page's settings.
const flags = (o = {}) => [...(o.width ? ['--width', o.width] : []), ...(o.height ? ['--height', o.height] : []), ...(o.depth !== undefined ? ['--depth', o.depth] : []), ...(o.aa !== undefined ? ['--aa', o.aa] : [])].map(String);

// A fresh profile (--user-data-dir, which playwright passes for a persistent context).
const context = await chromium.launchPersistentContext(join(work, 'profile'), {
  executablePath: '/usr/bin/chromium',
  headless: true,
  args: ['--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run', '--disable-background-networking',
    '--disable-component-update', '--disable-sync'],
  viewport: { width: 1440, height: 940 },
  acceptDownloads: true,
});
const page = context.pages()[0] || (await context.newPage());
const pageErrors = [];
page.on('pageerror', (e) => pageErrors.push(e.message));

async function setOptions(o = {}) {
  await page.fill('#opt-width', o.width ? String(o.width) : '');
  await page.fill('#opt-height', o.height ? String(o.height) : '');
  await page.fill('#opt-depth', o.depth !== undefined ? String(o.depth) : '');
  await page.selectOption('#opt-aa', { value: o.aa !== undefined ? String(o.aa) : '-1' });
}

// Renders a scene (a path in the page's file system) and waits for the hash or an error.
async function render(path, o = {}) {
  await setOptions(o);
  await page.evaluate((p) => { rtkApp.renderDone = false; rtkApp.lastError = ''; rtkApp.openAndRender(p); }, path);
  await page.waitForFunction(() => rtkApp.renderDone || (rtkApp.lastError && !rtkApp.busy), null, { timeout: 120000 });
  return page.evaluate(() => ({ hash: document.getElementById('stat-hash').textContent, error: rtkApp.lastError, seconds: rtkApp.renderSeconds }));
}

try {
  await page.goto(url);
  await page.waitForFunction(() => window.rtkApp?.ready && !rtkApp.busy, null, { timeout: 60000 });
  check('page loads the kernel and lists the corpus', (await page.locator('.scene').count()) >= 20);

  // ---- render hashes: the page's against native rtk's, same settings ----
  const hashScenes = [
    ['simple/box.yaml'], ['simple/sphere_refract.yaml'], ['simple/cylinder_refract.yaml'], ['simple/texture_reflection.yaml'],
    ['simple/cube_transparent.yaml'], ['trimeshes/chess.yaml'], ['trimeshes/martini.yaml'], ['more/lecture.yaml'],
    ['simple/box_cyl_reflect.yaml', { width: 200, height: 150, depth: 1, aa: 1 }],
  ];
  const times = [];
  for (const [scene, o] of hashScenes) {
    const got = await render(`cse457/assets/trace/${scene}`, o);
    const want = rtk(['render', join(corpusDir, 'assets/trace', scene), '--hash', '--quiet', ...flags(o)]).out.trim();
    check(`hash ${scene}${o ? ' ' + flags(o).join(' ') : ''} = native`, got.hash === want, `page ${got.hash} ${got.error}, native ${want}`);
    times.push(`${scene} ${got.seconds?.toFixed(2)} s`);
  }
  console.log(`      browser render times (2 workers, noisy): ${times.join(', ')}`);

  // ---- the debugger: clicked pixels against rtk debug ----
  async function clickPixel(x, y) {
    await page.evaluate(() => rtkApp.switchView('render'));
    const box = await page.locator('#render-canvas').boundingBox();
    const { w, h } = await page.evaluate(() => ({ w: rtkApp.width, h: rtkApp.height }));
    await page.mouse.click(box.x + ((x + 0.5) * box.width) / w, box.y + ((y + 0.5) * box.height) / h);
    await page.waitForFunction(([px, py]) => rtkApp.debugDoc && rtkApp.pixel.x === px && rtkApp.pixel.y === py, [x, y], { timeout: 20000 });
  }
  // The rows the table shows: kind, depth, t and colour as text.
  const tableRows = () => page.$$eval('#ray-table tbody tr', (rows) => rows.map((r) => ({
    kind: r.dataset.kind, depth: r.querySelector('.depth').textContent, t: r.querySelector('.t').textContent, color: r.querySelector('.color-text').textContent })));
  // The same from `rtk debug`'s text (printf %.9g): rays in print order.
  function nativeRows(text) {
    const rows = [];
    for (const line of text.split('\n')) {
      const ray = line.match(/^\s*(\w+) ray, depth (\d+)/);
      if (ray) rows.push({ kind: ray[1], depth: ray[2], t: '', color: null });
      const hit = line.match(/^\s*hit '.*': .*, t (\S+), material/);
      if (hit) rows[rows.length - 1].t = hit[1];
      const back = line.match(/^\s*(returns|attenuation) (\(.*\))$/);
      if (back) [...rows].reverse().find((r) => r.color === null && (back[1] === 'attenuation') === (r.kind === 'shadow')).color = back[2];
    }
    return rows;
  }
  const countRays = (doc) => { let n = 0; const v = (r) => { n++; r.lights.forEach((l) => l.shadow_rays.forEach(v)); r.children.forEach(v); }; doc.samples.forEach(v); return n; };
  const debugCases = [
    ['simple/sphere_refract.yaml', 200, 250], ['simple/sphere_refract.yaml', 331, 416], ['simple/box_cyl_trans_shadow.yaml', 250, 300],
    ['simple/texture_reflection.yaml', 256, 330], ['trimeshes/chess.yaml', 260, 300], ['simple/box_cyl_reflect.yaml', 300, 280],
  ];
  let current = null;
  for (const [scene, x, y] of debugCases) {
    if (current !== scene) await render(`cse457/assets/trace/${scene}`);
    current = scene;
    await clickPixel(x, y);
    const path = join(corpusDir, 'assets/trace', scene);
    const wantText = rtk(['debug', path, '--pixel', `${x},${y}`, '--json']).out, want = JSON.parse(wantText);
    const doc = await page.evaluate(() => rtkApp.debugDoc);
    check(`debug ${scene} (${x}, ${y}): the page's tree = rtk debug --json, and its text byte for byte`,
      same(doc, want) && (await page.textContent('#debug-json')) === wantText);
    const rows = await tableRows(), nat = nativeRows(rtk(['debug', path, '--pixel', `${x},${y}`]).out);
    check(`debug ${scene} (${x}, ${y}): table rows (kind, depth, t, colour) = rtk debug's text`, same(rows, nat), `page ${JSON.stringify(rows).slice(0, 400)}\n      native ${JSON.stringify(nat).slice(0, 400)}`);
    const counts = await page.evaluate(() => rtkApp.view3d.counts());
    const info = JSON.parse(rtk(['info', path, '--json']).out).primitives;
    check(`3D view of ${scene}: one object per primitive (${info.spheres + info.cylinders + info.meshes}), one segment per ray (${countRays(want)})`,
      counts.object === info.spheres + info.cylinders + info.meshes && counts.ray === countRays(want), JSON.stringify(counts));
  }
  await page.screenshot({ path: join(shots, 'debugger.png') });

  // Stepping through supersamples: 4 samples per pixel, the second one.
  {
    const scene = 'simple/sphere_refract.yaml', o = { aa: 1 };
    await render(`cse457/assets/trace/${scene}`, o);
    await clickPixel(331, 416);
    await page.click('#sample-next');
    await page.click('#sample-next');
    await page.waitForFunction(() => rtkApp.debugDoc.sample === 1);
    const want = JSON.parse(rtk(['debug', join(corpusDir, 'assets/trace', scene), '--pixel', '331,416', '--sample', '1', '--json', ...flags(o)]).out);
    check('supersample stepping: sample 1 of 4 = rtk debug --sample 1', same(await page.evaluate(() => rtkApp.debugDoc), want));
  }

  // ---- the comparison against rtk compare ----
  {
    const scene = 'simple/sphere_refract.yaml', solution = 'assets/trace/solution/sphere_refract_3.png';
    await render(`cse457/assets/trace/${scene}`);
    const png = join(work, 'sr.png');
    rtk(['render', join(corpusDir, 'assets/trace', scene), '-o', png, '--quiet']);
    const want = JSON.parse(rtk(['compare', png, join(corpusDir, solution), '--json']).out);
    await page.click('.tab[data-view=compare]');
    await page.selectOption('#ref-select', `cse457/${solution}`);
    await page.waitForFunction(() => rtkApp.compare.metrics);
    const got = await page.evaluate(() => rtkApp.compare.metrics);
    const shown = parseFloat(await page.textContent('#m-psnr'));
    check(`compare: PSNR ${shown} dB = rtk compare ${want.psnr.toFixed(3)} to 0.01 dB`, Math.abs(shown - want.psnr) < 0.01 && Math.abs(got.psnr - want.psnr) < 0.01);
    check('compare: within 1, max diff, worst pixel = rtk compare', got.within_pct['1'] === want.within_pct['1'] && got.max_diff === want.max_diff && same(got.worst, want.worst),
      `${JSON.stringify(got)} vs ${JSON.stringify(want)}`);
    await page.check('input[name=cmp-mode][value=difference]');
    await page.fill('#cmp-slider', '0');
    await page.dispatchEvent('#cmp-slider', 'input');
    const box = await page.locator('#compare-canvas').boundingBox();
    await page.mouse.click(box.x + ((want.worst.x + 0.5) * box.width) / 512, box.y + ((want.worst.y + 0.5) * box.height) / 512);
    await page.waitForFunction(([x, y]) => rtkApp.debugDoc && rtkApp.pixel.x === x && rtkApp.pixel.y === y, [want.worst.x, want.worst.y], { timeout: 10000 }).catch(() => {});
    const opened = await page.evaluate(() => ({ view: document.querySelector('.view.active').id, pixel: rtkApp.pixel }));
    check('a click in the heat map opens the debugger at that pixel', opened.view === 'view-debug' && same(opened.pixel, { x: want.worst.x, y: want.worst.y }), JSON.stringify(opened));
  }

  // The comparison's screenshot: the lens cut to depth 1 against the solution, split.
  {
    await render('cse457/assets/trace/simple/sphere_refract.yaml', { depth: 1 });
    await page.click('.tab[data-view=compare]');
    await page.waitForFunction(() => rtkApp.compare.metrics);
    await page.fill('#cmp-slider', '50');
    await page.dispatchEvent('#cmp-slider', 'input');
    await page.screenshot({ path: join(shots, 'compare.png') });
    await setOptions();
    await render('cse457/assets/trace/simple/sphere_refract.yaml');
  }

  // ---- Save PNG: the same pixels as native ----
  {
    await page.click('.tab[data-view=render]');
    const [download] = await Promise.all([page.waitForEvent('download'), page.click('#save-btn')]);
    const saved = join(work, 'saved.png');
    await download.saveAs(saved);
    const cmp = JSON.parse(rtk(['compare', saved, join(work, 'sr.png'), '--json']).out || '{}');
    check('Save PNG: the saved image has native rtk\'s pixels', cmp.max_diff === 0, JSON.stringify(cmp));
  }
  await page.evaluate(() => { document.querySelector('aside').scrollTop = 0; document.activeElement?.blur(); });
  await page.screenshot({ path: join(shots, 'render.png') });

  // ---- a user's scene folder through the file input ----
  async function openFolder(dir) {
    await page.evaluate(() => { rtkApp.renderDone = false; rtkApp.lastError = ''; });
    await page.setInputFiles('#folder-input', dir);
    await page.waitForFunction(() => rtkApp.renderDone || (rtkApp.lastError && !rtkApp.busy), null, { timeout: 60000 });
    return page.evaluate(() => ({ hash: document.getElementById('stat-hash').textContent, error: rtkApp.lastError }));
  }
  const folder = (name, scene, assets) => {
    const dir = join(work, name);
    mkdirSync(join(dir, 'assets'), { recursive: true });
    writeFileSync(join(dir, 'scene.yaml'), scene);
    for (const [to, from] of Object.entries(assets)) copyFileSync(from, join(dir, 'assets', to));
    return dir;
  };
  const trace = (f) => join(corpusDir, 'assets/trace', f);
  const chess = readFileSync(trace('trimeshes/chess.yaml'), 'utf8').replaceAll('assets/trace/trimeshes/', 'assets/');
  const plys = Object.fromEntries(['pawn', 'knight', 'table1', 'table2'].map((n) => [`${n}.ply`, trace(`trimeshes/${n}.ply`)]));
  {
    const dir = folder('my_chess', chess, plys);
    const got = await openFolder(dir);
    const want = rtk(['render', 'my_chess/scene.yaml', '--hash', '--quiet'], work).out.trim();
    check('a user folder (scene + assets/ with meshes) opened through the file input renders the native hash', got.hash === want, `${got.hash} ${got.error} vs ${want}`);
  }
  // ---- bad input: the native one-line message, paths as the user opened them ----
  const texture = readFileSync(trace('simple/texture_reflection.yaml'), 'utf8').replaceAll('assets/trace/simple/', 'assets/').replaceAll('assets/checkers.png', 'assets/checkers.png');
  const bad = [
    ['broken_yaml', readFileSync(trace('simple/box.yaml'), 'utf8').replace('Materials:', 'Materials: [oops\n  bad: {'), {}],
    ['missing_mesh', chess, { 'pawn.ply': plys['pawn.ply'] }],
    ['missing_texture', texture, {}],
    ['bad_value', readFileSync(trace('simple/box.yaml'), 'utf8').replace(/Shininess: [0-9.]+/, 'Shininess: shiny'), {}],
  ];
  for (const [name, scene, assets] of bad) {
    const dir = folder(name, scene, assets);
    const got = await openFolder(dir);
    const native = rtk(['render', `${name}/scene.yaml`, '--hash', '--quiet'], work);
    // Native paths are absolute on disk; the page's file system has the folder at /.
    const want = native.err.replaceAll(work, '');
    check(`bad input ${name}: the page shows native's line (exit ${native.rc})`, native.rc === 3 && got.error === want, `page: ${got.error}\n      native: ${want}`);
  }
  check('the page is alive after bad input', (await render('cse457/assets/trace/simple/box.yaml')).hash.length === 64);

  // ---- too big for the page ----
  {
    // The mechanism of the page's 1024 MiB limit, at a cap of 64 MiB (?max-memory=64) so the
    // test stays quick: two black 4096x3072 textures are 72 MiB of scene.
    await page.goto(`${url}?max-memory=64`);
    await page.waitForFunction(() => window.rtkApp?.ready && !rtkApp.busy, null, { timeout: 60000 });
    const dir = folder('too_big', texture.replace('assets/texture-checkerboard.png', 'assets/big1.png').replace('assets/checkers.png', 'assets/big2.png')
      .replace(/(    Sphere:\n[\s\S]*?)Color Map: ""\n(\s*)Use Texture: false/, '$1Color Map: Checkers Texture\n$2Use Texture: true'), {});
    writeFileSync(join(dir, 'assets/big1.png'), blackPng(4096, 3072));
    copyFileSync(join(dir, 'assets/big1.png'), join(dir, 'assets/big2.png'));
    const got = await openFolder(dir);
    const native = rtk(['render', 'too_big/scene.yaml', '--hash', '--quiet', '--max-memory', '64M'], work);
    const text = await page.textContent('#error');
    check(`a scene over the page's memory says so with native's line (exit ${native.rc})`,
      native.rc === 5 && /too big for the page's memory/.test(text) && got.error === native.err.replaceAll(work, '') && !(await page.evaluate(() => rtkApp.renderDone)),
      `page: ${text}\n      native: ${native.err}`);
    await page.goto(url);
    await page.waitForFunction(() => window.rtkApp?.ready && !rtkApp.busy, null, { timeout: 60000 });
  }
  {
    const got = await render('cse457/assets/trace/simple/box.yaml', { width: 16384, height: 16384 });
    const text = await page.textContent('#error');
    check('a scene too big for the page says so and is not rendered', /too big for the page's memory/.test(text) && !(await page.evaluate(() => rtkApp.renderDone)), text);
    await setOptions();
  }

  // ---- Cancel stops the workers ----
  {
    await setOptions({ aa: 3 });
    // The previous render's object stays in rtkApp.render until the scene has loaded: wait for the new one.
    await page.evaluate(() => { window.previousRender = rtkApp.render; rtkApp.lastError = ''; rtkApp.openAndRender('cse457/assets/trace/trimeshes/chess.yaml'); });
    await page.waitForFunction(() => rtkApp.render && rtkApp.render !== window.previousRender && rtkApp.render.done >= 1, null, { timeout: 60000 });
    const during = page.workers().length;
    await page.click('#cancel-btn');
    await page.waitForTimeout(1500);
    const after = await page.evaluate(() => ({ live: rtkApp.render.liveWorkers, done: rtkApp.render.done, total: rtkApp.render.total, status: document.getElementById('status').textContent, busy: rtkApp.busy }));
    await page.waitForTimeout(1000);
    const later = await page.evaluate(() => rtkApp.render.done);
    check(`Cancel stops the workers (${during} running before, ${page.workers().length} after; ${after.done} of ${after.total} tiles)`,
      during >= 1 && page.workers().length === 0 && after.live === 0 && later === after.done && after.done < after.total && /cancelled/.test(after.status) && !after.busy, JSON.stringify(after));
    await setOptions();
  }

  // Screenshot of the 3D view at a pixel with reflection, refraction and shadow rays.
  await render('cse457/assets/trace/simple/box_cyl_trans_shadow.yaml');
  await clickPixel(250, 300);
  await page.waitForTimeout(300);
  await page.screenshot({ path: join(shots, 'debugger.png') });
  check('no uncaught errors in the page', pageErrors.length === 0, pageErrors.join(' | '));
} catch (e) {
  check(`the test ran to the end`, false, e.stack);
} finally {
  await context.close();
  rmSync(work, { recursive: true, force: true });
}
console.log(`screenshots in ${shots}`);
console.log(`check-web: ${passed} passed, ${failed} failed`);
process.exitCode = failed ? 1 : 0;
