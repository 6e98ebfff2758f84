// Measures how fast the viewer plays the 4,096-ball pile back in headless Chromium, with the page's own frame
// counter (frames drawn per second of wall time while playing at 1×).
//
//   node scripts/measure_fps.js [--seconds S] [--steps N]
//
// Records the pile with the `rebound` command first (see test/engine.js). Wall time depends on the machine and
// on what else runs on it: state both when quoting the result.

import os from 'node:os';
import { serveViewer, launchChromium } from '../test/support.js';
import { record } from '../test/engine.js';

const argument = (name, fallback) => {
  const i = process.argv.indexOf(name);
  return i > 0 ? Number(process.argv[i + 1]) : fallback;
};
const seconds = argument('--seconds', 10);
const steps = argument('--steps', 240);

const file = record('scenes/benchmarks/balls.ron', 'pile.rrec', steps);
const server = await serveViewer({ '/rec/pile.rrec': file });
const chromium = await launchChromium();
try {
  const page = await chromium.context.newPage();
  await page.goto(`${server.url}?file=/rec/pile.rrec`);
  await page.waitForFunction(() => window.rebound?.state().loaded, null, { timeout: 120000 });
  const bodies = await page.evaluate(() => window.rebound.state().bodies.length);
  await page.evaluate(() => window.rebound.play());
  await page.waitForTimeout(2000); // warm-up: shader compilation, first uploads
  const start = await page.evaluate(() => ({ drawn: window.rebound.fps().drawn, at: performance.now(),
    frame: window.rebound.state().frame }));
  await page.waitForTimeout(seconds * 1000);
  const end = await page.evaluate(() => ({ drawn: window.rebound.fps().drawn, at: performance.now(),
    frame: window.rebound.state().frame }));
  const size = await page.evaluate(() => {
    const c = document.querySelector('#viewport canvas');
    return `${c.width}×${c.height}`;
  });
  const fps = ((end.drawn - start.drawn) * 1000) / (end.at - start.at);
  const load = os.loadavg()[0].toFixed(1);
  process.stdout.write(
    `pile: ${bodies} bodies, ${steps} recorded steps; canvas ${size}; ` +
      `${fps.toFixed(1)} frames drawn per second over ${seconds} s (load average ${load} on ${os.cpus().length} cores)\n`,
  );
} finally {
  await chromium.close();
  await server.close();
}
