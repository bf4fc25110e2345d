// The rules pages: /rules lists /v1/rules as a table, /rules/CODE shows /v1/rules/CODE
// with its documentation (Markdown, rendered here to DOM nodes: every string is inserted
// as text, never as HTML).
"use strict";

(function () {
  const $ = (id) => document.getElementById(id);

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

  function fail(message) {
    const box = $("error");
    box.replaceChildren(el("strong", {}, message), el("a", { href: "/rules" }, "All rules"));
    box.hidden = false;
  }

  async function getJson(url) {
    const response = await fetch(url, { headers: { Accept: "application/json" } });
    const data = await response.json().catch(() => null);
    if (!response.ok) {
      const detail = data && typeof data.detail === "string" ? data.detail : response.statusText;
      throw new Error(`${response.status}: ${detail}`);
    }
    return data;
  }

  const ruleUrl = (code) => `/rules/${encodeURIComponent(code)}`;

  // -- Markdown: headings, paragraphs, lists, fenced code, `code`, **strong**, *em* ---------

  const INLINE = /(`[^`]+`)|(\*\*[^*]+\*\*)|(\*[^*\s][^*]*\*)/g;

  function inline(text) {
    const nodes = [];
    let last = 0;
    for (const match of text.matchAll(INLINE)) {
      if (match.index > last) nodes.push(text.slice(last, match.index));
      const token = match[0];
      if (match[1]) nodes.push(el("code", {}, token.slice(1, -1)));
      else if (match[2]) nodes.push(el("strong", {}, token.slice(2, -2)));
      else nodes.push(el("em", {}, token.slice(1, -1)));
      last = match.index + token.length;
    }
    if (last < text.length) nodes.push(text.slice(last));
    return nodes;
  }

  function markdown(source) {
    const out = document.createDocumentFragment();
    const lines = source.replace(/\r\n/g, "\n").split("\n");
    let i = 0;
    while (i < lines.length) {
      const line = lines[i];
      if (!line.trim()) { i += 1; continue; }
      const fence = line.match(/^```\s*([\w-]*)/);
      if (fence) {
        const body = [];
        for (i += 1; i < lines.length && !lines[i].startsWith("```"); i += 1) body.push(lines[i]);
        i += 1;
        out.append(el("pre", {}, el("code", { "data-lang": fence[1] || null }, body.join("\n"))));
        continue;
      }
      const heading = line.match(/^(#{1,4})\s+(.*)$/);
      if (heading) {
        out.append(el(`h${Math.min(Math.max(heading[1].length, 2), 4)}`, {}, ...inline(heading[2])));
        i += 1;
        continue;
      }
      if (/^\s*[-*]\s+/.test(line)) {
        const list = el("ul");
        while (i < lines.length && /^\s*[-*]\s+/.test(lines[i])) {
          const item = [lines[i].replace(/^\s*[-*]\s+/, "")];
          for (i += 1; i < lines.length && /^\s+\S/.test(lines[i]) && !/^\s*[-*]\s+/.test(lines[i]); i += 1) {
            item.push(lines[i].trim());
          }
          list.append(el("li", {}, ...inline(item.join(" "))));
        }
        out.append(list);
        continue;
      }
      const para = [];
      while (i < lines.length && lines[i].trim() && !/^(```|#{1,4}\s|\s*[-*]\s)/.test(lines[i])) {
        para.push(lines[i].trim());
        i += 1;
      }
      out.append(el("p", {}, ...inline(para.join(" "))));
    }
    return out;
  }

  // -- the catalogue --------------------------------------------------------------------

  function severity(value) {
    return el("span", { class: "sev", "data-severity": value, title: "default severity" }, value);
  }

  async function catalogue() {
    $("catalogue").hidden = false;
    const data = await getJson("/v1/rules");
    const body = $("rules").tBodies[0];
    for (const rule of data.rules) {
      body.append(el("tr", { "data-code": rule.code, "data-severity": rule.severity },
        el("td", { class: "code" }, el("a", { href: ruleUrl(rule.code) }, rule.code)),
        el("td", { class: "name" }, rule.name),
        el("td", {}, severity(rule.severity)),
        el("td", { class: "family" }, rule.family),
        el("td", { class: "summary" }, ...inline(rule.summary || ""))));
    }
    const filter = $("filter");
    const apply = () => {
      const words = filter.value.toLowerCase().split(/\s+/).filter(Boolean);
      let shown = 0;
      for (const row of body.rows) {
        const text = row.textContent.toLowerCase();
        row.hidden = !words.every((word) => text.includes(word));
        if (!row.hidden) shown += 1;
      }
      $("count").textContent = `(${shown} of ${body.rows.length})`;
    };
    filter.addEventListener("input", apply);
    apply();
  }

  // -- one rule -------------------------------------------------------------------------

  async function rule(code) {
    const data = await getJson(`/v1/rules/${encodeURIComponent(code)}`);
    if (data.code !== code) {  // a name or a lower-case code: show the canonical address
      history.replaceState(null, "", ruleUrl(data.code));
    }
    document.title = `${data.code} ${data.name} · urdflint rules`;
    $("rule-code").textContent = data.code;
    $("rule-name").textContent = data.name;
    $("rule-summary").replaceChildren(...inline(data.summary || ""));
    $("rule-severity").textContent = data.severity;
    $("rule-severity").title = "default severity";
    $("rule-severity").dataset.severity = data.severity;
    $("rule-family").textContent = data.family;
    $("rule-needs").textContent = data.needs && data.needs.length ? `needs ${data.needs.join(", ")}` : "";
    $("rule-json").setAttribute("href", `/v1/rules/${encodeURIComponent(data.code)}`);
    const text = String(data.markdown || "");
    const start = text.search(/^## /m);  // the title and summary are shown above
    $("rule-doc").replaceChildren(markdown(start >= 0 ? text.slice(start) : text));
    $("rule").hidden = false;
  }

  const match = location.pathname.match(/^\/rules\/([^/]+)\/?$/);
  const shown = match ? rule(decodeURIComponent(match[1])) : catalogue();
  const what = match ? "this rule" : "the rules";
  shown.catch((error) => fail(`Could not load ${what} (${error.message}).`));
})();
