// The diagram of a model, one chart level at a time: breadcrumbs, drill-down, highlights.
//
// The server sends one SVG document: the index of the levels as JSON in its <metadata>, then
// one <svg class="level"> per level in the index's order. A level is shown for an instance
// path (the trace's state path of the chart or state it draws), so one picture of a skill
// serves every state that imports it; each of its elements gets that path in data-path: the
// level's frame (the graph) the instance path itself, a box the path of its state.

class DiagramView {
  constructor(box, crumbs, options = {}) {
    this.box = box;
    this.crumbs = crumbs;
    this.options = options; // onNavigate(), onPick(path, element), onOpen(key, view), selectOnClick
    this.levels = new Map();
    this.root = "";
    this.key = "";
    this.view = "";
    this.active = [];
    this.marks = {};
  }

  load(text) {
    const doc = new DOMParser().parseFromString(text, "image/svg+xml");
    const index = JSON.parse(doc.getElementById("levels").textContent);
    const pictures = [...doc.documentElement.children].filter(e => e.classList.contains("level"));
    this.levels.clear();
    index.levels.forEach((entry, i) => this.levels.set(entry.key, { ...entry, svg: pictures[i] }));
    this.root = index.root;
    this.rootName = index.root.split(".").pop();
    this.key = this.view = "";
  }

  // The levels a state path passes through, from the top: [{key, view}].
  chain(path) {
    const parts = path.split("/");
    let key = this.root, at = 1;
    const steps = [{ key, view: parts[0] }];
    while (at < parts.length) {
      const drills = this.levels.get(key).drills;
      let end = parts.length;
      while (end > at && !Object.hasOwn(drills, parts.slice(at, end).join("/"))) end--;
      if (end === at) break;
      key = drills[parts.slice(at, end).join("/")];
      steps.push({ key, view: parts.slice(0, end).join("/") });
      at = end;
    }
    return steps;
  }

  // Show the deepest level that draws every one of ``paths`` as a box (or draws their
  // deepest ancestors): one level for one active state, the level of their regions for
  // states active in several regions.
  reveal(paths) {
    const chains = (paths.length ? paths : [this.rootName]).map(path => {
      const steps = this.chain(path);
      if (steps.length > 1 && steps[steps.length - 1].view === path) steps.pop();
      return steps;
    });
    let depth = Math.min(...chains.map(c => c.length));
    const same = i => chains.every(c => c[i].key === chains[0][i].key && c[i].view === chains[0][i].view);
    while (depth > 1 && !same(depth - 1)) depth--;
    const last = chains[0][depth - 1];
    this.open(last.key, last.view);
  }

  open(key, view) {
    if (key === this.key && view === this.view) return false;
    const level = this.levels.get(key);
    if (!level) return false;
    this.key = key;
    this.view = view;
    const svg = document.importNode(level.svg, true);
    const [width, height] = naturalSize(svg);
    svg.setAttribute("width", width);
    svg.setAttribute("height", height);
    svg.dataset.key = key;
    this.box.replaceChildren(svg);
    this.annotate(svg, level, view);
    this.breadcrumbs();
    this.highlight(this.active);
    for (const [name, paths] of Object.entries(this.marks)) this.mark(name, paths);
    this.options.onOpen?.(key, view);
    return true;
  }

  annotate(svg, level, view) {
    for (const g of svg.querySelectorAll("g.graph, g.node, g.cluster, g.edge")) {
      const title = g.querySelector("title")?.textContent || "";
      let path = null;
      if (g.classList.contains("graph")) {
        path = view;
      } else if (g.classList.contains("cluster")) {
        const rel = title.replace(/^cluster_/, "");
        path = rel ? `${view}/${rel}` : view;
      } else if (g.classList.contains("node")) {
        if (title === "#do") path = view;
        else if (!title.includes("#")) path = `${view}/${title}`;
      } else if (g.classList.contains("transition")) {
        const [source, target] = title.split("->");
        path = `${view}/${source}->${view}/${target}`;
      }
      if (path === null) continue;
      g.dataset.path = path;
      g.dataset.element = g.classList.contains("cluster") ? title.replace(/^cluster_/, "") : title;
      if (Object.hasOwn(level.drills, title)) g.dataset.drill = level.drills[title];
      g.addEventListener("click", event => this.clicked(event, g));
      g.addEventListener("dblclick", event => this.opened(event, g));
      g.addEventListener("contextmenu", event => {
        event.preventDefault();
        event.stopPropagation();
        this.options.onPick?.(g.dataset.path, g);
      });
    }
  }

  // A click opens a box's level, or (shift-click, or everywhere with ``selectOnClick``)
  // picks the element; a double click always opens.
  clicked(event, g) {
    event.stopPropagation();
    if (g.dataset.drill && !event.shiftKey && !this.options.selectOnClick) this.opened(event, g);
    else this.options.onPick?.(g.dataset.path, g);
  }

  opened(event, g) {
    event.stopPropagation();
    if (!g.dataset.drill) return;
    this.options.onNavigate?.();
    this.open(g.dataset.drill, g.dataset.path);
  }

  breadcrumbs() {
    if (!this.crumbs) return;
    const items = this.chain(this.view).map(step => {
      const link = document.createElement("a");
      link.href = "#";
      link.textContent = step.view.split("/").pop();
      link.title = this.levels.get(step.key).title;
      link.dataset.view = step.view;
      link.addEventListener("click", event => {
        event.preventDefault();
        this.options.onNavigate?.();
        this.open(step.key, step.view);
      });
      return link;
    });
    const title = document.createElement("span");
    title.className = "level-title";
    title.textContent = this.levels.get(this.key).title;
    const parts = [];
    items.forEach((item, i) => parts.push(...(i ? [" › ", item] : [item])));
    this.crumbs.replaceChildren(...parts, title);
  }

  elements() {
    return [...this.box.querySelectorAll("[data-path]")];
  }

  // Outline every element that shows an active state; fill the innermost ones drawn.
  highlight(active) {
    this.active = active;
    const within = (state, path) => state === path || state.startsWith(path + "/");
    const innermost = innermostOf(active);
    const shapes = this.elements().filter(g => !g.classList.contains("edge"));
    const current = new Set();
    for (const state of innermost) {
      let best = null;
      for (const g of shapes) {
        if (!within(state, g.dataset.path)) continue;
        const longer = !best || g.dataset.path.length > best.dataset.path.length;
        const node = best && g.dataset.path === best.dataset.path && g.classList.contains("node");
        if (longer || node) best = g;
      }
      if (best) current.add(best);
    }
    for (const g of shapes) {
      g.classList.toggle("active", active.some(state => within(state, g.dataset.path)));
      g.classList.toggle("current", current.has(g));
    }
  }

  mark(name, paths) {
    this.marks[name] = paths;
    for (const g of this.elements()) g.classList.toggle(name, paths.includes(g.dataset.path));
  }
}

// The active states no other active state is inside of.
function innermostOf(active) {
  return active.filter(p => !active.some(q => q.startsWith(p + "/")));
}

// Graphviz writes points; the page sizes in CSS pixels.
function naturalSize(svg) {
  const points = value => /pt$/.test(value || "") ? parseFloat(value) * 4 / 3 : parseFloat(value);
  const box = (svg.getAttribute("viewBox") || "0 0 800 600").split(/[ ,]+/).map(Number);
  return [points(svg.getAttribute("width")) || box[2], points(svg.getAttribute("height")) || box[3]];
}
