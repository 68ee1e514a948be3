// Checks committed screenshots of the viewer: each a PNG under 400 KB that is a
// picture, not a blank page: its pixels vary (standard deviation of the grey
// level) and a good share of them are neither the page's background nor white.
// Decoded by headless Chromium (Debian's /usr/bin/chromium, driven by
// playwright-core), so no image library is needed.
// Usage: node test/screenshots.mjs PNG...
import { chromium } from 'playwright-core';
import { readFileSync, statSync } from 'node:fs';
import assert from 'node:assert/strict';
import { pngStats } from './png_stats.mjs';

const MAX_BYTES = 400 * 1024;
const files = process.argv.slice(2);
if (files.length === 0) {
  console.error('usage: node test/screenshots.mjs PNG...');
  process.exit(2);
}
const browser = await chromium.launch({
  executablePath: process.env.CHROMIUM ?? '/usr/bin/chromium',
  args: ['--no-sandbox'],
});
try {
  const page = await browser.newPage();
  for (const file of files) {
    const bytes = statSync(file).size;
    assert.ok(bytes < MAX_BYTES, `${file}: ${bytes} bytes, over ${MAX_BYTES}`);
    const url = `data:image/png;base64,${readFileSync(file).toString('base64')}`;
    const s = await pngStats(page, url);
    assert.ok(s.width >= 600 && s.height >= 400, `${file}: ${s.width} x ${s.height} px`);
    assert.ok(s.sd > 15, `${file}: grey levels vary by ${s.sd.toFixed(1)} only (blank?)`);
    assert.ok(s.drawn > 0.15, `${file}: ${(100 * s.drawn).toFixed(1)} % of the pixels drawn`);
    assert.ok(s.coloured > 0.002, `${file}: ${(100 * s.coloured).toFixed(2)} % coloured pixels (no legend, triad or heat map?)`);
    console.log(`ok - ${file}: ${s.width} x ${s.height} px, ${(bytes / 1024).toFixed(0)} KB, grey s.d. ${s.sd.toFixed(1)}, ${(100 * s.drawn).toFixed(0)} % drawn, ${(100 * s.coloured).toFixed(1)} % coloured`);
  }
} finally {
  await browser.close();
}
