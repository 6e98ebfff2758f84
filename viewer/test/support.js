// Shared test plumbing: a static file server for the viewer on 127.0.0.1, and Debian's Chromium launched
// headless through playwright-core (never a downloaded browser).

import http from 'node:http';
import fs from 'node:fs';
import path from 'node:path';
import os from 'node:os';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';

export const VIEWER_DIR = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
export const REPO_DIR = path.resolve(VIEWER_DIR, '..');

const TYPES = {
  '.html': 'text/html; charset=utf-8',
  '.js': 'text/javascript; charset=utf-8',
  '.css': 'text/css; charset=utf-8',
  '.json': 'application/json',
};

/**
 * Serves the viewer directory, plus `extra` (URL path → file on disk), on a free loopback port.
 * @returns {Promise<{url: string, close: () => Promise<void>}>}
 */
export async function serveViewer(extra = {}) {
  const server = http.createServer((request, response) => {
    const urlPath = decodeURIComponent(new URL(request.url, 'http://localhost').pathname);
    const file = extra[urlPath] ?? path.join(VIEWER_DIR, urlPath === '/' ? 'index.html' : urlPath);
    if (!file.startsWith(VIEWER_DIR) && !Object.values(extra).includes(file)) {
      response.writeHead(403).end();
      return;
    }
    fs.readFile(file, (error, data) => {
      if (error) {
        response.writeHead(404).end('not found');
        return;
      }
      response.writeHead(200, { 'content-type': TYPES[path.extname(file)] ?? 'application/octet-stream' });
      response.end(data);
    });
  });
  await new Promise((resolve) => server.listen(0, '127.0.0.1', resolve));
  const { port } = server.address();
  return {
    url: `http://127.0.0.1:${port}/`,
    close: () => new Promise((resolve) => server.close(resolve)),
  };
}

/** Debian's Chromium, headless, in a fresh profile directory (removed on close). */
export async function launchChromium() {
  const profile = fs.mkdtempSync(path.join(os.tmpdir(), 'rebound-viewer-chromium-'));
  // playwright takes the profile directory as launchPersistentContext's first argument (it refuses
  // --user-data-dir in args); the context is a fresh browser on that empty directory.
  const context = await chromium.launchPersistentContext(profile, {
    executablePath: process.env.CHROMIUM ?? '/usr/bin/chromium',
    headless: true,
    args: [
      '--headless',
      '--no-sandbox',
      '--disable-gpu',
      '--disable-quic',
      '--no-first-run',
      '--disable-background-networking',
      '--disable-component-update',
      '--disable-sync',
      // WebGL without a GPU: Chromium's software rasteriser (SwiftShader), which it asks to opt into.
      '--enable-unsafe-swiftshader',
      '--use-angle=swiftshader',
    ],
    viewport: { width: 1024, height: 700 },
  });
  return {
    context,
    close: async () => {
      await context.close();
      fs.rmSync(profile, { recursive: true, force: true });
    },
  };
}
