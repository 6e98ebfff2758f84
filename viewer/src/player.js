// The playback clock: which recorded frame is shown, and how wall-clock time moves it.
//
// Kept free of the DOM and of three.js so that node's test runner can check it directly.

/** Playback state over a recording of `frameCount` frames spaced `frameDt` seconds apart. */
export class Player {
  /**
   * @param {number} frameCount number of recorded frames (≥ 1)
   * @param {number} frameDt simulated seconds between two recorded frames (> 0)
   */
  constructor(frameCount, frameDt) {
    this.frameCount = Math.max(1, frameCount | 0);
    this.frameDt = frameDt > 0 && Number.isFinite(frameDt) ? frameDt : 1 / 60;
    this.frame = 0;
    this.playing = false;
    this.speed = 1;
    // Simulated seconds accumulated since the shown frame began, while playing.
    this.carry = 0;
  }

  /** Shows frame `index`, clamped to the recording; returns whether the shown frame changed. */
  seek(index) {
    const clamped = Math.min(this.frameCount - 1, Math.max(0, Math.round(Number(index) || 0)));
    const changed = clamped !== this.frame;
    this.frame = clamped;
    this.carry = 0;
    return changed;
  }

  /** Moves `delta` frames (negative goes back) and pauses; returns whether the frame changed. */
  step(delta) {
    this.playing = false;
    return this.seek(this.frame + delta);
  }

  /** Sets the playback speed, a multiple of real time (0 < speed ≤ 64). */
  setSpeed(speed) {
    const s = Number(speed);
    if (s > 0 && s <= 64) this.speed = s;
  }

  /** Starts playing; from the last frame, starts again at the first. */
  play() {
    if (this.frame >= this.frameCount - 1) this.seek(0);
    this.playing = true;
  }

  pause() {
    this.playing = false;
    this.carry = 0;
  }

  toggle() {
    if (this.playing) this.pause();
    else this.play();
  }

  /**
   * Advances by `wallSeconds` of real time at the current speed; playback wraps round to the first frame
   * at the end so a long run can be watched (and timed) continuously. Returns whether the frame changed.
   */
  tick(wallSeconds) {
    if (!this.playing || !(wallSeconds > 0)) return false;
    // A stalled tab (hidden, debugger) must not jump far ahead when it resumes.
    this.carry += Math.min(wallSeconds, 0.25) * this.speed;
    // The tolerance keeps 0.3 s / 0.1 s from rounding down to 2 frames.
    const advance = Math.floor(this.carry / this.frameDt + 1e-9);
    if (advance === 0) return false;
    this.carry = Math.max(0, this.carry - advance * this.frameDt);
    this.frame = (this.frame + advance) % this.frameCount;
    return true;
  }
}
