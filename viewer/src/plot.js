// The small energy-over-time plot: every series drawn once into a cached image, then the current frame
// marked with a vertical line on each redraw (so scrubbing costs one image copy, not a re-plot).

const SERIES_COLOURS = ['#f2a541', '#5aa0ff', '#7bd389', '#e36bae', '#c0c4cc'];

export class EnergyPlot {
  /** @param {HTMLCanvasElement} canvas */
  constructor(canvas) {
    this.canvas = canvas;
    this.context = canvas.getContext('2d');
    this.cache = null;
    this.frameCount = 0;
    this.margin = { left: 44, right: 6, top: 16, bottom: 14 };
  }

  /**
   * @param {{name: string, values: ArrayLike<number>}[]} series energy series (J), one value a frame
   */
  setSeries(series) {
    const { canvas, margin } = this;
    const cache = document.createElement('canvas');
    cache.width = canvas.width;
    cache.height = canvas.height;
    const g = cache.getContext('2d');
    const drawn = series.filter((s) => s.values.length > 0);
    this.frameCount = drawn.length > 0 ? drawn[0].values.length : 0;

    let lo = Infinity;
    let hi = -Infinity;
    for (const s of drawn) {
      for (const v of s.values) {
        if (Number.isFinite(v)) {
          lo = Math.min(lo, v);
          hi = Math.max(hi, v);
        }
      }
    }
    if (!(hi >= lo)) {
      lo = 0;
      hi = 1;
    }
    if (hi - lo < 1e-9 * Math.max(1, Math.abs(hi))) {
      hi += 0.5;
      lo -= 0.5;
    }
    this.range = { lo, hi };

    const w = cache.width - margin.left - margin.right;
    const h = cache.height - margin.top - margin.bottom;
    g.font = '10px ui-monospace, monospace';
    g.fillStyle = '#8a919c';
    g.fillText(`${formatJoules(hi)}`, 2, margin.top + 4);
    g.fillText(`${formatJoules(lo)}`, 2, margin.top + h);
    g.fillText('energy change since frame 0 (J)', margin.left, cache.height - 2);
    g.strokeStyle = '#333842';
    g.strokeRect(margin.left, margin.top, w, h);

    drawn.forEach((s, k) => {
      const colour = SERIES_COLOURS[k % SERIES_COLOURS.length];
      g.strokeStyle = colour;
      g.beginPath();
      const n = s.values.length;
      for (let i = 0; i < n; i++) {
        const x = margin.left + (n > 1 ? (i / (n - 1)) * w : 0);
        const y = margin.top + h - ((s.values[i] - lo) / (hi - lo)) * h;
        if (i === 0) g.moveTo(x, y);
        else g.lineTo(x, y);
      }
      g.stroke();
      g.fillStyle = colour;
      g.fillText(s.name, margin.left + 4 + k * 62, margin.top - 5);
    });
    this.cache = cache;
  }

  /** Redraws the plot with frame `frame` marked. */
  mark(frame) {
    const { context: g, canvas, margin } = this;
    g.clearRect(0, 0, canvas.width, canvas.height);
    if (this.cache === null) return;
    g.drawImage(this.cache, 0, 0);
    if (this.frameCount < 1) return;
    const w = canvas.width - margin.left - margin.right;
    const x = margin.left + (this.frameCount > 1 ? (frame / (this.frameCount - 1)) * w : 0);
    g.strokeStyle = '#ffffff';
    g.beginPath();
    g.moveTo(x + 0.5, margin.top);
    g.lineTo(x + 0.5, canvas.height - margin.bottom);
    g.stroke();
  }
}

function formatJoules(v) {
  const a = Math.abs(v);
  if (a !== 0 && (a >= 1e5 || a < 1e-2)) return v.toExponential(2);
  return v.toFixed(2);
}
