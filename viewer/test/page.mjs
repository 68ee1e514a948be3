// Opens a view folder's page in headless Chromium (Debian's /usr/bin/chromium, or
// $CHROMIUM; driven by playwright-core, no browser downloaded), served by a small
// static server on 127.0.0.1. Shared by the browser test and the screenshot script.
import { chromium } from 'playwright-core';
import { createServer } from 'node:http';
import { readFileSync } from 'node:fs';
import { extname, join, normalize } from 'node:path';

const types = { '.html': 'text/html', '.js': 'text/javascript', '.css': 'text/css', '.json': 'application/json', '.glb': 'model/gltf-binary' };

// The page of `dir`, loaded and ready: { page, close }.
export async function openView(dir, viewport = { width: 1200, height: 800 }) {
  const server = createServer((req, res) => {
    const rel = normalize(decodeURIComponent(req.url.split('?')[0])).replace(/^\/+/, '') || 'index.html';
    try {
      const body = readFileSync(join(dir, rel));
      res.writeHead(200, { 'Content-Type': types[extname(rel)] ?? 'application/octet-stream' });
      res.end(body);
    } catch {
      res.writeHead(404);
      res.end();
    }
  });
  await new Promise((ok) => server.listen(0, '127.0.0.1', ok));
  const browser = await chromium.launch({
    executablePath: process.env.CHROMIUM ?? '/usr/bin/chromium',
    args: ['--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--no-sandbox'],
  });
  const close = async () => {
    await browser.close();
    server.close();
  };
  try {
    const page = await browser.newPage({ viewport });
    page.on('pageerror', (e) => console.error('page error:', e.message));
    await page.goto(`http://127.0.0.1:${server.address().port}/`);
    await page.waitForFunction(() => window.swarfView && (window.swarfView.ready || window.swarfView.error), null, { timeout: 120000 });
    return { page, close };
  } catch (e) {
    await close();
    throw e;
  }
}
