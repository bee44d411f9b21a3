// Live plots of the wrench and the TCP: a time axis in simulated seconds, a value axis with
// its unit, a legend of the three components.

const PLOTS = {
  force: { label: "force [N]", scale: 1 },
  torque: { label: "torque [Nm]", scale: 1 },
  tcp: { label: "TCP [mm]", scale: 1000 },
};
const COMPONENTS = [["x", "#1f77b4"], ["y", "#ff7f0e"], ["z", "#2ca02c"]];
const MARGIN = { left: 54, right: 10, top: 18, bottom: 30 };

// Round steps (1, 2, 5 times a power of ten) that cut [lo, hi] into about ``count`` parts.
function ticks(lo, hi, count) {
  const raw = (hi - lo) / count;
  const power = 10 ** Math.floor(Math.log10(raw));
  const step = [1, 2, 5, 10].map(f => f * power).find(s => s >= raw) || raw;
  const first = Math.ceil(lo / step) * step;
  const found = [];
  for (let v = first; v <= hi + step * 1e-9; v += step) found.push(Math.abs(v) < step * 1e-9 ? 0 : v);
  return { values: found, step };
}

function label(value, step) {
  const digits = Math.max(0, -Math.floor(Math.log10(step)));
  return value.toFixed(Math.min(digits, 6));
}

function drawPlot(canvas, id, list) {
  const { label: title, scale } = PLOTS[id];
  const ratio = window.devicePixelRatio || 1;
  const width = canvas.clientWidth || 360, height = canvas.clientHeight || 150;
  canvas.width = width * ratio;
  canvas.height = height * ratio;
  const ctx = canvas.getContext("2d");
  ctx.setTransform(ratio, 0, 0, ratio, 0, 0);
  ctx.clearRect(0, 0, width, height);
  ctx.font = "11px sans-serif";
  ctx.fillStyle = "#000";
  ctx.textBaseline = "alphabetic";
  ctx.fillText(title, 4, 12);
  if (list.length < 2) {
    ctx.fillStyle = "#777";
    ctx.fillText("no samples yet", MARGIN.left, height / 2);
    return;
  }
  const t0 = list[0][0], t1 = Math.max(list[list.length - 1][0], t0 + 1e-3);
  let lo = Infinity, hi = -Infinity;
  for (const [, v] of list) for (const x of v) { lo = Math.min(lo, x * scale); hi = Math.max(hi, x * scale); }
  if (hi - lo < 1e-9) { hi += 1; lo -= 1; }
  const pad = (hi - lo) * 0.05;
  lo -= pad; hi += pad;
  const plotW = width - MARGIN.left - MARGIN.right, plotH = height - MARGIN.top - MARGIN.bottom;
  const x = t => MARGIN.left + (t - t0) / (t1 - t0) * plotW;
  const y = v => MARGIN.top + plotH - (v - lo) / (hi - lo) * plotH;

  ctx.strokeStyle = "#ddd";
  ctx.fillStyle = "#333";
  ctx.lineWidth = 1;
  const vertical = ticks(lo, hi, 4);
  ctx.textAlign = "right";
  for (const v of vertical.values) {
    ctx.beginPath(); ctx.moveTo(MARGIN.left, y(v)); ctx.lineTo(MARGIN.left + plotW, y(v)); ctx.stroke();
    ctx.fillText(label(v, vertical.step), MARGIN.left - 4, y(v) + 4);
  }
  const horizontal = ticks(t0, t1, 5);
  ctx.textAlign = "center";
  for (const t of horizontal.values) {
    ctx.beginPath(); ctx.moveTo(x(t), MARGIN.top); ctx.lineTo(x(t), MARGIN.top + plotH); ctx.stroke();
    ctx.fillText(label(t, horizontal.step), x(t), MARGIN.top + plotH + 13);
  }
  ctx.textAlign = "right";
  ctx.fillText("time [s]", MARGIN.left + plotW, height - 3);
  ctx.strokeStyle = "#888";
  ctx.strokeRect(MARGIN.left, MARGIN.top, plotW, plotH);

  COMPONENTS.forEach(([name, colour], axis) => {
    ctx.strokeStyle = colour;
    ctx.beginPath();
    list.forEach(([t, v], i) => (i ? ctx.lineTo : ctx.moveTo).call(ctx, x(t), y(v[axis] * scale)));
    ctx.stroke();
    const at = MARGIN.left + plotW - (COMPONENTS.length - axis) * 26;
    ctx.fillStyle = colour;
    ctx.fillRect(at, 5, 10, 3);
    ctx.textAlign = "left";
    ctx.fillText(name, at + 12, 11);
  });
  ctx.textAlign = "left";
}
