// The page: scene list, render settings and the tiled render, and the three views
// (render, debugger, compare). The kernel runs in rtk.wasm: one instance here (loading,
// debugging, comparing) and one per render worker.
import { Rtk, EXIT, ALL_SAMPLES } from './rtk.js';
import { TiledRender } from './render.js';
import { loadManifest, corpus, fromFileList, fromDrop, sceneFiles } from './files.js';
import { SceneView, RAY_STYLE } from './view3d.js';
import { fillRayTable } from './raytable.js';
import { CompareView } from './compare.js';

// Scene memory each wasm32 instance may use (its address space is 4 GiB, and the page
// holds one copy of the scene here and one per worker); ?max-memory=MIB changes it.
const memoryParam = Number(new URLSearchParams(location.search).get('max-memory'));
export const MAX_MEMORY_MIB = memoryParam >= 1 && memoryParam <= 3072 ? Math.floor(memoryParam) : 1024;
// Pixels the page renders at most: every worker and the page hold the image (and the
// canvas is limited too); larger images are refused before any worker starts.
export const MAX_PIXELS = 8192 * 8192;

const $ = (id) => document.getElementById(id);
const app = {
  rtk: null, module: null, manifest: null, files: {}, userFiles: {},
  scene: null, width: 0, height: 0, rgb: null, render: null, renderDone: false,
  pixel: null, sample: ALL_SAMPLES, debugDoc: null, view3d: null, sceneView: null,
  lastError: '', busy: false,
};
window.rtkApp = app; // for the browser tests and the curious

function status(text) { $('status').textContent = text; }
// <body data-state>: loading, ready, rendering, done, error or cancelled, for scripts driving the page.
function state(name) { document.body.dataset.state = name; }

function showError(text, headline) {
  app.lastError = text;
  const box = $('error');
  box.hidden = !text;
  box.innerHTML = '';
  if (!text) return;
  if (headline) box.append(Object.assign(document.createElement('strong'), { textContent: headline }));
  box.append(Object.assign(document.createElement('code'), { className: 'error-line', textContent: text }));
}

function switchView(name) {
  document.querySelectorAll('.tab').forEach((t) => t.classList.toggle('active', t.dataset.view === name));
  document.querySelectorAll('.view').forEach((v) => v.classList.toggle('active', v.id === `view-${name}`));
  if (name === 'debug') app.view3d?.resize();
  if (name === 'compare') app.compare.show();
}

// ---- scene list ----

function sceneEntry(path, label) {
  const b = document.createElement('button');
  b.className = 'scene';
  b.dataset.path = path;
  b.textContent = label;
  b.onclick = () => openAndRender(path);
  return b;
}

function fillSceneList() {
  const list = $('scene-list');
  list.innerHTML = '';
  const groups = new Map();
  const user = sceneFiles(app.userFiles).map((p) => p.slice(1));
  if (user.length) groups.set('your folder', user);
  const order = ['simple', 'trimeshes', 'more'];
  const scenes = [...app.manifest.scenes].sort((a, b) => order.indexOf(a.split('/').slice(-2, -1)[0]) - order.indexOf(b.split('/').slice(-2, -1)[0]) || a.localeCompare(b));
  for (const p of scenes) {
    const g = p.split('/').slice(-2, -1)[0];
    if (!groups.has(g)) groups.set(g, []);
    groups.get(g).push(p);
  }
  const filter = $('scene-filter').value.toLowerCase();
  for (const [name, paths] of groups) {
    const shown = paths.filter((p) => p.toLowerCase().includes(filter));
    if (!shown.length) continue;
    const h = document.createElement('h3');
    h.textContent = name;
    list.append(h);
    for (const p of shown) list.append(sceneEntry(p, p.split('/').pop().replace(/\.ya?ml$/, '')));
  }
  markCurrent();
}

function markCurrent() {
  document.querySelectorAll('.scene').forEach((b) => {
    b.classList.toggle('current', b.dataset.path === app.scene);
    if (b.dataset.path === app.scene) b.scrollIntoView({ block: 'nearest' });
  });
}

// ---- files ----

async function setUserFiles(files) {
  if (!Object.keys(files).length) return;
  state('loading');
  app.userFiles = files;
  await resetInstance();
  fillSceneList();
  const scenes = sceneFiles(files);
  if (!scenes.length) {
    state('error');
    return showError('no .yaml scene file in the folder you opened');
  }
  await openAndRender(scenes[0].slice(1));
}

// A fresh main instance over the corpus and the user's folder.
async function resetInstance() {
  app.rtk = await Rtk.create(app.module, { ...app.files, ...app.userFiles });
  app.compare.rtk = app.rtk;
}

// ---- rendering ----

function options() {
  const num = (id, none) => ($(id).value === '' ? none : Number($(id).value));
  return { width: num('opt-width', 0), height: num('opt-height', 0), depth: num('opt-depth', -1), aa: Number($('opt-aa').value) };
}

function setBusy(busy) {
  app.busy = busy;
  $('render-btn').disabled = busy || !app.scene;
  $('cancel-btn').disabled = !busy;
  $('save-btn').disabled = busy || !app.renderDone;
}

async function openAndRender(path) {
  if (app.busy) app.render?.cancel();
  app.scene = path;
  markCurrent();
  await renderScene();
}

async function renderScene() {
  showError('');
  app.renderDone = false;
  app.debugDoc = null;
  app.sceneView = null;
  setBusy(true);
  $('stat-scene').textContent = app.scene;
  $('stat-hash').textContent = '—';
  $('stat-time').textContent = '—';
  $('progress-bar').style.width = '0';
  const t0 = performance.now();
  status(`Loading ${app.scene}…`);
  state('loading');
  await new Promise((r) => setTimeout(r, 0));
  const rc = app.rtk.open(app.scene, { ...options(), maxMemoryMiB: MAX_MEMORY_MIB });
  if (rc !== EXIT.OK) {
    const line = app.rtk.stderr();
    state('error');
    showError(line, rc === EXIT.MEMORY ? `This scene is too big for the page's memory (${MAX_MEMORY_MIB} MiB of scene per WebAssembly instance); not rendered.` : null);
    status(rc === EXIT.MEMORY ? 'Scene too big for the page' : 'The scene could not be loaded');
    setBusy(false);
    return;
  }
  const width = app.rtk.width, height = app.rtk.height;
  if (width * height > MAX_PIXELS) {
    showError(`${app.scene}: a ${width}x${height} image is ${((width * height) / 1048576).toFixed(0)} Mpixels; the page renders at most ${MAX_PIXELS / 1048576} Mpixels`,
      "This scene is too big for the page's memory; not rendered. rtk render renders it natively.");
    status('Scene too big for the page');
    state('error');
    setBusy(false);
    return;
  }
  Object.assign(app, { width, height });
  $('stat-size').textContent = `${width} × ${height}, ${app.rtk.samples} sample${app.rtk.samples > 1 ? 's' : ''}/pixel`;
  const blob = app.rtk.pack();
  const canvas = $('render-canvas');
  canvas.width = width;
  canvas.height = height;
  const ctx = canvas.getContext('2d');
  ctx.fillStyle = '#1b1f26';
  ctx.fillRect(0, 0, width, height);
  const workers = navigator.hardwareConcurrency || 2;
  $('stat-workers').textContent = String(workers);
  status(`Rendering ${app.scene}…`);
  state('rendering');
  app.render = new TiledRender({
    module: app.module, blob, width, height, maxMemoryMiB: MAX_MEMORY_MIB, workers,
    onTile: (t, done, total) => {
      const w = t.x1 - t.x0, h = t.y1 - t.y0, img = ctx.createImageData(w, h);
      for (let i = 0; i < w * h; i++) img.data.set([t.rgb[3 * i], t.rgb[3 * i + 1], t.rgb[3 * i + 2], 255], 4 * i);
      ctx.putImageData(img, t.x0, t.y0);
      $('progress-bar').style.width = `${(100 * done) / total}%`;
      $('stat-time').textContent = `${((performance.now() - t0) / 1000).toFixed(2)} s…`;
    },
  });
  try {
    app.rgb = await app.render.run();
  } catch (e) {
    status(e.cancelled ? 'Render cancelled' : 'Render failed');
    state(e.cancelled ? 'cancelled' : 'error');
    if (!e.cancelled) showError(e.message, e.rc === EXIT.MEMORY ? "This scene is too big for the page's memory; not rendered." : null);
    setBusy(false);
    return;
  }
  const seconds = (performance.now() - t0) / 1000;
  app.renderSeconds = seconds;
  $('stat-time').textContent = `${seconds.toFixed(2)} s`;
  $('stat-hash').textContent = app.rtk.hash(app.rgb, width, height);
  app.renderDone = true;
  status(`Rendered ${app.scene} in ${seconds.toFixed(2)} s`);
  state('done');
  setBusy(false);
  drawDebugImage();
  app.compare.sceneChanged();
}

function cancelRender() {
  app.render?.cancel();
}

function savePng() {
  $('render-canvas').toBlob((blob) => {
    const a = document.createElement('a');
    a.href = URL.createObjectURL(blob);
    a.download = app.scene.split('/').pop().replace(/\.ya?ml$/i, '') + '.png';
    a.click();
    setTimeout(() => URL.revokeObjectURL(a.href), 1000);
  }, 'image/png');
}

// ---- debugger ----

function drawDebugImage() {
  const c = $('debug-canvas');
  c.width = app.width;
  c.height = app.height;
  c.getContext('2d').drawImage($('render-canvas'), 0, 0);
  if (app.pixel) ringPixel(c, app.pixel.x, app.pixel.y);
}

function ringPixel(c, x, y) {
  const ctx = c.getContext('2d');
  ctx.strokeStyle = '#ff3df2';
  ctx.lineWidth = Math.max(1, app.width / 256);
  const r = Math.max(4, app.width / 64);
  ctx.strokeRect(x - r, y - r, 2 * r + 1, 2 * r + 1);
}

function canvasPixel(canvas, ev) {
  const r = canvas.getBoundingClientRect();
  const x = Math.floor(((ev.clientX - r.left) / r.width) * canvas.width);
  const y = Math.floor(((ev.clientY - r.top) / r.height) * canvas.height);
  return x >= 0 && y >= 0 && x < canvas.width && y < canvas.height ? { x, y } : null;
}

function drawLoupe(x, y) {
  const loupe = $('loupe'), ctx = loupe.getContext('2d');
  const n = 11, cell = loupe.width / n;
  ctx.imageSmoothingEnabled = false;
  ctx.fillStyle = '#000';
  ctx.fillRect(0, 0, loupe.width, loupe.height);
  ctx.drawImage($('render-canvas'), x - (n >> 1), y - (n >> 1), n, n, 0, 0, loupe.width, loupe.height);
  ctx.strokeStyle = '#ff3df2';
  ctx.lineWidth = 2;
  ctx.strokeRect((n >> 1) * cell, (n >> 1) * cell, cell, cell);
}

function ensureSceneView() {
  if (!app.view3d) {
    app.view3d = new SceneView($('view3d'));
    $('legend').innerHTML = Object.values(RAY_STYLE).map((s) => `<div><span class="legend-line${s.dashed ? ' dashed' : ''}" style="border-color:${s.color}"></span>${s.label}</div>`).join('') +
      '<div><span class="legend-dot" style="background:#ffd84d"></span>point light · arrow: directional light</div><div><span class="legend-line" style="border-color:#8ab4f8"></span>camera and image plane</div>';
  }
  if (!app.sceneView) {
    app.sceneView = app.rtk.sceneView();
    app.view3d.setScene(app.sceneView);
  }
}

// Traces pixel (x, y) (sample: one sample, or ALL_SAMPLES) and shows its tree.
function debugPixel(x, y, sample = ALL_SAMPLES) {
  if (!app.renderDone) return;
  app.pixel = { x, y };
  app.sample = sample;
  switchView('debug');
  drawDebugImage();
  drawLoupe(x, y);
  const { rc, text, json, error } = app.rtk.debug(x, y, sample);
  if (rc !== EXIT.OK) return showError(error);
  showError(error); // "the ray log is full" when it is, else nothing
  app.debugDoc = json;
  $('debug-json').textContent = text;
  ensureSceneView();
  app.view3d.setTree(json);
  const rays = fillRayTable($('ray-table').tBodies[0], json, (i) => app.view3d.highlight(i));
  const [r, g, b] = json.bytes;
  $('pixel-info').innerHTML = `pixel <b>(${x}, ${y})</b> · bytes <b>${r} ${g} ${b}</b> <span class="swatch" style="background:rgb(${r},${g},${b})"></span><br>${rays} rays, ${json.samples_per_pixel} sample${json.samples_per_pixel > 1 ? 's' : ''} per pixel, max depth ${json.max_depth}`;
  $('sample-label').textContent = sample === ALL_SAMPLES ? `all ${json.samples_per_pixel} samples` : `sample ${sample + 1} of ${json.samples_per_pixel}`;
  status(`Debugging pixel (${x}, ${y}) of ${app.scene}`);
}

function stepSample(delta) {
  if (!app.pixel || !app.debugDoc) return;
  const n = app.debugDoc.samples_per_pixel;
  // The cycle: all samples, 0, 1, ..., n-1, all samples.
  const pos = app.sample === ALL_SAMPLES ? n : app.sample;
  const next = (pos + delta + n + 1) % (n + 1);
  debugPixel(app.pixel.x, app.pixel.y, next === n ? ALL_SAMPLES : next);
}

// ---- start ----

async function main() {
  try {
    const [module, manifest] = await Promise.all([WebAssembly.compile(await (await fetch('rtk.wasm')).arrayBuffer()), loadManifest()]);
    Object.assign(app, { module, manifest });
    app.compare = new CompareView(app, { debugPixel });
    app.files = await corpus(manifest);
    await resetInstance();
  } catch (e) {
    status('The kernel could not be loaded');
    showError(String(e.message || e));
    return;
  }
  fillSceneList();
  $('scene-filter').oninput = fillSceneList;
  $('folder-input').onchange = async (e) => setUserFiles(await fromFileList(e.target.files));
  const drop = document.body;
  drop.addEventListener('dragover', (e) => { e.preventDefault(); $('dropzone').classList.add('over'); });
  drop.addEventListener('dragleave', () => $('dropzone').classList.remove('over'));
  drop.addEventListener('drop', async (e) => {
    e.preventDefault();
    $('dropzone').classList.remove('over');
    await setUserFiles(await fromDrop(e.dataTransfer.items));
  });
  document.querySelectorAll('.tab').forEach((t) => (t.onclick = () => switchView(t.dataset.view)));
  $('render-btn').onclick = () => renderScene();
  $('cancel-btn').onclick = cancelRender;
  $('save-btn').onclick = savePng;
  $('render-canvas').onclick = (e) => { const p = canvasPixel(e.target, e); if (p) debugPixel(p.x, p.y); };
  $('debug-canvas').onclick = (e) => { const p = canvasPixel(e.target, e); if (p) debugPixel(p.x, p.y); };
  $('debug-canvas').onmousemove = (e) => { const p = canvasPixel(e.target, e); if (p && app.renderDone) drawLoupe(p.x, p.y); };
  $('debug-canvas').onmouseleave = () => app.pixel && drawLoupe(app.pixel.x, app.pixel.y);
  $('sample-prev').onclick = () => stepSample(-1);
  $('sample-next').onclick = () => stepSample(1);
  $('view3d-reset').onclick = () => app.view3d?.resetView();
  status(`Ready: ${app.manifest.scenes.length} corpus scenes`);
  app.ready = true;
  state('ready');
  const first = new URLSearchParams(location.search).get("scene") || app.manifest.scenes.find((s) => s.endsWith("/sphere_refract.yaml")) || app.manifest.scenes[0];
  if (first) openAndRender(first);
}

Object.assign(app, { openAndRender, renderScene, debugPixel, cancelRender, switchView, setUserFiles });
main();
