// Render time of each corpus scene in the page (headless Chromium, one worker per core)
// next to native build/rtk (all cores) on the same machine; checks the hashes agree.
// Prints a Markdown table for docs/web.md. Not a test: timings vary with the machine's load.
//   node web/test/timings.mjs URL [SCENE=OPTIONS ...]   e.g. more/cornell_ray.yaml="--width 128 --height 128"
import { chromium } from 'playwright-core';
import { spawnSync } from 'node:child_process';
import { mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join, resolve } from 'node:path';

const [url, ...overrides] = process.argv.slice(2);
const root = resolve(new URL('../..', import.meta.url).pathname);
const corpus = join(resolve(process.env.RTK_SHARED || join(root, '../shared')), 'cse457/assets/trace');
const options = Object.fromEntries(overrides.map((o) => [o.slice(0, o.indexOf('=')), o.slice(o.indexOf('=') + 1).split(' ').filter(Boolean)]));
const profile = mkdtempSync(join(tmpdir(), 'rtk-web-timings-'));
const context = await chromium.launchPersistentContext(profile, {
  executablePath: '/usr/bin/chromium', headless: true,
  args: ['--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run', '--disable-background-networking', '--disable-component-update', '--disable-sync'],
});
const page = context.pages()[0] || (await context.newPage());
try {
  await page.goto(url);
  await page.waitForFunction(() => window.rtkApp?.ready && !rtkApp.busy, null, { timeout: 60000 });
  const scenes = await page.evaluate(() => rtkApp.manifest.scenes);
  console.log('| scene | options | browser s | native s | same hash |\n|---|---|---|---|---|');
  for (const path of scenes) {
    const scene = path.replace('cse457/assets/trace/', '');
    const opts = options[scene] || [];
    const value = (flag) => (opts.includes(flag) ? opts[opts.indexOf(flag) + 1] : '');
    await page.fill('#opt-width', value('--width'));
    await page.fill('#opt-height', value('--height'));
    await page.evaluate((p) => { rtkApp.renderDone = false; rtkApp.lastError = ''; rtkApp.openAndRender(p); }, path);
    await page.waitForFunction(() => rtkApp.renderDone || (rtkApp.lastError && !rtkApp.busy), null, { timeout: 900000 });
    const got = await page.evaluate(() => ({ hash: document.getElementById('stat-hash').textContent, seconds: rtkApp.renderSeconds, error: rtkApp.lastError }));
    if (got.error) {
      console.log(`| ${scene} | ${opts.join(' ')} | not rendered: ${got.error.replace(/\|/g, '\\|')} | | |`);
      continue;
    }
    const start = process.hrtime.bigint();
    const native = spawnSync(join(root, 'build/rtk'), ['render', join(corpus, scene), '--hash', '--quiet', ...opts], { encoding: 'utf8' });
    const seconds = Number(process.hrtime.bigint() - start) / 1e9;
    console.log(`| ${scene} | ${opts.join(' ')} | ${got.seconds.toFixed(2)} | ${seconds.toFixed(2)} | ${native.stdout.trim() === got.hash ? 'yes' : 'NO'} |`);
  }
} finally {
  await context.close();
  rmSync(profile, { recursive: true, force: true });
}
