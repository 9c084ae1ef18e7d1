// Headless-browser test of the scene viewer (issue 15 part 4).
//
//   node test/screenshot.mjs URL OUT.png [OBJECT_ID]
//
// URL is a running `scenesmith view DIR` (e.g. http://127.0.0.1:PORT/). The test drives Debian's
// chromium through playwright-core and checks, through the page and through pixels:
//   1. the page reports ready (window.scenesmithViewer.ready) and the view is not blank;
//   2. a click at the object's projected screen point selects it: the info panel shows its id and
//      the screenshot (written to OUT.png) has highlight-coloured pixels, at the click, that the
//      screenshot before the click did not have;
//   3. unticking a kind (manipuland if present) changes the image, ticking it again restores it;
//   4. choosing a room in the room selector frames that room's floor polygon;
//   5. dragging orbits the camera without changing the selection;
//   6. the page logged no console error and threw nothing.
// Side screenshots go next to OUT.png as OUT-before.png, OUT-hidden.png, OUT-room.png, and
// OUT-failure.png when a check fails.
// Exits 0 on success, 1 with a message on the first failure, 2 on bad usage.

import { chromium } from 'playwright-core';
import { PNG } from 'pngjs';
import { mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';

const CHROMIUM = process.env.SCENESMITH_CHROMIUM ?? '/usr/bin/chromium';
const VIEWPORT = { width: 1280, height: 800 };
const READY_TIMEOUT_MS = 60_000;
const STEP_TIMEOUT_MS = 10_000;

// Must match main.js. The highlight is magenta (0xff00ff) shaded by the lights, with an emissive
// floor: green stays 0, red and blue stay above ~170 and close to each other.
const isHighlight = (r, g, b) => g <= 30 && r >= 150 && b >= 150 && Math.abs(r - b) <= 40;
// BACKGROUND_COLOR (0xdde3ea).
const isBackground = (r, g, b) =>
  Math.abs(r - 0xdd) <= 3 && Math.abs(g - 0xe3) <= 3 && Math.abs(b - 0xea) <= 3;

// Pixel thresholds, on the canvas region of a 1280x800 page (canvas 1000x800 CSS px at scale 1).
const THRESHOLDS = {
  minDistinctColors: 256, // a rendered textured room has thousands; a blank canvas has 1
  minLumaStdDev: 8, // grey levels (0-255)
  maxBackgroundFraction: 0.9, // the room must cover at least 10 % of the view
  minHighlightPixels: 100, // after the click (a small vase shows ~250, the bed ~30000)
  maxHighlightPixelsBefore: 50, // before the click: magenta does not occur in the scene
  clickRadiusPx: 6, // highlight pixels must be found this close to the click point...
  minHighlightNearClick: 5, // ...at least this many
  minChangedPixelsOnHide: 500, // hiding a kind must change at least this many pixels
  maxChangedPixelsOnShow: 50, // showing it again must restore the image (bar a few AA pixels)
  pixelDiffLevel: 24, // a pixel "changed" when a channel differs by more than this
  roomTargetToleranceM: 0.01,
};

const KIND_PREFERENCE = ['furniture', 'wall', 'ceiling', 'manipuland'];

class Failure extends Error {}

function check(condition, message) {
  if (!condition) throw new Failure(message);
}

async function main() {
  const [url, outPath, objectId] = process.argv.slice(2);
  if (!url || !outPath || process.argv.length > 5) {
    console.error('usage: node screenshot.mjs URL OUT.png [OBJECT_ID]');
    process.exit(2);
  }
  const userDataDir = mkdtempSync(join(tmpdir(), 'scenesmith-view-test-'));
  let context;
  try {
    context = await launch(userDataDir);
    const page = context.pages()[0] ?? (await context.newPage());
    const errors = collectPageErrors(page);
    try {
      await runChecks(page, url, outPath, objectId);
    } catch (error) {
      // What the page looked like when the check failed; best effort, the failure is what counts.
      await page.screenshot({ path: sidePath(outPath, 'failure') }).catch(() => {});
      throw error;
    }
    check(errors.length === 0, `the page logged errors:\n  ${errors.join('\n  ')}`);
    console.log(`viewer test passed; screenshot ${outPath}`);
  } finally {
    await context?.close();
    rmSync(userDataDir, { recursive: true, force: true });
  }
}

async function launch(userDataDir) {
  // Playwright's own browser download does not work offline; Debian's chromium does. The
  // user-data dir is fresh per run so no profile state leaks between runs.
  return chromium.launchPersistentContext(userDataDir, {
    executablePath: CHROMIUM,
    headless: true,
    viewport: VIEWPORT,
    deviceScaleFactor: 1,
    args: [
      '--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
      '--disable-background-networking', '--disable-component-update', '--disable-sync',
      // Without a GPU, WebGL needs SwiftShader, which recent Chromium only enables on request.
      '--enable-unsafe-swiftshader', '--use-angle=swiftshader',
    ],
  });
}

/** Console errors and uncaught exceptions, except the 404 of an absent (optional) metrics.json. */
function collectPageErrors(page) {
  const errors = [];
  page.on('console', (message) => {
    if (message.type() !== 'error') return;
    const optionalMissing = message.text().startsWith('Failed to load resource')
      && message.location().url.endsWith('/scene/metrics.json');
    if (!optionalMissing) errors.push(`console: ${message.text()} (${message.location().url})`);
  });
  page.on('pageerror', (error) => errors.push(`exception: ${error.message}`));
  return errors;
}

async function runChecks(page, url, outPath, objectId) {
  await page.goto(url, { timeout: STEP_TIMEOUT_MS });
  await waitForReady(page);
  const canvasBox = await page.locator('#viewport canvas').boundingBox();
  check(canvasBox && canvasBox.width > 100 && canvasBox.height > 100, 'no canvas in #viewport');
  const shoot = async (path) => {
    await settle(page);
    const png = await page.screenshot({ path });
    return cropToCanvas(PNG.sync.read(png), canvasBox);
  };
  const side = (suffix) => sidePath(outPath, suffix);

  // 1. Not blank.
  const before = await shoot(side('before'));
  checkNotBlank(before, 'before the click');

  // 2. Pick by clicking, check the panel and the highlight.
  const id = objectId ?? (await choosePickable(page));
  const point = await page.evaluate((i) => window.scenesmithViewer.screenPoint(i), id);
  check(point, `object ${id} is not visible in the default view`);
  check(point.hit, `no point of ${id} is reachable by a click in the default view`);
  await page.mouse.click(point.x, point.y);
  await page.waitForFunction((i) => window.scenesmithViewer.selected === i, id,
    { timeout: STEP_TIMEOUT_MS }).catch(() => {
    throw new Failure(`clicking at (${point.x.toFixed(0)}, ${point.y.toFixed(0)}) did not select ${id}`);
  });
  const shownId = await page.locator('#info dd[data-field="id"]').textContent();
  check(shownId === id, `info panel shows id "${shownId}", expected "${id}"`);
  const after = await shoot(outPath);
  checkNotBlank(after, 'after the click');
  checkHighlight(before, after, { x: point.x - canvasBox.x, y: point.y - canvasBox.y }, id);

  // 3. Hide and show a kind through its checkbox.
  await checkKindToggle(page, after, shoot, side('hidden'), id);

  // 4. Focus a room through the room selector.
  await checkRoomFocus(page, shoot, side('room'));

  // 5. A drag orbits the camera and is not taken for a click.
  await checkOrbitDrag(page, canvasBox);
}

/** OUT.png -> OUT-suffix.png */
function sidePath(outPath, suffix) {
  return outPath.replace(/(\.png)?$/i, `-${suffix}.png`);
}

async function waitForReady(page) {
  try {
    await page.waitForFunction(
      () => window.scenesmithViewer && (window.scenesmithViewer.ready || window.scenesmithViewer.error),
      null, { timeout: READY_TIMEOUT_MS });
  } catch {
    throw new Failure(`the viewer did not become ready within ${READY_TIMEOUT_MS / 1000} s`);
  }
  const error = await page.evaluate(() => window.scenesmithViewer.error);
  check(!error, `the viewer reported: ${error}`);
}

/** Two animation frames: the last render has been composited before the screenshot. */
async function settle(page) {
  await page.evaluate(() => new Promise((resolve) => {
    requestAnimationFrame(() => requestAnimationFrame(resolve));
  }));
}

/** The first object, furniture preferred, that a click in the default view reaches. */
async function choosePickable(page) {
  const id = await page.evaluate((preference) => {
    const viewer = window.scenesmithViewer;
    const rank = (id) => {
      const index = preference.indexOf(viewer.describe(id).kind);
      return index === -1 ? preference.length : index;
    };
    const ordered = [...viewer.objects].sort((a, b) => rank(a) - rank(b));
    return ordered.find((id) => viewer.screenPoint(id)?.hit) ?? null;
  }, KIND_PREFERENCE);
  check(id, 'no object can be clicked in the default view');
  return id;
}

async function checkKindToggle(page, shown, shoot, hiddenPath, selectedId) {
  const kinds = await page.evaluate(() =>
    [...document.querySelectorAll('#kinds input[data-kind]')].map((box) => box.dataset.kind));
  const kind = kinds.includes('manipuland') ? 'manipuland'
    : kinds.find((k) => k !== 'architecture');
  check(kind, `no kind to hide (kinds: ${kinds.join(', ')})`);
  const selectedKind = await page.evaluate((i) => window.scenesmithViewer.describe(i).kind, selectedId);
  const box = page.locator(`#kinds input[data-kind="${kind}"]`);

  await box.uncheck();
  const hidden = await shoot(hiddenPath);
  const changedOnHide = changedPixels(shown, hidden);
  check(changedOnHide >= THRESHOLDS.minChangedPixelsOnHide,
    `hiding ${kind} changed ${changedOnHide} pixels (< ${THRESHOLDS.minChangedPixelsOnHide})`);

  await box.check();
  const reshown = await shoot();
  // Hiding the selected object's kind clears the selection, so the image cannot come back.
  if (selectedKind !== kind) {
    const changedOnShow = changedPixels(shown, reshown);
    check(changedOnShow <= THRESHOLDS.maxChangedPixelsOnShow,
      `showing ${kind} again left ${changedOnShow} pixels different (> ${THRESHOLDS.maxChangedPixelsOnShow})`);
  }
}

async function checkRoomFocus(page, shoot, roomPath) {
  // scene.json straight from the server, so the expected frame is computed independently of the page.
  const rooms = await page.evaluate(async () => {
    const response = await fetch('scene/scene.json');
    return response.ok ? (await response.json()).rooms ?? [] : [];
  });
  if (rooms.length === 0) {
    console.log('no rooms in scene.json: room focus not tested');
    return;
  }
  const room = rooms[rooms.length - 1];
  await page.selectOption('#rooms', room.id);
  const state = await page.evaluate(() => ({
    focused: window.scenesmithViewer.focusedRoom,
    target: window.scenesmithViewer.view().target,
  }));
  check(state.focused === room.id, `room selector: focusedRoom is ${state.focused}, expected ${room.id}`);
  const expected = roomCenterInGltf(room);
  const error = Math.hypot(...state.target.map((v, i) => v - expected[i]));
  check(error <= THRESHOLDS.roomTargetToleranceM,
    `focusing ${room.id}: camera target ${fmt(state.target)} is ${error.toFixed(3)} m from the `
    + `room's centre ${fmt(expected)} (glTF frame)`);
  checkNotBlank(await shoot(roomPath), `focused on ${room.id}`);
}

async function checkOrbitDrag(page, canvasBox) {
  const state = () => page.evaluate(() => ({
    selected: window.scenesmithViewer.selected,
    position: window.scenesmithViewer.view().position,
  }));
  const before = await state();
  const x = canvasBox.x + canvasBox.width / 2;
  const y = canvasBox.y + canvasBox.height / 2;
  await page.mouse.move(x, y);
  await page.mouse.down();
  await page.mouse.move(x + 120, y + 40, { steps: 8 });
  await page.mouse.up();
  const after = await state();
  const moved = Math.hypot(...after.position.map((v, i) => v - before.position[i]));
  check(moved > 0.1, `dragging across the view moved the camera only ${moved.toFixed(3)} m`);
  check(after.selected === before.selected,
    `dragging changed the selection from ${before.selected} to ${after.selected}`);
}

/** Centre of the room's floor-polygon box up to its wall height, Z-up scene -> Y-up glTF. */
function roomCenterInGltf(room) {
  const xs = room.floor_polygon.map((p) => p[0]);
  const ys = room.floor_polygon.map((p) => p[1]);
  const mid = (v) => (Math.min(...v) + Math.max(...v)) / 2;
  return [mid(xs), (room.wall_height ?? 2.5) / 2, -mid(ys)];
}

const fmt = (v) => `(${v.map((x) => x.toFixed(2)).join(', ')})`;

// ---------------------------------------------------------------- pixel checks

function cropToCanvas(png, box) {
  const x0 = Math.round(box.x);
  const y0 = Math.round(box.y);
  const width = Math.min(Math.round(box.width), png.width - x0);
  const height = Math.min(Math.round(box.height), png.height - y0);
  const data = Buffer.alloc(width * height * 4);
  for (let y = 0; y < height; y++) {
    png.data.copy(data, y * width * 4, ((y0 + y) * png.width + x0) * 4, ((y0 + y) * png.width + x0 + width) * 4);
  }
  return { width, height, data };
}

function* pixels(image) {
  for (let i = 0; i < image.data.length; i += 4) {
    yield [image.data[i], image.data[i + 1], image.data[i + 2], i / 4];
  }
}

function checkNotBlank(image, when) {
  const colors = new Set();
  let background = 0;
  let sum = 0;
  let sumSquares = 0;
  for (const [r, g, b] of pixels(image)) {
    colors.add((r << 16) | (g << 8) | b);
    if (isBackground(r, g, b)) background++;
    const luma = 0.299 * r + 0.587 * g + 0.114 * b;
    sum += luma;
    sumSquares += luma * luma;
  }
  const n = image.width * image.height;
  const stdDev = Math.sqrt(Math.max(0, sumSquares / n - (sum / n) ** 2));
  const backgroundFraction = background / n;
  const t = THRESHOLDS;
  check(colors.size >= t.minDistinctColors,
    `${when}: ${colors.size} distinct colours (< ${t.minDistinctColors}): the view looks blank`);
  check(stdDev >= t.minLumaStdDev,
    `${when}: luminance std-dev ${stdDev.toFixed(1)} (< ${t.minLumaStdDev}): the view looks blank`);
  check(backgroundFraction <= t.maxBackgroundFraction,
    `${when}: ${(100 * backgroundFraction).toFixed(1)} % background (> ${100 * t.maxBackgroundFraction} %)`);
}

function countHighlight(image) {
  let count = 0;
  for (const [r, g, b] of pixels(image)) if (isHighlight(r, g, b)) count++;
  return count;
}

function checkHighlight(before, after, click, id) {
  const t = THRESHOLDS;
  const countBefore = countHighlight(before);
  const countAfter = countHighlight(after);
  check(countBefore <= t.maxHighlightPixelsBefore,
    `${countBefore} highlight-coloured pixels before any click (> ${t.maxHighlightPixelsBefore})`);
  check(countAfter >= t.minHighlightPixels,
    `${id} picked but only ${countAfter} highlight-coloured pixels (< ${t.minHighlightPixels})`);
  let near = 0;
  const r = t.clickRadiusPx;
  for (let y = Math.round(click.y) - r; y <= Math.round(click.y) + r; y++) {
    for (let x = Math.round(click.x) - r; x <= Math.round(click.x) + r; x++) {
      if (x < 0 || y < 0 || x >= after.width || y >= after.height) continue;
      const i = (y * after.width + x) * 4;
      if (isHighlight(after.data[i], after.data[i + 1], after.data[i + 2])) near++;
    }
  }
  check(near >= t.minHighlightNearClick,
    `${id} picked but only ${near} highlight pixels within ${r} px of the click (< ${t.minHighlightNearClick})`);
  console.log(`highlight: ${countBefore} -> ${countAfter} pixels, ${near} near the click`);
}

function changedPixels(a, b) {
  let changed = 0;
  for (let i = 0; i < a.data.length; i += 4) {
    if (Math.abs(a.data[i] - b.data[i]) > THRESHOLDS.pixelDiffLevel
      || Math.abs(a.data[i + 1] - b.data[i + 1]) > THRESHOLDS.pixelDiffLevel
      || Math.abs(a.data[i + 2] - b.data[i + 2]) > THRESHOLDS.pixelDiffLevel) changed++;
  }
  return changed;
}

main().catch((error) => {
  console.error(`viewer test FAILED: ${error instanceof Failure ? error.message : error.stack ?? error}`);
  process.exit(1);
});
