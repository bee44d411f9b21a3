// The studio page: a chart's diagram with the findings of check on it, and edits of it.
// Every edit names the version of the file it was made on; the server refuses it when the
// file changed on disk since, and the page reloads what is on disk. A form's text is checked
// by the server with the language's own parser, typing and context conditions while it is
// typed (a preview that writes nothing); nothing of the language is implemented here.
// Its requests carry the cookie the page's first load set: the token leaves the address bar.
const wanted = new URLSearchParams(location.search).get("chart");
history.replaceState(null, "", location.pathname);
const POLL = 1500;        // a look at the files when the change socket is closed
const CHECK_DELAY = 250;  // ms of quiet typing before a form's text is checked

let root = "";               // the statechart chosen above
const states = new Map();    // chart -> its state: version, findings, palette, levels
let selected = null;         // {element, path, kind}
let ends = { source: null, target: null };
let stamp = "";              // the files' state on disk the page shows
let refused = null;          // the last edit refused because the file changed: {request, done}
let loads = 0;               // diagrams loaded so far (the benchmark waits on it)
let reloading = false;       // a reload of what is on disk: forms being typed in stay
let busy = 0;                // edits under way: changes on disk wait until they are done
let waiting = null;          // the last change on disk told while an edit was under way

const $ = id => document.getElementById(id);
const diagram = new DiagramView($("diagram"), $("crumbs"), {
  selectOnClick: true,
  onPick: (path, g) => select(g),
  onOpen: () => { select(null); refreshSide(); },
});

function say(text, isRefusal = false) {
  $("message").textContent = text;
  $("message").classList.toggle("refused", isRefusal);
}

async function api(path, params = {}, body = null) {
  const search = new URLSearchParams(params);
  return fetch(`${path}?${search}`, body ? {
    method: "POST", headers: { "Content-Type": "application/json" }, body: JSON.stringify(body),
  } : {});
}

// The chart the level in view belongs to: edits change that chart's file.
function viewChart() {
  return diagram.key.split("/")[0] || root;
}

function level() {
  return states.get(viewChart())?.levels?.[diagram.key] || { boxes: {}, arrows: {} };
}

async function loadState(chart) {
  const answer = await api("state", { chart });
  if (answer.ok) {
    const state = await answer.json();
    states.set(chart, state);
    stamp = state.stamp;
  }
  return states.get(chart);
}

async function load(chart, keep = false) {
  const [key, view] = [diagram.key, diagram.view];
  const chosen = keep && selected ? selected.path : null;
  const answer = await api("diagram.svg", { chart });
  if (!answer.ok) {
    say((await answer.json()).error, true);
    return;
  }
  root = chart;
  reloading = keep;
  diagram.load(await answer.text());
  states.clear();
  await loadState(chart);
  if (keep && diagram.levels.has(key)) diagram.open(key, view);
  else diagram.reveal([]);
  reloading = false;
  $("file").textContent = states.get(chart)?.file || "";
  if ($("chart").value !== chart) await listCharts(chart);
  await refreshSide();
  const again = chosen && diagram.elements().find(g => g.dataset.path === chosen);
  if (again) select(again, true);
  showHistory();
  loads += 1;
  document.body.dataset.loads = loads;
  document.body.dataset.loadedAt = Date.now();
}

async function listCharts(chosen) {
  const charts = await (await api("charts")).json();
  $("chart").replaceChildren(...charts.map(c => new Option(`${c.name} (${c.layer || "plain"})`, c.name)));
  if (chosen && charts.some(c => c.name === chosen)) $("chart").value = chosen;
  return charts;
}

// -- selection and its forms -----------------------------------------------------------------

function select(g, keepForms = false) {
  document.querySelectorAll("#diagram .selected").forEach(e => e.classList.remove("selected"));
  if (!g) {
    selected = null;
  } else {
    g.classList.add("selected");
    const kind = g.classList.contains("edge") ? "edge" : g.classList.contains("node") ? "node"
      : g.classList.contains("graph") ? "frame" : "region";
    selected = { element: g.dataset.element, path: g.dataset.path, kind };
    if (kind === "node" && !selected.element.includes("#") && !keepForms) {
      if (ends.source && !ends.target) ends.target = selected.element;
      else ends = { source: selected.element, target: null };
    }
  }
  $("selected").textContent = selected ? `${selected.kind} ${selected.element || diagram.view}` : "nothing";
  const box = selected?.kind === "node" ? level().boxes[selected.element] : null;
  const state = box?.kind === "state";
  $("delete").disabled = !(box || selected?.kind === "edge");
  $("earlier").disabled = $("later").disabled = !state;
  showEnds();
  if (!((keepForms || reloading) && dirty())) showForms(box);
}

// Whether a form of the selection holds text not yet applied: a reload keeps it.
function dirty() {
  return [...document.querySelectorAll("#side form input, #side form textarea")]
    .some(input => input.dataset.applied !== undefined && input.value !== input.dataset.applied);
}

function field(input, value) {
  input.value = value;
  input.dataset.applied = value;
  return input;
}

function showForms(box) {
  const element = selected?.element;
  const own = selected?.kind === "frame" && diagram.key === viewChart();
  $("rename-form").hidden = !box && !own;
  field($("rename-to"), own ? viewChart().split(".").pop() : (box ? element.split("/").pop() : ""));
  outcomeChips(box);
  argumentsForm(box);
  conditionForm(box);
  transitionForms(selected?.kind === "edge" ? level().arrows[element] || [] : []);
}

// The selected box's outcomes, each dragged onto a target to add a transition from it.
function outcomeChips(box) {
  const chips = [];
  if (box && (box.kind === "state" || box.kind === "start condition" || box.kind === "choice")) {
    const outcomes = box.kind === "state" ? box.outcomes : [];
    for (const outcome of [...outcomes, ""]) {
      const chip = document.createElement("span");
      chip.className = "chip";
      chip.textContent = outcome || "→ (no stimulus)";
      chip.dataset.outcome = outcome;
      draggable(chip, () => ({ kind: "outcome", source: selected.element, stimulus: outcome }));
      chips.push(chip);
    }
  }
  $("outcome-chips").replaceChildren(...chips);
}

function argumentsForm(box) {
  const form = $("arguments-form");
  form.hidden = !(box && box.imports);
  if (form.hidden) return;
  const given = Object.fromEntries(box.arguments);
  $("arguments").replaceChildren(...box.parameters.map(([type, name, fallback]) => {
    const label = document.createElement("label");
    const input = field(document.createElement("input"), given[name] || "");
    input.dataset.parameter = name;
    input.placeholder = fallback || "(needed)";
    input.size = 16;
    label.append(`${name} : ${type} `, input);
    return label;
  }));
  $("arguments-check").textContent = "";
}

function argumentsRequest() {
  const values = [...$("arguments").querySelectorAll("input")].map(i => [i.dataset.parameter, i.value]);
  return { op: "set-arguments", state: selected.element, arguments: values };
}

function conditionForm(box) {
  const form = $("condition-form");
  form.hidden = !(box && box.kind.endsWith("condition"));
  if (!form.hidden) field($("condition-expression"), box.expression || "");
  $("condition-check").textContent = "";
}

// One form per transition the selected arrow draws.
function transitionForms(transitions) {
  const [source, target] = (selected?.element || "").split("->");
  $("transitions").replaceChildren(...transitions.map((t, number) => {
    const form = document.createElement("form");
    form.className = "transition";
    const inputs = {};
    for (const [name, multi] of [["stimulus", false], ["guard", false], ["action", true]]) {
      const label = document.createElement("label");
      const input = field(document.createElement(multi ? "textarea" : "input"), t[name]);
      input.name = name;
      if (multi) input.rows = 2;
      inputs[name] = input;
      label.append(name + " ", input);
      form.append(label);
    }
    const check = document.createElement("div");
    check.className = "check";
    const apply = document.createElement("button");
    apply.type = "submit";
    apply.textContent = "Apply transition";
    form.append(check, apply);
    const request = () => ({ op: "set-transition", source, target, number,
      stimulus: inputs.stimulus.value, guard: inputs.guard.value, action: inputs.action.value });
    checked(form, check, request, `changed ${source} -> ${target}`);
    return form;
  }));
}

// A form whose text the server checks while it is typed, applied by its submit button.
function checked(form, out, request, done) {
  let timer = null;
  form.addEventListener("input", () => {
    clearTimeout(timer);
    timer = setTimeout(() => preview(request(), out), CHECK_DELAY);
  });
  form.addEventListener("submit", event => {
    event.preventDefault();
    edit(request(), typeof done === "function" ? done() : done);
  });
}

// Each form's latest preview wins: an answer to an older text that comes late is dropped.
const previews = new WeakMap();

async function preview(request, out) {
  const chart = viewChart();
  const body = { chart, version: states.get(chart)?.version, level: diagram.key, ...request };
  const number = (previews.get(out) || 0) + 1;
  previews.set(out, number);
  const answer = await api("preview", {}, body);
  const result = await answer.json();
  if (previews.get(out) !== number) return;
  out.classList.remove("ok", "bad");
  if (!answer.ok) {
    out.textContent = result.error;
    out.classList.add("bad");
    return;
  }
  const fresh = result.findings.filter(f => f.new);
  out.textContent = fresh.length
    ? fresh.map(f => `${f.severity} ${f.code} ${f.message}`).join("\n")
    : "checks: nothing new";
  out.classList.add(fresh.some(f => f.severity === "error") ? "bad" : "ok");
}

function showEnds() {
  $("ends").textContent = `from ${ends.source || "–"} to ${ends.target || "–"}`;
  $("add-transition").disabled = !(ends.source && ends.target);
  const outcomes = level().boxes[ends.source]?.outcomes || [];
  $("outcomes").replaceChildren(...outcomes.map(o => new Option(o, o)));
}

async function refreshSide() {
  const chart = viewChart();
  const state = states.get(chart) || await loadState(chart);
  if (!state) return;
  const palette = $("palette"), chosen = palette.value;
  palette.replaceChildren(...state.palette.map(p => new Option(`${p.name} (${p.layer || "plain"})`, p.name)));
  if (state.palette.some(p => p.name === chosen)) palette.value = chosen;
  const simple = p => p.name.split(".").pop();
  const twice = new Set(state.palette.map(simple).filter((n, i, all) => all.indexOf(n) !== i));
  $("palette-list").replaceChildren(...state.palette.map(p => {
    const item = document.createElement("li");
    item.dataset.chart = p.name;
    item.className = "chip";
    item.textContent = twice.has(simple(p)) ? `${simple(p)} · ${p.name.split(".")[0]}` : simple(p);
    item.title = `${p.name} (${p.layer || "plain"})\nparameters: ` +
      (p.parameters.map(([t, n, d]) => `${t} ${n}${d ? " = " + d : ""}`).join(", ") || "none") +
      `\noutcomes: ${p.outcomes.join(", ") || "none"}`;
    draggable(item, () => ({ kind: "chart", name: p.name }));
    return item;
  }));
  const regions = [...$("diagram").querySelectorAll("g.cluster.region")].map(g => g.dataset.element);
  $("region-choice").hidden = !regions.length;
  $("region").replaceChildren(...regions.map(r => new Option(r, r)));
  $("chart-forms").hidden = diagram.key !== chart;
  if (!dirty()) parametersForm(state.parameters);
  showFindings();
  showEnds();
}

function parametersForm(rows) {
  $("parameters").tBodies[0].replaceChildren(...rows.map(parameterRow));
  $("parameters-check").textContent = "";
}

function parameterRow([type, name, fallback]) {
  const row = document.createElement("tr");
  for (const [value, size] of [[type, 8], [name, 10], [fallback, 9]]) {
    const cell = document.createElement("td");
    const input = field(document.createElement("input"), value);
    input.size = size;
    cell.append(input);
    row.append(cell);
  }
  const remove = document.createElement("button");
  remove.type = "button";
  remove.textContent = "×";
  remove.title = "remove this parameter";
  remove.addEventListener("click", () => {
    row.remove();
    $("parameters-form").dispatchEvent(new Event("input"));
  });
  const cell = document.createElement("td");
  cell.append(remove);
  row.append(cell);
  return row;
}

function parametersRequest() {
  const rows = [...$("parameters").tBodies[0].rows].map(r => [...r.querySelectorAll("input")].map(i => i.value));
  return { op: "set-parameters", parameters: rows.filter(r => r.some(v => v.trim())) };
}

// Findings of the chosen chart, on its levels: a click opens the level and shows the element.
function showFindings() {
  const state = states.get(root);
  const rootName = root.split(".").pop();
  const place = f => {
    const view = rootName + f.level.slice(root.length);
    if (!f.element) return view;
    if (!f.element.includes("->")) return `${view}/${f.element}`;
    const [source, target] = f.element.split("->");
    return `${view}/${source}->${view}/${target}`;
  };
  const findings = state?.findings || [];
  for (const severity of ["error", "warning"]) {
    diagram.mark(severity, findings.filter(f => f.severity === severity).map(place));
  }
  $("findings").replaceChildren(...findings.map(f => {
    const item = document.createElement("li");
    item.className = f.severity;
    item.textContent = `${f.line}:${f.column} ${f.code} ${f.message}`;
    item.title = f.hint || "";
    item.addEventListener("click", () => {
      diagram.open(f.level, rootName + f.level.slice(root.length));
      const g = diagram.elements().find(e => e.dataset.path === place(f));
      if (g) {
        select(g);
        g.classList.add("flash");
        setTimeout(() => g.classList.remove("flash"), 1500);
      }
    });
    return item;
  }));
  if (!findings.length) $("findings").textContent = "none";
}

function showHistory() {
  const history = states.get(root)?.history || { undo: "", redo: "" };
  $("undo").disabled = !history.undo;
  $("undo").title = history.undo ? "undo " + history.undo : "";
  $("redo").disabled = !history.redo;
  $("redo").title = history.redo ? "redo " + history.redo : "";
}

// -- edits -------------------------------------------------------------------------------

// Changes of the page's own (an edit, undo, a new chart) hold back the news of changes on
// disk until the page shows what they did: those come back with the stamp it shows then.
async function own(work) {
  busy += 1;
  try {
    return await work();
  } finally {
    busy -= 1;
    if (!busy && waiting) changed(waiting);
  }
}

function edit(request, done) {
  return own(() => editing(request, done));
}

async function editing(request, done) {
  const chart = viewChart();
  const body = { chart, version: states.get(chart)?.version, level: diagram.key, ...request };
  const answer = await api(request.op === "rename" ? "rename" : "edit", {}, body);  // a rename has a route of its own
  const result = await answer.json();
  if (!answer.ok && answer.status !== 409) {
    say(`refused: ${result.error}`, true);
    return false;
  }
  ends = { source: null, target: null };
  $("stimulus").value = "";
  $("name").value = "";
  for (const input of document.querySelectorAll("#side form [data-applied]")) input.dataset.applied = input.value;
  let next = root;
  if (request.op === "rename" && request.element === "" && chart === root) next = result.chart;
  await load(next, true);  // what is on disk now, edited or changed by someone else
  refused = answer.ok ? null : { request, done };
  $("again").hidden = answer.ok;
  if (answer.ok) say(done);
  else say(`refused: ${result.error}; reloaded what is on disk`, true);
  return answer.ok;
}

function region() {
  return $("region-choice").hidden ? "" : $("region").value + "/";
}

// A state's name for a chart dropped in: the chart's name numbered from 1.
function uniqueName(base, where = region()) {
  const taken = new Set(diagram.elements().map(g => g.dataset.element));
  let n = 1;
  while (taken.has(where + base + n)) n++;
  return base + n;
}

function addState(chart, where = region()) {
  const name = $("name").value.trim() || uniqueName(chart.split(".").pop(), where);
  return edit({ op: "add-state", name: where + name, imports: chart }, `added ${name}`);
}

// -- dragging ----------------------------------------------------------------------------
// Pointer events: a chip follows the pointer; where it is let go decides the edit.

function draggable(element, payload) {
  element.addEventListener("pointerdown", event => {
    if (event.button !== 0) return;
    event.preventDefault();
    const ghost = $("ghost");
    const data = payload();
    ghost.textContent = element.textContent;
    const follow = e => {
      ghost.hidden = false;
      ghost.style.left = `${e.clientX + 10}px`;
      ghost.style.top = `${e.clientY + 10}px`;
      document.querySelectorAll("#diagram .drop").forEach(g => g.classList.remove("drop"));
      dropTarget(e.clientX, e.clientY)?.classList.add("drop");
    };
    const end = e => {
      document.removeEventListener("pointermove", follow);
      document.removeEventListener("pointerup", end);
      ghost.hidden = true;
      document.querySelectorAll("#diagram .drop").forEach(g => g.classList.remove("drop"));
      const inside = document.elementFromPoint(e.clientX, e.clientY)?.closest("#diagram");
      if (inside) dropped(data, dropTarget(e.clientX, e.clientY));
    };
    document.addEventListener("pointermove", follow);
    document.addEventListener("pointerup", end);
  });
}

// The box under the pointer; else the smallest box whose bounds (a condition's bullseye
// with its label) hold it, or one a few pixels away: small targets stay easy to hit.
// A box dragged onto another: a transition from it, with the outcome picked from a menu
// where it has several (a click without a move only selects).
function boxDragging() {
  let start = null;
  $("diagram").addEventListener("pointerdown", event => {
    const g = event.target.closest("g.node[data-path]");
    if (event.button !== 0 || !g || g.dataset.element.includes("#")) return;
    start = { x: event.clientX, y: event.clientY, source: g.dataset.element, moved: false };
  });
  document.addEventListener("pointermove", event => {
    if (!start) return;
    if (!start.moved && Math.hypot(event.clientX - start.x, event.clientY - start.y) < 8) return;
    start.moved = true;
    const ghost = $("ghost");
    ghost.textContent = `${start.source} →`;
    ghost.hidden = false;
    ghost.style.left = `${event.clientX + 10}px`;
    ghost.style.top = `${event.clientY + 10}px`;
    document.querySelectorAll("#diagram .drop").forEach(g => g.classList.remove("drop"));
    dropTarget(event.clientX, event.clientY)?.classList.add("drop");
  });
  document.addEventListener("pointerup", event => {
    const drag = start;
    start = null;
    if (!drag?.moved) return;
    const swallow = e => e.stopPropagation();  // the click that ends a drag selects nothing
    document.addEventListener("click", swallow, { capture: true, once: true });
    setTimeout(() => document.removeEventListener("click", swallow, { capture: true }), 0);
    $("ghost").hidden = true;
    document.querySelectorAll("#diagram .drop").forEach(g => g.classList.remove("drop"));
    const target = dropTarget(event.clientX, event.clientY);
    if (!target || !target.classList.contains("node") || target.dataset.element.includes("#")) return;
    const outcomes = level().boxes[drag.source]?.outcomes || [];
    const link = stimulus => dropped({ kind: "outcome", source: drag.source, stimulus }, target);
    if (!outcomes.length) link("");
    else outcomeMenu(event.clientX, event.clientY, outcomes, link);
  });
}

function outcomeMenu(x, y, outcomes, chosen) {
  const menu = $("outcome-menu");
  menu.replaceChildren(...[...outcomes, ""].map(outcome => {
    const item = document.createElement("li");
    item.textContent = outcome || "(no stimulus)";
    item.dataset.outcome = outcome;
    item.addEventListener("click", () => { menu.hidden = true; chosen(outcome); });
    return item;
  }));
  menu.style.left = `${x}px`;
  menu.style.top = `${y}px`;
  menu.hidden = false;
  setTimeout(() => document.addEventListener("click", event => {
    if (!menu.contains(event.target)) menu.hidden = true;
  }, { once: true }), 0);
}

function dropTarget(x, y) {
  const hit = document.elementFromPoint(x, y)?.closest("#diagram g.node[data-path]");
  if (hit) return hit;
  const near = [];
  for (const g of document.querySelectorAll("#diagram g.node[data-path]")) {
    const r = g.getBoundingClientRect();
    const dx = Math.max(r.left - x, 0, x - r.right), dy = Math.max(r.top - y, 0, y - r.bottom);
    if (Math.hypot(dx, dy) <= 12) near.push([Math.hypot(dx, dy), r.width * r.height, g]);
  }
  near.sort((a, b) => a[0] - b[0] || a[1] - b[1]);
  if (near.length) return near[0][2];
  return document.elementFromPoint(x, y)?.closest("#diagram g.cluster.region[data-path]") || null;
}

function dropped(data, target) {
  if (data.kind === "chart") {
    const where = target?.classList.contains("region") ? target.dataset.element + "/" : region();
    addState(data.name, where);
  } else if (data.kind === "outcome") {
    if (!target || !target.classList.contains("node") || target.dataset.element.includes("#")) {
      say("drop an outcome on the state or condition the transition leads to", true);
      return;
    }
    const to = target.dataset.element;
    const stimulus = data.stimulus;
    edit({ op: "add-transition", source: data.source, target: to, stimulus },
      `added ${data.source} -> ${to}${stimulus ? " " + stimulus : ""}`);
  }
}

// -- wiring ------------------------------------------------------------------------------

function submit(id, handler) {
  $(id).addEventListener("submit", event => {
    event.preventDefault();
    handler();
  });
}

function historyStep(way) {
  return own(async () => {
    const answer = await api(`history/${way}`, {}, {});
    const result = await answer.json();
    await load(root, true);
    if (answer.ok) say(`${way === "undo" ? "undone" : "redone"}: ${result.done}`);
    else say(`refused: ${result.error}`, true);
  });
}

function wire() {
  $("chart").addEventListener("change", () => load($("chart").value));
  $("palette").addEventListener("change", () => {
    $("name").value = uniqueName($("palette").value.split(".").pop());
  });
  $("add-state").addEventListener("click", () => addState($("palette").value));
  $("add-transition").addEventListener("click", () => {
    const stimulus = $("stimulus").value.trim();
    edit({ op: "add-transition", source: ends.source, target: ends.target, stimulus },
      `added ${ends.source} -> ${ends.target} ${stimulus}`);
  });
  $("delete").addEventListener("click", () =>
    edit({ op: "delete", element: selected.element }, `deleted ${selected.element}`));
  $("earlier").addEventListener("click", () =>
    edit({ op: "move", state: selected.element, steps: -1 }, `moved ${selected.element} earlier`));
  $("later").addEventListener("click", () =>
    edit({ op: "move", state: selected.element, steps: 1 }, `moved ${selected.element} later`));
  $("undo").addEventListener("click", () => historyStep("undo"));
  $("redo").addEventListener("click", () => historyStep("redo"));
  $("again").addEventListener("click", () => refused && edit(refused.request, refused.done));
  submit("rename-form", () => {
    const element = selected.kind === "frame" ? "" : selected.element;
    const to = $("rename-to").value.trim();
    edit({ op: "rename", element, to }, `renamed ${element || viewChart()} to ${to}`);
  });
  checked($("arguments-form"), $("arguments-check"), argumentsRequest,
    () => `set the arguments of ${selected.element}`);
  checked($("condition-form"), $("condition-check"),
    () => ({ op: "set-condition", name: selected.element, expression: $("condition-expression").value }),
    () => `changed the condition ${selected.element}`);
  checked($("parameters-form"), $("parameters-check"), parametersRequest, "set the parameters");
  $("add-parameter").addEventListener("click", () => {
    $("parameters").tBodies[0].append(parameterRow(["", "", ""]));
  });
  checked($("add-condition-form"), $("add-condition-check"),
    () => ({ op: "add-condition", kind: $("condition-kind").value, name: $("condition-name").value.trim(),
      expression: $("condition-when").value }),
    () => `added ${$("condition-kind").value} condition ${$("condition-name").value.trim()}`);
  $("add-condition-form").addEventListener("submit", () => {
    setTimeout(() => { $("condition-name").value = ""; $("condition-when").value = ""; }, 0);
  });
  $("new-toggle").addEventListener("click", async () => {
    $("new-chart").hidden = !$("new-chart").hidden;
    if ($("new-chart").hidden) return;
    const catalogue = await (await api("catalogue")).json();
    $("packages").replaceChildren(...catalogue.packages.map(p => new Option(p, p)));
    $("new-layer").replaceChildren(...catalogue.layers.map(l => new Option(l, l)), new Option("plain", ""));
    $("new-cell").replaceChildren(new Option("none", ""), ...catalogue.cells.map(c => new Option(c, c)));
  });
  submit("new-chart", () => own(async () => {
    const body = { package: $("new-package").value.trim(), name: $("new-name").value.trim(),
      layer: $("new-layer").value, cell: $("new-cell").value };
    const answer = await api("new", {}, body);
    const result = await answer.json();
    if (!answer.ok) { say(`refused: ${result.error}`, true); return; }
    $("new-chart").hidden = true;
    await listCharts(result.chart);
    await load(result.chart);
    say(`created ${result.chart}`);
  }));
}

// -- changes on disk ---------------------------------------------------------------------
// The server says when the files change (an editor, git, another page); the page's own
// edits come back with the stamp it already shows.

function watchFiles() {
  const socket = new WebSocket(location.href.replace(/^http/, "ws").replace(/\/[^/]*$/, "/events"));
  let polling = null;
  socket.onmessage = message => changed(JSON.parse(message.data));
  socket.onclose = () => {
    polling = polling || setInterval(() => poll().catch(() => {}), POLL);
  };
}

async function changed(change) {
  waiting = busy ? change : null;
  if (busy || change.stamp === stamp) return;
  const shown = root;
  const charts = await listCharts(shown);  // charts come and go with their files
  const still = charts.some(c => c.name === shown);
  await load(still ? shown : charts[0]?.name || shown, still);
  say(`reloaded: ${change.files.join(", ") || "the files"} changed on disk` +
    (still ? "" : `; ${shown} is gone (or does not parse)`), !still);
}

async function poll() {
  const answer = await api("state", { chart: root });
  if (!answer.ok) return;
  const state = await answer.json();
  if (state.stamp !== stamp) {
    await load(root, true);
    say(`reloaded: the files changed on disk`);
  }
}

async function start() {
  const charts = await listCharts();
  const first = charts.find(c => c.name === wanted) || charts.find(c => c.layer === "task") || charts[0];
  wire();
  boxDragging();
  if (typeof wireRun === "function") wireRun();
  if (!first) { say("no statechart below the studio's folders", true); return; }
  $("chart").value = first.name;
  await load(first.name);
  watchFiles();
}

start();
