// The monitor page: highlights the active path, plots the samples, logs the trace.
const token = new URLSearchParams(location.search).get("token");
const query = "?token=" + encodeURIComponent(token);
const WINDOW = 2000;
let samples, active;

function reset() {
  samples = { force: [], torque: [], tcp: [] };
  active = [];
  document.getElementById("log").replaceChildren();
  document.getElementById("command").textContent = "none";
  document.getElementById("summary").textContent = "running";
}

function title(g) {
  const t = g.querySelector("title");
  return t ? t.textContent.replace(/^cluster_/, "") : "";
}
const CLICKABLE = "#task g.node, #task g.cluster, #task g.edge";

// Every active state drawn gets an outline; the innermost one drawn is filled as well.
function highlight() {
  const groups = [...document.querySelectorAll("#task g.node, #task g.cluster")];
  let current = null;
  for (const path of active) current = groups.find(g => title(g) === path) || current;
  groups.forEach(g => {
    g.classList.toggle("active", active.includes(title(g)));
    g.classList.toggle("current", g === current);
  });
  document.getElementById("task").dataset.active = active[active.length - 1] || "";
}

function markBreakpoints(points) {
  document.querySelectorAll(CLICKABLE).forEach(g => {
    g.classList.toggle("breakpoint", points.includes(title(g)));
  });
}

function apply(record) {
  if (record.kind === "enter") {
    const depth = record.state.split("/").length;
    active = active.filter(p => p.split("/").length < depth);
    active.push(record.state);
  } else if (record.kind === "exit") {
    active = active.filter(p => p !== record.state);
  } else if (record.kind === "command") {
    document.getElementById("command").textContent =
      `${record.device}.${record.command} in ${record.state} (budget ${record.budget} s)`;
  } else if (record.kind === "stop") {
    document.getElementById("command").textContent =
      `${record.state} stopped: ${record.outcome}`;
  } else if (record.kind === "finished") {
    document.getElementById("summary").textContent = "outcome: " + record.outcome;
  } else if (record.kind === "aborted") {
    document.getElementById("command").textContent = "aborted in " + record.active.join(" / ");
  }
  if (record.kind === "sample") {
    for (const [key, value] of Object.entries(record)) {
      if (key.endsWith(".wrench")) {
        samples.force.push([record.time, value.force]);
        samples.torque.push([record.time, value.torque]);
      } else if (key.endsWith(".tcp")) {
        samples.tcp.push([record.time, value]);
      }
    }
    for (const list of Object.values(samples)) if (list.length > WINDOW) list.splice(0, list.length - WINDOW);
    return;
  }
  const line = document.createElement("div");
  line.textContent = JSON.stringify(record);
  const log = document.getElementById("log");
  log.appendChild(line);
  log.scrollTop = log.scrollHeight;
}

function draw(id, list) {
  const canvas = document.getElementById(id), ctx = canvas.getContext("2d");
  ctx.clearRect(0, 0, canvas.width, canvas.height);
  if (list.length < 2) return;
  const t0 = list[0][0], t1 = list[list.length - 1][0] || t0 + 1;
  let lo = Infinity, hi = -Infinity;
  for (const [, v] of list) for (const x of v) { lo = Math.min(lo, x); hi = Math.max(hi, x); }
  if (hi - lo < 1e-9) { hi += 1; lo -= 1; }
  ["#1f77b4", "#ff7f0e", "#2ca02c"].forEach((colour, axis) => {
    ctx.strokeStyle = colour; ctx.beginPath();
    list.forEach(([t, v], i) => {
      const x = (t - t0) / (t1 - t0 || 1) * canvas.width;
      const y = canvas.height - (v[axis] - lo) / (hi - lo) * canvas.height;
      if (i === 0) ctx.moveTo(x, y); else ctx.lineTo(x, y);
    });
    ctx.stroke();
  });
  ctx.fillStyle = "#000"; ctx.fillText(`${id} [${lo.toFixed(3)}, ${hi.toFixed(3)}]`, 4, 12);
}

function showStatus(status) {
  document.getElementById("state").textContent = status.measurements ? "run over"
    : (status.paused ? "paused" : "running") + (status.where ? " at " + status.where : "");
  document.body.dataset.paused = status.paused;
  markBreakpoints(status.breakpoints || []);
  if (status.measurements) {
    document.getElementById("measurements").innerHTML = Object.entries(status.measurements)
      .map(([k, v]) => `<tr><td>${k}</td><td>${v}</td></tr>`).join("");
  }
}

async function control(action, at) {
  const extra = at ? "&at=" + encodeURIComponent(at) : "";
  const answer = await fetch("control/" + action + query + extra, { method: "POST" });
  showStatus(await answer.json());
}

async function start() {
  const svg = await (await fetch("task.svg" + query)).text();
  document.getElementById("task").innerHTML = svg;
  document.querySelectorAll(CLICKABLE).forEach(g =>
    g.addEventListener("click", event => { event.stopPropagation(); control("break", title(g)); }));
  for (const action of ["pause", "resume", "step", "abort"]) {
    document.getElementById(action).addEventListener("click", () => control(action));
  }
  const socket = new WebSocket(location.href.replace(/^http/, "ws").replace(/\/[^/]*$/, "/stream") + query);
  socket.onmessage = message => {
    const data = JSON.parse(message.data);
    if (data.title) document.getElementById("title").textContent = data.title;
    if (data.replay) { replay(data.replay); return; }
    (data.history || []).forEach(apply);
    (data.records || []).forEach(apply);
    if (data.status) showStatus(data.status);
    redraw();
  };
}

function redraw() {
  highlight();
  for (const [id, list] of Object.entries(samples)) draw(id, list);
}

// A recorded run: the slider picks a simulated time and the page shows the run up to it.
function replay(records) {
  document.getElementById("controls").hidden = true;
  document.getElementById("replay").hidden = false;
  const slider = document.getElementById("slider"), play = document.getElementById("play");
  const end = records.length ? records[records.length - 1].time : 0;
  slider.max = end;
  slider.step = "any";
  const show = () => {
    const until = Number(slider.value);
    reset();
    records.filter(r => r.time <= until).forEach(apply);
    document.getElementById("at").textContent = until.toFixed(3) + " s of " + end.toFixed(3) + " s";
    redraw();
  };
  slider.addEventListener("input", show);
  let timer = null;
  play.addEventListener("click", () => {
    if (timer) { clearInterval(timer); timer = null; play.textContent = "Play"; return; }
    if (Number(slider.value) >= end) slider.value = 0;
    play.textContent = "Stop";
    let last = performance.now();
    timer = setInterval(() => {
      const now = performance.now();
      slider.value = Math.min(end, Number(slider.value) + (now - last) / 1000);
      last = now;
      show();
      if (Number(slider.value) >= end) play.click();
    }, 100);
  });
  slider.value = end;
  show();
}

reset();
start();
