// fairsub view: the page. WebGL2 (gl.js), no framework. The server sends each surface as one
// binary buffer; shading is per pixel from the interpolated exact normals and curvatures. The
// URL carries the state, so a view can be shared and tested; `?bench=N` measures the frame rate.
"use strict";

const MODES = { shaded: 0, highlight: 1, reflection: 2, isophotes: 3, gauss: 4, mean: 5, provenance: 6 };
const CAMERA = { az: -60, el: 30, dist: 1, px: 0, py: 0 };
const $ = (id) => document.getElementById(id);
// The page's own state; the scheme options (named as on the command line) are in `opts`.
const state = {
  mode: "shaded", scheme: "", split: "", rings: "", stripes: 16, light: 0, range: "",
  net: false, patches: false, ...CAMERA,
};
const NUMERIC = ["stripes", "light", "az", "el", "dist", "px", "py"];
const opts = {};
let meta = null, bench = 0;
const panels = [null, null];

// The option words of a scheme (empty for none or a .bv file).
function optionsOf(name) {
  const s = meta && meta.schemes.find((x) => x.name === name);
  return s ? s.options : [];
}
function allOptionNames() {
  const names = new Set();
  for (const s of meta.schemes) for (const o of s.options) names.add(o.name);
  return names;
}

function readUrl() {
  const q = new URLSearchParams(location.search);
  for (const k of Object.keys(state)) {
    if (!q.has(k)) continue;
    const v = q.get(k);
    if (typeof state[k] === "boolean") state[k] = v === "1" || v === "true";
    else if (NUMERIC.includes(k)) { const x = parseFloat(v); if (isFinite(x)) state[k] = x; }
    else state[k] = v;
  }
  if (q.has("overlay")) {
    const o = q.get("overlay").split(",");
    state.net = o.includes("net");
    state.patches = o.includes("patches");
  }
  if (!(state.mode in MODES)) state.mode = "shaded";
  state.el = Math.max(-89.9, Math.min(89.9, state.el)); // the pan and screen axes stay defined
  for (const name of allOptionNames()) if (q.has(name)) opts[name] = q.get(name);
  bench = Math.max(0, Math.min(10000, parseInt(q.get("bench") || "0", 10) || 0));
}

// The URL follows the state (at most every 200 ms: dragging changes the camera every frame).
let urlTimer = 0;
function writeUrl() {
  if (urlTimer) return;
  urlTimer = setTimeout(() => {
    urlTimer = 0;
    const q = new URLSearchParams();
    for (const [k, v] of Object.entries(state)) {
      if (typeof v === "boolean") { if (v) q.set(k, "1"); }
      else if (v !== "") q.set(k, NUMERIC.includes(k) ? String(+(+v).toPrecision(7)) : v);
    }
    for (const [k, v] of Object.entries(opts)) if (v !== "") q.set(k, v);
    history.replaceState(null, "", "?" + q.toString());
  }, 200);
}

function showError(msg) {
  const e = $("error");
  e.textContent = msg || "";
  e.style.display = msg ? "block" : "none";
  if (msg) document.title = "fairsub view: error";
}

// ---- small matrix helpers (column-major 4x4) ----
function perspective(fovy, aspect, near, far) {
  const f = 1 / Math.tan(fovy / 2), r = new Float32Array(16);
  r[0] = f / aspect; r[5] = f; r[10] = (far + near) / (near - far); r[11] = -1;
  r[14] = (2 * far * near) / (near - far);
  return r;
}
function sub(a, b) { return [a[0] - b[0], a[1] - b[1], a[2] - b[2]]; }
function cross(a, b) { return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]; }
function normalize(a) { const l = Math.hypot(a[0], a[1], a[2]) || 1; return [a[0] / l, a[1] / l, a[2] / l]; }
function dot(a, b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
function lookAt(eye, at, up) {
  const z = normalize(sub(eye, at)), x = normalize(cross(up, z)), y = cross(z, x);
  return new Float32Array([x[0], y[0], z[0], 0, x[1], y[1], z[1], 0, x[2], y[2], z[2], 0,
    -dot(x, eye), -dot(y, eye), -dot(z, eye), 1]);
}

const canvas = $("gl");
const gl = canvas.getContext("webgl2", { antialias: true });
let progs = null;

function scene() {
  const ps = panels.filter((p) => p);
  const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
  for (const p of ps) for (let i = 0; i < 3; i++) { lo[i] = Math.min(lo[i], p.bbox[i]); hi[i] = Math.max(hi[i], p.bbox[3 + i]); }
  const centre = [0, 1, 2].map((i) => (lo[i] + hi[i]) / 2);
  const radius = Math.max(Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]) / 2, 1e-9);
  return { centre, radius };
}

// The curvature range: fixed, or the 98th percentile of |value| over the shown surfaces'
// area (as `render` takes it over the visible pixels; the dense small ring patches near an
// extraordinary point do not outweigh the rest). Computed when the surfaces, the mode or the
// range field change, never per frame.
let rangeCache = { key: null, value: 1 };
let loaded = 0;
function curvatureRange() {
  const fixed = parseFloat(state.range);
  if (isFinite(fixed) && fixed > 0) return fixed;
  if (state.mode !== "gauss" && state.mode !== "mean") return 1;
  const key = `${loaded}/${state.mode}/${state.split ? 2 : 1}`;
  if (rangeCache.key === key) return rangeCache.value;
  const vals = [];
  let total = 0;
  for (const p of panels.slice(0, state.split ? 2 : 1)) if (p) {
    const a = state.mode === "gauss" ? p.k : p.h;
    for (let i = 0; i < a.length; i++) if (a[i] === a[i]) { vals.push([Math.abs(a[i]), p.area[i]]); total += p.area[i]; }
  }
  let value = 1;
  if (vals.length && total > 0) {
    vals.sort((x, y) => x[0] - y[0]);
    let acc = 0;
    value = vals[vals.length - 1][0] || 1e-6;
    for (const [v, w] of vals) { acc += w; if (acc >= 0.98 * total) { value = v || 1e-6; break; } }
  }
  rangeCache = { key, value };
  return value;
}

let legendKey = "";
function drawLegend(range) {
  const show = state.mode === "gauss" || state.mode === "mean";
  $("legend").style.display = show ? "block" : "none";
  if (!show) return;
  const key = `${state.mode}/${range}/${state.range}`;
  if (key === legendKey) return;
  legendKey = key;
  const c = $("legendbar").getContext("2d");
  for (let x = 0; x < 256; x++) {
    const t = (x / 255) * 2 - 1, u = t * 0.5 + 0.5;
    const f = (s) => Math.round(255 * Math.min(1, Math.max(0, 1.5 - Math.abs(4 * u - s))));
    c.fillStyle = `rgb(${f(3)},${f(2)},${f(1)})`;
    c.fillRect(x, 0, 1, 14);
  }
  const name = state.mode === "gauss" ? "K" : "H";
  $("lmin").textContent = (-range).toPrecision(3);
  $("lmid").textContent = `${name} ${parseFloat(state.range) > 0 ? "fixed" : "auto"}`;
  $("lmax").textContent = range.toPrecision(3);
}

function draw() {
  const dpr = window.devicePixelRatio || 1;
  const w = Math.max(1, Math.round(canvas.clientWidth * dpr)), hgt = Math.max(1, Math.round(canvas.clientHeight * dpr));
  if (canvas.width !== w || canvas.height !== hgt) { canvas.width = w; canvas.height = hgt; }
  gl.enable(gl.SCISSOR_TEST);
  gl.scissor(0, 0, w, hgt);
  gl.clearColor(0.12, 0.12, 0.14, 1);
  gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
  if (!panels[0]) return;
  gl.enable(gl.DEPTH_TEST);
  const { centre, radius } = scene();
  const n = state.split && panels[1] ? 2 : 1;
  const pw = Math.floor(w / n);
  const az = (state.az * Math.PI) / 180, el = (state.el * Math.PI) / 180;
  // Fit the bounding sphere into the narrower side of a panel.
  const aspect = pw / hgt;
  const dist = (radius / Math.sin((30 * Math.PI) / 360)) * Math.max(1, 1 / aspect) * 1.05 * state.dist;
  const dir = [Math.cos(el) * Math.cos(az), Math.cos(el) * Math.sin(az), Math.sin(el)];
  // The screen's axes (as lookAt makes them): the pan moves the target along them.
  const right = normalize(cross([0, 0, 1], dir)), up = cross(dir, right);
  const at = [0, 1, 2].map((i) => centre[i] + (state.px * right[i] + state.py * up[i]) * radius);
  const eye = [0, 1, 2].map((i) => at[i] + dir[i] * dist);
  const mv = lookAt(eye, at, up);
  const proj = perspective((30 * Math.PI) / 180, aspect, dist / 100, dist + 4 * radius);
  const range = curvatureRange();
  const look = {
    mode: MODES[state.mode], stripes: state.stripes, angle: (state.light * Math.PI) / 180,
    range, radius, centreZ: -dist,
  };
  for (let i = 0; i < n; i++) {
    if (!panels[i]) continue;
    gl.viewport(i * pw, 0, pw, hgt);
    gl.scissor(i * pw, 0, pw, hgt);
    drawPanel(gl, progs, panels[i], mv, proj, look, state);
  }
  gl.bindVertexArray(null);
  drawLegend(range);
}

function panelName(i) {
  const p = panels[i];
  return `${i ? state.split : state.scheme || meta.input} (${p.nt} triangles)`;
}

function labels() {
  const two = !!(state.split && panels[1]);
  $("label0").textContent = two ? panelName(0) : "";
  $("label1").textContent = two ? panelName(1) : "";
  $("label1").style.display = two ? "" : "none";
}

let pending = false;
function redraw() {
  writeUrl();
  if (pending) return;
  pending = true;
  requestAnimationFrame(() => { pending = false; draw(); });
}

// The API query of a panel's scheme: rings and the options that scheme takes (files stay on
// the server, as the command line gave them).
function query(scheme) {
  const q = new URLSearchParams();
  if (scheme) q.set("scheme", scheme);
  if (state.rings !== "") q.set("rings", state.rings);
  for (const o of optionsOf(scheme)) if (!o.file && opts[o.name]) q.set(o.name, opts[o.name]);
  return q.toString();
}

async function fetchOk(url, as) {
  const r = await fetch(url);
  if (!r.ok) {
    let msg = `${url}: HTTP ${r.status}`;
    try { msg = (await r.json()).error || msg; } catch (_) { /* not JSON */ }
    throw new Error(msg);
  }
  return as === "json" ? r.json() : r.arrayBuffer();
}

// Loads the surfaces of the panels (and the check summary of the left one), then draws.
let generation = 0;
async function load() {
  const gen = ++generation;
  document.title = "fairsub view: loading";
  showError("");
  writeUrl();
  try {
    const schemes = [state.scheme, state.split].filter((s, i) => i === 0 || s);
    document.body.dataset.query = query(state.scheme);
    const bufs = await Promise.all(schemes.map((s) => fetchOk("/api/surface?" + query(s))));
    if (gen !== generation) return;
    panels.forEach((p) => p && p.free());
    panels[0] = panels[1] = null;
    bufs.forEach((b, i) => (panels[i] = upload(gl, b)));
    loaded++;
    draw();
    labels();
    document.body.dataset.triangles = panels.reduce((s, p) => s + (p ? p.nt : 0), 0);
    $("check").textContent = "...";
    fetchOk("/api/check?" + query(state.scheme), "json").then(showCheck, (e) => ($("check").textContent = e.message));
    if (bench) await runBench(bench);
    document.title = "fairsub view: ready";
  } catch (e) {
    if (gen === generation) showError(e.message);
  }
}

// `?bench=N`: N frames paced by requestAnimationFrame while the camera turns (what a user
// dragging sees: frames per second), then N frames each drawn and waited for by reading one
// pixel back (the time the GPU takes per frame, not capped by the display's refresh; Chromium's
// gl.finish() does not wait). The results go to the page (#bench), to document.body.dataset
// and to window.fairsubBench.
async function runBench(n) {
  const frame = () => new Promise((r) => requestAnimationFrame(r));
  const pixel = new Uint8Array(4);
  const wait = () => gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, pixel);
  const az0 = state.az;
  await frame();
  draw();
  wait();
  const stamps = [];
  for (let i = 0; i < n; i++) {
    stamps.push(await frame());
    state.az = az0 + (360 * i) / n;
    draw();
  }
  stamps.push(await frame());
  const span = stamps[stamps.length - 1] - stamps[0];
  const waited = [];
  for (let i = 0; i < n; i++) {
    state.az = az0 + (360 * i) / n;
    const t0 = performance.now();
    draw();
    wait();
    waited.push(performance.now() - t0);
  }
  // The JavaScript side of a frame: draw() alone (the calls handed to the GPU process, no
  // waiting for them), then one frame's WebGL calls counted by name.
  const js = [];
  for (let i = 0; i < n; i++) {
    state.az = az0 + (360 * i) / n;
    const t0 = performance.now();
    draw();
    js.push(performance.now() - t0);
    wait();
  }
  state.az = az0;
  const calls = countCalls(draw);
  waited.sort((a, b) => a - b);
  js.sort((a, b) => a - b);
  const count = (names) => names.reduce((s, k) => s + (calls[k] || 0), 0);
  const r = {
    frames: n,
    triangles: panels.reduce((s, p) => s + (p ? p.nt : 0), 0),
    fps: span > 0 ? (n * 1000) / span : 0,
    msPerFrame: span / n,
    drawMsMedian: waited[Math.floor(n / 2)],
    jsMsMedian: js[Math.floor(n / 2)],
    calls,
    callsTotal: count(Object.keys(calls)),
    uploads: count(UPLOADS),
    draws: count(["drawElements", "drawArrays"]),
    renderer: rendererName(),
  };
  window.fairsubBench = r;
  Object.assign(document.body.dataset, {
    benchFrames: r.frames, benchFps: r.fps.toFixed(2), benchMs: r.msPerFrame.toFixed(2),
    benchDrawMs: r.drawMsMedian.toFixed(2), benchJsMs: r.jsMsMedian.toFixed(3),
    benchCalls: JSON.stringify(calls), benchUploads: r.uploads, benchDraws: r.draws,
  });
  $("bench").textContent = `${r.triangles} triangles: ${r.fps.toFixed(1)} frames/s ` +
    `(${r.msPerFrame.toFixed(1)} ms/frame), draw + read-back ${r.drawMsMedian.toFixed(1)} ms, ` +
    `JavaScript ${r.jsMsMedian.toFixed(2)} ms, ${r.callsTotal} WebGL calls (${r.uploads} uploads, ` +
    `${r.draws} draws) per frame; ${r.renderer}`;
  $("bench").style.display = "block";
}

// WebGL calls that send data to the GPU: none may happen in a frame of a loaded surface.
const UPLOADS = ["bufferData", "bufferSubData", "texImage2D", "texSubImage2D", "texImage3D",
  "texSubImage3D", "compressedTexImage2D", "compressedTexSubImage2D", "copyBufferSubData"];

// Runs `f` with every method of the WebGL context counted (by name, on the context object, so
// nothing else is touched) and returns the counts.
function countCalls(f) {
  const counts = {};
  const proto = Object.getPrototypeOf(gl);
  const names = Object.getOwnPropertyNames(proto).filter((k) => {
    const d = Object.getOwnPropertyDescriptor(proto, k);
    return k !== "constructor" && d && typeof d.value === "function";
  });
  for (const k of names) {
    const orig = proto[k];
    gl[k] = (...a) => {
      counts[k] = (counts[k] || 0) + 1;
      return orig.apply(gl, a);
    };
  }
  try {
    f();
  } finally {
    for (const k of names) delete gl[k];
  }
  return counts;
}

function rendererName() {
  const ext = gl.getExtension("WEBGL_debug_renderer_info");
  return ext ? gl.getParameter(ext.UNMASKED_RENDERER_WEBGL) : gl.getParameter(gl.RENDERER);
}

// The side panel's tables: built as DOM nodes with textContent (the reports name files and
// elements; nothing from them is parsed as HTML).
function el(tag, text, cls) {
  const e = document.createElement(tag);
  if (text !== undefined) e.textContent = text;
  if (cls) e.className = cls;
  return e;
}

// A table of rows (arrays of cells), with a header row when `head` is given.
function table(rows, head) {
  const t = el("table");
  if (head) { const tr = t.insertRow(); for (const h of head) tr.appendChild(el("th", h)); }
  for (const r of rows) {
    const tr = t.insertRow();
    r.forEach((c, i) => tr.appendChild(el(i === 0 && !head ? "th" : "td", String(c))));
  }
  return t;
}

// Numbers as short as they stay readable: integers whole, 0.01..1000 to 3 digits, else 1.2e-5.
const num = (x) => {
  if (typeof x !== "number") return x == null ? "-" : String(x);
  if (Number.isInteger(x)) return String(x);
  const a = Math.abs(x);
  return a >= 0.01 && a < 1000 ? x.toPrecision(3) : x.toExponential(1).replace("e+", "e");
};
const counts = (m) => Object.entries(m || {}).map(([k, v]) => `${k}: ${v}`).join(", ") || "none";
const elementName = (e) => (e && typeof e === "object" ? (e.type !== undefined ? `${e.type} ${e.index}` : Object.values(e).join(" ")) : String(e));
const listed = (a, f, n = 6) => (a.length ? a.slice(0, n).map(f).join(", ") + (a.length > n ? `, ... (${a.length})` : "") : "none");

// The net's `info` report (or a .bv file's counts) as a table of its facts.
function showInfo(i) {
  const box = $("info");
  box.replaceChildren();
  if (i.patches !== undefined) {
    const k = i.kinds || {};
    box.appendChild(table([["file", i.source], ["patches", i.patches], ["tensor-product", num(k.tensor)], ["rational", num(k.rational)],
      ["triangular", num(k.triangular)], ["polyhedra", `${num(k.polyhedra)} (${num(k.polyhedron_faces)} faces)`]]));
    return;
  }
  const bb = i.bounding_box || [[], []];
  const rows = [["file", i.source], ["vertices", i.vertices], ["edges", i.edges], ["faces", i.faces],
    ["Euler char.", i.euler_characteristic], ["face sizes", counts(i.face_sizes)],
    ["interior valences", counts(i.interior_valences)], ["boundary valences", counts(i.boundary_valences)],
    ["boundary loops", i.boundary_loops.length ? i.boundary_loops.join(", ") : "none"],
    ["extraord. vertices", listed(i.extraordinary_vertices, (v) => `${v.vertex} (n=${v.valence}${v.boundary ? ", boundary" : ""})`)],
    ["extraord. faces", listed(i.extraordinary_faces, (f) => `${f.face} (${f.sides} sides)`)],
    ["box min", bb[0].map((x) => x.toPrecision(4)).join(" ")], ["box max", bb[1].map((x) => x.toPrecision(4)).join(" ")]];
  if (i.dropped_vertices && i.dropped_vertices.length) rows.push(["dropped vertices", listed(i.dropped_vertices, String)]);
  if (i.non_manifold) rows.push(["non-manifold", `${i.non_manifold.edges.length} edges, ${i.non_manifold.vertices.length} vertices`]);
  const facts = table(rows);
  facts.className = "facts";
  box.appendChild(facts);
  const rules = Object.entries(i.rules_by_valence || {});
  if (rules.length) {
    box.appendChild(el("div", "rules at the extraordinary valences", "sub"));
    const t = table(rules.map(([s, rs]) => [s, rs.map((r) => `n=${r.valence}: ${r.rules}`).join("; ")]), ["scheme", "rules"]);
    t.className = "text";
    box.appendChild(t);
  }
  for (const p of i.problems || []) box.appendChild(el("div", "problem: " + p, "note"));
}

// `check --json`'s report as tables: the joins by kind, C^1 up to scaling, curvature per ring.
function showCheck(r) {
  const box = $("check");
  if (r.mesh) {
    // a scheme without exact patches: its refined net
    const m = r.mesh;
    box.replaceChildren(el("div", `net at level ${m.levels}${m.limit ? " (limit points)" : ""}: ${m.faces} faces, ${m.vertices} vertices`, "sum"));
    for (const n of r.notes || []) box.appendChild(el("div", "note: " + n, "note"));
    return;
  }
  const c = r.continuity;
  box.replaceChildren(el("div", `patches ${c.patches}, open sides ${c.open_sides}, size ${num(c.size)}`, "sum"));
  if (r.kinds) {
    const k = r.kinds;
    box.appendChild(el("div", `read: ${k.tensor} tensor-product, ${k.rational} rational, ${k.triangular} triangular, ${k.polyhedron_faces} polyhedron faces`, "note"));
  }
  const row = (name, d) => [name, d.pieces, num(d.c0), num(d.c1), num(d.c2), num(d.g1)];
  const joins = Object.entries(c.by_kind || {}).map(([k, d]) => row(k, d));
  if (c.sharp && c.sharp.pieces > 0) joins.push(row("sharp (C0)", c.sharp));
  if (c.all) joins.push(row("all", c.all));
  box.appendChild(table(joins, ["join", "pieces", "C0", "C1", "C2", "G1 rad"]));
  const sc = r.c1_up_to_scaling;
  if (sc && Object.keys(sc.by_kind || {}).length) {
    box.appendChild(el("div", "C1 up to per-piece scaling", "sub"));
    box.appendChild(table(Object.entries(sc.by_kind).map(([k, d]) => [k, d.pieces, num(d.c1_relative), num(d.kappa_min), num(d.kappa_max), num(d.g1)]),
      ["join", "pieces", "C1 rel.", "kappa min", "kappa max", "G1 rad"]));
  }
  const curv = [];
  for (const e of r.curvature || []) for (const g of e.rings) {
    curv.push([elementName(e.element), g.ring === 0 ? "cap" : `ring ${g.ring}`, num(g.gauss_min), num(g.gauss_max), num(g.mean_min), num(g.mean_max)]);
  }
  if (curv.length) {
    box.appendChild(el("div", "curvature per ring", "sub"));
    box.appendChild(table(curv, ["element", "ring", "K min", "K max", "H min", "H max"]));
  }
  for (const n of r.notes || []) box.appendChild(el("div", "note: " + n, "note"));
}

// The option controls of the shown schemes (left, then right), built from the option words
// the server describes: a menu for a fixed set of values, a box for a flag, a field otherwise;
// files show what the command line gave. In the side-by-side view each scheme's own options
// are under its name (an option both take is shown once, under the left one, and applies to
// both).
function buildOptions() {
  const box = $("opts");
  box.textContent = "";
  if (meta.bv) { box.textContent = "(the patches of a .bv file)"; return; }
  const seen = new Set();
  for (const scheme of state.split ? [state.scheme, state.split] : [state.scheme]) {
    const own = optionsOf(scheme).filter((o) => !seen.has(o.name));
    if (state.split) {
      const h = document.createElement("div");
      h.className = "scheme";
      h.textContent = own.length ? scheme : `${scheme}: no other options`;
      box.append(h);
    }
    for (const o of own) { seen.add(o.name); box.append(control(o)); }
  }
  if (!seen.size && !state.split) box.textContent = "(none)";
}

function control(o) {
  const label = document.createElement("label");
  label.title = o.help;
  label.append(o.name + " ");
  let el;
  if (o.file) {
    const given = (meta.start.files || []).find(([k]) => k === o.name);
    el = document.createElement("span");
    el.className = "file";
    el.textContent = given ? given[1] : "(none given)";
    el.title = "files are named on the command line of fairsub view (--q-file, --fcv-file)";
  } else if (o.flag) {
    el = document.createElement("input");
    el.type = "checkbox";
    el.checked = opts[o.name] === "1";
    el.onchange = () => { opts[o.name] = el.checked ? "1" : ""; load(); };
  } else if (o.choices.length) {
    el = document.createElement("select");
    el.add(new Option("default", ""));
    for (const c of o.choices) el.add(new Option(c, c));
    el.value = opts[o.name] || "";
    el.onchange = () => { opts[o.name] = el.value; load(); };
  } else {
    el = document.createElement("input");
    el.type = "text";
    el.size = o.repeated ? 14 : 5;
    el.placeholder = o.repeated ? "a;b" : "default";
    el.value = opts[o.name] || "";
    el.onchange = () => { opts[o.name] = el.value.trim(); load(); };
  }
  el.dataset.option = o.name;
  label.append(el);
  return label;
}

// The rings field counts levels of the refined net for a scheme without exact patches.
function ringsLabel() {
  const s = meta.schemes.find((x) => x.name === state.scheme);
  $("ringsname").textContent = s && s.patches === false ? "levels" : "rings";
}

function bindControls() {
  const sel = $("scheme"), split = $("split");
  for (const s of meta.schemes) {
    sel.add(new Option(s.name, s.name));
    split.add(new Option(s.name, s.name));
  }
  if (meta.bv) { sel.disabled = split.disabled = $("rings").disabled = true; sel.add(new Option(meta.input, "")); }
  if (!state.scheme && meta.start.scheme) state.scheme = meta.start.scheme;
  if (state.rings === "" && !meta.bv) state.rings = String(meta.start.rings);
  const inputs = ["mode", "scheme", "split", "rings", "stripes", "light", "range"];
  for (const k of inputs) {
    const el = $(k);
    el.value = state[k];
    const recompute = ["scheme", "split", "rings"].includes(k);
    el.addEventListener(el.tagName === "SELECT" || recompute ? "change" : "input", () => {
      state[k] = NUMERIC.includes(k) ? parseFloat(el.value) : el.value;
      if (k === "scheme" || k === "split") { buildOptions(); ringsLabel(); }
      if (recompute) load(); else redraw();
    });
  }
  buildOptions();
  ringsLabel();
  for (const k of ["net", "patches"]) {
    $(k).checked = state[k];
    $(k).addEventListener("change", () => { state[k] = $(k).checked; redraw(); });
  }
  $("reset").onclick = () => { Object.assign(state, CAMERA); redraw(); };
  // The drawing buffer is not kept between frames (cheaper on a GPU), so the screenshot draws
  // and copies in one task.
  $("shot").onclick = () => {
    draw();
    canvas.toBlob((b) => {
      const a = document.createElement("a");
      a.href = URL.createObjectURL(b);
      a.download = `fairsub-${state.scheme || "surface"}-${state.mode}.png`;
      a.click();
    }, "image/png");
  };
  let drag = null;
  canvas.addEventListener("pointerdown", (e) => { drag = { x: e.clientX, y: e.clientY, pan: e.shiftKey || e.button !== 0 }; canvas.setPointerCapture(e.pointerId); });
  canvas.addEventListener("pointerup", () => (drag = null));
  canvas.addEventListener("contextmenu", (e) => e.preventDefault());
  canvas.addEventListener("pointermove", (e) => {
    if (!drag) return;
    const dx = e.clientX - drag.x, dy = e.clientY - drag.y;
    drag.x = e.clientX; drag.y = e.clientY;
    if (drag.pan) { state.px -= (dx / canvas.clientHeight) * 2 * state.dist; state.py += (dy / canvas.clientHeight) * 2 * state.dist; }
    else { state.az -= dx * 0.4; state.el = Math.max(-89.9, Math.min(89.9, state.el + dy * 0.4)); }
    redraw();
  });
  canvas.addEventListener("wheel", (e) => { e.preventDefault(); state.dist *= Math.exp(e.deltaY * 0.001); redraw(); }, { passive: false });
  window.addEventListener("resize", redraw);
}

async function main() {
  if (!gl) { showError("this browser has no WebGL2"); return; }
  try {
    progs = programs(gl);
    meta = await fetchOk("/api/schemes", "json");
    readUrl();
    bindControls();
    fetchOk("/api/info", "json").then(showInfo, (e) => ($("info").textContent = e.message));
  } catch (e) {
    showError(e.message);
    return;
  }
  await load();
}
main();
