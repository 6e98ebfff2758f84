// The viewer page: opens a recording (from ?file=URL, the file picker or a file dropped on the page), plays
// it back through the Player clock, draws it with SceneView, and answers the controls. `window.rebound`
// is a small read-back hook for tests and the browser console.

import { SceneView } from './scene.js';
import { EnergyPlot } from './plot.js';
import { Player } from './player.js';
import { readRecording, RecordingError } from './recording.js';
import { describeBody } from './inspector.js';

const $ = (id) => document.getElementById(id);

const view = new SceneView($('viewport'));
const plot = new EnergyPlot($('energy'));
const toggles = {
  contacts: $('show-contacts').checked,
  joints: $('show-joints').checked,
  aabbs: $('show-aabbs').checked,
  sleeping: $('show-sleeping').checked,
};

let recording = null;
let player = null;
let shownFrame = null;
let name = '';

// ---- opening ----

function showMessage(text) {
  const box = $('message');
  box.textContent = text;
  box.hidden = text === '';
}

/** Opens the recording in `bytes`; on a bad file shows why and keeps whatever was shown before. */
function openBytes(bytes, fileName) {
  let next;
  try {
    next = readRecording(bytes);
  } catch (error) {
    const reason = error instanceof RecordingError ? error.message : `unexpected error: ${error}`;
    showMessage(`Cannot open ${fileName}: ${reason}`);
    if (!(error instanceof RecordingError)) console.error(error);
    return false;
  }
  showMessage(
    next.truncated === null ? '' : `${fileName} is cut short (${next.truncated}); showing its ${next.frameCount} complete frames.`,
  );
  recording = next;
  name = fileName;
  player = new Player(recording.frameCount, recording.frameDt);
  player.setSpeed(Number($('speed').value));
  view.load(recording);
  view.fit();
  plot.setSeries(recording.energySeries());
  $('timeline').max = String(recording.frameCount - 1);
  $('title').textContent = `${fileName} — ${recording.bodies.length} bodies, ${recording.frameCount} frames`;
  $('drop-hint').hidden = true;
  showFrame();
  return true;
}

async function openUrl(url) {
  let response;
  try {
    response = await fetch(url);
  } catch (error) {
    showMessage(`Cannot fetch ${url}: ${error.message}`);
    return false;
  }
  if (!response.ok) {
    showMessage(`Cannot fetch ${url}: HTTP ${response.status} ${response.statusText}`);
    return false;
  }
  const fileName = decodeURIComponent(url.split('/').pop() || url);
  return openBytes(await response.arrayBuffer(), fileName);
}

async function openFile(file) {
  try {
    return openBytes(await file.arrayBuffer(), file.name);
  } catch (error) {
    showMessage(`Cannot read ${file.name}: ${error.message}`);
    return false;
  }
}

$('file').addEventListener('change', (event) => {
  const file = event.target.files[0];
  if (file) openFile(file);
  event.target.value = '';
});

document.addEventListener('dragover', (event) => {
  event.preventDefault();
  document.body.classList.add('dragging');
});
document.addEventListener('dragleave', () => document.body.classList.remove('dragging'));
document.addEventListener('drop', (event) => {
  event.preventDefault();
  document.body.classList.remove('dragging');
  const file = event.dataTransfer?.files?.[0];
  if (file) openFile(file);
});

// ---- showing a frame ----

function showFrame() {
  if (recording === null) return;
  shownFrame = recording.frame(player.frame);
  view.show(shownFrame, toggles);
  $('timeline').value = String(player.frame);
  $('frame-label').textContent = `${player.frame} / ${recording.frameCount - 1}  t=${shownFrame.time.toFixed(3)} s`;
  $('play').textContent = player.playing ? '❚❚' : '▶';
  plot.mark(player.frame);
  const inspector = $('inspector');
  if (view.selected >= 0) {
    inspector.hidden = false;
    inspector.textContent = describeBody(recording, shownFrame, view.selected);
  } else {
    inspector.hidden = true;
  }
}

// ---- controls ----

$('play').addEventListener('click', () => {
  if (player === null) return;
  player.toggle();
  showFrame();
});
$('back').addEventListener('click', () => stepBy(-1));
$('forward').addEventListener('click', () => stepBy(1));
$('timeline').addEventListener('input', (event) => seek(Number(event.target.value)));
$('speed').addEventListener('change', (event) => player?.setSpeed(Number(event.target.value)));
for (const [key, id] of [['contacts', 'show-contacts'], ['joints', 'show-joints'], ['aabbs', 'show-aabbs'],
  ['sleeping', 'show-sleeping']]) {
  $(id).addEventListener('change', (event) => setToggle(key, event.target.checked));
}

document.addEventListener('keydown', (event) => {
  if (event.target instanceof HTMLInputElement && event.target.type !== 'range') return;
  if (event.key === ' ') {
    event.preventDefault();
    $('play').click();
  } else if (event.key === 'ArrowRight') {
    event.preventDefault();
    stepBy(1);
  } else if (event.key === 'ArrowLeft') {
    event.preventDefault();
    stepBy(-1);
  }
});

// A click (press and release without dragging the camera) selects the body under the pointer.
let pressedAt = null;
const canvas = view.renderer.domElement;
canvas.addEventListener('pointerdown', (event) => {
  pressedAt = { x: event.clientX, y: event.clientY };
});
canvas.addEventListener('pointerup', (event) => {
  if (pressedAt === null || recording === null) return;
  const moved = Math.hypot(event.clientX - pressedAt.x, event.clientY - pressedAt.y);
  pressedAt = null;
  if (moved < 4) select(view.pick(event.clientX, event.clientY));
});

function stepBy(delta) {
  if (player === null) return;
  player.step(delta);
  showFrame();
}

function seek(index) {
  if (player === null) return;
  player.seek(index);
  showFrame();
}

function setToggle(key, on) {
  toggles[key] = Boolean(on);
  const id = { contacts: 'show-contacts', joints: 'show-joints', aabbs: 'show-aabbs', sleeping: 'show-sleeping' }[key];
  if (id !== undefined) $(id).checked = toggles[key];
  showFrame();
}

function select(body) {
  view.selected = recording !== null && body >= 0 && body < recording.bodies.length ? body : -1;
  showFrame();
}

// ---- the draw loop and its frame counter ----

const counter = { drawn: 0, windowStart: performance.now(), windowDrawn: 0, fps: 0 };
let last = performance.now();
view.controls.addEventListener('change', () => {
  view.dirty = true;
});

function loop(now) {
  const wall = (now - last) / 1000;
  last = now;
  if (player !== null && player.tick(wall)) showFrame();
  if (view.render()) {
    counter.drawn++;
    counter.windowDrawn++;
  }
  if (now - counter.windowStart >= 1000) {
    counter.fps = (counter.windowDrawn * 1000) / (now - counter.windowStart);
    counter.windowStart = now;
    counter.windowDrawn = 0;
    $('fps').textContent = `${counter.fps.toFixed(1)} fps`;
  }
  requestAnimationFrame(loop);
}
requestAnimationFrame(loop);

// ---- the read-back hook ----

window.rebound = {
  /** What the page shows: the frame, playback state, toggles, the message and every body's drawn pose. */
  state() {
    const text = $('message').hidden ? null : $('message').textContent;
    if (recording === null) return { loaded: false, message: text };
    return {
      loaded: true,
      name,
      message: text,
      frame: player.frame,
      frameCount: recording.frameCount,
      time: shownFrame.time,
      playing: player.playing,
      speed: player.speed,
      toggles: { ...toggles },
      selected: view.selected,
      inspector: $('inspector').hidden ? null : $('inspector').textContent,
      camera: { position: view.camera.position.toArray(), target: view.controls.target.toArray() },
      bodies: view.displayedPoses(),
    };
  },
  openUrl,
  openBytes: (bytes, fileName = 'bytes') => openBytes(bytes, fileName),
  seek,
  step: stepBy,
  play() {
    player?.play();
    showFrame();
  },
  pause() {
    player?.pause();
    showFrame();
  },
  setSpeed: (s) => player?.setSpeed(s),
  toggle: setToggle,
  select,
  pick: (x, y) => view.pick(x, y),
  setCamera: (position, target) => view.setCamera(position, target),
  project: (p) => view.project(p),
  /** Frames drawn in the last whole second, and in total since the page opened. */
  fps: () => ({ fps: counter.fps, drawn: counter.drawn }),
  /** Draws now, so a screenshot taken next shows the latest state. */
  draw: () => view.render(true),
};

const initial = new URLSearchParams(location.search).get('file');
if (initial) openUrl(initial);
