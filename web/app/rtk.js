// rtk.wasm (web/wasm/rtk_wasm*.c) in one WASI instance: files come from an in-memory
// file system (@bjorn3/browser_wasi_shim), stdout and stderr are captured per call so
// the native code's JSON and one-line errors reach the page unchanged.
import { WASI, File, Directory, PreopenDirectory, ConsoleStdout, OpenFile } from './vendor/browser_wasi_shim/index.js';

export const EXIT = { OK: 0, USAGE: 2, INPUT: 3, OUTPUT: 4, MEMORY: 5 };
export const ALL_SAMPLES = 0xffffffff;

// A tree of shim Directory/File nodes from {"/a/b.yaml": Uint8Array, ...}.
function buildTree(files) {
  const root = new Map();
  for (const [path, data] of Object.entries(files)) {
    const parts = path.split('/').filter(Boolean);
    let dir = root;
    for (const part of parts.slice(0, -1)) {
      if (!dir.has(part)) dir.set(part, new Map());
      dir = dir.get(part);
    }
    dir.set(parts[parts.length - 1], data);
  }
  const toNodes = (map) => new Map([...map].map(([name, v]) => [name, v instanceof Map ? new Directory(toNodes(v)) : new File(v, { readonly: true })]));
  return toNodes(root);
}

export class Rtk {
  // module: a compiled WebAssembly.Module of rtk.wasm; files: absolute path -> bytes.
  static async create(module, files = {}) {
    const rtk = new Rtk();
    rtk.out = [];
    rtk.err = [];
    rtk.root = new PreopenDirectory('/', buildTree(files));
    const fds = [
      new OpenFile(new File([])),
      new ConsoleStdout((bytes) => rtk.out.push(bytes.slice())),
      new ConsoleStdout((bytes) => rtk.err.push(bytes.slice())),
      rtk.root,
    ];
    rtk.wasi = new WASI(['rtk'], [], fds, { debug: false });
    rtk.instance = await WebAssembly.instantiate(module, { wasi_snapshot_preview1: rtk.wasi.wasiImport });
    rtk.wasi.initialize(rtk.instance);
    rtk.x = rtk.instance.exports;
    return rtk;
  }

  // Adds or replaces a file of the in-memory file system (parent folders are made).
  writeFile(path, bytes) {
    const parts = path.split('/').filter(Boolean);
    let dir = this.root.dir;
    for (const part of parts.slice(0, -1)) {
      if (!dir.contents.has(part)) {
        const child = new Directory(new Map());
        child.parent = dir;
        dir.contents.set(part, child);
      }
      dir = dir.contents.get(part);
    }
    dir.contents.set(parts[parts.length - 1], new File(bytes));
  }

  get memory() { return new Uint8Array(this.x.memory.buffer); }

  // Runs fn with C strings for args (freed afterwards); resets the captured output first.
  call(fn, strings = [], ...numbers) {
    this.out = [];
    this.err = [];
    const enc = new TextEncoder();
    const ptrs = strings.map((s) => {
      const bytes = enc.encode(s + '\0');
      const p = this.x.rtk_alloc(bytes.length);
      this.memory.set(bytes, p);
      return p;
    });
    try {
      return fn(...ptrs, ...numbers);
    } finally {
      ptrs.forEach((p) => this.x.rtk_free(p));
    }
  }

  static text(chunks) {
    const dec = new TextDecoder();
    return chunks.map((c) => dec.decode(c, { stream: true })).join('') + dec.decode();
  }
  stdout() { return Rtk.text(this.out); }
  // The native one-line messages, newline-free.
  stderr() { return Rtk.text(this.err).trim(); }

  // Opens a scene file; width/height 0 and depth/aa -1 keep the file's values.
  open(path, { width = 0, height = 0, depth = -1, aa = -1, maxMemoryMiB }) {
    return this.call(this.x.rtk_open, [path], width, height, depth, aa, maxMemoryMiB);
  }
  get width() { return this.x.rtk_width(); }
  get height() { return this.x.rtk_height(); }
  get samples() { return this.x.rtk_samples(); }

  pack() {
    const p = this.x.rtk_pack();
    if (!p) return null;
    return this.memory.slice(p, p + Number(this.x.rtk_blob_size()));
  }

  openBlob(bytes, maxMemoryMiB) {
    const p = this.x.rtk_alloc(bytes.length);
    this.memory.set(bytes, p);
    this.out = [];
    this.err = [];
    try {
      return this.x.rtk_open_blob(p, bytes.length, maxMemoryMiB);
    } finally {
      this.x.rtk_free(p);
    }
  }

  // Renders a region and returns its pixels, (x1 - x0) * (y1 - y0) * 3 bytes, row by row.
  renderRegion(x0, y0, x1, y1) {
    this.x.rtk_render_region(x0, y0, x1, y1);
    const w = this.width, image = this.x.rtk_image(), rowBytes = (x1 - x0) * 3;
    const out = new Uint8Array(rowBytes * (y1 - y0));
    const mem = this.memory;
    for (let y = y0; y < y1; y++) out.set(mem.subarray(image + (y * w + x0) * 3, image + (y * w + x1) * 3), (y - y0) * rowBytes);
    return out;
  }

  // SHA-256 of the P6 PPM of rgb, as hex: the render hash.
  hash(rgb, width, height) {
    const p = this.x.rtk_alloc(rgb.length + 32);
    this.memory.set(rgb, p);
    this.x.rtk_hash(p, width, height, p + rgb.length);
    const digest = this.memory.slice(p + rgb.length, p + rgb.length + 32);
    this.x.rtk_free(p);
    return [...digest].map((b) => b.toString(16).padStart(2, '0')).join('');
  }

  // `rtk debug --json` of a pixel of the open scene: {rc, text, json, error}.
  debug(x, y, sample = ALL_SAMPLES) {
    const rc = this.call(this.x.rtk_debug, [], x, y, sample);
    const text = this.stdout();
    return { rc, text, json: rc === EXIT.OK ? JSON.parse(text) : null, error: this.stderr() };
  }

  sceneView() {
    this.call(this.x.rtk_scene_json);
    const view = JSON.parse(this.stdout());
    const pos = new Float64Array(this.x.memory.buffer, this.x.rtk_positions(), view.vertex_count * 3);
    const tri = new Uint32Array(this.x.memory.buffer, this.x.rtk_triangles(), view.triangle_count * 3);
    view.positions = Float32Array.from(pos);
    view.triangles = Uint32Array.from(tri);
    return view;
  }

  // `rtk compare A B --json` on two files of the file system: {rc, text, metrics, error}.
  compare(a, b) {
    const rc = this.call(this.x.rtk_compare, [a, b]);
    const text = this.stdout();
    return { rc, text, metrics: rc === EXIT.OK ? JSON.parse(text) : null, error: this.stderr() };
  }

  // The `rtk compare --diff` heat map of two files (width * height * 3 bytes), or null.
  diffMap(a, b, width, height) {
    const p = this.call(this.x.rtk_diff_map, [a, b]);
    if (!p) return null;
    const rgb = this.memory.slice(p, p + width * height * 3);
    this.x.rtk_free(p);
    return rgb;
  }
}

// A P6 PPM file of rgb, for handing a render to rtk compare.
export function ppm(rgb, width, height) {
  const head = new TextEncoder().encode(`P6\n${width} ${height}\n255\n`);
  const out = new Uint8Array(head.length + rgb.length);
  out.set(head);
  out.set(rgb, head.length);
  return out;
}
