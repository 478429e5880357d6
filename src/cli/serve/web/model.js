// contrail serve: the model view of a run's page. The deformed mesh (element edges, one
// colour per body), the rigid surfaces, and the contact points coloured by state with the
// forces their slaves receive (normal and tangential), at any increment, drawn on a canvas
// from the service: GET /api/runs/ID/model (the reference mesh and the index of increments)
// and GET /api/runs/ID/model/INCREMENT (that increment's node positions and contact points).
// Coordinates come as flat arrays of `dim` numbers per point; this file draws dim = 2, and
// model3d.js (Model3D) a 3D run's model (dim = 3) with the same controls and side panel.
// app.js calls ModelView.show(slot, id, status, api) each time it draws a run's page; the
// view (its canvas and the frames it fetched) survives those redraws.
"use strict";

const ModelView = (() => {
  const BODY_COLORS = ["#2f6fdb", "#d9822b", "#1f8a4c", "#a23bc2", "#c23b32", "#5b6b8a"];
  const STATE_COLORS = { stick: "#1f8a4c", slip: "#d9822b", open: "#9aa3b2", closed: "#0096a0" };
  const NORMAL_COLOR = "#1d2330", TANGENT_COLOR = "#c23b32", RIGID_COLOR = "#4a5262";
  const FRAME_MS = 90, CACHE = 96, ARROW = 0.12;
  const MAGNIFY = [1, 2, 5, 10, 20, 50, 100, 1000];
  let view = null;

  const num = (x, d = 4) => (typeof x === "number" && isFinite(x))
    ? (Math.abs(x) >= 1e4 || (Math.abs(x) < 1e-3 && x !== 0) ? x.toExponential(3) : String(+x.toFixed(d))) : "–";
  const txt = (s) => String(s ?? "").replace(/[&<>"']/g, (c) => ({ "&": "&amp;", "<": "&lt;", ">": "&gt;", '"': "&quot;", "'": "&#39;" })[c]);

  function card() {
    const root = document.createElement("div");
    root.className = "card model-card";
    root.id = "model-card";
    root.innerHTML = `<h2>model <span class="muted" id="model-note"></span></h2>
      <div class="model-controls">
        <button type="button" id="model-play" disabled>▶ play</button>
        <input type="range" id="model-slider" min="0" max="0" value="0" step="1" aria-label="increment" disabled>
        <span id="model-increment" class="muted"></span>
        <label>magnify displacements <select id="model-magnify">${MAGNIFY.map((m) => `<option value="${m}">×${m}</option>`).join("")}</select></label>
        <label><input type="checkbox" id="model-arrows" checked> forces</label>
      </div>
      <div class="model-body">
        <div class="model-canvas-box"><canvas id="model-canvas" role="img" aria-label="the deformed model"></canvas></div>
        <div class="model-side"><div id="model-info"></div><div id="model-legend" class="model-legend"></div></div>
      </div>`;
    return root;
  }

  function create(id, status, api) {
    const root = card();
    const v = { id, status, api, root, model: null, frames: new Map(), pending: new Map(), inc: 0, want: 0,
      playing: false, magnify: 1, arrows: true, requests: 0, frame: null, loadedAt: 0, follow: true };
    const $ = (s) => root.querySelector(s);
    v.canvas = $("#model-canvas");
    Model3D.attach(v, () => redraw(v));
    $("#model-slider").addEventListener("input", (e) => { v.follow = false; pause(v); goTo(v, +e.target.value); });
    $("#model-play").addEventListener("click", () => (v.playing ? pause(v) : play(v)));
    $("#model-magnify").addEventListener("change", (e) => { v.magnify = +e.target.value; redraw(v); });
    $("#model-arrows").addEventListener("change", (e) => { v.arrows = e.target.checked; redraw(v); });
    return v;
  }

  // The mesh and the index of increments (again without the mesh while the run runs).
  async function load(v) {
    const path = `/api/runs/${encodeURIComponent(v.id)}/model` + (v.model ? "?mesh=false" : "");
    v.loadedAt = Date.now();
    let m;
    try {
      m = await v.api(path);
    } catch (e) {
      if (!v.model) note(v, e.message);
      return;
    }
    v.requests++;
    v.model = v.model ? Object.assign({}, v.model, m, { nodes: v.model.nodes, elements: v.model.elements,
      element_body: v.model.element_body, bodies: v.model.bodies, rigid: v.model.rigid, pairs: v.model.pairs,
      faces: v.model.faces, face_body: v.model.face_body, _edges: v.model._edges }) : m;
    const incs = m.frames.increment, last = incs.length ? incs[incs.length - 1] : 0;
    const slider = v.root.querySelector("#model-slider");
    slider.max = last;
    slider.disabled = v.root.querySelector("#model-play").disabled = !incs.length;
    note(v, m.partial ? `running: the ${incs.length} increments recorded so far` : "");
    legend(v);
    if (v.follow || v.inc > last) await goTo(v, last);
  }

  function note(v, text) { v.root.querySelector("#model-note").textContent = text ? "· " + text : ""; }

  // One increment's frame, fetched once (and the next few while playing).
  function frame(v, inc) {
    if (v.frames.has(inc)) return Promise.resolve(v.frames.get(inc));
    if (v.pending.has(inc)) return v.pending.get(inc);
    const p = v.api(`/api/runs/${encodeURIComponent(v.id)}/model/${inc}`).then((f) => {
      v.requests++;
      v.frames.set(inc, f);
      if (v.frames.size > CACHE) v.frames.delete(v.frames.keys().next().value);
      return f;
    }).finally(() => v.pending.delete(inc));
    v.pending.set(inc, p);
    return p;
  }

  async function goTo(v, inc) {
    v.want = inc;
    v.root.querySelector("#model-slider").value = inc;
    let f;
    try {
      f = await frame(v, inc);
    } catch (e) {
      return note(v, e.message);
    }
    if (v.want !== inc) return;
    v.inc = inc;
    v.frame = f;
    redraw(v);
  }

  async function play(v) {
    const last = +v.root.querySelector("#model-slider").max;
    v.playing = true;
    v.follow = false;
    v.root.querySelector("#model-play").textContent = "❚❚ pause";
    if (v.inc >= last) await goTo(v, 0);
    while (v.playing && v.inc < last && v.root.isConnected) {
      const t0 = performance.now(), next = v.inc + 1;
      for (let k = 1; k <= 3 && next + k <= last; k++) frame(v, next + k).catch(() => {});
      await goTo(v, next);
      await new Promise((r) => setTimeout(r, Math.max(0, FRAME_MS - (performance.now() - t0))));
    }
    pause(v);
  }

  function pause(v) {
    v.playing = false;
    v.root.querySelector("#model-play").textContent = "▶ play";
  }

  function redraw(v) {
    if (!v.model || !v.frame || !v.root.isConnected) return;
    const solid = v.model.dim === 3;
    const drawn = solid ? Model3D.draw(v, v.model, v.frame, TOOLS) : draw(v, v.model, v.frame);
    Object.assign(v.canvas.dataset, { increment: v.frame.increment, positionsIncrement: v.frame.positions_increment,
      contacts: drawn.contacts, contactsRecorded: v.frame.contact.count, requests: v.requests },
      solid ? { edges: drawn.edges, azimuth: v.turn.az.toFixed(3), elevation: v.turn.el.toFixed(3) } : { elements: drawn.elements });
    v.canvas.style.cursor = solid ? "grab" : "";
    info(v, v.model, v.frame, drawn.contacts);
  }

  // Node i as drawn: X + magnify · (x − X).
  function nodeAt(m, f, mag, i) {
    const X = m.nodes[2 * i], Y = m.nodes[2 * i + 1];
    return [X + mag * (f.nodes[2 * i] - X), Y + mag * (f.nodes[2 * i + 1] - Y)];
  }

  // A contact point's slave as drawn: a node slave magnified as its node is.
  function pointAt(m, f, mag, k) {
    const c = f.contact, p = [c.position[2 * k], c.position[2 * k + 1]], n = c.node[k];
    if (n === null || mag === 1) return p;
    const X = m.nodes[2 * n], Y = m.nodes[2 * n + 1];
    return [X + mag * (p[0] - X), Y + mag * (p[1] - Y)];
  }

  // The box to fit: the run's bounds, grown to hold this frame's magnified nodes.
  function box(v, m, f) {
    const b = m.bounds.slice();
    if (v.magnify !== 1) {
      for (let i = 0; i < m.node_count; i++) {
        const [x, y] = nodeAt(m, f, v.magnify, i);
        if (isFinite(x) && isFinite(y)) { b[0] = Math.min(b[0], x); b[1] = Math.min(b[1], y); b[2] = Math.max(b[2], x); b[3] = Math.max(b[3], y); }
      }
    }
    const w = Math.max(b[2] - b[0], 1e-12), h = Math.max(b[3] - b[1], 1e-12 * w), pad = 0.05 * Math.max(w, h);
    return [b[0] - pad, b[1] - pad, b[2] + pad, b[3] + pad];
  }

  // Size the canvas to its box (the model's aspect, 260 to 560 px high) and map model
  // coordinates to pixels with equal scales in x and y.
  function transform(v, b) {
    const ratio = window.devicePixelRatio || 1, boxEl = v.canvas.parentElement;
    const W = Math.max(200, boxEl.clientWidth), bw = b[2] - b[0], bh = b[3] - b[1];
    const H = Math.round(Math.min(560, Math.max(260, W * bh / bw)));
    v.canvas.style.width = W + "px";
    v.canvas.style.height = H + "px";
    v.canvas.width = Math.round(W * ratio);
    v.canvas.height = Math.round(H * ratio);
    const s = Math.min(W / bw, H / bh), ox = (W - s * bw) / 2, oy = (H - s * bh) / 2;
    const ctx = v.canvas.getContext("2d");
    ctx.setTransform(ratio, 0, 0, ratio, 0, 0);
    return { ctx, W, H, s, span: Math.max(bw, bh), px: (p) => [ox + (p[0] - b[0]) * s, H - oy - (p[1] - b[1]) * s] };
  }

  function draw(v, m, f) {
    const T = transform(v, box(v, m, f)), ctx = T.ctx;
    ctx.clearRect(0, 0, T.W, T.H);
    drawRigid(T, m, f);
    const elements = drawMesh(T, m, f, v.magnify);
    const contacts = drawContacts(T, m, f, v);
    scaleBar(T);
    return { elements, contacts };
  }

  function drawMesh(T, m, f, mag) {
    const ctx = T.ctx, per = m.nodes_per_element, count = m.elements.length / per;
    const at = new Array(m.node_count);
    for (let i = 0; i < m.node_count; i++) at[i] = T.px(nodeAt(m, f, mag, i));
    let drawn = 0;
    m.bodies.forEach((body, k) => {
      ctx.beginPath();
      for (let e = 0; e < count; e++) {
        if (m.element_body[e] !== k) continue;
        for (let j = 0; j < per; j++) {
          const p = at[m.elements[per * e + j]];
          j ? ctx.lineTo(p[0], p[1]) : ctx.moveTo(p[0], p[1]);
        }
        ctx.closePath();
        drawn++;
      }
      const c = BODY_COLORS[k % BODY_COLORS.length];
      ctx.fillStyle = c + "26";
      ctx.fill();
      ctx.strokeStyle = c;
      ctx.lineWidth = 1;
      ctx.stroke();
    });
    return drawn;
  }

  function drawRigid(T, m, f) {
    const ctx = T.ctx;
    ctx.strokeStyle = ctx.fillStyle = RIGID_COLOR;
    m.rigid.forEach((r, k) => {
      const ox = f.rigid_offsets[2 * k] || 0, oy = f.rigid_offsets[2 * k + 1] || 0;
      r.pieces.forEach((piece) => {
        const pts = [];
        for (let i = 0; i + 1 < piece.length; i += 2) pts.push(T.px([piece[i] + ox, piece[i + 1] + oy]));
        if (pts.length === 1) {
          const [x, y] = pts[0];
          ctx.beginPath(); ctx.moveTo(x, y); ctx.lineTo(x - 6, y - 11); ctx.lineTo(x + 6, y - 11); ctx.closePath(); ctx.fill();
          return;
        }
        ctx.beginPath();
        pts.forEach((p, i) => (i ? ctx.lineTo(p[0], p[1]) : ctx.moveTo(p[0], p[1])));
        ctx.lineWidth = 2.5;
        ctx.stroke();
      });
    });
  }

  function arrow(ctx, from, dx, dy, color) {
    const len = Math.hypot(dx, dy);
    if (!(len >= 2)) return;
    const [x, y] = from, ux = dx / len, uy = dy / len, head = Math.min(7, 0.4 * len);
    ctx.strokeStyle = ctx.fillStyle = color;
    ctx.lineWidth = 1.5;
    ctx.beginPath(); ctx.moveTo(x, y); ctx.lineTo(x + dx, y + dy); ctx.stroke();
    ctx.beginPath(); ctx.moveTo(x + dx, y + dy);
    ctx.lineTo(x + dx - head * ux + 0.5 * head * uy, y + dy - head * uy - 0.5 * head * ux);
    ctx.lineTo(x + dx - head * ux - 0.5 * head * uy, y + dy - head * uy + 0.5 * head * ux);
    ctx.closePath(); ctx.fill();
  }

  // Contact points by state; arrows of the normal force and the tangential traction the
  // slave receives, at one scale for the whole run (its largest force is 12 % of the view).
  // An open slave out of reach of every segment may have no position (null): not drawn.
  function drawContacts(T, m, f, v) {
    const ctx = T.ctx, c = f.contact, largest = m.largest.force;
    const k = largest > 0 ? ARROW * T.span * T.s / largest : 0;
    const shown = [];
    for (let i = 0; i < c.count; i++) if (c.position[2 * i] !== null && c.position[2 * i + 1] !== null) shown.push(i);
    for (const i of shown) {
      const p = T.px(pointAt(m, f, v.magnify, i));
      if (v.arrows && c.state[i] !== "open" && k > 0) {
        const fn = c.normal_force[i], ft = c.traction[i];
        arrow(ctx, p, k * fn * c.normal[2 * i], -k * fn * c.normal[2 * i + 1], NORMAL_COLOR);
        arrow(ctx, p, k * ft * c.tangent[2 * i], -k * ft * c.tangent[2 * i + 1], TANGENT_COLOR);
      }
    }
    for (const i of shown) {
      const p = T.px(pointAt(m, f, v.magnify, i)), open = c.state[i] === "open";
      ctx.beginPath();
      ctx.arc(p[0], p[1], open ? 3 : 4, 0, 2 * Math.PI);
      ctx.lineWidth = 1.5;
      ctx.strokeStyle = STATE_COLORS[c.state[i]] || "#000";
      ctx.fillStyle = open ? "#fff" : STATE_COLORS[c.state[i]];
      ctx.fill();
      ctx.stroke();
    }
    return shown.length;
  }

  // A bar of a round length in the lower left corner.
  function scaleBar(T) {
    const want = 120 / T.s, p10 = Math.pow(10, Math.floor(Math.log10(want)));
    const len = [5, 2, 1].map((d) => d * p10).find((l) => l <= want) || p10, px = len * T.s;
    const ctx = T.ctx, y = T.H - 12;
    ctx.strokeStyle = ctx.fillStyle = "#1d2330";
    ctx.lineWidth = 1.5;
    ctx.beginPath(); ctx.moveTo(12, y - 4); ctx.lineTo(12, y); ctx.lineTo(12 + px, y); ctx.lineTo(12 + px, y - 4); ctx.stroke();
    ctx.font = "11px system-ui, sans-serif";
    ctx.fillText(num(len, 6), 16, y - 5);
  }

  function info(v, m, f, drawn) {
    const c = f.contact, by = { stick: 0, slip: 0, open: 0, closed: 0 };
    c.state.forEach((s, i) => { const k = m.dim === 3 ? Model3D.stateOf(m, c, i) : s; by[k] = (by[k] || 0) + 1; });
    const n = m.frames.increment.length, mon = (f.monitors || [])[0];
    const positions = f.positions_exact ? "this increment's"
      : f.positions_increment === 0 ? "the reference configuration (no positions recorded before this increment)"
        : `increment ${f.positions_increment}'s (positions are recorded every ${m.positions_every || "?"} increments)`;
    v.root.querySelector("#model-increment").textContent = `increment ${f.increment} of ${n}`;
    const rows = {
      increment: `${f.increment} of ${n}${f.increment === 0 ? " (reference)" : ""}`,
      "load level t": `${num(f.t)} of ${num(m.end)}`,
      ...(mon ? { [`monitor ${mon.label}`]: `displacement ${num(mon.displacement)}, force ${num(mon.force)}` } : {}),
      "Newton iterations": f.iterations ?? "–",
      "cut-backs": f.cutbacks ?? "–",
      "contact points": `${c.count}: ${by.stick} stick, ${by.slip} slip, ${by.closed ? `${by.closed} closed (frictionless), ` : ""}${by.open} open` +
        (drawn < c.count ? ` (${c.count - drawn} open out of reach, without a position: not drawn)` : ""),
      mesh: `<span id="model-positions" class="${f.positions_exact ? "" : "stale"}">${txt(positions)}</span>`,
    };
    v.root.querySelector("#model-info").innerHTML = `<dl>${Object.entries(rows).map(([k, x]) => `<dt>${txt(k)}</dt><dd>${k === "mesh" ? x : txt(x)}</dd>`).join("")}</dl>`;
  }

  function legend(v) {
    const m = v.model, swatch = (c, hollow) => `<i class="dot" style="${hollow ? `border-color:${c}` : `background:${c};border-color:${c}`}"></i>`;
    const bodies = m.bodies.map((b, k) => `<span><i class="swatch" style="background:${BODY_COLORS[k % BODY_COLORS.length]}"></i>${txt(b.name)}</span>`);
    const rigid = m.rigid.map((r) => `<span><i class="swatch" style="background:${RIGID_COLOR}"></i>${txt(r.name)} (rigid ${txt(r.kind)})</span>`);
    const solid = m.dim === 3, closed = solid && m.pairs.some((p) => p.mu === 0);
    const mesh = solid ? `${m.node_count} nodes, ${m.element_count} hexahedra, ${m.face_count} boundary faces` : `${m.node_count} nodes, ${m.element_count} elements`;
    v.root.querySelector("#model-legend").innerHTML = `<div>${bodies.concat(rigid).join("")}</div>
      <div>${swatch(STATE_COLORS.stick)}stick ${swatch(STATE_COLORS.slip)}slip ${closed ? `${swatch(STATE_COLORS.closed)}closed (frictionless) ` : ""}${swatch(STATE_COLORS.open, true)}open</div>
      <div><i class="swatch" style="background:${NORMAL_COLOR}"></i>normal force <i class="swatch" style="background:${TANGENT_COLOR}"></i>tangential traction
      <span class="muted">(on the slave; the run's largest force, ${num(m.largest.force)}, is ${100 * ARROW} % of the view)</span></div>
      ${solid ? `<div class="muted">drag the picture to turn it (z up); double-click: the first view</div>` : ""}
      <div class="muted">${mesh}; mesh positions recorded at ${m.positions_at.length} of ${m.frames.increment.length} increments</div>`;
  }

  // Show run `id`'s model in `slot` (an element of the page app.js has just drawn).
  function show(slot, id, status, api) {
    if (!slot) return;
    const same = view && view.id === id;
    if (same && view.status !== status) { view.frames.clear(); view.model = null; }
    if (!same) { if (view) pause(view); view = create(id, status, api); }
    const v = view, changed = v.status !== status || !v.model;
    v.status = status;
    slot.replaceWith(v.root);
    if (changed || (status === "running" && Date.now() - v.loadedAt > 1500)) load(v);
    else redraw(v);
  }

  const TOOLS = { ARROW, STATE_COLORS, NORMAL_COLOR, TANGENT_COLOR, RIGID_COLOR, arrow, scaleBar,
    bodyColor: (k) => BODY_COLORS[k % BODY_COLORS.length] };

  window.addEventListener("resize", () => { if (view) redraw(view); });
  return { show, state: () => view };
})();
