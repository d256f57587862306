// The files the page's WASI file system holds: the bundled corpus (listed in corpus.json,
// fetched on first use, at /cse457/...) and a folder the user opened (at /<folder>/...),
// so rtk sees the same relative layout as on disk: a scene and its assets/ folder.

let corpusFiles = null;

export async function loadManifest() {
  const res = await fetch('corpus.json');
  if (!res.ok) throw new Error(`corpus.json: ${res.status} ${res.statusText}`);
  return res.json();
}

// Every corpus file as {"/cse457/...": bytes}, fetched once.
export async function corpus(manifest) {
  if (corpusFiles) return corpusFiles;
  const entries = await Promise.all(manifest.files.map(async (path) => {
    const res = await fetch(path);
    if (!res.ok) throw new Error(`${path}: ${res.status} ${res.statusText}`);
    return ['/' + path, new Uint8Array(await res.arrayBuffer())];
  }));
  corpusFiles = Object.fromEntries(entries);
  return corpusFiles;
}

// The files of an <input webkitdirectory> as {"/<folder>/...": bytes}.
export async function fromFileList(list) {
  const entries = await Promise.all([...list].map(async (f) => ['/' + (f.webkitRelativePath || f.name), new Uint8Array(await f.arrayBuffer())]));
  return Object.fromEntries(entries);
}

// The files of a dropped folder (DataTransfer items) as {"/<folder>/...": bytes}.
export async function fromDrop(items) {
  const out = {};
  const readAll = (reader) => new Promise((resolve, reject) => {
    const all = [];
    const next = () => reader.readEntries((batch) => (batch.length ? (all.push(...batch), next()) : resolve(all)), reject);
    next();
  });
  const walk = async (entry) => {
    if (entry.isFile) {
      const file = await new Promise((resolve, reject) => entry.file(resolve, reject));
      out[entry.fullPath] = new Uint8Array(await file.arrayBuffer());
    } else if (entry.isDirectory) {
      for (const child of await readAll(entry.createReader())) await walk(child);
    }
  };
  const roots = [...items].map((i) => i.webkitGetAsEntry?.()).filter(Boolean);
  for (const e of roots) await walk(e);
  return out;
}

// The scene files among them, shortest path first.
export const sceneFiles = (files) => Object.keys(files).filter((p) => /\.ya?ml$/i.test(p)).sort((a, b) => a.split('/').length - b.split('/').length || a.localeCompare(b));
