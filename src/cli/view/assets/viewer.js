// fairsub view: the page. WebGL2, no framework. The server sends each surface as one binary
// buffer (see src/cli/view/api.rs for the layout); shading is per pixel from the interpolated
// exact normals and curvatures. The URL carries the state, so a view can be shared and tested.
"use strict";

const MODES = { shaded: 0, highlight: 1, reflection: 2, isophotes: 3, gauss: 4, mean: 5, provenance: 6 };
const $ = (id) => document.getElementById(id);
const state = {
  mode: "shaded", scheme: "", split: "", rings: "", lambda: "", rules: "",
  stripes: 16, light: 0, range: "", net: false, patches: false, az: -60, el: 30, dist: 1, px: 0, py: 0,
};
const NUMERIC = ["stripes", "light", "az", "el", "dist", "px", "py"];
let meta = null;
const panels = [null, null];

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
}

function writeUrl() {
  const q = new URLSearchParams();
  for (const [k, v] of Object.entries(state)) {
    if (typeof v === "boolean") { if (v) q.set(k, "1"); }
    else if (v !== "") q.set(k, NUMERIC.includes(k) ? String(+(+v).toFixed(3)) : v);
  }
  history.replaceState(null, "", "?" + q.toString());
}

function showError(msg) {
  const e = $("error");
  e.textContent = msg || "";
  e.style.display = msg ? "block" : "none";
  if (msg) document.title = "fairsub view: error";
}

// ---- small matrix helpers (column-major 4x4) ----
function mul(a, b) {
  const r = new Float32Array(16);
  for (let i = 0; i < 4; i++) for (let j = 0; j < 4; j++) {
    let s = 0;
    for (let k = 0; k < 4; k++) s += a[k * 4 + j] * b[i * 4 + k];
    r[i * 4 + j] = s;
  }
  return r;
}
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

// ---- WebGL ----
const canvas = $("gl");
const gl = canvas.getContext("webgl2", { preserveDrawingBuffer: true, antialias: true });

const VS = `#version 300 es
layout(location=0) in vec3 aPos; layout(location=1) in vec3 aNor;
layout(location=2) in float aK; layout(location=3) in float aH; layout(location=4) in float aProv;
uniform mat4 uMV, uP;
out vec3 vP, vN; out float vK, vH, vProv;
void main() {
  vec4 p = uMV * vec4(aPos, 1.0);
  vP = p.xyz; vN = mat3(uMV) * aNor; vK = aK; vH = aH; vProv = aProv;
  gl_Position = uP * p;
}`;
const FS = `#version 300 es
precision highp float;
in vec3 vP, vN; in float vK, vH, vProv;
uniform int uMode; uniform float uStripes, uAngle, uRange, uRadius, uCentreZ;
out vec4 o;
vec3 ramp(float t) {            // t in [-1, 1]: blue, cyan, green, yellow, red
  t = clamp(t, -1.0, 1.0) * 0.5 + 0.5;
  vec3 c = vec3(clamp(1.5 - abs(4.0 * t - 3.0), 0.0, 1.0), clamp(1.5 - abs(4.0 * t - 2.0), 0.0, 1.0),
    clamp(1.5 - abs(4.0 * t - 1.0), 0.0, 1.0));
  return c;
}
float stripe(float s) {         // anti-aliased light/dark stripes, half of each period dark
  float tri = abs(fract(s) - 0.5) * 2.0;
  float w = min(2.0 * fwidth(s), 0.5);
  return smoothstep(0.5 - w, 0.5 + w, tri);
}
void main() {
  vec3 n = normalize(vN);
  if (!gl_FrontFacing) n = -n;
  vec3 v = normalize(-vP);
  vec3 e = vec3(cos(uAngle), sin(uAngle), 0.0);     // light line direction in the image
  vec3 d = vec3(-e.y, e.x, 0.0);                     // across the light lines
  vec3 l = normalize(vec3(0.3, 0.5, 1.0));
  float diff = max(dot(n, l), 0.0);
  float spec = pow(max(dot(reflect(-l, n), v), 0.0), 40.0);
  vec3 c;
  if (uMode == 1) {
    // Beier-Chen highlight lines: parallel light lines in the plane z = zL between eye and
    // object; a point is on a highlight line when its normal line meets that light line.
    float zL = uCentreZ + 2.0 * uRadius;
    float nz = n.z;
    float t = (zL - vP.z) / max(nz, 1e-3);
    vec3 q = vP + t * n;
    // Light lines spaced evenly in the angle they span seen from the object's centre plane.
    float s = atan(dot(q, d) / (2.0 * uRadius)) / 3.14159265 * uStripes;
    float b = stripe(s);
    c = mix(vec3(0.05), vec3(0.95), b) * (nz > 0.02 ? 1.0 : 0.3);
  } else if (uMode == 2) {
    vec3 r = reflect(-v, n);
    float phi = atan(dot(r, d), r.z + 1.0);
    c = mix(vec3(0.05), vec3(0.95), stripe(phi / 3.14159265 * uStripes));
  } else if (uMode == 3) {
    vec3 li = normalize(vec3(0.6 * e.y, -0.6 * e.x, 1.0));
    c = mix(vec3(0.1, 0.1, 0.3), vec3(1.0, 0.95, 0.8), stripe(max(dot(n, li), 0.0) * uStripes * 0.5));
  } else if (uMode == 4 || uMode == 5) {
    float k = uMode == 4 ? vK : vH;
    c = (k != k) ? vec3(0.4) : ramp(k / uRange) * (0.55 + 0.45 * diff);
  } else if (uMode == 6) {
    vec3 pal[6] = vec3[6](vec3(0.9, 0.6, 0.2), vec3(0.3, 0.7, 0.9), vec3(0.5, 0.85, 0.4),
      vec3(0.85, 0.45, 0.8), vec3(0.95, 0.9, 0.35), vec3(0.4, 0.5, 0.95));
    vec3 b = vProv < -0.5 ? vec3(0.3) : vProv < 0.5 ? vec3(0.75) : vProv > 999.0 ? vec3(0.95, 0.2, 0.2)
      : pal[int(vProv + 0.5) % 6];
    c = b * (0.35 + 0.65 * diff) + 0.2 * spec;
  } else {
    c = vec3(0.8, 0.72, 0.55) * (0.2 + 0.8 * diff) + 0.35 * spec;
  }
  o = vec4(c, 1.0);
}`;
const LVS = `#version 300 es
layout(location=0) in vec3 aPos; uniform mat4 uMV, uP;
void main() { gl_Position = uP * uMV * vec4(aPos, 1.0); gl_Position.z -= 0.0005 * gl_Position.w; }`;
const LFS = `#version 300 es
precision mediump float; uniform vec3 uColor; out vec4 o; void main() { o = vec4(uColor, 1.0); }`;

function program(vs, fs) {
  const p = gl.createProgram();
  for (const [type, src] of [[gl.VERTEX_SHADER, vs], [gl.FRAGMENT_SHADER, fs]]) {
    const s = gl.createShader(type);
    gl.shaderSource(s, src);
    gl.compileShader(s);
    if (!gl.getShaderParameter(s, gl.COMPILE_STATUS)) throw new Error(gl.getShaderInfoLog(s));
    gl.attachShader(p, s);
  }
  gl.linkProgram(p);
  if (!gl.getProgramParameter(p, gl.LINK_STATUS)) throw new Error(gl.getProgramInfoLog(p));
  const u = {};
  for (let i = 0; i < gl.getProgramParameter(p, gl.ACTIVE_UNIFORMS); i++) {
    const name = gl.getActiveUniform(p, i).name;
    u[name] = gl.getUniformLocation(p, name);
  }
  return { p, u };
}

// One surface: one vertex buffer (the server's buffer as it came), one index buffer, and line
// vertex arrays into the same buffer; one draw call each.
function upload(buf) {
  const h = new Uint32Array(buf, 0, 6);
  if (h[0] !== 0x31565346) throw new Error("not a fairsub surface buffer");
  const [nv, nt, nb, ne, np] = [h[1], h[2], h[3], h[4], h[5]];
  const bbox = new Float32Array(buf, 24, 6);
  const off = { pos: 48, nor: 48 + 12 * nv, k: 48 + 24 * nv, h: 48 + 28 * nv, prov: 48 + 32 * nv };
  const idx = 48 + 36 * nv, bnd = idx + 12 * nt, net = bnd + 24 * nb;
  const vbo = gl.createBuffer();
  gl.bindBuffer(gl.ARRAY_BUFFER, vbo);
  gl.bufferData(gl.ARRAY_BUFFER, buf, gl.STATIC_DRAW);
  const vao = gl.createVertexArray();
  gl.bindVertexArray(vao);
  const attr = (loc, size, offset) => {
    gl.enableVertexAttribArray(loc);
    gl.vertexAttribPointer(loc, size, gl.FLOAT, false, 0, offset);
  };
  attr(0, 3, off.pos); attr(1, 3, off.nor); attr(2, 1, off.k); attr(3, 1, off.h); attr(4, 1, off.prov);
  const ibo = gl.createBuffer();
  gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, ibo);
  gl.bufferData(gl.ELEMENT_ARRAY_BUFFER, new Uint32Array(buf, idx, 3 * nt), gl.STATIC_DRAW);
  const lines = (offset) => {
    const a = gl.createVertexArray();
    gl.bindVertexArray(a);
    attr(0, 3, offset);
    return a;
  };
  const bvao = lines(bnd), nvao = lines(net);
  gl.bindVertexArray(null);
  // Surface area per vertex (a third of each triangle's), the weights of the automatic range.
  const pos = new Float32Array(buf, off.pos, 3 * nv), tri = new Uint32Array(buf, idx, 3 * nt);
  const area = new Float32Array(nv);
  for (let t = 0; t < 3 * nt; t += 3) {
    const [a, b, c] = [3 * tri[t], 3 * tri[t + 1], 3 * tri[t + 2]];
    const u = [pos[b] - pos[a], pos[b + 1] - pos[a + 1], pos[b + 2] - pos[a + 2]];
    const v = [pos[c] - pos[a], pos[c + 1] - pos[a + 1], pos[c + 2] - pos[a + 2]];
    const w = Math.hypot(...cross(u, v)) / 6;
    area[tri[t]] += w; area[tri[t + 1]] += w; area[tri[t + 2]] += w;
  }
  return {
    vao, bvao, nvao, nv, nt, nb, ne, np, bbox, area,
    k: new Float32Array(buf, off.k, nv), h: new Float32Array(buf, off.h, nv),
    free() { gl.deleteBuffer(vbo); gl.deleteBuffer(ibo); [vao, bvao, nvao].forEach((x) => gl.deleteVertexArray(x)); },
  };
}

let surf, lin;
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
// extraordinary point do not outweigh the rest).
function curvatureRange() {
  const fixed = parseFloat(state.range);
  if (isFinite(fixed) && fixed > 0) return fixed;
  const vals = [];
  let total = 0;
  for (const p of panels) if (p) {
    const a = state.mode === "gauss" ? p.k : p.h;
    for (let i = 0; i < a.length; i++) if (a[i] === a[i]) { vals.push([Math.abs(a[i]), p.area[i]]); total += p.area[i]; }
  }
  if (!vals.length || !(total > 0)) return 1;
  vals.sort((x, y) => x[0] - y[0]);
  let acc = 0;
  for (const [v, w] of vals) { acc += w; if (acc >= 0.98 * total) return v || 1e-6; }
  return vals[vals.length - 1][0] || 1e-6;
}

function drawLegend(range) {
  const show = state.mode === "gauss" || state.mode === "mean";
  $("legend").style.display = show ? "block" : "none";
  if (!show) return;
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
  const right = normalize(cross(dir, [0, 0, 1])), up = cross(right, dir);
  const at = [0, 1, 2].map((i) => centre[i] + (state.px * right[i] + state.py * up[i]) * radius);
  const eye = [0, 1, 2].map((i) => at[i] + dir[i] * dist);
  const mv = lookAt(eye, at, Math.abs(Math.sin(el)) > 0.999 ? [0, 1, 0] : [0, 0, 1]);
  const proj = perspective((30 * Math.PI) / 180, aspect, dist / 100, dist + 4 * radius);
  const range = curvatureRange();
  for (let i = 0; i < n; i++) {
    const p = panels[i];
    if (!p) continue;
    gl.viewport(i * pw, 0, pw, hgt);
    gl.scissor(i * pw, 0, pw, hgt);
    gl.useProgram(surf.p);
    gl.uniformMatrix4fv(surf.u.uMV, false, mv);
    gl.uniformMatrix4fv(surf.u.uP, false, proj);
    gl.uniform1i(surf.u.uMode, MODES[state.mode]);
    gl.uniform1f(surf.u.uStripes, state.stripes);
    gl.uniform1f(surf.u.uAngle, (state.light * Math.PI) / 180);
    gl.uniform1f(surf.u.uRange, range);
    gl.uniform1f(surf.u.uRadius, radius);
    gl.uniform1f(surf.u.uCentreZ, -dist);
    gl.bindVertexArray(p.vao);
    gl.drawElements(gl.TRIANGLES, 3 * p.nt, gl.UNSIGNED_INT, 0);
    gl.useProgram(lin.p);
    gl.uniformMatrix4fv(lin.u.uMV, false, mv);
    gl.uniformMatrix4fv(lin.u.uP, false, proj);
    if (state.patches) {
      gl.uniform3f(lin.u.uColor, 0.1, 0.1, 0.1);
      gl.bindVertexArray(p.bvao);
      gl.drawArrays(gl.LINES, 0, 2 * p.nb);
    }
    if (state.net) {
      gl.uniform3f(lin.u.uColor, 1.0, 0.3, 0.2);
      gl.bindVertexArray(p.nvao);
      gl.drawArrays(gl.LINES, 0, 2 * p.ne);
    }
  }
  gl.bindVertexArray(null);
  drawLegend(range);
  $("label0").textContent = n === 2 ? panelName(0) : "";
  $("label1").textContent = n === 2 ? panelName(1) : "";
  $("label1").style.display = n === 2 ? "" : "none";
}

function panelName(i) {
  const p = panels[i];
  return `${i ? state.split : state.scheme || meta.input} (${p.nt} triangles)`;
}

let pending = false;
function redraw() {
  if (pending) return;
  pending = true;
  requestAnimationFrame(() => { pending = false; draw(); writeUrl(); });
}

function query(scheme) {
  const q = new URLSearchParams();
  if (scheme) q.set("scheme", scheme);
  for (const k of ["rings", "lambda", "rules"]) if (state[k] !== "") q.set(k, state[k]);
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
  try {
    const schemes = [state.scheme, state.split].filter((s, i) => i === 0 || s);
    const bufs = await Promise.all(schemes.map((s) => fetchOk("/api/surface?" + query(s))));
    if (gen !== generation) return;
    panels.forEach((p) => p && p.free());
    panels[0] = panels[1] = null;
    bufs.forEach((b, i) => (panels[i] = upload(b)));
    const t0 = performance.now();
    draw();
    gl.finish();
    const ms = performance.now() - t0;
    writeUrl();
    document.body.dataset.frameMs = ms.toFixed(1);
    document.body.dataset.triangles = panels.reduce((s, p) => s + (p ? p.nt : 0), 0);
    document.title = "fairsub view: ready";
    fetchOk("/api/check?" + query(state.scheme), "json").then(showCheck, (e) => ($("check").textContent = e.message));
  } catch (e) {
    if (gen === generation) showError(e.message);
  }
}

function showCheck(r) {
  const c = r.continuity, a = c.all || {};
  const lines = [`patches ${c.patches}`, `open sides ${c.open_sides}`];
  for (const [k, v] of Object.entries(a)) lines.push(`${k}: ${typeof v === "number" ? v.toExponential(2) : JSON.stringify(v)}`);
  for (const e of r.curvature || []) lines.push(JSON.stringify(e).slice(0, 300));
  for (const n of r.notes || []) lines.push("note: " + n);
  $("check").textContent = lines.join("\n");
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
  const inputs = { mode: "mode", scheme: "scheme", split: "split", rings: "rings", lambda: "lambda", rules: "rules", stripes: "stripes", light: "light", range: "range" };
  for (const [k, id] of Object.entries(inputs)) {
    const el = $(id);
    el.value = state[k];
    const recompute = ["scheme", "split", "rings", "lambda", "rules"].includes(k);
    el.addEventListener(el.tagName === "SELECT" || recompute ? "change" : "input", () => {
      state[k] = NUMERIC.includes(k) ? parseFloat(el.value) : el.value;
      if (recompute) load(); else redraw();
    });
  }
  for (const k of ["net", "patches"]) {
    $(k).checked = state[k];
    $(k).addEventListener("change", () => { state[k] = $(k).checked; redraw(); });
  }
  $("reset").onclick = () => { Object.assign(state, { az: -60, el: 30, dist: 1, px: 0, py: 0 }); redraw(); };
  $("shot").onclick = () => canvas.toBlob((b) => {
    const a = document.createElement("a");
    a.href = URL.createObjectURL(b);
    a.download = `fairsub-${state.scheme || "surface"}-${state.mode}.png`;
    a.click();
  }, "image/png");
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
  readUrl();
  try {
    surf = program(VS, FS);
    lin = program(LVS, LFS);
    meta = await fetchOk("/api/schemes", "json");
    bindControls();
    fetchOk("/api/info", "json").then((i) => ($("info").textContent = JSON.stringify(i, null, 1)), (e) => ($("info").textContent = e.message));
  } catch (e) {
    showError(e.message);
    return;
  }
  await load();
}
main();
