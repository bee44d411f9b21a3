// Runs from the studio: the dry run or a simulation of the chart in view, started here and
// watched on the same diagram. The server runs it with the monitor's pieces and serves the
// monitor's own stream and controls below run/ (the full monitor page, with its plots, is
// run/ itself); this file only shows what they send.
let runSocket = null;
let runActive = [];
let runFrames = null;

function runButtons(status) {
  const running = Boolean(status.running);
  $("run-start").disabled = running;
  for (const id of ["run-pause", "run-resume", "run-step", "run-abort", "run-break"]) {
    $(id).disabled = !running;
  }
  $("run-monitor").hidden = !status.chart;
}

function runSay(text) {
  $("run-status").textContent = text;
}

function applyRecord(record) {
  if (record.kind === "enter") {
    runActive = runActive.filter(p => p !== record.state);
    runActive.push(record.state);
  } else if (record.kind === "exit") {
    runActive = runActive.filter(p => p !== record.state && !p.startsWith(record.state + "/"));
  }
  if (["enter", "finished", "aborted", "paused", "fault"].includes(record.kind)) {
    const item = document.createElement("li");
    item.textContent = `${record.time.toFixed(3)} s ${record.kind} ${record.state || record.outcome || record.at || ""}`;
    const log = $("run-log");
    log.append(item);
    while (log.children.length > 200) log.firstChild.remove();
    log.scrollTop = log.scrollHeight;
  }
}

// The level in view follows the innermost active states while "follow" is ticked.
function showRun() {
  if ($("run-follow").checked && runActive.length && diagram.levels.size) {
    diagram.reveal(innermostOf(runActive));
  }
  diagram.highlight(runActive);
  $("diagram").dataset.active = runActive[runActive.length - 1] || "";
}

let runBreakpoints = [];

function runStatus(status) {
  runBreakpoints = status.breakpoints || runBreakpoints;
  diagram.mark("breakpoint", runBreakpoints);
  if (status.error) {
    runSay(`error: ${status.error}`);
  } else if (status.outcome) {
    runSay(`outcome: ${status.outcome}`);
  } else if (status.measurements) {
    runSay("run over");
  } else {
    runSay((status.paused ? "paused" : "running") + (status.where ? " at " + status.where : ""));
  }
  const over = Boolean(status.outcome || status.error || status.measurements);
  runButtons({ running: !over, chart: true });
  if (over) stopFrames();
}

function watchRun() {
  runSocket?.close();
  runActive = [];
  $("run-log").replaceChildren();
  const url = location.href.replace(/^http/, "ws").replace(/\/[^/]*$/, "/run/stream");
  runSocket = new WebSocket(url);
  runSocket.onmessage = message => {
    const data = JSON.parse(message.data);
    (data.history || []).forEach(applyRecord);
    (data.records || []).forEach(applyRecord);
    if (data.status) runStatus(data.status);
    showRun();
  };
}

function startFrames() {
  stopFrames();
  $("run-view").hidden = false;
  let n = 0;
  // Each frame loads beside the one shown and takes its place once whole (no frame yet: none).
  runFrames = setInterval(() => {
    const next = new Image();
    next.onload = () => {
      next.id = "run-view";
      next.alt = "the simulated cell";
      next.dataset.frame = n;
      $("run-view").replaceWith(next);
    };
    next.src = `runs/frame.png?n=${++n}`;
  }, 300);
}

function stopFrames() {
  if (runFrames) clearInterval(runFrames);
  runFrames = null;
}

async function runControl(action, at = "") {
  const where = at ? "?at=" + encodeURIComponent(at) : "";
  const answer = await fetch(`run/control/${action}${where}`, { method: "POST" });
  const status = await answer.json();
  if (answer.ok) runStatus(status);
  else runSay(status.error);
}

function wireRun() {
  $("run-start").addEventListener("click", async () => {
    runSay("starting…");
    const body = { chart: root, adapter: $("run-adapter").value, script: $("run-script").value,
      robot: $("run-robot").value, paused: $("run-paused").checked };
    const answer = await api("runs/start", {}, body);
    const status = await answer.json();
    if (!answer.ok) { runSay(`refused: ${status.error}`); return; }
    runButtons(status);
    watchRun();
    if (status.view) startFrames();
    else $("run-view").hidden = true;
  });
  for (const action of ["pause", "resume", "step", "abort"]) {
    $(`run-${action}`).addEventListener("click", () => runControl(action));
  }
  // The selected box or arrow, by the path the trace names it with (as the monitor's are).
  $("run-break").addEventListener("click", () => selected && runControl("break", selected.path));
  api("runs").then(answer => answer.json()).then(options => {
    $("run-adapter").replaceChildren(...options.adapters.map(a => new Option(a, a)), new Option("none (plain chart)", ""));
    if (options.adapters.includes("dryrun")) $("run-adapter").value = "dryrun";
    $("run-robot").replaceChildren(new Option("the cell's", ""), ...options.robots.map(r => new Option(r, r)));
    $("run-script").replaceChildren(new Option("none", ""), ...options.scripts.map(s => new Option(s, s)));
    runButtons(options);
    if (options.chart) watchRun();
  });
}
