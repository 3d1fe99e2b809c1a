// Two time series over the last 60 s, drawn on canvases a few times a second: the drone's
// altitude and horizontal speed, or a robot's speed and turn rate (from its odometry).

const WINDOW_S = 60;
const REDRAW_MS = 200;

const CHARTS = {
  drone: [
    { key: "z", title: "altitude", unit: "m", color: "#61afef", min: 0, max: 4 },
    { key: "speed", title: "horizontal speed", unit: "m/s", color: "#e5c07b", min: 0, max: 2 },
  ],
  robot: [
    { key: "speed", title: "speed (odom)", unit: "m/s", color: "#61afef", min: -0.4, max: 0.4 },
    { key: "turn", title: "turn rate (odom)", unit: "rad/s", color: "#e5c07b", min: -2, max: 2 },
  ],
};

export class Plots {
  constructor({ world, altitude, speed }) {
    this.world = world; // anything with a `history` of samples {t, ...keys}
    this.canvases = [altitude, speed];
    this.use(world, "drone");
  }

  /** Plot `source.history` with the charts of world `kind` ("drone" or "robot"). */
  use(source, kind) {
    this.world = source;
    this.charts = CHARTS[kind].map((chart, i) => ({ ...chart, canvas: this.canvases[i] }));
  }

  start() {
    const tick = () => {
      for (const chart of this.charts) this._draw(chart);
    };
    tick();
    setInterval(tick, REDRAW_MS);
  }

  _draw(chart) {
    const { canvas } = chart;
    const rect = canvas.getBoundingClientRect();
    if (rect.width < 10 || rect.height < 10) return;
    const dpr = window.devicePixelRatio || 1;
    if (canvas.width !== Math.round(rect.width * dpr) || canvas.height !== Math.round(rect.height * dpr)) {
      canvas.width = Math.round(rect.width * dpr);
      canvas.height = Math.round(rect.height * dpr);
    }
    const ctx = canvas.getContext("2d");
    ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
    const w = rect.width;
    const h = rect.height;
    const pad = { left: 38, right: 10, top: 20, bottom: 18 };
    ctx.fillStyle = "#0e1319";
    ctx.fillRect(0, 0, w, h);
    const history = this.world.history;
    const now = performance.now() / 1000;
    const values = history.map((s) => s[chart.key]);
    // The y range grows to fit the data and never shrinks below the chart's default.
    const top = niceCeil(Math.max(chart.max, ...values));
    const bottom = chart.min < 0 ? -niceCeil(Math.max(-chart.min, ...values.map((v) => -v))) : chart.min;
    const px = (t) => pad.left + ((t - (now - WINDOW_S)) / WINDOW_S) * (w - pad.left - pad.right);
    const py = (v) => h - pad.bottom - ((v - bottom) / (top - bottom)) * (h - pad.top - pad.bottom);
    ctx.font = "10px ui-monospace, monospace";
    ctx.textAlign = "right";
    ctx.textBaseline = "middle";
    for (let i = 0; i <= 4; i++) {
      const v = bottom + ((top - bottom) * i) / 4;
      ctx.strokeStyle = "#1c2630";
      ctx.beginPath();
      ctx.moveTo(pad.left, Math.round(py(v)) + 0.5);
      ctx.lineTo(w - pad.right, Math.round(py(v)) + 0.5);
      ctx.stroke();
      ctx.fillStyle = "#6f8193";
      ctx.fillText(formatTick(v), pad.left - 4, py(v));
    }
    ctx.textAlign = "center";
    ctx.textBaseline = "bottom";
    for (let s = 0; s <= WINDOW_S; s += 15) ctx.fillText(s ? `-${s}s` : "now", px(now - s), h - 2);
    ctx.strokeStyle = chart.color;
    ctx.lineWidth = 1.5;
    ctx.beginPath();
    history.forEach((sample, i) => {
      const x = px(sample.t);
      const y = py(sample[chart.key]);
      if (i === 0) ctx.moveTo(x, y);
      else ctx.lineTo(x, y);
    });
    ctx.stroke();
    const last = history[history.length - 1];
    ctx.textAlign = "left";
    ctx.textBaseline = "top";
    ctx.fillStyle = "#d7dde3";
    ctx.font = "12px system-ui, sans-serif";
    const current = last ? `${last[chart.key].toFixed(2)} ${chart.unit}` : "–";
    ctx.fillText(`${chart.title}: ${current}`, pad.left, 3);
  }
}

function niceCeil(value) {
  for (const step of [1, 2, 4, 5, 8, 10, 15, 20, 30, 50, 100]) if (value <= step) return step;
  return Math.ceil(value / 100) * 100;
}

function formatTick(v) {
  return Number.isInteger(v) ? String(v) : v.toFixed(1);
}
