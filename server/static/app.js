// urdflint web page: posts the form to /v1/check (or /v1/fix) and shows the JSON it returns.
// Every string from the response is inserted as text (textContent), never as HTML; the
// diff of /v1/fix is split into lines shown as text, and the fixed file is offered as a
// Blob URL download (no markup is ever built from it).
// The tree SVG is parsed as XML and rebuilt from an allowlist of elements and
// attributes (see cleanSvg), so even a broken server could not inject script.
// The outline (outline.js), the 3D view (scene.js) and the statics panel (statics.js) are
// modules fed through events on document: "urdflint:results" carries the answer's scene and
// statics; "urdflint:select" {link, from} is sent by whichever part the reader clicks (a
// finding row, the outline, the diagram, the 3D view, a joint of the statics panel) and
// every part shows that link.
"use strict";

(function () {
  const SEVERITIES = ["error", "warning", "info"];
  const PLURAL = { error: "errors", warning: "warnings", info: "infos" };
  const SVG_NS = "http://www.w3.org/2000/svg";
  const SVG_TAGS = new Set(["svg", "g", "rect", "circle", "path", "line", "polyline", "text", "tspan", "title"]);
  const SVG_ATTRS = new Set([
    "viewBox", "width", "height", "x", "y", "rx", "ry", "cx", "cy", "r", "d", "points",
    "x1", "y1", "x2", "y2", "fill", "stroke", "stroke-width", "stroke-dasharray",
    "font-family", "font-size", "font-weight", "font-style", "text-anchor", "role",
    "aria-label", "class",
  ]);
  const STATUS = {
    413: "The upload is too large.",
    415: "That kind of upload is not accepted.",
    422: "The request was rejected.",
    429: "The server is busy. Try again in a moment.",
    503: "The server is busy. Try again in a moment.",
    504: "Checking took too long and was stopped.",
  };

  const OUTCOMES = {
    loads: "loads",
    changes: "loads with changes",
    refused: "refused",
    crashes: "crashes",
    "not-installed": "not installed",
  };

  const $ = (id) => document.getElementById(id);
  const form = $("check-form");
  // what the server offers (GET /v1/capabilities): confirm, the engines, target -> engine
  const offer = { confirm: false, installed: [], engineOf: {} };
  let download = null; // the Blob URL of the fixed file, revoked when replaced
  let linkOf = []; // finding index -> the link it belongs to (from the scene), or undefined
  let rowIds = []; // finding index -> its row's id
  let groups = []; // the findings table's rule groups: {id, code, body, rows: [{row, text, ...}], ...}
  let sections = []; // the severities: {severity, head, total, rules}
  let ruleIds = new Map(); // rule code -> the id of its group (its tbody) in the findings table
  let linkOrder = []; // the scene's links, in tree order (the link filter lists them so)
  let showAll = false; // every rule unfolded past LIMIT ("Show all")
  let perRule = 3; // rows each rule shows now (LIMIT, or fewer when many rules match)
  const filters = { severity: "", rule: "", link: "", text: "" };
  // how many rows a rule shows before "Show N more": LIMIT, fewer when many rules match (a
  // big robot's page stays a few screens long: about ROWS rows in all), never none
  const LIMIT = 3;
  const ROWS = 24;
  const picked = { scene: null, findings: [] }; // what the selected link's box reads
  const LEGIBLE = 0.8; // the diagram is never shrunk below this (labels of about 9 px)
  const BIG_TREE = 40; // links past which the diagram starts folded (the outline reads better)

  function el(tag, attrs, ...children) {
    const node = document.createElement(tag);
    for (const [key, value] of Object.entries(attrs || {})) {
      if (value !== undefined && value !== null) node.setAttribute(key, value);
    }
    for (const child of children) {
      if (child === null || child === undefined) continue;
      node.append(child instanceof Node ? child : String(child));
    }
    return node;
  }

  function number(value, digits) {
    if (typeof value !== "number" || !isFinite(value)) return "—";
    return Number(value.toPrecision(digits || 4)).toString();
  }

  // -- the form -------------------------------------------------------------------------

  function mode() {
    return form.querySelector("input[name=mode]:checked").value;
  }

  function showMode() {
    $("file-panel").hidden = mode() !== "file";
    $("paste-panel").hidden = mode() !== "paste";
  }

  function buildRequest() {
    // the form's fields, and the upload's file name (the fixed file is saved under it)
    const data = new FormData();
    let name;
    if (mode() === "file") {
      const file = $("urdf-file").files[0];
      if (!file) throw new Error("Choose a URDF or xacro file first.");
      name = file.name;
      data.append("urdf", file, file.name);
      const meshes = $("meshes-file").files[0];
      if (meshes) data.append("meshes", meshes, meshes.name);
    } else {
      const text = $("urdf-text").value;
      if (!text.trim()) throw new Error("Paste the URDF or xacro XML first.");
      name = /xmlns:xacro\s*=/.test(text) ? "pasted.urdf.xacro" : "pasted.urdf";
      data.append("urdf", new Blob([text], { type: "application/xml" }), name);
    }
    for (const id of ["target", "fail-on", "select", "ignore", "expect-mass", "expect-com", "xacro-args", "q"]) {
      const input = $(id);
      const value = input.value.trim();
      if (value) data.append(input.name, value);
    }
    data.append("svg", "true");
    data.append("scene", "true");
    data.append("statics", "true"); // the statics panel and the support polygon
    if ($("want-matrix").checked) data.append("matrix", "true");
    const engines = confirmEngines();
    if (engines.length && $("want-confirm").checked && !$("confirm-field").hidden) {
      data.append("confirm", engines.join(","));
    }
    return { data, name };
  }

  function confirmEngines() {
    // the installed engines of the chosen simulator (all of them for "All simulators")
    const target = $("target").value;
    if (target === "all") return offer.installed.slice();
    if (!target) return []; // inferred on the server: choose a simulator to confirm in it
    const engine = offer.engineOf[target];
    return engine && offer.installed.includes(engine) ? [engine] : [];
  }

  function showConfirm() {
    const engines = confirmEngines();
    $("want-confirm").disabled = engines.length === 0;
    $("confirm-engines").textContent = engines.length
      ? `(${engines.join(", ")}; slower: each engine loads the model)`
      : "(no engine for this simulator is installed on the server)";
  }

  function learnOffer(found) {
    const confirm = found && found.confirm;
    if (!confirm || confirm.allowed !== true || typeof confirm.engines !== "object") return;
    offer.installed = Object.keys(confirm.engines).filter((name) => confirm.engines[name] === true);
    for (const target of Array.isArray(found.targets) ? found.targets : []) {
      if (target && typeof target.name === "string") offer.engineOf[target.name] = target.engine;
    }
    offer.confirm = true;
    $("confirm-field").hidden = false;
    showConfirm();
  }

  function submit(event) {
    event.preventDefault();
    send(false);
  }

  async function send(fixing) {
    // POST the form to /v1/check, or to /v1/fix when fixing, and show the answer
    hideError();
    let body, name;
    try {
      ({ data: body, name } = buildRequest());
    } catch (problem) {
      showError(problem.message);
      return;
    }
    const unsafe = fixing && $("want-unsafe").checked;
    if (unsafe) body.append("unsafe_fixes", "true");
    const buttons = [$("submit"), $("fix")];
    buttons.forEach((button) => { button.disabled = true; });
    form.setAttribute("aria-busy", "true");
    const confirming = body.has("confirm");
    const asked = { matrix: body.has("matrix") };
    const doing = fixing ? "Fixing…" : "Checking…";
    $("status").textContent = confirming ? `${doing} (the engines load the model too)` : doing;
    try {
      const response = await fetch(fixing ? "/v1/fix" : "/v1/check", {
        method: "POST",
        body: body,
        headers: { Accept: "application/json" },
      });
      let payload = null;
      try {
        payload = await response.json();
      } catch (ignored) {
        payload = null;
      }
      const started = performance.now(); // the 3D view says how long it took from here
      if (!response.ok) {
        const detail = payload && typeof payload.detail === "string" ? payload.detail
          : payload && Array.isArray(payload.detail) ? payload.detail.map((d) => d.msg || "").join("; ")
          : "";
        const retry = response.headers.get("Retry-After");
        showError(STATUS[response.status] || `The server answered ${response.status}.`,
          detail + (retry ? ` (retry after ${retry} s)` : ""), response.status);
        return;
      }
      if (!payload || !Array.isArray(payload.findings)) {
        showError("The server sent an answer this page does not understand.");
        return;
      }
      render(payload, asked, started);
      renderFix(fixing ? payload : null, name, unsafe);
      $("status").textContent = "Done.";
      $("results").scrollIntoView({ behavior: "smooth", block: "start" });
    } catch (problem) {
      showError("Could not reach the urdflint server.", String(problem && problem.message || problem));
    } finally {
      buttons.forEach((button) => { button.disabled = false; });
      form.removeAttribute("aria-busy");
      if ($("status").textContent.startsWith(doing)) $("status").textContent = "";
    }
  }

  function showError(title, detail, status) {
    const box = $("error");
    box.replaceChildren(el("strong", {}, title));
    if (detail) box.append(el("span", { class: "detail" }, detail));
    box.dataset.status = status ? String(status) : "";
    box.hidden = false;
    $("results").hidden = true;
    renderFix(null);
  }

  function hideError() {
    $("error").hidden = true;
    $("error").replaceChildren();
  }

  // -- results --------------------------------------------------------------------------

  function render(doc, asked, started) {
    const summary = doc.summary || {};
    const passed = doc.passed === true;
    const banner = $("banner");
    banner.dataset.passed = String(passed);
    $("verdict").textContent = passed ? "Passed" : "Failed";
    const paths = Object.keys(doc.models || {});
    $("file-name").textContent = paths.join(", ");
    $("counts").replaceChildren(...SEVERITIES.map((sev) => {
      const n = summary[sev] || 0;
      return el("li", { class: n ? sev : `${sev} zero`, "data-severity": sev, "data-count": n },
        `${n} ${n === 1 ? sev : PLURAL[sev]}`);
    }));
    renderModels(doc.models || {});
    renderTargets(doc.targets || {});
    const scene = firstScene(doc.scene);
    linkOf = linksOfFindings(doc.findings, scene);
    linkOrder = scene ? scene.links.map((l) => l.name) : [];
    const anchors = renderFindings(doc.findings, paths[0]);
    renderMatrix(Array.isArray(doc.matrix) ? doc.matrix : [], !!(asked && asked.matrix), anchors);
    renderTrees(doc.svg || {});
    $("results").hidden = false;
    zoom("auto"); // after showing the results: fitting needs the box's width
    centreOnRoot();
    picked.scene = scene;
    picked.findings = doc.findings;
    showPicked(null);
    const statics = doc.statics && typeof doc.statics === "object" ? Object.values(doc.statics)[0] || null : null;
    document.dispatchEvent(new CustomEvent("urdflint:results", {
      detail: { scene, findings: doc.findings, rows: rowIds, started, statics },
    }));
  }

  function renderTargets(found) {
    // which targets the findings are for, and how they were chosen (as the CLI's line)
    const chosen = Object.values(found)[0];
    const line = $("targets-line");
    if (!chosen || !Array.isArray(chosen.names)) { line.textContent = ""; return; }
    const why = (chosen.evidence || []).filter((e) => e && e.why).map((e) => e.why);
    const how = chosen.how === "given" ? "as chosen"
      : chosen.how === "assumed" ? "assumed: nothing in the model names a simulator"
        : `inferred from ${why.slice(0, 3).join("; ")}`;
    line.textContent = `Checked for ${chosen.names.join(", ")} (${how})`;
  }

  function renderModels(models) {
    const box = $("summary");
    box.replaceChildren();
    const paths = Object.keys(models);
    if (!paths.length) box.append(el("p", { class: "not-built" }, "No model."));
    for (const path of paths) {
      const model = models[path];
      const part = el("div", { class: "model", "data-path": path, "data-built": String(!!model) });
      if (paths.length > 1) part.append(el("h3", {}, path));
      if (!model) {
        part.append(el("p", { class: "not-built" },
          "Model not built: Pinocchio could not load it (see the errors) or is not installed."));
      } else {
        const com = Array.isArray(model.com) && model.com.length === 3
          ? el("span", { class: "com" }, ...["x", "y", "z"].map((axis, i) =>
            el("span", {}, el("abbr", {}, axis), " ", number(model.com[i], 3))))
          : "—";
        const rows = [
          ["Name", model.name], ["Root link", model.root], ["Links", model.links],
          ["Joints", model.joints], ["DOF", model.dof],
          ["Mass", typeof model.mass === "number" ? `${number(model.mass)} kg` : "—"],
          ["Centre of mass (m)", com],
        ];
        const list = el("dl");
        for (const [key, value] of rows) {
          list.append(el("dt", {}, key),
            el("dd", { "data-field": key.toLowerCase().replace(/ \(.*\)/, "").replace(/ /g, "-") }, value ?? "—"));
        }
        part.append(list);
      }
      box.append(part);
    }
  }

  function renderFindings(findings, upload) {
    // one row group (tbody) per rule within each severity, the rule's header saying how
    // many; past its first few rows a rule shows "Show N more". The filters hide what does
    // not match
    const table = $("findings");
    rowIds = [];
    groups = [];
    sections = [];
    ruleIds = new Map();
    const indexOf = new Map(findings.map((f, i) => [f, i]));
    table.querySelectorAll("tbody").forEach((body) => body.remove());
    $("no-findings").hidden = findings.length > 0;
    table.hidden = findings.length === 0;
    $("findings-tools").hidden = findings.length === 0;
    const many = new Set(findings.map((f) => f.path)).size > 1;
    const anchors = new Map(); // "path|line|code|element" and "line|code" -> the row's id
    let count = 0;
    for (const sev of SEVERITIES) {
      const bySeverity = findings.filter((f) => f.severity === sev);
      if (!bySeverity.length) continue;
      const head = el("th", { class: "group", colspan: "2", scope: "rowgroup" });
      const top = el("tbody", { class: `severity ${sev}`, "data-severity": sev }, el("tr", { class: "group-row" }, head));
      table.append(top);
      const section = { severity: sev, head, top, total: bySeverity.length, rules: [] };
      const codes = [...new Set(bySeverity.map((f) => String(f.code)))].sort();
      for (const code of codes) {
        const same = bySeverity.filter((f) => String(f.code) === code);
        const group = ruleGroup(sev, code, same);
        if (!ruleIds.has(code)) ruleIds.set(code, group.id);
        for (const f of same) {
          const id = `finding-${++count}`;
          rowIds[indexOf.get(f)] = id;
          for (const key of [anchorKey(f, true), anchorKey(f, false)]) {
            if (!anchors.has(key)) anchors.set(key, id);
          }
          const link = linkOf[indexOf.get(f)];
          const row = findingRow(f, id, link, many ? `${f.path}:${f.line}` : f.line, group.fix ? null : f.fix, fixable(f, upload));
          row.dataset.group = group.id;
          group.body.insertBefore(row, group.more);
          const words = [f.code, f.name, f.message, f.element, f.fix, link, f.path, f.line];
          group.rows.push({ row, link, severity: sev, code, text: words.filter((w) => w !== null && w !== undefined).join(" ").toLowerCase() });
        }
        section.rules.push(group);
        groups.push(group);
        table.append(group.body);
      }
      sections.push(section);
    }
    fillFilters(findings);
    applyFilters();
    return anchors;
  }

  function ruleGroup(sev, code, same) {
    // a rule's tbody: its header (a fold button with the rule's code, name and count, the
    // rule's page, the fix when every finding shares it) and its "Show N more" row
    const id = `rule-${sev}-${code.replace(/[^A-Za-z0-9_-]/g, "_")}`;
    const shared = same.length > 1 && same.every((f) => f.fix && f.fix === same[0].fix) ? same[0].fix : null;
    const fold = el("button", { type: "button", class: "rule-toggle", "aria-expanded": "true", "aria-controls": id,
      title: "Fold or unfold this rule's findings" },
    el("span", { class: "rule-code" }, code), " ", el("span", { class: "rule-name" }, same[0].name), " ",
    el("span", { class: "rule-count" }));
    const page = el("a", { class: "rule-link", href: `/rules/${encodeURIComponent(code)}`, target: "_blank", rel: "noopener",
      "aria-label": `Rule ${code}: what it checks and how to fix it` }, "rule");
    const head = el("th", { colspan: "2", scope: "rowgroup", class: "rule-head" },
      el("div", { class: "rule-line" }, fold, page, shared ? el("p", { class: "fix" }, shared) : null));
    const more = el("button", { type: "button", class: "more", "aria-expanded": "false", "aria-controls": id });
    const moreRow = el("tr", { class: "more-row" }, el("td", { colspan: "2" }, more));
    const body = el("tbody", { id, class: `rule ${sev}`, "data-severity": sev, "data-code": code },
      el("tr", { class: "rule-row", "data-code": code, tabindex: "-1" }, head), moreRow);
    const group = { id, code, severity: sev, body, fold, button: more, more: moreRow, rows: [], fix: shared, expanded: false, folded: false };
    fold.addEventListener("click", () => {
      group.folded = !group.folded;
      applyFilters();
    });
    more.addEventListener("click", () => {
      group.expanded = !group.expanded;
      applyFilters();
      if (!group.expanded) group.body.scrollIntoView({ block: "nearest" });
    });
    return group;
  }

  function findingRow(f, id, link, line, fix, kind) {
    // the line; the message with the element after it (small), the fix, the badge
    const problem = el("td", { class: "problem" },
      el("p", { class: "what" }, el("span", { class: "message" }, f.message), " ",
        el("span", { class: "element", title: "The element (XPath)" }, ...breakable(f.element))));
    if (kind) {
      problem.firstChild.append(" ", el("span", {
        class: "badge fixable", "data-applicability": kind,
        title: typeof f.autofix.description === "string" ? f.autofix.description : null,
      }, kind === "unsafe" ? "fixable, unsafe" : "fixable"));
    }
    if (fix) problem.append(el("p", { class: "fix" }, fix));
    return el("tr", {
      id: id, tabindex: "-1",
      class: "finding", "data-code": f.code, "data-line": f.line, "data-severity": f.severity,
      "data-element": f.element, "data-link": link, title: link ? `Click to show link ‘${link}’ in the 3D view and the tree` : null,
    }, el("td", { class: "num" }, line), problem);
  }

  // -- the findings' filters ---------------------------------------------------------------

  function fillFilters(findings) {
    // the rules and the links with findings, with their counts; the filters start cleared
    const rules = new Map();
    for (const f of findings) {
      const code = String(f.code);
      if (!rules.has(code)) rules.set(code, { name: f.name, n: 0 });
      rules.get(code).n += 1;
    }
    $("filter-rule").replaceChildren(el("option", { value: "" }, "all rules"),
      ...[...rules.keys()].sort().map((code) => el("option", { value: code }, `${code} ${rules.get(code).name} (${rules.get(code).n})`)));
    const links = new Map();
    for (const name of linkOf) if (name !== undefined) links.set(name, (links.get(name) || 0) + 1);
    const named = [...links.keys()].sort((a, b) => (linkOrder.indexOf(a) - linkOrder.indexOf(b)) || (a < b ? -1 : 1));
    $("filter-link").replaceChildren(el("option", { value: "" }, "all links"),
      ...named.map((name) => el("option", { value: name }, `${name} (${links.get(name)})`)));
    $("filter-link").disabled = named.length === 0;
    for (const key of Object.keys(filters)) filters[key] = "";
    $("filter-severity").value = $("filter-rule").value = $("filter-link").value = $("filter-text").value = "";
    showAll = false;
  }

  function matches(item) {
    return (!filters.severity || item.severity === filters.severity)
      && (!filters.rule || item.code === filters.rule)
      && (!filters.link || item.link === filters.link)
      && (!filters.text || item.text.includes(filters.text));
  }

  function applyFilters() {
    // which rows show: those matching the filters, the first few of each rule (LIMIT, or
    // fewer when many rules match) unless it is opened (or the only rule left); the
    // headers count what matches
    const filtered = Object.values(filters).some(Boolean);
    const found = groups.map((g) => g.rows.filter(matches));
    const ruling = found.filter((m) => m.length).length;
    const alone = ruling === 1;
    const few = Math.max(1, Math.min(LIMIT, Math.floor(ROWS / Math.max(ruling, 1))));
    perRule = few;
    let matching = 0;
    let shown = 0;
    let rules = 0;
    groups.forEach((group, i) => {
      const hits = found[i];
      const all = group.rows.length;
      matching += hits.length;
      group.body.hidden = hits.length === 0;
      if (!hits.length) return;
      rules += 1;
      const open = !group.folded;
      const room = group.expanded || showAll || alone ? Infinity : few;
      const visible = new Set(open ? hits.slice(0, room) : []);
      for (const item of group.rows) item.row.hidden = !visible.has(item);
      shown += visible.size;
      group.fold.setAttribute("aria-expanded", String(open));
      group.fold.querySelector(".rule-count").textContent = hits.length === all ? `×${all}` : `×${hits.length} of ${all}`;
      const rest = hits.length - few;
      group.more.hidden = !open || rest <= 0 || showAll || alone;
      group.button.setAttribute("aria-expanded", String(group.expanded));
      group.button.textContent = group.expanded ? "Show fewer" : `Show ${rest} more`;
    });
    for (const section of sections) {
      const hits = section.rules.reduce((n, g) => n + g.rows.filter(matches).length, 0);
      section.top.hidden = hits === 0;
      const noun = section.total === 1 ? section.severity : PLURAL[section.severity];
      const title = hits === section.total ? `${section.total} ${noun}` : `${hits} of ${section.total} ${noun}`;
      section.head.textContent = title[0].toUpperCase() + title.slice(1);
    }
    const total = groups.reduce((n, g) => n + g.rows.length, 0);
    const nothing = filtered && matching === 0;
    $("no-match").hidden = !nothing;
    $("findings").hidden = total === 0 || nothing;
    $("filter-clear").hidden = !filtered;
    const expand = $("findings-expand");
    expand.hidden = total === 0;
    expand.textContent = showAll ? "Show fewer" : "Show all";
    expand.setAttribute("aria-expanded", String(showAll));
    const of = filtered ? `${matching} of ${total} findings match` : `${total} finding${total === 1 ? "" : "s"}`;
    $("findings-count").textContent = total
      ? `${of} in ${rules} rule${rules === 1 ? "" : "s"}${shown < matching ? `; ${shown} shown` : ""}` : "";
  }

  function onFilter() {
    filters.severity = $("filter-severity").value;
    filters.rule = $("filter-rule").value;
    filters.link = $("filter-link").value;
    filters.text = $("filter-text").value.trim().toLowerCase();
    applyFilters();
  }

  function clearFilters() {
    for (const key of Object.keys(filters)) filters[key] = "";
    $("filter-severity").value = $("filter-rule").value = $("filter-link").value = $("filter-text").value = "";
    applyFilters();
  }

  function reveal(target) {
    // make a finding's row (or a rule's group) visible: the filters cleared if they hide
    // it, its rule unfolded, and opened past its first rows if it is further down
    const body = target.closest("tbody");
    const group = groups.find((g) => g.body === body);
    if (!group) return;
    const item = group.rows.find((r) => r.row === target);
    if (item ? !matches(item) : !group.rows.some(matches)) clearFilters();
    group.folded = false;
    if (item && group.rows.filter(matches).indexOf(item) >= perRule) group.expanded = true;
    applyFilters();
  }

  function fixable(f, upload) {
    // "safe" or "unsafe" when Fix can apply the finding's fix (every edit in the upload)
    const fix = f.autofix;
    if (!fix || typeof fix !== "object" || fix.unavailable) return null;
    const edits = Array.isArray(fix.edits) ? fix.edits : [];
    if (!edits.length || !edits.every((e) => e && e.path === upload)) return null;
    return fix.applicability === "unsafe" ? "unsafe" : "safe";
  }

  // -- the fixes (POST /v1/fix) -------------------------------------------------------------

  function renderFix(doc, name, unsafe) {
    // the diff, the download and what is left; a check (doc null) hides the card
    const card = $("fix-card");
    const link = $("download");
    if (download) URL.revokeObjectURL(download);
    download = null;
    link.hidden = true;
    link.setAttribute("href", "#");
    if (!doc) {
      card.hidden = true;
      return;
    }
    const applied = Number.isInteger(doc.applied) ? doc.applied : 0;
    const diff = typeof doc.diff === "string" ? doc.diff : "";
    const upload = Object.keys(doc.models || {})[0];
    const waiting = unsafe ? 0 : doc.findings.filter((f) => fixable(f, upload) === "unsafe").length;
    let text = diff
      ? `Applied ${applied} fix${applied === 1 ? "" : "es"}; the findings below are what is left.`
      : "No automatic fix applies to this file.";
    if (waiting) {
      text += ` ${waiting} more with “include unsafe fixes (physics)”.`;
    }
    $("fix-summary").textContent = text;
    renderDiff(diff);
    $("diff").closest(".diff-wrap").hidden = !diff;
    if (diff && typeof doc.fixed === "string") {
      download = URL.createObjectURL(new Blob([doc.fixed], { type: "application/xml" }));
      link.href = download;
      link.download = name || "fixed.urdf";
      link.hidden = false;
    }
    card.hidden = false;
  }

  function renderDiff(diff) {
    // one text span (a block) per line, classed: file header, hunk, added, removed, context
    const box = $("diff");
    box.replaceChildren();
    const lines = diff.split("\n");
    if (lines[lines.length - 1] === "") lines.pop();
    let inHunk = false;
    for (const raw of lines) {
      const line = raw.replace(/\r$/, "");
      let kind = "context";
      if (line.startsWith("@@")) {
        kind = "hunk";
        inHunk = true;
      } else if (!inHunk) kind = "file";
      else if (line.startsWith("+")) kind = "add";
      else if (line.startsWith("-")) kind = "del";
      else if (line.startsWith("\\")) kind = "note";
      box.append(el("span", { class: `line ${kind}`, "data-kind": kind }, line));
    }
  }

  function anchorKey(f, exact) {
    return exact ? [f.path, f.line, f.code, f.element].join("|") : [f.line, f.code].join("|");
  }

  // -- the simulators (the compatibility matrix) ------------------------------------------

  function outcome(key) {
    const known = Object.prototype.hasOwnProperty.call(OUTCOMES, key);
    return el("span", { class: "outcome", "data-outcome": known ? key : "unknown" },
      known ? OUTCOMES[key] : String(key));
  }

  function findingLinks(found, anchors, describe) {
    // the deciding findings by rule: "CODE line N" for one, "CODE ×N" for several, each a
    // link to its row (or its rule's group) in the findings table, with what it does
    const list = el("ul", { class: "deciding" });
    const byCode = new Map();
    for (const f of Array.isArray(found) ? found : []) {
      const code = String(f.code);
      if (!byCode.has(code)) byCode.set(code, []);
      byCode.get(code).push(f);
    }
    for (const [code, same] of byCode) {
      const one = same.length === 1;
      const label = one ? `${code} line ${same[0].line}` : `${code} ×${same.length}`;
      const row = anchors.get(anchorKey(same[0], true)) || anchors.get(anchorKey(same[0], false));
      const id = one ? row : ruleIds.get(code) || row;
      const link = id
        ? el("a", { href: `#${id}`, class: "finding-link", "data-finding": id, "data-code": code, "data-count": same.length }, label)
        : el("span", { class: "finding-ref", "data-code": code, "data-count": same.length }, label);
      const notes = same.map(describe);
      const distinct = (key) => [...new Set(notes.map((n) => n[key]).filter(Boolean))];
      const texts = distinct("text");
      const titles = distinct("title");
      const title = titles.length > 3 ? `${titles.slice(0, 3).join("\n")}\n…` : titles.join("\n");
      list.append(el("li", { title: title || null }, link, texts.length ? el("span", { class: "why" }, texts.join(", ")) : null));
    }
    return list.childElementCount ? list : null;
  }

  function renderMatrix(rows, asked, anchors) {
    const card = $("matrix-card");
    const body = $("matrix").querySelector("tbody");
    body.replaceChildren();
    card.hidden = !asked && rows.length === 0;
    $("no-matrix").hidden = rows.length > 0;
    $("matrix").closest(".table-wrap").hidden = rows.length === 0;
    const many = new Set(rows.map((r) => r.path)).size > 1;
    for (const row of rows) {
      const predicted = row.predicted || {};
      const confirmed = row.confirmed && typeof row.confirmed === "object" ? row.confirmed : null;
      const name = el("th", { scope: "row", class: "target" }, row.label || row.target);
      if (many) name.append(el("span", { class: "basis" }, row.path));
      if (row.basis && row.basis !== "engine") name.append(el("span", { class: "basis" }, `from its ${row.basis}`));
      // every target has a row; those the check was not for are there to compare
      if (row.selected === false) name.append(el("span", { class: "basis" }, "not checked: for comparison"));
      const engine = el("td", { class: "engine" });
      if (confirmed) {
        engine.append(el("span", { class: "engine-name" }, confirmed.engine), " ", outcome(confirmed.outcome));
        const shown = findingLinks(confirmed.findings, anchors, (f) => ({ title: f.message }));
        if (shown) engine.append(shown);
      } else {
        engine.append(el("span", { class: "muted" }, "—"));
      }
      const why = findingLinks(predicted.findings, anchors,
        (f) => ({ text: f.consequence, title: f.detail || null }));
      body.append(el("tr", {
        class: "matrix-row", "data-target": row.target, "data-outcome": predicted.outcome,
        "data-selected": typeof row.selected === "boolean" ? String(row.selected) : null,
        "data-confirmed": confirmed ? confirmed.outcome : "",
      }, name, el("td", { class: "predicted" }, outcome(predicted.outcome)), engine,
      el("td", { class: "why" }, why || el("span", { class: "muted" }, "—"))));
    }
  }

  function goToFinding(event) {
    // a finding's row, or a rule's group (its header row), shown, highlighted and focused
    const link = event.target.closest("a.finding-link");
    if (!link) return;
    const target = document.getElementById(link.dataset.finding);
    if (!target) return;
    event.preventDefault();
    const row = target.tagName === "TBODY" ? target.querySelector("tr.rule-row") : target;
    reveal(row);
    document.querySelectorAll("#findings tr.highlight").forEach((tr) => tr.classList.remove("highlight"));
    row.classList.add("highlight");
    row.scrollIntoView({ behavior: "smooth", block: "center" });
    row.focus({ preventScroll: true });
  }

  function breakable(path) {
    // "/robot/link[@name='arm']/inertial" with a line-break opportunity before each step
    const parts = [];
    String(path).split(/(?=\/)/).forEach((step, i) => {
      if (i) parts.push(el("wbr"));
      parts.push(step);
    });
    return parts;
  }

  // -- the selected link: the 3D view, the outline, the diagram and the rows agree ----------

  function firstScene(scenes) {
    if (!scenes || typeof scenes !== "object") return null;
    const found = Object.values(scenes)[0];
    return found && typeof found === "object" && Array.isArray(found.links) ? found : null;
  }

  function linksOfFindings(findings, scene) {
    // each finding's link: the scene lists each link's findings (its joints' included)
    const found = [];
    if (!scene) return found;
    for (const link of scene.links) {
      for (const index of Array.isArray(link.findings) ? link.findings : []) {
        if (found[index] === undefined) found[index] = link.name;
      }
    }
    return found;
  }

  function select(link, from) {
    document.dispatchEvent(new CustomEvent("urdflint:select", { detail: { link, from } }));
  }

  function onSelect(event) {
    const name = event.detail && event.detail.link;
    document.querySelectorAll("#findings tr.of-selected").forEach((tr) => tr.classList.remove("of-selected"));
    document.querySelectorAll("#tree g.link.selected").forEach((g) => g.classList.remove("selected"));
    if (name) {
      document.querySelectorAll("#findings tr.finding").forEach((tr) => {
        if (tr.dataset.link === name) tr.classList.add("of-selected");
      });
      document.querySelectorAll("#tree g.link").forEach((g) => {
        if (g.getAttribute("data-link") === name) g.classList.add("selected");
      });
    }
    showPicked(name);
  }

  function showPicked(name) {
    // the selected link, under the 3D view: its mass, centre of mass, inertia box, findings
    const box = $("picked");
    const link = name && picked.scene ? picked.scene.links.find((l) => l.name === name) : null;
    box.hidden = !link;
    box.replaceChildren();
    if (!link) return;
    const facts = [];
    const inertial = link.inertial;
    if (inertial && typeof inertial.mass === "number") facts.push(`mass ${number(inertial.mass)} kg`);
    if (inertial && Array.isArray(inertial.com)) facts.push(`centre of mass (${inertial.com.map((v) => number(v, 3)).join(", ")}) m in the world frame`);
    if (inertial && inertial.box) facts.push(`inertia box ${inertial.box.size.map((v) => number(v, 3)).join(" × ")} m${inertial.box.valid ? "" : " (impossible tensor)"}`);
    else if (inertial && inertial.problem) facts.push(`no inertia box: ${inertial.problem}`);
    else if (!inertial) facts.push("no <inertial>");
    box.append(el("p", { class: "picked-head" }, el("strong", {}, link.name), " ", el("span", { class: "muted" }, facts.join(" · "))));
    const list = el("ul", { class: "deciding" });
    for (const index of link.findings) {
      const f = picked.findings[index];
      if (!f) continue;
      list.append(el("li", {}, el("a", { href: `#${rowIds[index]}`, class: "finding-link", "data-finding": rowIds[index], "data-code": f.code },
        el("span", { class: "sev", "data-severity": f.severity }, f.severity), ` ${f.code} line ${f.line}`), " ", el("span", { class: "why" }, f.message)));
    }
    box.append(list.childElementCount ? list : el("p", { class: "muted" }, "No findings on this link."));
  }

  function rowClicked(event) {
    if (event.target.closest("a, button") || String(window.getSelection() || "")) return;
    const row = event.target.closest("tr.finding");
    if (!row || !row.dataset.link) return;
    document.querySelectorAll("#findings tr.highlight").forEach((tr) => tr.classList.remove("highlight"));
    row.classList.add("highlight");
    select(row.dataset.link, "finding");
    const view = $("view-card");
    const rect = view.getBoundingClientRect();
    if (rect.bottom < 0 || rect.top > window.innerHeight) view.scrollIntoView({ behavior: "smooth", block: "start" });
  }

  function diagramClicked(event) {
    const group = event.target.closest && event.target.closest("g.link");
    if (group && group.getAttribute("data-kind") === "link") select(group.getAttribute("data-link"), "diagram");
  }

  // -- the tree ---------------------------------------------------------------------------

  function cleanSvg(markup) {
    const parsed = new DOMParser().parseFromString(markup, "image/svg+xml");
    const source = parsed.documentElement;
    if (!source || source.namespaceURI !== SVG_NS || source.localName !== "svg"
        || parsed.getElementsByTagName("parsererror").length) {
      return null;
    }
    const copy = (node) => {
      if (node.nodeType === Node.TEXT_NODE) return document.createTextNode(node.nodeValue);
      if (node.nodeType !== Node.ELEMENT_NODE || node.namespaceURI !== SVG_NS
          || !SVG_TAGS.has(node.localName)) return null;
      const out = document.createElementNS(SVG_NS, node.localName);
      for (const attr of Array.from(node.attributes)) {
        if (attr.namespaceURI) continue;
        const name = attr.name;
        if (SVG_ATTRS.has(name) || /^data-[a-z-]+$/.test(name)) out.setAttribute(name, attr.value);
      }
      for (const child of Array.from(node.childNodes)) {
        const kept = copy(child);
        if (kept) out.append(kept);
      }
      return out;
    };
    return copy(source);
  }

  function renderTrees(svgs) {
    const box = $("tree");
    box.replaceChildren();
    const paths = Object.keys(svgs);
    let links = 0;
    for (const path of paths) {
      if (paths.length > 1) box.append(el("p", { class: "tree-name" }, path));
      const svg = cleanSvg(String(svgs[path]));
      if (!svg) {
        box.append(el("p", { class: "muted" }, "The tree picture could not be read."));
        continue;
      }
      svg.dataset.naturalWidth = svg.getAttribute("width") || "0";
      links += svg.querySelectorAll("g.link").length;
      box.append(svg);
    }
    if (!paths.length) box.append(el("p", { class: "muted" }, "No tree picture was returned."));
    // a big robot's diagram is very wide: folded at first, the outline above reads better
    $("diagram-card").open = links <= BIG_TREE;
    $("diagram-hint").textContent = links > BIG_TREE
      ? `${links} links: wide; the tree above is easier to read` : "";
  }

  let scale = 1;
  let fitting = true; // follow the box's width until the reader zooms

  function zoom(how) {
    const svgs = $("tree").querySelectorAll("svg");
    if (!svgs.length) return;
    const widest = Math.max(...Array.from(svgs, (s) => parseFloat(s.dataset.naturalWidth) || 1));
    const room = $("tree").clientWidth - 12;
    fitting = how === "fit" || how === "auto";
    const fit = room > 0 ? Math.min(1, room / widest) : 1;
    // fitting never shrinks the labels past legible: a big tree scrolls instead
    if (how === "fit" || how === "auto") scale = Math.max(fit, LEGIBLE);
    else if (how === "one") scale = 1;
    else if (how === "in") scale = Math.min(4, scale * 1.25);
    else if (how === "out") scale = Math.max(0.1, scale / 1.25);
    for (const svg of svgs) {
      const natural = parseFloat(svg.dataset.naturalWidth) || 1;
      svg.style.width = `${Math.round(natural * scale)}px`;
      svg.removeAttribute("height");
    }
    $("zoom-note").hidden = !(fitting && room > 0 && widest * scale > room + 1);
  }

  function centreOnRoot() {
    // a big tree opens scrolled to its (first) root, which sits at the top
    const box = $("tree");
    const root = box.querySelector("svg g.link[data-root] rect");
    if (!root || box.scrollWidth <= box.clientWidth) return;
    const boxRect = box.getBoundingClientRect();
    const rootRect = root.getBoundingClientRect();
    box.scrollLeft += rootRect.left + rootRect.width / 2 - (boxRect.left + boxRect.width / 2);
  }

  // -- start --------------------------------------------------------------------------------

  form.addEventListener("submit", submit);
  $("fix").addEventListener("click", () => send(true));
  $("target").addEventListener("change", () => { if (offer.confirm) showConfirm(); });
  $("matrix").addEventListener("click", goToFinding);
  $("picked").addEventListener("click", goToFinding);
  $("findings").addEventListener("click", rowClicked);
  for (const id of ["filter-severity", "filter-rule", "filter-link"]) $(id).addEventListener("change", onFilter);
  $("filter-text").addEventListener("input", onFilter);
  $("filter-clear").addEventListener("click", clearFilters);
  $("findings-expand").addEventListener("click", () => {
    showAll = !showAll;
    groups.forEach((g) => { g.expanded = false; if (showAll) g.folded = false; });
    applyFilters();
  });
  $("tree").addEventListener("click", diagramClicked);
  document.addEventListener("urdflint:select", onSelect);
  $("diagram-card").addEventListener("toggle", () => {
    if ($("diagram-card").open) {
      zoom("auto");
      centreOnRoot();
    }
  });
  form.querySelectorAll("input[name=mode]").forEach((radio) => radio.addEventListener("change", showMode));
  document.querySelectorAll("[data-zoom]").forEach((button) =>
    button.addEventListener("click", () => zoom(button.dataset.zoom)));
  window.addEventListener("resize", () => { if (fitting) zoom("auto"); });
  showMode();
  fetch("/v1/capabilities").then((r) => (r.ok ? r.json() : null)).then(learnOffer).catch(() => {});
  fetch("/version").then((r) => (r.ok ? r.json() : null)).then((v) => {
    const version = v && (v.urdflint || v.version);
    if (typeof version === "string") $("version").textContent = `v${version}`;
  }).catch(() => {});
}());
