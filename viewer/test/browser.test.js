// The viewer in Debian's Chromium, headless: engine-written recordings opened through the page's own controls,
// what the page draws read back and compared with the Rust reader's numbers, screenshots checked pixel by pixel.

import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { PNG } from 'pngjs';
import { serveViewer, launchChromium } from './support.js';
import { record, dumpFrames, OUT_DIR } from './engine.js';

/** Displayed positions are rebuilt from f32 instance matrices: agreement to 10 µm is float rounding. */
const POSITION_TOLERANCE = 1e-5;

let server;
let chromium;
let cradle;
let cradleDump;

before(async () => {
  const cradleFile = record('scenes/newtons_cradle.ron', 'cradle.rrec', 180);
  const broken = path.join(OUT_DIR, 'cradle-cut.rrec');
  const bytes = fs.readFileSync(cradleFile);
  fs.writeFileSync(broken, bytes.subarray(0, Math.floor(bytes.length * 0.6)));
  const summary = dumpFrames(cradleFile, [0]);
  const every = [];
  for (let k = 0; k < summary.frame_count; k += 3) every.push(k);
  cradleDump = dumpFrames(cradleFile, every);
  cradle = { file: cradleFile, url: '/rec/cradle.rrec', cutUrl: '/rec/cradle-cut.rrec' };
  server = await serveViewer({ '/rec/cradle.rrec': cradleFile, '/rec/cradle-cut.rrec': broken });
  chromium = await launchChromium();
});

after(async () => {
  await chromium?.close();
  await server?.close();
});

/** A fresh page with the viewer, failing the test on any uncaught page error. */
async function openViewer(query = '') {
  const page = await chromium.context.newPage();
  const errors = [];
  page.on('pageerror', (error) => errors.push(error.message));
  await page.goto(`${server.url}${query}`);
  await page.waitForFunction(() => window.rebound !== undefined);
  return { page, errors };
}

async function loaded(page) {
  await page.waitForFunction(() => window.rebound.state().loaded || window.rebound.state().message !== null);
  return page.evaluate(() => window.rebound.state());
}

/** The dumped frame whose last body is furthest (horizontally) from where it starts. */
function widestSwing(dump) {
  const last = dump.bodies.length - 1;
  const start = dump.frames[0].bodies[last].position;
  let best = dump.frames[0];
  let bestDistance = -1;
  for (const frame of dump.frames) {
    const p = frame.bodies[last].position;
    const d = Math.hypot(p[0] - start[0], p[2] - start[2]);
    if (d > bestDistance) {
      best = frame;
      bestDistance = d;
    }
  }
  return best;
}

async function screenshot(page) {
  await page.evaluate(() => window.rebound.draw());
  return PNG.sync.read(await page.screenshot());
}

function pixel(png, x, y) {
  const i = 4 * (Math.round(y) * png.width + Math.round(x));
  return [png.data[i], png.data[i + 1], png.data[i + 2]];
}

/** Pixels close to `rgb` (each channel within `tolerance`). */
function countColour(png, rgb, tolerance) {
  let n = 0;
  for (let i = 0; i < png.data.length; i += 4) {
    if (Math.abs(png.data[i] - rgb[0]) <= tolerance && Math.abs(png.data[i + 1] - rgb[1]) <= tolerance
      && Math.abs(png.data[i + 2] - rgb[2]) <= tolerance) n++;
  }
  return n;
}

const BACKGROUND = [0x1b, 0x1e, 0x24];
const CONTACT = [0xff, 0x00, 0xff];
const JOINT = [0xff, 0xd4, 0x00];
const AABB = [0x39, 0xd3, 0x53];
const near = (a, b, tolerance) => a.every((v, i) => Math.abs(v - b[i]) <= tolerance);

test('the page shows, at a stepped-to frame, the body positions the engine recorded', async () => {
  const { page, errors } = await openViewer();
  await page.setInputFiles('#file', cradle.file);
  const state0 = await loaded(page);
  assert.equal(state0.message, null);
  assert.equal(state0.frameCount, cradleDump.frame_count);

  // Scrub the timeline to just before the frame, then step onto it with the "next frame" button.
  const target = widestSwing(cradleDump);
  await page.locator('#timeline').evaluate((el, k) => {
    el.value = String(k);
    el.dispatchEvent(new Event('input'));
  }, target.index - 1);
  await page.click('#forward');
  const state = await page.evaluate(() => window.rebound.state());
  assert.equal(state.frame, target.index);
  assert.equal(state.time, target.time);
  assert.equal(await page.textContent('#frame-label').then((t) => t.startsWith(`${target.index} /`)), true);

  assert.equal(state.bodies.length, cradleDump.bodies.length);
  target.bodies.forEach((body, i) => {
    if (!body.present) return;
    const shown = state.bodies[i].position;
    for (let k = 0; k < 3; k++) {
      assert.ok(Math.abs(shown[k] - body.position[k]) <= POSITION_TOLERANCE,
        `body ${i} axis ${k}: page ${shown[k]}, recording ${body.position[k]}`);
    }
  });
  assert.deepEqual(errors, []);
  await page.close();
});

test('the screenshot has the last ball where the recording puts it, and contacts and joints add their colours', async () => {
  const { page, errors } = await openViewer(`?file=${cradle.url}`);
  await loaded(page);
  const last = cradleDump.bodies.length - 1;
  const swing = widestSwing(cradleDump);
  const start = cradleDump.frames[0].bodies[last].position;
  const radius = cradleDump.bodies[last].colliders[0].shape.Ball.radius;

  await page.evaluate((k) => {
    window.rebound.toggle('joints', false);
    window.rebound.seek(k);
  }, swing.index);
  const png = await screenshot(page);
  const at = await page.evaluate((p) => window.rebound.project(p), swing.bodies[last].position);
  const home = await page.evaluate((p) => window.rebound.project(p), start);
  const edge = await page.evaluate(
    ([p, r]) => window.rebound.project([p[0], p[1] + r, p[2]]), [swing.bodies[last].position, radius]);
  const radiusPx = Math.hypot(edge.x - at.x, edge.y - at.y);
  assert.ok(Math.hypot(at.x - home.x, at.y - home.y) > 2.2 * radiusPx,
    `the swing (${JSON.stringify(at)} from ${JSON.stringify(home)}) must be wider than the ball (${radiusPx} px)`);
  // The ball's pixels (orange: red well above blue; background, grid and the panel are grey-blue) span
  // 0.7 of its radius round the recorded centre in each direction and stop before 1.3: the drawn ball sits
  // within 0.3 radius (3 cm) of where the recording puts it.
  const isBall = (rgb) => rgb[0] > rgb[2] + 40;
  const centrePixel = pixel(png, at.x, at.y);
  assert.ok(isBall(centrePixel), `the ball's centre pixel ${centrePixel} is not the ball colour`);
  for (const [dx, dy] of [[1, 0], [-1, 0], [0, 1], [0, -1]]) {
    const inside = pixel(png, at.x + 0.7 * radiusPx * dx, at.y + 0.7 * radiusPx * dy);
    const outside = pixel(png, at.x + 1.3 * radiusPx * dx, at.y + 1.3 * radiusPx * dy);
    assert.ok(isBall(inside), `0.7 r towards (${dx}, ${dy}): ${inside} should be the ball`);
    assert.ok(!isBall(outside), `1.3 r towards (${dx}, ${dy}): ${outside} should not be the ball`);
  }
  const empty = pixel(png, home.x, home.y);
  assert.ok(near(empty, BACKGROUND, 24), `where the ball started, pixel ${empty} should be background now`);

  // Contacts: a frame with contact points, before and after toggling them on (magenta is theirs alone).
  const touching = cradleDump.frames.find((f) => f.contacts.length > 0);
  assert.ok(touching !== undefined, 'the cradle recording has contacts');
  await page.evaluate((k) => window.rebound.seek(k), touching.index);
  const without = countColour(await screenshot(page), CONTACT, 40);
  await page.check('#show-contacts');
  const withContacts = countColour(await screenshot(page), CONTACT, 40);
  assert.equal(without, 0);
  assert.ok(withContacts >= 20 * Math.min(touching.contacts.length, 4), `${withContacts} contact pixels`);

  // Joints: the cradle's ropes, drawn in their own yellow.
  const jointsOff = countColour(await screenshot(page), JOINT, 40);
  await page.check('#show-joints');
  const jointsOn = countColour(await screenshot(page), JOINT, 40);
  assert.equal(jointsOff, 0);
  assert.ok(jointsOn > 50, `${jointsOn} joint pixels`);

  // Bounding boxes: green outlines round every ball.
  const boxesOff = countColour(await screenshot(page), AABB, 40);
  await page.check('#show-aabbs');
  const boxesOn = countColour(await screenshot(page), AABB, 40);
  assert.equal(boxesOff, 0);
  assert.ok(boxesOn > 100, `${boxesOn} bounding-box pixels`);
  assert.deepEqual(errors, []);
  await page.close();
});

test('clicking a body shows its mass, velocity and contacts at that frame', async () => {
  const { page, errors } = await openViewer(`?file=${cradle.url}`);
  await loaded(page);
  const last = cradleDump.bodies.length - 1;
  const frame = widestSwing(cradleDump);
  await page.evaluate((k) => window.rebound.seek(k), frame.index);
  const at = await page.evaluate((p) => window.rebound.project(p), frame.bodies[last].position);
  await page.mouse.click(at.x, at.y);
  const state = await page.evaluate(() => window.rebound.state());
  assert.equal(state.selected, last);
  const text = await page.textContent('#inspector');
  assert.match(text, new RegExp(`^body ${last} \\(dynamic\\)`));
  assert.match(text, new RegExp(`mass +${cradleDump.bodies[last].mass.toFixed(4)} kg`));
  const v = frame.bodies[last].linear_velocity;
  const speed = Math.hypot(...v);
  const shownSpeed = Number(/\|v\| = (\S+)/.exec(text)[1]);
  assert.ok(Math.abs(shownSpeed - speed) < 1e-3, `inspector |v| ${shownSpeed}, recording ${speed}`);
  const contacts = frame.contacts.filter((c) => c.a === last || c.b === last).length;
  assert.match(text, new RegExp(`contacts +${contacts}`));
  assert.deepEqual(errors, []);
  await page.close();
});

test('play advances the frames, and pause holds them', async () => {
  const { page, errors } = await openViewer(`?file=${cradle.url}`);
  await loaded(page);
  await page.selectOption('#speed', '2');
  await page.click('#play');
  await page.waitForFunction(() => window.rebound.state().frame > 5, null, { timeout: 20000 });
  await page.click('#play');
  const paused = await page.evaluate(() => window.rebound.state());
  assert.equal(paused.playing, false);
  assert.equal(paused.speed, 2);
  await page.waitForTimeout(300);
  assert.equal(await page.evaluate(() => window.rebound.state().frame), paused.frame);
  assert.deepEqual(errors, []);
  await page.close();
});

test('a broken file shows a clear message, keeps the page working, and a cut file opens its whole frames', async () => {
  const { page, errors } = await openViewer(`?file=${cradle.url}`);
  const before = await loaded(page);

  // Dropped onto the page: bytes that are not a recording at all.
  await page.evaluate(() => {
    const transfer = new DataTransfer();
    transfer.items.add(new File(['this is not a recording, just text'], 'notes.rrec'));
    document.dispatchEvent(new DragEvent('drop', { dataTransfer: transfer, bubbles: true, cancelable: true }));
  });
  await page.waitForFunction(() => window.rebound.state().message !== null);
  const state = await page.evaluate(() => window.rebound.state());
  assert.match(state.message, /^Cannot open notes\.rrec: not a Rebound recording \(wrong magic bytes at offset 0\)$/);
  assert.equal(await page.isVisible('#message'), true);
  // The recording shown before stays, and still answers the controls.
  assert.equal(state.name, before.name);
  await page.click('#forward');
  assert.equal(await page.evaluate(() => window.rebound.state().frame), 1);

  // A recording cut short mid-frame: its complete frames open, with a message saying so.
  await page.evaluate((url) => window.rebound.openUrl(url), cradle.cutUrl);
  const cut = await page.evaluate(() => window.rebound.state());
  assert.equal(cut.name, 'cradle-cut.rrec');
  assert.ok(cut.frameCount > 0 && cut.frameCount < cradleDump.frame_count, `${cut.frameCount} frames`);
  assert.match(cut.message, /is cut short \(truncated: frame \d+ at byte \d+ needs \d+ bytes but the file ends at byte \d+\)/);

  // A missing file.
  await page.evaluate(() => window.rebound.openUrl('/rec/nothing-here.rrec'));
  assert.match(await page.evaluate(() => window.rebound.state().message), /HTTP 404/);
  assert.deepEqual(errors, []);
  await page.close();
});

test('the mouse orbits, pans and zooms the camera', async () => {
  const { page, errors } = await openViewer(`?file=${cradle.url}`);
  await loaded(page);
  const box = await page.locator('#viewport canvas').boundingBox();
  const cx = box.x + box.width / 2;
  const cy = box.y + box.height / 2;
  const camera = () => page.evaluate(() => window.rebound.state().camera);
  const distance = (c) => Math.hypot(...c.position.map((p, i) => p - c.target[i]));
  const start = await camera();

  await page.mouse.move(cx, cy);
  await page.mouse.down();
  await page.mouse.move(cx + 120, cy, { steps: 6 });
  await page.mouse.up();
  const orbited = await camera();
  // Orbiting keeps the target to rounding: the controls recompute it from the eye's spherical offset.
  assert.ok(Math.hypot(...orbited.target.map((p, i) => p - start.target[i])) < 1e-9, 'orbiting keeps the target');
  assert.ok(Math.hypot(...orbited.position.map((p, i) => p - start.position[i])) > 0.1, 'the eye moved round');
  assert.ok(Math.abs(distance(orbited) - distance(start)) < 1e-6 * distance(start), 'at the same distance');

  await page.mouse.move(cx, cy);
  await page.mouse.down({ button: 'right' });
  await page.mouse.move(cx + 80, cy + 40, { steps: 6 });
  await page.mouse.up({ button: 'right' });
  const panned = await camera();
  assert.ok(Math.hypot(...panned.target.map((p, i) => p - orbited.target[i])) > 0.01, 'panning moves the target');

  await page.mouse.move(cx, cy);
  await page.mouse.wheel(0, -400);
  await page.waitForFunction((d) => {
    const c = window.rebound.state().camera;
    return Math.hypot(...c.position.map((p, i) => p - c.target[i])) < d;
  }, distance(panned) * 0.99, { timeout: 5000 });
  assert.deepEqual(errors, []);
  await page.close();
});
