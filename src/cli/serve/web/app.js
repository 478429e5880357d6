// contrail serve: the web page. Plain JavaScript over the JSON API (schemas/openapi.json):
// the runs table (#/), a run's page (#/runs/ID) and the comparison of two runs
// (#/compare/A/B), and the form that submits a run (#/submit). Live updates come from the
// server-sent events of /api/events. The model view of a run's page is model.js's.
"use strict";

const query = new URLSearchParams(location.search);
const token = query.get("token");
// ?live=0: no event streams (a snapshot of the page, e.g. for a headless browser's screenshot)
const liveUpdates = query.get("live") !== "0";
const withToken = (url) => token ? url + (url.includes("?") ? "&" : "?") + "token=" + encodeURIComponent(token) : url;
const api = async (path) => {
  const res = await fetch(withToken(path));
  const body = await res.json();
  if (!res.ok) throw new Error(body.error ? body.error.message : res.statusText);
  return body;
};
const esc = (s) => String(s ?? "").replace(/[&<>"']/g, (c) => ({ "&": "&amp;", "<": "&lt;", ">": "&gt;", '"': "&quot;", "'": "&#39;" })[c]);
const fmt = (x, d = 4) => (typeof x === "number" && isFinite(x)) ? (Math.abs(x) >= 1e4 || (Math.abs(x) < 1e-3 && x !== 0) ? x.toExponential(3) : +x.toFixed(d)) : "–";
const $ = (sel) => document.querySelector(sel);

let runs = new Map();
let sortKey = "seq", sortDesc = true;
const selected = new Set();

function paramsText(r) {
  return Object.entries(r.params || {}).map(([k, v]) => `${k}=${v}`).join(" ");
}
function statusCell(r) {
  let html = `<span class="status ${esc(r.status)}">${esc(r.status)}</span>`;
  if (r.status === "running") {
    const f = r.progress && typeof r.progress.fraction === "number" ? r.progress.fraction : 0;
    html += `<span class="bar" title="${Math.round(100 * f)} %"><span style="width:${(100 * f).toFixed(1)}%"></span></span>`;
  }
  return html;
}
function increments(r) {
  if (r.status === "running" && r.progress) return r.progress.increment ?? "";
  return r.figures ? r.figures.increments : "";
}
function sortValue(r, key) {
  switch (key) {
    case "params": return paramsText(r);
    case "increments": return +increments(r) || 0;
    case "wall": return r.figures ? r.figures.wall_time_s : -1;
    default: return r[key] ?? "";
  }
}

function renderTable() {
  const q = $("#filter").value.trim().toLowerCase();
  const st = $("#status-filter").value;
  let rows = [...runs.values()].filter((r) => (!st || r.status === st) &&
    (!q || [r.id, r.scene, paramsText(r), r.failure_kind, r.sweep].join(" ").toLowerCase().includes(q)));
  rows.sort((a, b) => {
    const x = sortValue(a, sortKey), y = sortValue(b, sortKey);
    const c = typeof x === "number" && typeof y === "number" ? x - y : String(x).localeCompare(String(y));
    return sortDesc ? -c : c;
  });
  $("#runs tbody").innerHTML = rows.map((r) => `<tr data-id="${esc(r.id)}" class="run-row">
    <td><input type="checkbox" class="pick" value="${esc(r.id)}" ${selected.has(r.id) ? "checked" : ""}></td>
    <td><a href="#/runs/${encodeURIComponent(r.id)}">${esc(r.id)}</a></td>
    <td>${esc(r.scene)}</td>
    <td class="params">${esc(paramsText(r))}</td>
    <td class="status-cell">${statusCell(r)}</td>
    <td>${esc(r.failure_kind || "")}</td>
    <td class="num">${esc(increments(r))}</td>
    <td class="num">${r.figures ? fmt(r.figures.wall_time_s, 2) : ""}</td>
    <td class="num">${r.seq}</td></tr>`).join("");
  $("#count").textContent = `${rows.length} of ${runs.size} runs`;
  document.querySelectorAll("th[data-sort]").forEach((th) => {
    th.classList.toggle("sorted", th.dataset.sort === sortKey);
    th.classList.toggle("desc", th.dataset.sort === sortKey && sortDesc);
  });
  $("#compare").disabled = selected.size !== 2;
}

async function loadRuns() {
  const body = await api("/api/runs?limit=1000&order=desc");
  runs = new Map(body.runs.map((r) => [r.id, r]));
  renderTable();
}

// ---- the load–displacement chart (SVG drawn here; crossings marked) ----
const COLORS = ["#2f6fdb", "#d9822b", "#1f8a4c", "#a23bc2"];
function chart(series, opts = {}) {
  const W = 640, H = 360, L = 70, R = 16, T = 16, B = 44;
  const pts = series.flatMap((s) => s.points).filter((p) => isFinite(p[0]) && isFinite(p[1]));
  if (!pts.length) return `<p class="muted">no load–displacement points${opts.empty ? ": " + esc(opts.empty) : ""}</p>`;
  let [x0, x1] = [Math.min(...pts.map((p) => p[0])), Math.max(...pts.map((p) => p[0]))];
  let [y0, y1] = [Math.min(...pts.map((p) => p[1])), Math.max(...pts.map((p) => p[1]))];
  if (x0 === x1) { x0 -= 1; x1 += 1; } if (y0 === y1) { y0 -= 1; y1 += 1; }
  const sx = (x) => L + (x - x0) / (x1 - x0) * (W - L - R), sy = (y) => H - B - (y - y0) / (y1 - y0) * (H - T - B);
  let g = "";
  for (let i = 0; i <= 5; i++) {
    const snap = (v, span) => Math.abs(v) < 1e-9 * span ? 0 : v;
    const xv = snap(x0 + i * (x1 - x0) / 5, x1 - x0), yv = snap(y0 + i * (y1 - y0) / 5, y1 - y0);
    g += `<line class="grid" x1="${sx(xv)}" x2="${sx(xv)}" y1="${T}" y2="${H - B}"/><text x="${sx(xv)}" y="${H - B + 16}" text-anchor="middle">${fmt(xv, 3)}</text>`;
    g += `<line class="grid" x1="${L}" x2="${W - R}" y1="${sy(yv)}" y2="${sy(yv)}"/><text x="${L - 6}" y="${sy(yv) + 4}" text-anchor="end">${fmt(yv, 3)}</text>`;
  }
  g += `<line class="axis" x1="${L}" x2="${W - R}" y1="${H - B}" y2="${H - B}"/><line class="axis" x1="${L}" x2="${L}" y1="${T}" y2="${H - B}"/>`;
  g += `<text x="${(L + W - R) / 2}" y="${H - 8}" text-anchor="middle">displacement</text><text x="14" y="${(T + H - B) / 2}" transform="rotate(-90 14 ${(T + H - B) / 2})" text-anchor="middle">force</text>`;
  series.forEach((s, k) => {
    const c = COLORS[k % COLORS.length];
    const d = s.points.filter((p) => isFinite(p[0]) && isFinite(p[1])).map((p, i) => `${i ? "L" : "M"}${sx(p[0]).toFixed(1)},${sy(p[1]).toFixed(1)}`).join("");
    g += `<path class="curve" data-series="${esc(s.label)}" stroke="${c}" d="${d}"/>`;
    (s.crossings || []).forEach((i) => {
      const p = s.points[i];
      if (p && isFinite(p[0]) && isFinite(p[1])) g += `<circle class="crossing" fill="${c}" cx="${sx(p[0]).toFixed(1)}" cy="${sy(p[1]).toFixed(1)}" r="4.5"><title>crossing at increment ${i + 1}</title></circle>`;
    });
  });
  const legend = series.map((s, k) => `<span><i class="swatch" style="background:${COLORS[k % COLORS.length]}"></i>${esc(s.label)}${s.crossings && s.crossings.length ? ` (${s.crossings.length} crossings ●)` : ""}</span>`).join("");
  return `<svg class="chart" id="${opts.id || "curve"}" viewBox="0 0 ${W} ${H}" role="img" aria-label="load–displacement curve">${g}</svg><div class="legend">${legend}</div>`;
}
const curveSeries = (c, label) => ({ label, points: c.points.map((p) => [p[1], p[2]]), crossings: c.crossings });

// ---- a run's page ----
let current = null, currentStream = null;
function closeStream() { if (currentStream) { currentStream.close(); currentStream = null; } }

function dl(obj) {
  return `<dl>${Object.entries(obj).map(([k, v]) => `<dt>${esc(k)}</dt><dd>${v}</dd>`).join("")}</dl>`;
}
function culpritHtml(c) {
  if (!c || !c.length) return "";
  return `<h3>culprit</h3><table class="culprit-table"><tr><th>point</th><th>pair</th><th>changes</th><th>from iteration</th><th>ξ</th></tr>${c.slice(0, 6).map((p) =>
    `<tr class="culprit"><td>${esc(p.slave_label)}</td><td>${esc(p.pair_name)}</td><td class="num">${p.changes}</td><td class="num">${p.first_change}</td><td class="num">${fmt(p.xi)}</td></tr>`).join("")}</table>`;
}

async function showRun(id) {
  current = id;
  const view = $("#run-view");
  const [r, c] = await Promise.all([api(`/api/runs/${encodeURIComponent(id)}`), api(`/api/runs/${encodeURIComponent(id)}/curve`)]);
  if (current !== id) return;
  const f = r.figures || {}, m = r.metrics || {};
  const prog = r.progress ? `increment ${r.progress.increment}, t = ${fmt(r.progress.t)} of ${fmt(r.progress.t_end)}, force ${fmt(r.progress.force)}, ${r.progress.cutbacks} cut-backs, ${r.progress.crossings} crossings` : "";
  const files = r.files || {};
  const link = (u, t) => u ? `<a href="${esc(withToken(u))}" download>${t}</a>` : "";
  const notice = submitted && submitted.id === id ? (submitted.existing
    ? "this scene with these overrides is catalogued already: here is that run (tick “solve it again” to re-run it)"
    : `submitted from this page${liveUpdates ? "; followed live" : ""}`) : "";
  // the model view (model.js): from the recording, or the partial one of a running run
  const showsModel = Boolean((r.files && r.files.recording) || r.status === "running");
  view.innerHTML = `
    <p><a href="#/">← all runs</a></p>
    ${notice ? `<p class="notice" id="submit-notice">${esc(notice)}</p>` : ""}
    <div class="card"><h2 id="run-id">${esc(r.id)} <span class="status ${esc(r.status)}" id="run-status">${esc(r.status)}</span>${r.status === "running" ? statusCell(r).replace(/^<span class="status[^<]*<\/span>/, "") : ""}</h2>
      ${dl({ scene: esc(r.scene) + (r.sweep ? ` <span class="muted">(sweep ${esc(r.sweep)})</span>` : ""),
        parameters: `<span class="params">${esc(r.sets.join("  ")) || "<span class=muted>none</span>"}</span>`,
        submitted: new Date(r.submitted_at * 1000).toLocaleString(), attempt: r.attempt, backend: esc(r.backend || "") + (r.job ? ` job ${esc(r.job)}` : ""),
        ...(prog ? { progress: esc(prog) } : {}) })}
    </div>
    ${showsModel ? `<div id="model-slot"></div>` : ""}
    <div class="grid">
      <div class="card"><h2>outcome</h2>
        ${dl({ status: `<span class="status ${esc(r.status)}">${esc(r.status)}</span>` + (r.failure_kind ? ` <b class="culprit" id="failure-kind">${esc(r.failure_kind)}</b>` : ""),
          message: esc(r.message) || "<span class=muted>–</span>",
          increments: f.increments ?? "–", "Newton iterations": f.newton_iterations ?? "–", "cut-backs": f.cutbacks ?? "–",
          crossings: f.crossings ?? "–", "load reached": f.t_end ? `${fmt(f.t_reached)} of ${fmt(f.t_end)}` : "–",
          DOFs: f.dofs ?? "–", transfer: esc((f.transfer || []).join(", ")) || "–", "wall time": f.wall_time_s !== undefined ? fmt(f.wall_time_s, 3) + " s" : "–",
          "largest crossing jump": fmt(m.jump_max), roughness: fmt(m.roughness) })}
        ${culpritHtml(r.culprit)}
      </div>
      <div class="card"><h2>load–displacement</h2>${chart([curveSeries(c, r.id)], { empty: r.status })}</div>
    </div>
    <div class="card downloads"><h2>downloads</h2>
      ${link(files.recording, "recording (MCAP)")}${link(files.curve_csv, "curve (CSV)")}${link(files.curve_svg, "curve (SVG)")}${link(files.scene, "scene (TOML)")}
      <h3>open it in rerun</h3>
      <pre id="rerun-command">${esc(r.commands.fetch)}${token ? " --token …" : ""}\n${esc(r.commands.rerun)}</pre>
      <p class="muted">on the service's machine: <code>${esc(r.commands.local)}</code></p>
    </div>
    ${r.log ? `<div class="card"><h2>solver summary</h2><pre>${esc(r.log)}</pre></div>` : ""}`;
  if (showsModel) ModelView.show($("#model-slot"), id, r.status, api);
  if (liveUpdates && (r.status === "running" || r.status === "queued")) {
    closeStream();
    currentStream = new EventSource(withToken(`/api/runs/${encodeURIComponent(id)}/events`));
    let pending = false;
    const refresh = () => { if (!pending) { pending = true; setTimeout(() => { pending = false; if (current === id) showRun(id); }, 700); } };
    currentStream.addEventListener("progress", refresh);
    currentStream.addEventListener("status", (e) => { const d = JSON.parse(e.data); if (d.data && d.data.status && d.data.status !== r.status) { closeStream(); refresh(); } });
  }
}

// ---- the comparison of two runs ----
async function showCompare(a, b) {
  const view = $("#compare-view");
  view.innerHTML = `<p><a href="#/">← all runs</a></p><p class="muted">comparing…</p>`;
  const [ra, rb, ca, cb] = await Promise.all([a, b].flatMap((id) => [api(`/api/runs/${encodeURIComponent(id)}`)]).concat(
    [a, b].map((id) => api(`/api/runs/${encodeURIComponent(id)}/curve`))));
  let diffHtml;
  try {
    const d = await api(`/api/diff?a=${encodeURIComponent(a)}&b=${encodeURIComponent(b)}&align=load`);
    diffHtml = `<p>aligned by load level: ${d.matched_increments} matched increments (only in A ${d.only_in_a}, only in B ${d.only_in_b}); tolerance ${d.tol}:
      <b class="${d.within_tolerance ? "" : "culprit"}" id="diff-verdict">${d.within_tolerance ? "within tolerance" : "beyond tolerance"}</b></p>
      <table id="diff-fields"><tr><th>field</th><th class="num">compared</th><th class="num">beyond</th><th class="num">max abs</th><th class="num">max rel</th><th>first divergence</th></tr>
      ${d.fields.map((f) => `<tr><td>${esc(f.field)}</td><td class="num">${f.compared}</td><td class="num">${f.beyond_tolerance}</td><td class="num">${fmt(f.max_abs)}</td><td class="num">${fmt(f.max_rel)}</td>
        <td>${f.first_divergence ? `increment ${f.first_divergence.increment_a} (t = ${fmt(f.first_divergence.t)})${f.first_divergence.point ? " at " + esc(f.first_divergence.point) : ""}: A ${esc(f.first_divergence.a)} B ${esc(f.first_divergence.b)}` : ""}</td></tr>`).join("")}</table>
      <p class="muted">crossings only in A: ${d.crossings_only_in_a.length}, only in B: ${d.crossings_only_in_b.length}</p>`;
  } catch (e) {
    diffHtml = `<p class="error" id="diff-error">${esc(e.message)}</p>`;
  }
  const row = (r) => `<tr><td><a href="#/runs/${encodeURIComponent(r.id)}">${esc(r.id)}</a></td><td>${statusCell(r)}</td><td class="params">${esc(r.sets.join(" "))}</td><td class="num">${r.figures ? r.figures.increments : ""}</td><td class="num">${r.figures ? r.figures.crossings : ""}</td></tr>`;
  view.innerHTML = `<p><a href="#/">← all runs</a></p>
    <div class="card"><h2>comparison</h2><table><tr><th>run</th><th>status</th><th>parameters</th><th class="num">increments</th><th class="num">crossings</th></tr>${row(ra)}${row(rb)}</table></div>
    <div class="grid"><div class="card"><h2>load–displacement</h2>${chart([curveSeries(ca, "A " + a), curveSeries(cb, "B " + b)], { id: "compare-curve" })}</div>
    <div class="card"><h2>diff</h2>${diffHtml}</div></div>`;
}

// ---- the submit form (#/submit): POST /api/runs; the service checks the scene and overrides ----
let scenesLoaded = null, submitted = null;
const form = $("#submit-form");

async function showSubmit() {
  if (!scenesLoaded) {
    scenesLoaded = api("/api/scenes").then((body) => {
      $("#scene-select").innerHTML = body.scenes.map((s) =>
        `<option value="${esc(s.name)}" title="${esc(s.description)}">${esc(s.name)}</option>`).join("");
      return new Map(body.scenes.map((s) => [s.name, s.description]));
    });
    scenesLoaded.catch(() => { scenesLoaded = null; });
  }
  const descriptions = await scenesLoaded;
  $("#scene-description").textContent = descriptions.get($("#scene-select").value) || "";
  const own = form.elements.source.value === "toml";
  $("#builtin-fields").hidden = own;
  $("#toml-fields").hidden = !own;
}

// The request as `contrail submit` sends it: one override per non-empty line.
function submitBody() {
  const body = form.elements.source.value === "toml" ? { scene_toml: $("#scene-toml").value } : { scene: $("#scene-select").value };
  body.set = $("#sets").value.split("\n").map((l) => l.trim()).filter((l) => l);
  if ($("#rerun").checked) body.rerun = true;
  return body;
}

function showSubmitError(message, hint) {
  const box = $("#submit-error");
  box.innerHTML = `<pre id="submit-message">${esc(message)}</pre>${hint ? `<span class="muted">hint: ${esc(hint)}</span>` : ""}`;
  box.hidden = false;
}

async function submitRun(e) {
  e.preventDefault();
  const button = $("#submit-run");
  $("#submit-error").hidden = true;
  button.disabled = true;
  $("#submit-state").textContent = "submitting…";
  try {
    const headers = { "Content-Type": "application/json" };
    if (token) headers.Authorization = "Bearer " + token;
    const res = await fetch("/api/runs", { method: "POST", headers, body: JSON.stringify(submitBody()) });
    const body = await res.json().catch(() => null);
    if (!res.ok) {
      const err = body && body.error;
      return showSubmitError(err ? err.message : `${res.status} ${res.statusText}`, err && err.hint);
    }
    submitted = { id: body.id, existing: body.existing };
    location.hash = `#/runs/${encodeURIComponent(body.id)}`;
  } catch (err) {
    showSubmitError(`the service did not answer: ${err.message}`, "is it still running? a body over 16 MiB is cut off");
  } finally {
    button.disabled = false;
    $("#submit-state").textContent = "";
  }
}

form.addEventListener("submit", submitRun);
form.addEventListener("change", (e) => { if (e.target.name === "source" || e.target.id === "scene-select") showSubmit(); });
$("#scene-file").addEventListener("change", async (e) => {
  const f = e.target.files[0];
  if (f) $("#scene-toml").value = await f.text();
});

// ---- routing and live updates ----
async function route() {
  const h = location.hash.replace(/^#\/?/, "").split("/").map(decodeURIComponent);
  const show = (v) => ["list-view", "run-view", "compare-view", "submit-view"].forEach((x) => { $("#" + x).hidden = x !== v; });
  closeStream();
  current = null;
  try {
    if (h[0] === "runs" && h[1]) { show("run-view"); await showRun(h[1]); }
    else if (h[0] === "compare" && h[1] && h[2]) { show("compare-view"); await showCompare(h[1], h[2]); }
    else if (h[0] === "submit") { show("submit-view"); await showSubmit(); }
    else { show("list-view"); await loadRuns(); }
  } catch (e) {
    $("#main").insertAdjacentHTML("afterbegin", `<p class="error">${esc(e.message)}</p>`);
  }
  document.body.dataset.ready = "1";
}

function live() {
  const es = new EventSource(withToken("/api/events"));
  let pending = false;
  const reload = () => { if (!pending) { pending = true; setTimeout(() => { pending = false; if (!$("#list-view").hidden) loadRuns(); }, 500); } };
  es.addEventListener("status", reload);
  es.addEventListener("progress", (e) => {
    const d = JSON.parse(e.data), r = runs.get(d.id);
    if (!r) return reload();
    const t = d.data.t, end = d.data.t_end;
    r.progress = Object.assign({}, d.data, { fraction: end > 0 ? Math.min(1, t / end) : 0 });
    const tr = document.querySelector(`tr[data-id="${CSS.escape(d.id)}"]`);
    if (tr) { tr.querySelector(".status-cell").innerHTML = statusCell(r); tr.children[6].textContent = d.data.increment; }
  });
}

async function health() {
  try {
    const h = await api("/api/health");
    $("#health").textContent = `contrail ${h.version} · ${h.backend} backend, ${h.workers} workers · ` +
      Object.entries(h.runs).map(([k, v]) => `${v} ${k}`).join(", ");
  } catch (e) { $("#health").textContent = e.message; }
}

document.querySelectorAll("th[data-sort]").forEach((th) => th.addEventListener("click", () => {
  if (sortKey === th.dataset.sort) sortDesc = !sortDesc; else { sortKey = th.dataset.sort; sortDesc = false; }
  renderTable();
}));
$("#filter").addEventListener("input", renderTable);
$("#status-filter").addEventListener("change", renderTable);
$("#runs").addEventListener("change", (e) => {
  if (!e.target.classList.contains("pick")) return;
  if (e.target.checked) selected.add(e.target.value); else selected.delete(e.target.value);
  $("#compare").disabled = selected.size !== 2;
});
$("#compare").addEventListener("click", () => { const [a, b] = [...selected]; location.hash = `#/compare/${encodeURIComponent(a)}/${encodeURIComponent(b)}`; });
window.addEventListener("hashchange", route);
route();
health();
if (liveUpdates) live();
