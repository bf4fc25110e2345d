// urdflint web page: the statics panel, from the check answer's "statics" (what `urdflint
// info --statics --format json` gives, urdflint/outputs/statics_info.py). One row per
// actuated joint, the weakest first: a bar of the largest gravity torque (or force) it
// needs against its effort limit (the tick), in red when it cannot hold it (D001), amber
// under a 1.5x margin, green when it holds, grey when its bound proves it holds in every
// configuration, or it is passive, unloaded or unlimited; each row says so in words too.
// The first rows show (every joint that cannot hold, at least three); "Show all" the rest.
// Below: the weakest joint, the payload it allows and, for a mobile base, its stability,
// with a button for the support polygon in the 3D view (scene.js draws it).
// Events on document: urdflint:results {statics, scene} -> rebuild; a click on a joint
// sends urdflint:select {link: the link it moves, from: "statics"}; urdflint:select marks
// the joint of the selected link and opens its details (where the load peaks, the bound).
// Every name from the file is inserted as text.

const SHOWN = 3; // rows shown before "Show all" (more when more joints cannot hold)
const TIGHT = 1.5; // a margin under this is amber
const TIPS = 10; // degrees: a base that a smaller tilt tips over is close to tipping (amber)
const $ = (id) => document.getElementById(id);
const state = { rows: [], all: false, selected: null };

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

function num(value, digits) {
  if (typeof value !== "number" || !isFinite(value)) return "—";
  return Number(value.toPrecision(digits || 3)).toString();
}

function positive(value) {
  return typeof value === "number" && isFinite(value) && value > 0;
}

function judged(joint) {
  // a joint D001 judges: driven, with an effort limit and a load
  return !joint.passive && positive(joint.effort) && positive(joint.needed);
}

function status(joint) {
  // [data-status, the word shown, the sentence of its details]
  if (joint.passive) return ["passive", "passive", "passive: no actuator drives it (no <transmission> names it), not judged"];
  if (!positive(joint.effort)) return ["unlimited", "no limit", "no effort limit to judge against"];
  if (!positive(joint.needed)) return ["unloaded", "no load", "gravity puts no load on it"];
  const margin = joint.effort / joint.needed;
  if (margin < 1) return ["fails", "cannot hold", "cannot hold it: the simulator clamps its force and the joint sags (D001)"];
  if (margin < TIGHT) return ["tight", "tight", `holds, but with a margin under ${TIGHT}×: a payload or an acceleration can exceed its effort`];
  if (joint.proven) return ["proven", "proven", "holds in every configuration: even the bound is within the effort"];
  return ["holds", "holds", "holds wherever the search looked (the bound does not prove it)"];
}

function where(joint) {
  const values = Object.entries(joint.at || {}).map(([name, value]) => `${name}=${num(value, 4)}`);
  if (values.length) return `at ${values.join(", ")} (the other joints at 0)`;
  return positive(joint.needed) ? "in any configuration" : "";
}

function bar(joint) {
  // the needed load and the effort limit on one scale: the larger of the two fills the bar
  const scale = Math.max(positive(joint.effort) ? joint.effort : 0, positive(joint.needed) ? joint.needed : 0);
  const box = el("span", { class: "bar", "aria-hidden": "true" });
  const fill = el("span", { class: "fill" });
  fill.style.width = scale > 0 && positive(joint.needed) ? `${Math.max(1, (100 * joint.needed) / scale)}%` : "0";
  box.append(fill);
  if (positive(joint.effort) && scale > 0) {
    const tick = el("span", { class: "limit" });
    tick.style.left = `${(100 * joint.effort) / scale}%`;
    box.append(tick);
  }
  return box;
}

function row(joint, link, weakest) {
  const [kind, word, sentence] = status(joint);
  const unit = joint.unit || "";
  const effort = positive(joint.effort) ? `${num(joint.effort)} ${unit}` : "no limit";
  const margin = judged(joint) ? ` · margin ${num(joint.effort / joint.needed)}` : "";
  const name = link
    ? el("button", { type: "button", class: "joint-name", title: `Show link ‘${link}’, which this joint moves, in the 3D view and the tree` }, joint.name)
    : el("span", { class: "joint-name" }, joint.name);
  const details = [`${joint.name}: ${sentence}.`];
  if (positive(joint.needed)) details.push(`It needs ${num(joint.needed, 4)} ${unit} ${where(joint)}; no configuration needs more than ${num(joint.bound, 4)} ${unit} (the bound).`);
  const item = el("li", { class: "joint", "data-joint": joint.name, "data-status": kind, "data-link": link || null, "data-weakest": weakest ? "true" : null,
    "data-margin": judged(joint) ? String(joint.effort / joint.needed) : null },
    el("span", { class: "head" }, name, weakest ? el("span", { class: "weakest" }, "weakest") : null),
    bar(joint),
    el("span", { class: "numbers" }, `${num(joint.needed)} of ${effort}${margin}`),
    el("span", { class: "status" }, word),
    el("p", { class: "joint-detail", hidden: "" }, details.join(" ")));
  return { item, joint, link, kind };
}

function childLinks(scene) {
  const found = new Map();
  for (const joint of Array.isArray(scene && scene.joints) ? scene.joints : []) {
    if (joint && typeof joint.name === "string") found.set(joint.name, joint.child);
  }
  return found;
}

function order(joints) {
  // the judged joints by margin (the weakest first), then the others as the file has them
  const indexed = joints.map((joint, index) => ({ joint, index }));
  indexed.sort((a, b) => (judged(b.joint) - judged(a.joint))
    || (judged(a.joint) ? a.joint.effort / a.joint.needed - b.joint.effort / b.joint.needed : 0)
    || a.index - b.index);
  return indexed.map((i) => i.joint);
}

function summary(data) {
  // the weakest joint and the payload it allows, in words
  // (the weakest joint is the first row, marked)
  const parts = [];
  const weakest = data.weakest;
  if (!weakest || typeof weakest.margin !== "number") parts.push("No actuated joint has both a load and an effort limit.");
  const payload = data.allowed_payload;
  if (payload && payload.already_exceeded) parts.push(`No payload at ${payload.link}: ${payload.joint} cannot hold the robot itself.`);
  else if (payload && typeof payload.mass === "number") parts.push(`Payload: ${num(payload.mass)} kg at ${payload.link} at full reach (${payload.joint} reaches its limit).`);
  if (data.payload && typeof data.payload.mass === "number") parts.push(`With ${num(data.payload.mass)} kg at ${data.payload.link}.`);
  return parts.join(" ");
}

function baseOf(data) {
  const sections = Array.isArray(data.sections) ? data.sections : [];
  const found = sections.find((s) => s && s.name === "base");
  return found && found.data && typeof found.data === "object" ? found.data : null;
}

function baseLine(base) {
  // the mobile base's stability: [status, sentence], or null for a robot that is not one
  if (!base || !base.mobile) return null;
  const support = base.support;
  if (!support || !Array.isArray(support.polygon) || support.kind === "none" || !base.zero) {
    return ["unjudged", `Base: not judged${base.reason ? `: ${base.reason}` : ""}.`];
  }
  const stance = base.given || base.zero;
  const margin = stance.margin_mm;
  const tilt = stance.tipping_angle_deg;
  const kind = margin < 0 ? "falls" : typeof tilt === "number" && tilt < TIPS ? "close" : "stands";
  const pose = base.given ? "at the joint positions given" : "at the zero pose";
  let text = margin < 0
    ? `Base: falls ${pose}, its centre of mass ${num(-margin)} mm outside the support polygon, towards ${stance.direction}`
    : `Base: stands ${pose}, its centre of mass ${num(margin)} mm inside the support polygon (nearest edge ${stance.direction})${typeof tilt === "number" ? `, tips at a ${num(tilt)}° tilt` : ""}`;
  if (base.worst) text += `; ${num(base.worst.margin_mm)} mm at worst`;
  if (base.reach) text += `; reach ${num(base.reach.max_distance)} m`;
  text += ".";
  return [kind, text];
}

function showRows() {
  // the first rows (every joint that cannot hold, at least SHOWN), the selected one, or all
  const failing = state.rows.filter((r) => r.kind === "fails").length;
  const room = state.all ? Infinity : Math.max(SHOWN, failing);
  state.rows.forEach((r, i) => {
    const chosen = state.selected !== null && r.link === state.selected;
    r.item.hidden = i >= room && !chosen;
    r.item.classList.toggle("selected", chosen);
    r.item.querySelector(".joint-detail").hidden = !chosen;
  });
  const more = $("statics-more");
  const rest = state.rows.length - room;
  more.hidden = state.rows.length <= Math.max(SHOWN, failing);
  more.textContent = state.all ? "Show fewer" : `Show all ${state.rows.length} joints (${rest} more)`;
  more.setAttribute("aria-expanded", String(state.all));
}

function render(detail) {
  const card = $("statics-card");
  const data = detail && detail.statics;
  state.rows = [];
  state.all = false;
  state.selected = null;
  $("statics-joints").replaceChildren();
  $("statics-base").replaceChildren();
  $("statics-base").hidden = true;
  if (!data || typeof data !== "object") {
    card.hidden = true;
    return;
  }
  const joints = Array.isArray(data.joints) ? data.joints : [];
  const base = baseLine(baseOf(data));
  card.hidden = data.computed === true && !joints.length && !base;
  if (data.computed !== true) {
    $("statics-summary").textContent = `Not computed: ${data.problem || "the model could not be built"}.`;
    $("statics-count").textContent = "";
    showRows();
    return;
  }
  const links = childLinks(detail.scene);
  const weakest = data.weakest && data.weakest.joint;
  state.rows = order(joints).map((j) => row(j, links.get(j.name), j.name === weakest));
  $("statics-joints").replaceChildren(...state.rows.map((r) => r.item));
  const failing = state.rows.filter((r) => r.kind === "fails").length;
  const tight = state.rows.filter((r) => r.kind === "tight").length;
  const counts = [`${joints.length} actuated joint${joints.length === 1 ? "" : "s"}`];
  if (failing) counts.push(`${failing} cannot hold`);
  if (tight) counts.push(`${tight} tight`);
  $("statics-count").textContent = counts.join(" · ");
  $("statics-summary").textContent = summary(data);
  showBase(base);
  showRows();
}

function showBase(base) {
  const box = $("statics-base");
  box.hidden = !base;
  if (!base) return;
  box.dataset.status = base[0];
  box.append(el("span", { class: "base-text" }, base[1]));
  if (["falls", "close", "stands"].includes(base[0])) {
    const button = el("button", { type: "button", id: "statics-support", class: "link-button" });
    button.addEventListener("click", toggleSupport);
    box.append(" ", button);
    labelSupport();
  }
}

function supportBox() {
  return document.querySelector("[data-show='support']");
}

function labelSupport() {
  const button = $("statics-support");
  const box = supportBox();
  if (button && box) button.textContent = box.checked ? "Hide it in 3D" : "Show it in 3D";
}

function toggleSupport() {
  const box = supportBox();
  if (!box || box.disabled) return;
  box.checked = !box.checked;
  box.dispatchEvent(new Event("change"));
  if (box.checked) $("view-card").scrollIntoView({ behavior: "smooth", block: "start" });
}

function select(link) {
  state.selected = link || null;
  showRows();
}

$("statics-joints").addEventListener("click", (event) => {
  const button = event.target.closest("button.joint-name");
  const item = button && button.closest("li.joint");
  if (!item || !item.dataset.link) return;
  document.dispatchEvent(new CustomEvent("urdflint:select", { detail: { link: item.dataset.link, from: "statics" } }));
});
$("statics-more").addEventListener("click", () => {
  state.all = !state.all;
  showRows();
});
document.addEventListener("urdflint:results", (event) => render(event.detail));
document.addEventListener("urdflint:select", (event) => select(event.detail && event.detail.link));
document.addEventListener("change", (event) => {
  if (event.target === supportBox()) labelSupport();
});
