// The comparison tool: the render next to a reference image (a bundled corpus solution or
// a file the user loads), split by a slider, against the reference or the heat map of
// `rtk compare --diff`, zoomable; the numbers are `rtk compare --json`'s, computed by the
// same code in rtk.wasm. A click on the image opens the debugger at that pixel.
import { ppm } from './rtk.js';

const $ = (id) => document.getElementById(id);
const RENDER_PATH = '/tmp/render.ppm';

const fmt = (x, digits) => (typeof x === 'number' ? x.toFixed(digits) : String(x));

export class CompareView {
  constructor(app, { debugPixel }) {
    this.app = app;
    this.debugPixel = debugPixel;
    this.refPath = null;
    this.ref = null;   // {width, height, rgb}
    this.diff = null;  // rgb
    this.metrics = null;
    const select = $('ref-select');
    select.append(new Option('— choose a reference —', ''));
    for (const p of app.manifest.solutions) select.append(new Option(p.split('/').pop(), p));
    select.onchange = () => this.setReference(select.value ? '/' + select.value : null);
    $('ref-input').onchange = async (e) => {
      const f = e.target.files[0];
      if (!f) return;
      const path = `/reference/${f.name}`;
      this.app.rtk.writeFile(path, new Uint8Array(await f.arrayBuffer()));
      select.append(new Option(f.name, path.slice(1)));
      select.value = path.slice(1);
      this.setReference(path);
    };
    document.querySelectorAll('input[name=cmp-mode]').forEach((r) => (r.onchange = () => this.draw()));
    $('cmp-slider').oninput = () => this.draw();
    $('cmp-zoom').onchange = () => this.draw();
    const canvas = $('compare-canvas');
    canvas.onclick = (e) => {
      const p = this.pixelAt(e);
      if (p) this.debugPixel(p.x, p.y);
    };
    canvas.onmousemove = (e) => this.hover(this.pixelAt(e));
  }

  get mode() { return document.querySelector('input[name=cmp-mode]:checked').value; }

  // The bundled solution whose name starts with the scene's, if any.
  guessReference() {
    const name = this.app.scene.split('/').pop().replace(/\.ya?ml$/i, '');
    return this.app.manifest.solutions.find((p) => p.split('/').pop().replace(/_\d+\.png$/, '') === name) || null;
  }

  sceneChanged() {
    this.metrics = null;
    const guess = this.guessReference();
    if (guess) $('ref-select').value = guess;
    this.refPath = $('ref-select').value ? '/' + $('ref-select').value : this.refPath;
    if ($('view-compare').classList.contains('active')) this.show();
  }

  show() {
    if (!this.metrics && this.refPath) this.setReference(this.refPath);
    else this.draw();
  }

  // Reads the reference (rtk's image reader), compares the render with it and draws.
  setReference(path) {
    this.refPath = path;
    this.metrics = this.ref = this.diff = null;
    const box = $('metrics');
    if (!path || !this.app.renderDone) {
      box.innerHTML = `<dt>PSNR</dt><dd>${this.app.renderDone ? 'choose a reference' : 'render a scene first'}</dd>`;
      return this.draw();
    }
    const rtk = this.app.rtk, { width, height } = this.app;
    rtk.writeFile(RENDER_PATH, ppm(this.app.rgb, width, height));
    const { rc, text, metrics, error } = rtk.compare(RENDER_PATH, path);
    $('compare-json').textContent = text;
    if (rc !== 0) {
      box.innerHTML = `<dt>error</dt><dd class="error-line"></dd>`;
      box.querySelector('dd').textContent = error;
      return this.draw();
    }
    this.metrics = metrics;
    this.ref = { width, height, rgb: this.readImage(path, width, height) };
    this.diff = rtk.diffMap(RENDER_PATH, path, width, height);
    const m = metrics, w = m.worst;
    box.innerHTML =
      `<dt>PSNR</dt><dd id="m-psnr" class="big">${m.psnr === 'inf' ? '∞ (identical)' : fmt(m.psnr, 3) + ' dB'}</dd>` +
      `<dt>within 1 level</dt><dd id="m-within1">${fmt(m.within_pct['1'], 3)}% of channels</dd>` +
      `<dt>max diff</dt><dd id="m-maxdiff">${m.max_diff} levels</dd>` +
      `<dt>worst pixel</dt><dd id="m-worst"><a href="#" id="worst-link">(${w.x}, ${w.y})</a>: render (${w.a.join(', ')}) · reference (${w.b.join(', ')})</dd>` +
      `<dt>mean diff</dt><dd>${fmt(m.mean_diff, 4)} levels</dd>` +
      `<dt>within 0/2/8</dt><dd>${fmt(m.within_pct['0'], 3)}% · ${fmt(m.within_pct['2'], 3)}% · ${fmt(m.within_pct['8'], 3)}%</dd>` +
      `<dt>pixels off by &gt; 2</dt><dd>${m.pixels_over_2}</dd>`;
    $('worst-link').onclick = (e) => { e.preventDefault(); this.debugPixel(w.x, w.y); };
    this.draw();
  }

  // The reference's pixels, through rtk's own reader (PNG or PPM, 8-bit RGB).
  readImage(path, width, height) {
    const rtk = this.app.rtk;
    const p = rtk.call(rtk.x.rtk_read_image, [path]);
    if (!p) return null;
    const rgb = rtk.memory.slice(p, p + width * height * 3);
    rtk.x.rtk_free(p);
    return rgb;
  }

  pixelAt(e) {
    const c = $('compare-canvas'), r = c.getBoundingClientRect();
    const x = Math.floor(((e.clientX - r.left) / r.width) * this.app.width), y = Math.floor(((e.clientY - r.top) / r.height) * this.app.height);
    return x >= 0 && y >= 0 && x < this.app.width && y < this.app.height ? { x, y } : null;
  }

  hover(p) {
    const el = $('cmp-hover');
    if (!p || !this.ref?.rgb) return (el.textContent = '');
    const i = 3 * (p.y * this.app.width + p.x), a = this.app.rgb.subarray(i, i + 3), b = this.ref.rgb.subarray(i, i + 3);
    el.textContent = `(${p.x}, ${p.y}): render ${a.join(' ')} · reference ${b.join(' ')} · max diff ${Math.max(...[0, 1, 2].map((k) => Math.abs(a[k] - b[k])))}`;
  }

  draw() {
    const c = $('compare-canvas'), { width, height, rgb } = this.app;
    if (!rgb || !this.app.renderDone) return;
    const zoom = Number($('cmp-zoom').value);
    c.width = width;
    c.height = height;
    c.style.width = `${width * zoom}px`;
    c.style.height = `${height * zoom}px`;
    const right = this.mode === 'difference' ? this.diff : this.ref?.rgb;
    const split = Math.round((Number($('cmp-slider').value) / 100) * width);
    const img = c.getContext('2d').createImageData(width, height);
    for (let y = 0; y < height; y++)
      for (let x = 0; x < width; x++) {
        const i = y * width + x, src = x < split || !right ? rgb : right;
        img.data[4 * i] = src[3 * i];
        img.data[4 * i + 1] = src[3 * i + 1];
        img.data[4 * i + 2] = src[3 * i + 2];
        img.data[4 * i + 3] = 255;
      }
    const ctx = c.getContext('2d');
    ctx.putImageData(img, 0, 0);
    if (right) {
      ctx.fillStyle = '#ff3df2';
      ctx.fillRect(split - 0.5, 0, 1, height);
    }
  }
}
