// A progressive tiled render over Web Workers, one per hardware core: each worker builds
// the scene from the same blob and renders the tiles it is handed; the page assembles
// them. Every pixel depends on the scene alone, so the image (and its hash) is the one
// `rtk render` makes whatever the worker count or tile order.

export const TILE = 32;

// Tiles in rings around the image's centre, so the middle of the picture comes first.
function tiles(width, height) {
  const list = [];
  for (let y = 0; y < height; y += TILE)
    for (let x = 0; x < width; x += TILE) list.push({ x0: x, y0: y, x1: Math.min(x + TILE, width), y1: Math.min(y + TILE, height) });
  const cx = width / 2, cy = height / 2;
  const ring = (t) => Math.max(Math.abs((t.x0 + t.x1) / 2 - cx), Math.abs((t.y0 + t.y1) / 2 - cy));
  return list.sort((a, b) => ring(a) - ring(b));
}

export class TiledRender {
  // onTile(tile, rgb) after each tile, with the tiles done and the total.
  constructor({ module, blob, width, height, maxMemoryMiB, workers, onTile }) {
    Object.assign(this, { module, blob, width, height, maxMemoryMiB, onTile });
    this.workerCount = workers;
    this.rgb = new Uint8Array(width * height * 3);
    this.queue = tiles(width, height);
    this.total = this.queue.length;
    this.done = 0;
    this.workers = [];
    this.cancelled = false;
  }

  // Resolves with the image when every tile is in; rejects on a worker's error or cancel().
  run() {
    return new Promise((resolve, reject) => {
      this.reject = reject;
      const n = Math.max(1, Math.min(this.workerCount, this.total));
      for (let i = 0; i < n; i++) {
        const worker = new Worker(new URL('./render_worker.js', import.meta.url), { type: 'module' });
        this.workers.push(worker);
        worker.onmessage = ({ data }) => {
          if (this.cancelled) return;
          if (data.type === 'error') {
            this.stop();
            reject(Object.assign(new Error(data.error), { rc: data.rc }));
            return;
          }
          if (data.type === 'tile') {
            const rowBytes = (data.x1 - data.x0) * 3;
            for (let y = data.y0; y < data.y1; y++)
              this.rgb.set(data.rgb.subarray((y - data.y0) * rowBytes, (y - data.y0 + 1) * rowBytes), (y * this.width + data.x0) * 3);
            this.done++;
            this.onTile?.(data, this.done, this.total);
            if (this.done === this.total) {
              this.stop();
              resolve(this.rgb);
              return;
            }
          }
          const next = this.queue.shift();
          if (next) worker.postMessage({ type: 'tile', ...next });
        };
        worker.onerror = (e) => {
          this.stop();
          reject(new Error(`render worker failed: ${e.message}`));
        };
        worker.postMessage({ type: 'open', module: this.module, blob: this.blob, maxMemoryMiB: this.maxMemoryMiB });
      }
    });
  }

  get liveWorkers() { return this.workers.length; }

  stop() {
    this.workers.forEach((w) => w.terminate());
    this.workers = [];
  }

  cancel() {
    if (this.cancelled) return;
    this.cancelled = true;
    this.stop();
    this.reject?.(Object.assign(new Error('cancelled'), { cancelled: true }));
  }
}
