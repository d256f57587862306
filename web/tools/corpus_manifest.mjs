// Lists the corpus copied into the site (SITE/cse457) as SITE/corpus.json: every file the
// page loads into its WASI file system, the scenes (assets/trace/**/*.yaml) and the
// solution images (assets/trace/solution/*.png).   node corpus_manifest.mjs SITE
import { readdirSync, writeFileSync } from 'node:fs';
import { join, relative } from 'node:path';

const site = process.argv[2];
const files = readdirSync(join(site, 'cse457'), { recursive: true, withFileTypes: true })
  .filter((e) => e.isFile())
  .map((e) => relative(site, join(e.parentPath ?? e.path, e.name)).split('\\').join('/'))
  .sort();
const scenes = files.filter((f) => f.startsWith('cse457/assets/trace/') && f.endsWith('.yaml'));
const solutions = files.filter((f) => f.startsWith('cse457/assets/trace/solution/') && f.endsWith('.png'));
writeFileSync(join(site, 'corpus.json'), JSON.stringify({ files, scenes, solutions }, null, 1) + '\n');
console.log(`corpus.json: ${files.length} files, ${scenes.length} scenes, ${solutions.length} solutions`);
