// The studio page: a chart's diagram with the findings of check on it, and edits of it.
// Every edit names the version of the file it was made on; the server refuses it when the
// file changed on disk since, and the page reloads what is on disk.
// Its requests carry the cookie the page's first load set: the token leaves the address bar.
const wanted = new URLSearchParams(location.search).get("chart");
history.replaceState(null, "", location.pathname);
const POLL = 1500;

let root = "";               // the statechart chosen above
const states = new Map();    // chart -> its state: version, findings, palette, outcomes
let selected = null;         // {element, path, kind}
let ends = { source: null, target: null };

const $ = id => document.getElementById(id);
const diagram = new DiagramView($("diagram"), $("crumbs"), {
  selectOnClick: true,
  onPick: (path, g) => select(g),
  onOpen: () => { select(null); refreshSide(); },
});

function say(text, refused = false) {
  $("message").textContent = text;
  $("message").classList.toggle("refused", refused);
}

async function api(path, params = {}, body = null) {
  const search = new URLSearchParams(params);
  const answer = await fetch(`${path}?${search}`, body ? {
    method: "POST", headers: { "Content-Type": "application/json" }, body: JSON.stringify(body),
  } : {});
  return answer;
}

// The chart the level in view belongs to: edits change that chart's file.
function viewChart() {
  return diagram.key.split("/")[0] || root;
}

async function loadState(chart) {
  const answer = await api("state", { chart });
  if (answer.ok) states.set(chart, await answer.json());
  return states.get(chart);
}

async function load(chart, keep = false) {
  const [key, view] = [diagram.key, diagram.view];
  const answer = await api("diagram.svg", { chart });
  if (!answer.ok) {
    say((await answer.json()).error, true);
    return;
  }
  root = chart;
  diagram.load(await answer.text());
  states.clear();
  await loadState(chart);
  if (keep && diagram.levels.has(key)) diagram.open(key, view);
  else diagram.reveal([]);
  $("file").textContent = states.get(chart)?.file || "";
  await refreshSide();
}

function select(g) {
  document.querySelectorAll("#diagram .selected").forEach(e => e.classList.remove("selected"));
  if (!g) {
    selected = null;
  } else {
    g.classList.add("selected");
    const kind = g.classList.contains("edge") ? "edge" : g.classList.contains("node") ? "node"
      : g.classList.contains("graph") ? "frame" : "region";
    selected = { element: g.dataset.element, path: g.dataset.path, kind };
    if (kind === "node" && !selected.element.includes("#")) {  // a state, condition or pseudostate
      if (ends.source && !ends.target) ends.target = selected.element;
      else ends = { source: selected.element, target: null };
    }
  }
  $("selected").textContent = selected ? `${selected.kind} ${selected.element || diagram.view}` : "nothing";
  const state = selected?.kind === "node" && !selected.element.includes("#");
  $("delete").disabled = !(state || selected?.kind === "edge");
  $("earlier").disabled = $("later").disabled = !state;
  showEnds();
}

function showEnds() {
  $("ends").textContent = `from ${ends.source || "–"} to ${ends.target || "–"}`;
  $("add-transition").disabled = !(ends.source && ends.target);
  const outcomes = states.get(viewChart())?.outcomes?.[diagram.key]?.[ends.source] || [];
  $("outcomes").replaceChildren(...outcomes.map(o => new Option(o, o)));
}

async function refreshSide() {
  const chart = viewChart();
  const state = states.get(chart) || await loadState(chart);
  if (!state) return;
  const palette = $("palette"), chosen = palette.value;
  palette.replaceChildren(...state.palette.map(p => new Option(`${p.name} (${p.layer || "plain"})`, p.name)));
  if (state.palette.some(p => p.name === chosen)) palette.value = chosen;
  const regions = [...$("diagram").querySelectorAll("g.cluster.region")].map(g => g.dataset.element);
  $("region-choice").hidden = !regions.length;
  $("region").replaceChildren(...regions.map(r => new Option(r, r)));
  showFindings();
  showEnds();
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

async function edit(request, done) {
  const chart = viewChart();
  const body = { chart, version: states.get(chart)?.version, level: diagram.key, ...request };
  const answer = await api("edit", {}, body);
  const result = await answer.json();
  if (!answer.ok && answer.status !== 409) {
    say(`refused: ${result.error}`, true);
    return;
  }
  ends = { source: null, target: null };
  $("stimulus").value = "";
  await load(root, true);  // what is on disk now, edited or changed by someone else
  if (answer.ok) say(done);
  else say(`refused: ${result.error}; reloaded what is on disk`, true);
}

function region() {
  return $("region-choice").hidden ? "" : $("region").value + "/";
}

function uniqueName(base) {
  const taken = new Set(diagram.elements().map(g => g.dataset.element));
  let name = base, n = 2;
  while (taken.has(region() + name)) name = base + n++;
  return name;
}

function wire() {
  $("chart").addEventListener("change", () => load($("chart").value));
  $("palette").addEventListener("change", () => {
    $("name").value = uniqueName($("palette").value.split(".").pop());
  });
  $("add-state").addEventListener("click", () => {
    const name = $("name").value.trim() || uniqueName($("palette").value.split(".").pop());
    edit({ op: "add-state", name: region() + name, imports: $("palette").value }, `added ${name}`);
  });
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
}

// A file changed on disk (an editor, git, another page): show what is there now.
async function poll() {
  for (const chart of new Set([root, viewChart()])) {
    const known = states.get(chart)?.version;
    const answer = await api("state", { chart });
    if (!answer.ok || !known) continue;
    const state = await answer.json();
    if (state.version !== known) {
      say(`reloaded: ${state.file} changed on disk`);
      await load(root, true);
      return;
    }
  }
}

async function start() {
  const charts = await (await api("charts")).json();
  $("chart").replaceChildren(...charts.map(c => new Option(`${c.name} (${c.layer || "plain"})`, c.name)));
  const first = charts.find(c => c.name === wanted) || charts.find(c => c.layer === "task") || charts[0];
  if (!first) { say("no statechart below the studio's folders", true); return; }
  $("chart").value = first.name;
  wire();
  await load(first.name);
  setInterval(() => poll().catch(() => {}), POLL);
}

start();
