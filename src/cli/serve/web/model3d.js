// contrail serve: the model view of a 3D run (dim = 3), drawn by model.js's view when the
// model it fetched has dim 3. An orthographic view, z up, turned by dragging the canvas
// (double-click: the default view): the boundary quadrilaterals of the hexahedra (filled
// back to front, their edges in the body's colour), the rigid masters of the 3D pairs moved
// by their offsets (a plane as a square outline, a sphere as its outline circle, a cylinder
// as its outline and axis), the contact points by state with the force each slave receives
// split into its normal and tangential parts, a scale bar and the axes.
"use strict";

const Model3D = (() => {
  const AZIMUTH = -2.2, ELEVATION = 0.45, TURN = 0.008;
  const AXES = [["x", "#c23b32"], ["y", "#1f8a4c"], ["z", "#2f6fdb"]];

  const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];

  // The screen's right, up and towards-the-viewer directions for an azimuth and elevation.
  function camera(az, el) {
    const ca = Math.cos(az), sa = Math.sin(az), ce = Math.cos(el), se = Math.sin(el);
    return { r: [-sa, ca, 0], u: [-se * ca, -se * sa, ce], d: [ce * ca, ce * sa, se] };
  }

  // The faces' edges, each once (node pairs), kept on the model.
  function edges(m) {
    if (m._edges) return m._edges;
    const seen = new Set(), out = [];
    for (let q = 0; 4 * q < m.faces.length; q++) {
      for (let k = 0; k < 4; k++) {
        const a = m.faces[4 * q + k], b = m.faces[4 * q + (k + 1) % 4], key = Math.min(a, b) * 4294967296 + Math.max(a, b);
        if (!seen.has(key)) { seen.add(key); out.push(a, b); }
      }
    }
    m._edges = out;
    return out;
  }

  // Node i as drawn: X + magnify · (x − X), or null where the frame has no position.
  function nodeAt(m, f, mag, i) {
    const x = f.nodes[3 * i], y = f.nodes[3 * i + 1], z = f.nodes[3 * i + 2];
    if (x === null || y === null || z === null) return null;
    const X = m.nodes[3 * i], Y = m.nodes[3 * i + 1], Z = m.nodes[3 * i + 2];
    return [X + mag * (x - X), Y + mag * (y - Y), Z + mag * (z - Z)];
  }

  // The run's bounds grown to hold this frame's magnified nodes: centre and radius of the
  // sphere about the box (the view fits it, so turning it keeps its scale).
  function extent(m, nodes) {
    const b = m.bounds.slice();
    for (const p of nodes) {
      if (!p) continue;
      for (let c = 0; c < 3; c++) { b[c] = Math.min(b[c], p[c]); b[c + 3] = Math.max(b[c + 3], p[c]); }
    }
    const centre = [0, 1, 2].map((c) => (b[c] + b[c + 3]) / 2);
    const radius = Math.max(1e-12, 0.5 * Math.hypot(b[3] - b[0], b[4] - b[1], b[5] - b[2]));
    return { centre, radius };
  }

  // Size the canvas (its box's width, 0.62 of it high within 360 to 560 px) and map model
  // points to pixels: [x, y, depth towards the viewer].
  function transform(v, m, nodes) {
    const ratio = window.devicePixelRatio || 1, W = Math.max(200, v.canvas.parentElement.clientWidth);
    const H = Math.round(Math.min(560, Math.max(360, 0.62 * W)));
    v.canvas.style.width = W + "px";
    v.canvas.style.height = H + "px";
    v.canvas.width = Math.round(W * ratio);
    v.canvas.height = Math.round(H * ratio);
    const ctx = v.canvas.getContext("2d");
    ctx.setTransform(ratio, 0, 0, ratio, 0, 0);
    const cam = camera(v.turn.az, v.turn.el), { centre, radius } = extent(m, nodes);
    const s = 0.92 * Math.min(W, H) / (2 * radius), c = [dot(centre, cam.r), dot(centre, cam.u)];
    const px = (p) => [W / 2 + (dot(p, cam.r) - c[0]) * s, H / 2 - (dot(p, cam.u) - c[1]) * s, dot(p, cam.d)];
    return { ctx, W, H, s, span: 2 * radius, cam, px };
  }

  // The boundary faces, back to front: a front face filled in its body's colour, lighter as
  // it turns to the viewer; a back face only outlined, faintly. Returns the edges drawn.
  function drawFaces(T, m, at, tools) {
    const ctx = T.ctx, n = m.faces.length / 4, order = [];
    for (let q = 0; q < n; q++) {
      const p = [0, 1, 2, 3].map((k) => at[m.faces[4 * q + k]]);
      if (p.some((x) => !x)) continue;
      // the outward normal's component towards the viewer (screen y is down)
      const a = [p[2][0] - p[0][0], p[0][1] - p[2][1], T.s * (p[2][2] - p[0][2])];
      const b = [p[3][0] - p[1][0], p[1][1] - p[3][1], T.s * (p[3][2] - p[1][2])];
      const nz = a[0] * b[1] - a[1] * b[0], len = Math.hypot(a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], nz);
      order.push({ q, p, depth: (p[0][2] + p[1][2] + p[2][2] + p[3][2]) / 4, facing: len > 0 ? nz / len : 0 });
    }
    order.sort((x, y) => x.depth - y.depth);
    for (const { q, p, facing } of order) {
      const color = tools.bodyColor(m.face_body[q] ?? 0);
      ctx.beginPath();
      p.forEach((x, k) => (k ? ctx.lineTo(x[0], x[1]) : ctx.moveTo(x[0], x[1])));
      ctx.closePath();
      if (facing > 0) {
        ctx.globalAlpha = 0.88;
        ctx.fillStyle = shade(color, 0.15 + 0.3 * facing);
        ctx.fill();
        ctx.globalAlpha = 1;
      } else ctx.globalAlpha = 0.25;
      ctx.strokeStyle = color;
      ctx.lineWidth = 1;
      ctx.stroke();
      ctx.globalAlpha = 1;
    }
    const e = edges(m);
    let drawn = 0;
    for (let k = 0; k < e.length; k += 2) if (at[e[k]] && at[e[k + 1]]) drawn++;
    return drawn;
  }

  // `#rrggbb` mixed with white: 0 white, 1 the colour.
  function shade(hex, t) {
    const c = [1, 3, 5].map((i) => parseInt(hex.slice(i, i + 2), 16));
    return `rgb(${c.map((x) => Math.round(255 - t * (255 - x))).join(",")})`;
  }

  // The rigid masters moved by their pair's offset at this increment.
  function drawRigid(T, m, f, color) {
    const ctx = T.ctx, line = (pts, close) => {
      ctx.beginPath();
      pts.forEach((p, i) => (i ? ctx.lineTo(p[0], p[1]) : ctx.moveTo(p[0], p[1])));
      if (close) ctx.closePath();
      ctx.stroke();
    };
    ctx.strokeStyle = ctx.fillStyle = color;
    ctx.lineWidth = 2;
    for (const r of m.rigid) {
      const o = [0, 1, 2].map((c) => f.rigid_offsets[3 * r.pair + c] || 0);
      const at = (a, k) => T.px([a[3 * k] + o[0], a[3 * k + 1] + o[1], a[3 * k + 2] + o[2]]);
      if (r.kind === "plane") line([0, 1, 2, 3].map((k) => at(r.corners, k)), true);
      if (r.kind === "sphere") {
        const c = at(r.centre, 0);
        ctx.beginPath(); ctx.arc(c[0], c[1], r.radius * T.s, 0, 2 * Math.PI); ctx.stroke();
      }
      if (r.kind === "cylinder") drawCylinder(T, r, at, line);
    }
  }

  // A cylinder as its axis (dashed) and, seen from the side, the two lines of its outline;
  // seen along its axis, its circle.
  function drawCylinder(T, r, at, line) {
    const a = at(r.ends, 0), b = at(r.ends, 1), dx = b[0] - a[0], dy = b[1] - a[1], len = Math.hypot(dx, dy);
    const w = r.radius * T.s, ctx = T.ctx;
    if (len < 1e-6 * Math.max(1, w)) {
      ctx.beginPath(); ctx.arc(a[0], a[1], w, 0, 2 * Math.PI); ctx.stroke();
      return;
    }
    const nx = -dy / len * w, ny = dx / len * w;
    line([[a[0] + nx, a[1] + ny], [b[0] + nx, b[1] + ny]]);
    line([[a[0] - nx, a[1] - ny], [b[0] - nx, b[1] - ny]]);
    ctx.setLineDash([6, 4]);
    ctx.lineWidth = 1;
    line([a, b]);
    ctx.setLineDash([]);
  }

  // A point's colour key: open, stick, slip, or closed (a closed point of a frictionless
  // pair, which the record calls slip).
  function stateOf(m, c, i) {
    const s = c.state[i];
    return s === "slip" && (m.pairs[c.pair[i]] || {}).mu === 0 ? "closed" : s;
  }

  // Contact points by state (a slave magnified as its node is); arrows of the normal and
  // tangential parts of the force the slave receives, at one scale for the whole run.
  function drawContacts(T, m, f, v, tools) {
    const ctx = T.ctx, c = f.contact, largest = m.largest.force, mag = v.magnify;
    const k = largest > 0 ? tools.ARROW * T.span * T.s / largest : 0, shown = [];
    for (let i = 0; i < c.count; i++) {
      const p = [0, 1, 2].map((j) => c.position[3 * i + j]);
      if (p.some((x) => x === null)) continue;
      const X = [0, 1, 2].map((j) => m.nodes[3 * c.node[i] + j]);
      shown.push([i, T.px(p.map((x, j) => X[j] + mag * (x - X[j])))]);
    }
    if (v.arrows && k > 0) {
      for (const [i, p] of shown) {
        const n = [0, 1, 2].map((j) => c.normal[3 * i + j]), F = [0, 1, 2].map((j) => c.force[3 * i + j]);
        if (c.state[i] === "open" || n.some((x) => x === null) || F.some((x) => x === null)) continue;
        const along = dot(F, n), t = F.map((x, j) => x - along * n[j]);
        const screen = (w) => [k * dot(w, T.cam.r), -k * dot(w, T.cam.u)];
        tools.arrow(ctx, p, ...screen(n.map((x) => along * x)), tools.NORMAL_COLOR);
        tools.arrow(ctx, p, ...screen(t), tools.TANGENT_COLOR);
      }
    }
    for (const [i, p] of shown) {
      const key = stateOf(m, c, i), open = key === "open";
      ctx.beginPath();
      ctx.arc(p[0], p[1], open ? 2.5 : 4, 0, 2 * Math.PI);
      ctx.lineWidth = open ? 1 : 1.5;
      ctx.strokeStyle = tools.STATE_COLORS[key] || "#000";
      ctx.fillStyle = open ? "#fff" : tools.STATE_COLORS[key];
      ctx.fill();
      ctx.stroke();
    }
    return shown.length;
  }

  // The x, y, z directions in the lower right corner.
  function drawAxes(T) {
    const ctx = T.ctx, o = [T.W - 40, T.H - 40];
    ctx.font = "11px system-ui, sans-serif";
    ctx.lineWidth = 1.5;
    AXES.forEach(([name, color], c) => {
      const e = [0, 0, 0];
      e[c] = 1;
      const x = o[0] + 24 * dot(e, T.cam.r), y = o[1] - 24 * dot(e, T.cam.u);
      ctx.strokeStyle = ctx.fillStyle = color;
      ctx.beginPath(); ctx.moveTo(o[0], o[1]); ctx.lineTo(x, y); ctx.stroke();
      ctx.fillText(name, x + 3, y + 3);
    });
  }

  // Draw frame f of model m on view v's canvas; `tools`: model.js's colours, arrow and
  // scale bar. Returns the counts the page shows in the canvas's data attributes.
  function draw(v, m, f, tools) {
    const nodes = new Array(m.node_count);
    for (let i = 0; i < m.node_count; i++) nodes[i] = nodeAt(m, f, v.magnify, i);
    const T = transform(v, m, nodes), ctx = T.ctx;
    ctx.clearRect(0, 0, T.W, T.H);
    drawRigid(T, m, f, tools.RIGID_COLOR);
    const at = nodes.map((p) => p && T.px(p));
    const drawnEdges = drawFaces(T, m, at, tools);
    const contacts = drawContacts(T, m, f, v, tools);
    tools.scaleBar(T);
    drawAxes(T);
    return { edges: drawnEdges, contacts };
  }

  // Turn the view by dragging view v's canvas (`redraw` after each move); double-click:
  // the default view.
  function attach(v, redraw) {
    v.turn = { az: AZIMUTH, el: ELEVATION };
    let from = null;
    const c = v.canvas, is3d = () => v.model && v.model.dim === 3;
    c.addEventListener("pointerdown", (e) => {
      if (!is3d()) return;
      from = { x: e.clientX, y: e.clientY, az: v.turn.az, el: v.turn.el };
      c.setPointerCapture(e.pointerId);
    });
    c.addEventListener("pointermove", (e) => {
      if (!from) return;
      v.turn.az = from.az - TURN * (e.clientX - from.x);
      v.turn.el = Math.max(-1.5, Math.min(1.5, from.el + TURN * (e.clientY - from.y)));
      redraw();
    });
    const stop = () => { from = null; };
    c.addEventListener("pointerup", stop);
    c.addEventListener("pointercancel", stop);
    c.addEventListener("dblclick", () => { if (is3d()) { v.turn = { az: AZIMUTH, el: ELEVATION }; redraw(); } });
  }

  return { draw, attach, stateOf };
})();
