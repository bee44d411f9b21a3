// The monitor page: shows the level of the active state, plots the samples, logs the trace.
// Its requests carry the cookie the page's first load set: the token leaves the address bar.
history.replaceState(null, "", location.pathname);
const WINDOW = 2000;
let samples, active, breakpoints = [];

const follow = document.getElementById("follow");
const diagram = new DiagramView(document.getElementById("task"), document.getElementById("crumbs"), {
  onNavigate: () => { follow.checked = false; },
  onPick: path => control("break", path),
});

function reset() {
  samples = { force: [], torque: [], tcp: [] };
  active = [];
  document.getElementById("log").replaceChildren();
  document.getElementById("command").textContent = "none";
  document.getElementById("summary").textContent = "running";
}

// The level in view follows the innermost active states, unless the user navigates.
function highlight() {
  const last = active[active.length - 1] || "";
  if (follow.checked && diagram.levels.size) diagram.reveal(innermostOf(active));
  diagram.highlight(active);
  diagram.mark("breakpoint", breakpoints);
  if (follow.checked) diagram.box.querySelector(".current")?.scrollIntoView({ block: "nearest" });
  document.getElementById("task").dataset.active = last;
}

function apply(record) {
  if (record.kind === "enter") {
    active = active.filter(p => p !== record.state);
    active.push(record.state);
  } else if (record.kind === "exit") {
    active = active.filter(p => p !== record.state && !p.startsWith(record.state + "/"));
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
    // Trimmed in batches: trimming at every sample would move the whole window each time.
    for (const list of Object.values(samples)) if (list.length > 2 * WINDOW) list.splice(0, list.length - WINDOW);
    return;
  }
  const line = document.createElement("div");
  line.textContent = JSON.stringify(record);
  const log = document.getElementById("log");
  log.appendChild(line);
}

function showStatus(status) {
  document.getElementById("state").textContent = status.measurements ? "run over"
    : (status.paused ? "paused" : "running") + (status.where ? " at " + status.where : "");
  document.body.dataset.paused = status.paused;
  breakpoints = status.breakpoints || [];
  diagram.mark("breakpoint", breakpoints);
  if (status.measurements) {
    const rows = Object.entries(status.measurements).map(([name, value]) => {
      const row = document.createElement("tr");
      for (const text of [name, String(value)]) {
        const cell = document.createElement("td");
        cell.textContent = text;
        row.appendChild(cell);
      }
      return row;
    });
    document.getElementById("measurements").replaceChildren(...rows);
  }
}

async function control(action, at) {
  const where = at ? "?at=" + encodeURIComponent(at) : "";
  const answer = await fetch("control/" + action + where, { method: "POST" });
  showStatus(await answer.json());
}

async function start() {
  diagram.load(await (await fetch("task.svg")).text());
  diagram.reveal([]);
  follow.addEventListener("change", redraw);
  for (const action of ["pause", "resume", "step", "abort"]) {
    document.getElementById(action).addEventListener("click", () => control(action));
  }
  const socket = new WebSocket(location.href.replace(/^http/, "ws").replace(/\/[^/]*$/, "/stream"));
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

// Once per batch of records: reading the log's height lays the page out.
function redraw() {
  highlight();
  for (const [id, list] of Object.entries(samples)) drawPlot(document.getElementById(id), id, list.slice(-WINDOW));
  const log = document.getElementById("log");
  log.scrollTop = log.scrollHeight;
}

// A recorded run: the slider picks a simulated time and the page shows the run up to it.
function replay(records) {
  document.getElementById("controls").hidden = true;
  document.getElementById("replay").hidden = false;
  const slider = document.getElementById("slider"), play = document.getElementById("play");
  const end = records.length ? records[records.length - 1].time : 0;
  slider.max = end;
  slider.step = "any";
  // Moving on applies only the records passed; moving back starts again from the first.
  let applied = 0;
  const show = () => {
    const until = Number(slider.value);
    if (applied > 0 && records[applied - 1].time > until) {
      reset();
      applied = 0;
    }
    while (applied < records.length && records[applied].time <= until) apply(records[applied++]);
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
