// One render worker: builds the scene from a blob (rtk pack's bytes) in its own rtk.wasm
// instance, then renders the tiles the page hands it, one at a time.
import { Rtk, EXIT } from './rtk.js';

let rtk = null;

onmessage = async ({ data }) => {
  if (data.type === 'open') {
    rtk = await Rtk.create(data.module);
    const rc = rtk.openBlob(data.blob, data.maxMemoryMiB);
    postMessage(rc === EXIT.OK ? { type: 'ready' } : { type: 'error', rc, error: rtk.stderr() });
  } else if (data.type === 'tile') {
    const { x0, y0, x1, y1 } = data;
    const rgb = rtk.renderRegion(x0, y0, x1, y1);
    postMessage({ type: 'tile', x0, y0, x1, y1, rgb }, [rgb.buffer]);
  }
};
