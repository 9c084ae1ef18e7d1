// Bundles the viewer into one directory the Rust server serves as-is:
//   node build.mjs OUT_DIR   ->  OUT_DIR/{index.html, style.css, main.js, main.js.map}
// three.js comes from node_modules, so the page fetches nothing from the internet at run time.

import * as esbuild from 'esbuild';
import { copyFileSync, mkdirSync, rmSync } from 'node:fs';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';

const STATIC_FILES = ['index.html', 'style.css'];

const outDir = process.argv[2];
if (!outDir || process.argv.length > 3) {
  console.error('usage: node build.mjs OUT_DIR');
  process.exit(2);
}
const webDir = dirname(fileURLToPath(import.meta.url));
const out = resolve(outDir);

// Start clean so a renamed or removed file does not linger in the bundle.
rmSync(out, { recursive: true, force: true });
mkdirSync(out, { recursive: true });

try {
  await esbuild.build({
    entryPoints: [join(webDir, 'main.js')],
    outfile: join(out, 'main.js'),
    bundle: true,
    format: 'esm',
    target: 'es2020',
    minify: true,
    sourcemap: true,
    logLevel: 'warning',
  });
} catch {
  // esbuild has already printed the errors with file and line.
  process.exit(1);
}
for (const file of STATIC_FILES) copyFileSync(join(webDir, file), join(out, file));
