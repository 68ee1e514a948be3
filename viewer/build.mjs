// Builds the viewer page into dist/: index.html, viewer.css and viewer.js (the page's
// modules and three.js from node_modules, bundled by esbuild).
import * as esbuild from 'esbuild';
import { copyFileSync, mkdirSync, rmSync } from 'node:fs';

rmSync('dist', { recursive: true, force: true });
mkdirSync('dist');
await esbuild.build({
  entryPoints: ['src/main.js'],
  bundle: true,
  format: 'esm',
  target: 'es2020',
  minify: true,
  legalComments: 'linked',
  outfile: 'dist/viewer.js',
  logLevel: 'warning',
});
copyFileSync('index.html', 'dist/index.html');
copyFileSync('src/viewer.css', 'dist/viewer.css');
console.log('viewer built into dist/');
