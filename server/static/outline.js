// urdflint web page: the kinematic tree as an indented outline (left to right, one line per
// link), readable at any size: collapsible subtrees, a search box, the findings' colours.
// Built from the check answer's "scene" (each link's tree joint); every name is inserted as
// text. Talks to the rest of the page through events on document:
//   urdflint:results  {scene, findings, rows}  -> rebuild
//   urdflint:select   {link, from}             -> mark the link, open its ancestors
// and sends urdflint:select {link, from: "outline"} when a link is chosen here.

const INDENT = 16; // px per level, for the first DEEP levels
const DEEP = 14; // below this the indent grows slowly, so a long chain stays on screen
const $ = (id) => document.getElementById(id);

const state = { nodes: [], byName: new Map(), collapsed: new Set(), selected: null, query: "" };

function el(tag, attrs, ...children) {
  const node = document.createElement(tag);
  for (const [key, value] of Object.entries(attrs || {})) {
    if (value !== undefined && value !== null && value !== false) node.setAttribute(key, value);
  }
  for (const child of children) {
    if (child !== null && child !== undefined) node.append(child instanceof Node ? child : String(child));
  }
  return node;
}

function build(scene) {
  // nodes in tree order: each link under its tree joint's parent; a joint naming a link the
  // file does not define becomes a "missing" leaf under its parent
  const links = Array.isArray(scene && scene.links) ? scene.links : [];
  const joints = Array.isArray(scene && scene.joints) ? scene.joints : [];
  const jointOf = new Map(joints.map((j) => [j.name, j]));
  const defined = new Set(links.map((l) => l.name));
  const kids = new Map();
  const add = (parent, node) => {
    if (!kids.has(parent)) kids.set(parent, []);
    kids.get(parent).push(node);
  };
  const roots = [];
  for (const link of links) {
    const joint = link.parent ? jointOf.get(link.parent) : null;
    const extra = joints.filter((j) => j.child === link.name && j.name !== link.parent && defined.has(j.parent));
    const node = { name: link.name, link, joint, extra, missing: false, children: [] };
    if (joint && defined.has(joint.parent)) add(joint.parent, node);
    else roots.push(node);
  }
  for (const joint of joints) {
    if (!defined.has(joint.child) && defined.has(joint.parent)) {
      add(joint.parent, { name: joint.child || "(no child)", link: null, joint, extra: [], missing: true, children: [] });
    }
  }
  const order = [];
  const walk = (node, depth, parent) => {
    node.depth = depth;
    node.parent = parent;
    order.push(node);
    node.children = node.missing ? [] : kids.get(node.name) || [];
    for (const child of node.children) walk(child, depth + 1, node);
  };
  roots.forEach((root) => walk(root, 0, null));
  return order;
}

function severityOf(node) {
  // the link's own worst severity (its tree joint's findings count for it)
  if (node.link) return node.link.severity || null;
  return node.joint ? node.joint.severity || null : null;
}

function row(node) {
  const severity = severityOf(node);
  const count = node.link ? node.link.findings.length : node.joint ? node.joint.findings.length : 0;
  const twisty = node.children.length
    ? el("button", { type: "button", class: "twisty", "aria-label": `Collapse ${node.name}`, tabindex: "-1" })
    : el("span", { class: "twisty leaf", "aria-hidden": "true" });
  const name = el("button", { type: "button", class: "name", title: node.missing ? `link '${node.name}' is not defined` : null }, node.name);
  const via = node.joint ? el("span", { class: "via" }, `${node.joint.name} · ${node.joint.type || "?"}`) : null;
  const extra = node.extra.length
    ? el("span", { class: "extra", title: `also the child of ${node.extra.map((j) => j.name).join(", ")} (a loop or a second parent)` }, `+${node.extra.length}`)
    : null;
  const badge = count ? el("span", { class: "count", "data-severity": severity }, String(count)) : null;
  const line = el("div", { class: "row" }, twisty, el("span", { class: "dot", "data-severity": severity }), name, via, extra, badge);
  const depth = node.depth;
  line.style.paddingLeft = `${4 + Math.min(depth, DEEP) * INDENT + Math.max(0, depth - DEEP) * 4}px`;
  const item = el("li", {
    role: "treeitem", "aria-level": String(depth + 1), "data-link": node.name,
    "data-severity": severity, "data-kind": node.missing ? "missing" : "link",
    "data-depth": String(depth), "aria-expanded": node.children.length ? "true" : null,
  }, line);
  node.item = item;
  return item;
}

function render(detail) {
  const list = $("outline");
  state.nodes = build(detail && detail.scene);
  state.byName = new Map(state.nodes.filter((n) => !n.missing).map((n) => [n.name, n]));
  state.collapsed = new Set();
  state.selected = null;
  if (state.nodes.length > 300) {
    state.nodes.forEach((n) => { if (n.depth >= 3 && n.children.length) state.collapsed.add(n); });
  }
  list.replaceChildren(...state.nodes.map(row));
  if (!state.nodes.length) {
    list.append(el("li", { class: "empty-tree muted" }, "No kinematic tree: the file is not a usable robot."));
  }
  $("outline-search").value = state.query = "";
  show();
}

function hiddenByCollapse(node) {
  for (let up = node.parent; up; up = up.parent) if (state.collapsed.has(up)) return true;
  return false;
}

function show() {
  // which rows are visible: the collapsed subtrees closed; a search shows the matches and
  // their ancestors, whatever is collapsed
  const query = state.query;
  const matches = new Set();
  if (query) {
    for (const node of state.nodes) {
      const joint = node.joint ? node.joint.name.toLowerCase() : "";
      if (node.name.toLowerCase().includes(query) || joint.includes(query)) {
        for (let up = node; up && !matches.has(up); up = up.parent) matches.add(up);
        node.item.classList.add("match");
      } else node.item.classList.remove("match");
    }
  } else state.nodes.forEach((n) => n.item.classList.remove("match"));
  for (const node of state.nodes) {
    node.item.hidden = query ? !matches.has(node) : hiddenByCollapse(node);
    if (node.children.length) {
      const open = query ? true : !state.collapsed.has(node);
      node.item.setAttribute("aria-expanded", String(open));
      node.item.querySelector(".twisty").setAttribute("aria-label", `${open ? "Collapse" : "Expand"} ${node.name}`);
    }
  }
  const links = state.byName.size;
  const found = query ? state.nodes.filter((n) => n.item.classList.contains("match")).length : 0;
  $("outline-count").textContent = query
    ? `${found} of ${links} match` : `${links} link${links === 1 ? "" : "s"}`;
}

function select(name, scroll) {
  if (state.selected) state.selected.item.classList.remove("selected");
  state.selected = null;
  const node = name ? state.byName.get(name) : null;
  if (!node) return;
  state.selected = node;
  for (let up = node.parent; up; up = up.parent) state.collapsed.delete(up);
  show();
  node.item.classList.add("selected");
  if (scroll) {
    const list = $("outline");
    const top = node.item.offsetTop - list.offsetTop;
    if (top < list.scrollTop || top > list.scrollTop + list.clientHeight - node.item.offsetHeight) {
      list.scrollTop = Math.max(0, top - list.clientHeight / 3);
    }
  }
}

function choose(name) {
  document.dispatchEvent(new CustomEvent("urdflint:select", { detail: { link: name, from: "outline" } }));
}

$("outline").addEventListener("click", (event) => {
  const item = event.target.closest("li[data-link]");
  if (!item) return;
  const node = state.nodes.find((n) => n.item === item);
  if (!node) return;
  if (event.target.closest(".twisty") && node.children.length) {
    if (state.collapsed.has(node)) state.collapsed.delete(node);
    else state.collapsed.add(node);
    show();
    return;
  }
  if (!node.missing) choose(node.name);
});
$("outline-search").addEventListener("input", (event) => {
  state.query = event.target.value.trim().toLowerCase();
  show();
});
$("outline-search").addEventListener("keydown", (event) => {
  if (event.key !== "Enter") return;
  event.preventDefault();
  const first = state.nodes.find((n) => !n.missing && n.item.classList.contains("match"));
  if (first) choose(first.name);
});
document.querySelectorAll("[data-outline]").forEach((button) => button.addEventListener("click", () => {
  state.collapsed = new Set(button.dataset.outline === "collapse"
    ? state.nodes.filter((n) => n.children.length && n.depth >= 1) : []);
  if (state.selected) select(state.selected.name, true);
  else show();
}));
document.addEventListener("urdflint:results", (event) => render(event.detail));
document.addEventListener("urdflint:select", (event) => select(event.detail.link, event.detail.from !== "outline"));
