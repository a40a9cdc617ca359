// Drives viewer/index.html in Debian's headless Chromium (playwright-core, no browser
// download) and checks what a person would see. Run by tests/viewer.rs, which builds the
// recordings, decodes them with the Rust reader and writes the expectations to a JSON file:
//
//   node viewer_test.js <config.json>
//
// For each case: the page loads the recording (file picker from file://, or ?file= from a
// local static server on 127.0.0.1), is not blank, and at each checked frame — reached by
// scrubbing the timeline — the pixel where the page's own camera projects a body's recorded
// position shows that body's colour; a click there selects the body and the info panel shows
// its id, user_data, sleep state and speed. Screenshots go to the config's outDir.
'use strict';

const fs = require('fs');
const http = require('http');
const path = require('path');
const zlib = require('zlib');
const { chromium } = require('playwright-core');

const config = JSON.parse(fs.readFileSync(process.argv[2], 'utf8'));
let passed = 0;
let failed = 0;
function check(cond, what) {
  if (cond) { passed++; } else { failed++; console.log('FAILED: ' + what); }
}

// ---------------------------------------------------------------- PNG decoding (RGB/RGBA, 8 bit)
function decodePng(buf) {
  let at = 8, width = 0, height = 0, channels = 0;
  const idat = [];
  while (at < buf.length) {
    const len = buf.readUInt32BE(at);
    const type = buf.toString('ascii', at + 4, at + 8);
    const data = buf.subarray(at + 8, at + 8 + len);
    if (type === 'IHDR') {
      width = data.readUInt32BE(0); height = data.readUInt32BE(4);
      if (data[8] !== 8 || data[12] !== 0) throw new Error('unsupported PNG');
      channels = { 2: 3, 6: 4 }[data[9]];
      if (!channels) throw new Error('unsupported PNG colour type ' + data[9]);
    } else if (type === 'IDAT') idat.push(data);
    at += 12 + len;
  }
  const raw = zlib.inflateSync(Buffer.concat(idat));
  const stride = width * channels;
  const out = Buffer.alloc(width * height * 3);
  let prev = Buffer.alloc(stride);
  for (let y = 0; y < height; y++) {
    const filter = raw[y * (stride + 1)];
    const line = Buffer.from(raw.subarray(y * (stride + 1) + 1, (y + 1) * (stride + 1)));
    for (let i = 0; i < stride; i++) {
      const a = i >= channels ? line[i - channels] : 0, b = prev[i], c = i >= channels ? prev[i - channels] : 0;
      let p = 0;
      if (filter === 1) p = a; else if (filter === 2) p = b; else if (filter === 3) p = (a + b) >> 1;
      else if (filter === 4) { const pa = Math.abs(b - c), pb = Math.abs(a - c), pc = Math.abs(a + b - 2 * c); p = pa <= pb && pa <= pc ? a : pb <= pc ? b : c; }
      line[i] = (line[i] + p) & 255;
    }
    for (let x = 0; x < width; x++) for (let k = 0; k < 3; k++) out[3 * (y * width + x) + k] = line[x * channels + k];
    prev = line;
  }
  return { width, height, px: (x, y) => { const o = 3 * (y * width + x); return [out[o], out[o + 1], out[o + 2]]; } };
}

// ---------------------------------------------------------------- the viewer's documented colours
// viewer/README.md: dynamic bodies hue = fract(slot * 0.618034), saturation 0.6, value 0.95.
function hsv(h, s, v) {
  const i = Math.floor(h * 6), f = h * 6 - i;
  const p = v * (1 - s), q = v * (1 - f * s), t = v * (1 - (1 - f) * s);
  return [[v, t, p], [q, v, p], [p, v, t], [p, q, v], [t, p, v], [v, p, q]][i % 6];
}
function expectedColor(slot) { return hsv((slot * 0.618033988749895) % 1, 0.6, 0.95).map((c) => 255 * c); }
// Lighting multiplies the colour by one factor k: the pixel must be k × colour.
function matches(pixel, color) {
  const k = (pixel[0] * color[0] + pixel[1] * color[1] + pixel[2] * color[2]) / (color[0] ** 2 + color[1] ** 2 + color[2] ** 2);
  const residual = Math.hypot(pixel[0] - k * color[0], pixel[1] - k * color[1], pixel[2] - k * color[2]);
  return k > 0.3 && k < 1.1 && residual < 12;
}
// Most of the 5 × 5 pixels around (x, y) show the colour.
function blockMatches(img, x, y, color) {
  let n = 0;
  for (let dy = -2; dy <= 2; dy++) for (let dx = -2; dx <= 2; dx++) n += matches(img.px(x + dx, y + dy), color) ? 1 : 0;
  return n >= 13;
}

function project(cam, p) {
  const m = cam.viewProj;
  const cx = m[0] * p[0] + m[4] * p[1] + m[8] * p[2] + m[12];
  const cy = m[1] * p[0] + m[5] * p[1] + m[9] * p[2] + m[13];
  const cw = m[3] * p[0] + m[7] * p[1] + m[11] * p[2] + m[15];
  return { x: cam.left + (cx / cw + 1) / 2 * cam.width, y: cam.top + (1 - cy / cw) / 2 * cam.height, depth: cw };
}

// A static file server for ?file= (loopback only, stops with the test).
function serve(root) {
  const types = { '.html': 'text/html', '.js': 'text/javascript', '.hrec': 'application/octet-stream' };
  const server = http.createServer((req, res) => {
    const rel = decodeURIComponent(new URL(req.url, 'http://x').pathname);
    const file = path.join(root, path.normalize(rel));
    if (!file.startsWith(root) || !fs.existsSync(file) || fs.statSync(file).isDirectory()) { res.writeHead(404); res.end(); return; }
    res.writeHead(200, { 'Content-Type': types[path.extname(file)] || 'application/octet-stream' });
    fs.createReadStream(file).pipe(res);
  });
  return new Promise((resolve) => server.listen(0, '127.0.0.1', () => resolve(server)));
}

async function runCase(browser, c, server) {
  const page = await browser.newPage({ viewport: { width: 1280, height: 760 } });
  const errors = [];
  page.on('pageerror', (e) => errors.push(e.message));
  page.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
  if (c.via === 'url') {
    const port = server.address().port;
    const rel = path.relative(config.serveRoot, c.file);
    await page.goto(`http://127.0.0.1:${port}/viewer/index.html?file=/${rel.split(path.sep).join('/')}`);
  } else {
    await page.goto('file://' + path.join(config.viewerDir, 'index.html'));
    await page.setInputFiles('#file-input', c.file);
  }
  await page.waitForFunction(() => window.hearthViewer && (window.hearthViewer.ready || window.hearthViewer.error), null, { timeout: 60000 });
  const error = await page.evaluate(() => window.hearthViewer.error);
  check(error === null, `${c.name}: loads (${error})`);
  const frames = await page.evaluate(() => window.hearthViewer.frameCount());
  check(frames === c.frames, `${c.name}: ${frames} frames, the Rust reader found ${c.frames}`);
  if (c.truncated) {
    const status = await page.textContent('#status');
    check(/truncated/.test(status), `${c.name}: says it is truncated ("${status}")`);
  }
  for (const f of c.checks) {
    // Scrub: set the timeline the way a drag does (an input event), then check the label.
    await page.$eval('#timeline', (el, v) => { el.value = String(v); el.dispatchEvent(new Event('input')); }, f.frame);
    const label = await page.textContent('#frame-label');
    check(label.startsWith(`frame ${f.frame} /`), `${c.name}: scrubbed to frame ${f.frame} ("${label}")`);
    const shot = path.join(config.outDir, `${c.name}_frame${f.frame}.png`);
    const png = await page.screenshot({ path: shot });
    console.log('screenshot: ' + shot);
    const img = decodePng(png);
    const cam = await page.evaluate(() => window.hearthViewer.camera());
    // Not blank: the canvas shows several colours, and not only background.
    const colors = new Set();
    let background = 0, samples = 0;
    for (let y = Math.ceil(cam.top) + 2; y < cam.top + cam.height - 2; y += 7) {
      for (let x = Math.ceil(cam.left) + 2; x < cam.left + cam.width - 2; x += 7) {
        const p = img.px(x, y);
        colors.add(p.join(','));
        samples++;
        if (Math.abs(p[0] - 33) + Math.abs(p[1] - 38) + Math.abs(p[2] - 46) < 6) background++;
      }
    }
    check(colors.size >= 8 && samples - background >= 20, `${c.name} frame ${f.frame}: not blank (${colors.size} colours, ${background}/${samples} background)`);
    // The bodies nearest the camera whose projection lies well inside the canvas.
    // Big enough to check a 5 x 5 block: at least 5 pixels from centre to surface.
    const inside = f.bodies.map((b) => ({ b, p: project(cam, b.position) }))
      .filter(({ b, p }) => p.depth > 0 && b.extent * cam.viewProj[5] / p.depth * cam.height / 2 >= 5)
      .filter(({ p }) => p.x > cam.left + 10 && p.x < cam.left + cam.width - 10 && p.y > cam.top + 10 && p.y < cam.top + cam.height - 10)
      .sort((a, b) => a.p.depth - b.p.depth);
    check(inside.length > 0, `${c.name} frame ${f.frame}: some body projects into the canvas`);
    if (inside.length === 0) continue;
    const { b, p } = inside[0];
    const x = Math.round(p.x), y = Math.round(p.y);
    const color = expectedColor(b.index);
    check(blockMatches(img, x, y, color),
      `${c.name} frame ${f.frame}: body ${b.index} at pixel (${x}, ${y}) shows its colour ${color.map(Math.round)}; got ${img.px(x, y)}`);
    // Picking: click it; the panel names it.
    await page.mouse.click(x, y);
    const info = await page.textContent('#body-info');
    const selectedIndex = await page.evaluate(() => window.hearthViewer.selected());
    check(selectedIndex === b.index, `${c.name} frame ${f.frame}: click selects body ${b.index} (got ${selectedIndex})`);
    check(info.includes(`{index ${b.index}, generation ${b.generation}}`), `${c.name}: panel shows the id of body ${b.index}:\n${info}`);
    check(info.includes(`user_data    ${b.userData}`), `${c.name}: panel shows user_data ${b.userData}:\n${info}`);
    check(info.includes(`state        ${b.awake ? 'awake' : 'asleep'}`), `${c.name}: panel shows the sleep state:\n${info}`);
    const speed = /\|v\| ([0-9.]+) m\/s/.exec(info);
    check(speed && Math.abs(+speed[1] - b.speed) <= 0.002 + 0.001 * b.speed,
      `${c.name}: panel shows |v| ${speed && speed[1]}, recorded ${b.speed}`);
    const picked = path.join(config.outDir, `${c.name}_frame${f.frame}_picked.png`);
    await page.screenshot({ path: picked });
    console.log('screenshot: ' + picked);
  }
  // Stepping with the keyboard moves one frame.
  const before = await page.evaluate(() => window.hearthViewer.frame());
  await page.keyboard.press(before > 0 ? 'ArrowLeft' : 'ArrowRight');
  const after = await page.evaluate(() => window.hearthViewer.frame());
  check(Math.abs(after - before) === 1, `${c.name}: arrow key steps one frame (${before} -> ${after})`);
  if (c.screenshot) {
    await page.$eval('#timeline', (el, v) => { el.value = String(v); el.dispatchEvent(new Event('input')); }, c.screenshot.frame);
    await page.screenshot({ path: c.screenshot.path });
    console.log('screenshot: ' + c.screenshot.path);
  }
  check(errors.length === 0, `${c.name}: no page errors (${errors.join('; ')})`);
  await page.close();
}

(async () => {
  const started = Date.now();
  fs.mkdirSync(config.outDir, { recursive: true });
  const server = await serve(config.serveRoot);
  const userDataDir = fs.mkdtempSync(path.join(require('os').tmpdir(), 'hearth-viewer-'));
  const browser = await chromium.launchPersistentContext(userDataDir, {
    executablePath: config.chromium,
    headless: true,
    args: ['--no-sandbox', '--disable-gpu', '--use-gl=angle', '--use-angle=swiftshader', '--enable-unsafe-swiftshader',
      '--disable-quic', '--no-first-run', '--disable-background-networking', '--disable-component-update', '--disable-sync'],
  });
  try {
    for (const c of config.cases) await runCase(browser, c, server);
  } catch (e) {
    failed++;
    console.log('FAILED: ' + (e.stack || e));
  } finally {
    await browser.close();
    server.close();
    fs.rmSync(userDataDir, { recursive: true, force: true });
  }
  console.log(`viewer: ${(Date.now() - started) / 1000} s in the browser`);
  console.log(`${passed} passed, ${failed} failed`);
  process.exit(failed === 0 ? 0 : 1);
})();
