// Browser test of the demo's page (`index.html` that `swarf demo` writes) in headless
// Chromium (Debian's /usr/bin/chromium, or $CHROMIUM; driven by playwright-core, no
// browser downloaded), opened from disk through file:// as a reader opens it.
// Usage: node test/index_page.mjs DEMO_DIR [--shot SCREENSHOT.png]
// Checks: nothing is fetched but files under DEMO_DIR, the page renders (a screenshot
// that is not blank), its tables and pictures are there, every picture decodes,
// every relative link names a file in DEMO_DIR and every anchor a section.
import { chromium } from 'playwright-core';
import { existsSync, statSync, writeFileSync } from 'node:fs';
import { resolve, join, sep } from 'node:path';
import { pathToFileURL, fileURLToPath } from 'node:url';
import assert from 'node:assert/strict';
import { pngStats } from './png_stats.mjs';

const [dir, ...rest] = process.argv.slice(2);
const k = rest.indexOf('--shot');
const shot = k >= 0 ? rest[k + 1] : undefined;
if (!dir) {
  console.error('usage: node test/index_page.mjs DEMO_DIR [--shot SCREENSHOT.png]');
  process.exit(2);
}
const root = resolve(dir);
const index = join(root, 'index.html');

let checks = 0;
const ok = (cond, what) => {
  assert.ok(cond, what);
  checks += 1;
  console.log(`ok ${checks} - ${what}`);
};

ok(existsSync(index), `${index} exists`);
const browser = await chromium.launch({
  executablePath: process.env.CHROMIUM ?? '/usr/bin/chromium',
  args: ['--no-sandbox', '--allow-file-access-from-files'],
});
try {
  const page = await browser.newPage({ viewport: { width: 1280, height: 1500 } });
  const errors = [];
  page.on('pageerror', (e) => errors.push(e.message));
  const outside = [];
  await page.route('**/*', (route) => {
    const url = route.request().url();
    if (url.startsWith('file:') && (fileURLToPath(url) + sep).startsWith(root + sep)) return route.continue();
    outside.push(url);
    return route.abort();
  });
  await page.goto(pathToFileURL(index).href, { waitUntil: 'load' });
  ok(errors.length === 0, `no page errors (${errors.join('; ') || 'none'})`);
  ok(outside.length === 0, `nothing fetched from outside the folder (${outside.join(', ') || 'none'})`);
  ok((await page.locator('script').count()) === 0, 'the page has no script');

  const title = await page.title();
  ok(title === 'swarf demo', `title "${title}"`);
  const tables = await page.locator('table').count();
  ok(tables >= 5, `${tables} tables (contents, Table 1, five-axis, rest, edges)`);
  const sections = await page.locator('section h2').allTextContents();
  ok(sections.length === 7, `7 sections: ${sections.map((s) => s.replace(/\s+/g, ' ')).join(' | ')}`);
  ok(sections.every((s) => /\d+\.\d s$/.test(s.trim())), 'every section states its time');
  const table1 = await page.locator('table', { hasText: 'machining time' }).count();
  ok(table1 === 1, 'Table 1 (machining time, scallop, remaining material, gouge) is there');

  const images = await page.evaluate(() => [...document.images].map((i) => ({ src: i.getAttribute('src'), w: i.naturalWidth, h: i.naturalHeight })));
  ok(images.length >= 10, `${images.length} pictures`);
  const broken = images.filter((i) => !(i.w > 0 && i.h > 0)).map((i) => i.src);
  ok(broken.length === 0, `every picture decodes (${broken.join(', ') || 'all'})`);

  const links = await page.evaluate(() => [...document.querySelectorAll('a[href], img[src]')].map((e) => e.getAttribute('href') ?? e.getAttribute('src')));
  const anchors = links.filter((l) => l.startsWith('#'));
  for (const a of anchors) assert.ok(await page.locator(a).count() === 1, `anchor ${a}`);
  ok(anchors.length === sections.length, `${anchors.length} anchors, each to its section`);
  const files = links.filter((l) => !l.startsWith('#'));
  ok(files.every((l) => !/^[a-z]+:/i.test(l) && !l.startsWith('/')), 'every other link is relative');
  const dangling = files.filter((l) => {
    const p = join(root, decodeURIComponent(l));
    return !(p.startsWith(root + sep) && existsSync(p) && statSync(p).isFile());
  });
  ok(dangling.length === 0, `all ${files.length} relative links name files in the folder (${dangling.join(', ') || 'none dangling'})`);
  const views = files.filter((l) => l.endsWith('.view/index.html'));
  ok(views.length >= 1, `${views.length} links to 3D views`);

  const png = await page.screenshot({ fullPage: false });
  const stats = await pngStats(page, `data:image/png;base64,${png.toString('base64')}`);
  ok(stats.notWhite > 0.03, `the screenshot is not blank (${(100 * stats.notWhite).toFixed(1)} % of its pixels drawn)`);
  if (shot) {
    writeFileSync(shot, png);
    console.log(`screenshot: ${shot} (${png.length} bytes)`);
  }
} finally {
  await browser.close();
}
console.log(`${checks} passed, 0 failed`);
