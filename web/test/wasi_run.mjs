// Runs a wasm32-wasi command under node's built-in WASI with the host's file system
// ("/" preopened) and returns its exit code:  node web/test/wasi_run.mjs PROGRAM.wasm ARGS...
// wasi-libc resolves relative paths against "/", so pass absolute paths. Run node with
// --single-threaded: node 20 otherwise crashes (SIGSEGV) at exit, after the program has
// finished, once the instance's memory has grown past about 64 MiB (a background
// compiler thread, it seems; the flag makes it go away).
import { WASI } from 'node:wasi';
import { readFileSync } from 'node:fs';
import { basename } from 'node:path';

const [program, ...args] = process.argv.slice(2);
const wasi = new WASI({ version: 'preview1', args: [basename(program, '.wasm'), ...args], env: {}, preopens: { '/': '/' }, returnOnExit: true });
const module = await WebAssembly.compile(readFileSync(program));
const instance = await WebAssembly.instantiate(module, wasi.getImportObject());
process.exitCode = wasi.start(instance);
