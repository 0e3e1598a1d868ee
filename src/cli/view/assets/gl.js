// fairsub view: the WebGL2 part. Shaders, the upload of a surface buffer (see
// src/cli/view/api.rs for the layout) and the drawing of one panel. Per frame a panel costs a
// few uniforms and one indexed draw of its triangles (plus one line draw per overlay): the
// geometry stays on the GPU from the upload on, and nothing per frame is proportional to it.
"use strict";

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

function program(gl, vs, fs) {
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

// The surface and line programs of a context.
function programs(gl) {
  return { surf: program(gl, VS, FS), lin: program(gl, LVS, LFS) };
}

// One surface on the GPU: one vertex buffer (positions, normals, K, H, provenance as the
// server laid them out), one index buffer, one line buffer (patch boundaries, then net edges);
// uploaded once. Also the per-vertex area (a third of each triangle's), the weights of the
// automatic curvature range, computed here once.
function upload(gl, buf) {
  const h = new Uint32Array(buf, 0, 6);
  if (h[0] !== 0x31565346) throw new Error("not a fairsub surface buffer");
  const [nv, nt, nb, ne, np] = [h[1], h[2], h[3], h[4], h[5]];
  const bbox = new Float32Array(buf, 24, 6);
  const off = { pos: 48, nor: 48 + 12 * nv, k: 48 + 24 * nv, h: 48 + 28 * nv, prov: 48 + 32 * nv };
  const idx = 48 + 36 * nv, bnd = idx + 12 * nt;
  const attr = (loc, size, offset) => {
    gl.enableVertexAttribArray(loc);
    gl.vertexAttribPointer(loc, size, gl.FLOAT, false, 0, offset);
  };
  const vao = gl.createVertexArray();
  gl.bindVertexArray(vao);
  const vbo = gl.createBuffer();
  gl.bindBuffer(gl.ARRAY_BUFFER, vbo);
  gl.bufferData(gl.ARRAY_BUFFER, new Uint8Array(buf, 0, idx), gl.STATIC_DRAW);
  attr(0, 3, off.pos); attr(1, 3, off.nor); attr(2, 1, off.k); attr(3, 1, off.h); attr(4, 1, off.prov);
  const ibo = gl.createBuffer();
  gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, ibo);
  gl.bufferData(gl.ELEMENT_ARRAY_BUFFER, new Uint32Array(buf, idx, 3 * nt), gl.STATIC_DRAW);
  const lbo = gl.createBuffer();
  const lines = (first) => {
    const a = gl.createVertexArray();
    gl.bindVertexArray(a);
    gl.bindBuffer(gl.ARRAY_BUFFER, lbo);
    attr(0, 3, 24 * first);
    return a;
  };
  gl.bindBuffer(gl.ARRAY_BUFFER, lbo);
  gl.bufferData(gl.ARRAY_BUFFER, new Uint8Array(buf, bnd, 24 * (nb + ne)), gl.STATIC_DRAW);
  const bvao = lines(0), nvao = lines(nb);
  gl.bindVertexArray(null);
  const pos = new Float32Array(buf, off.pos, 3 * nv), tri = new Uint32Array(buf, idx, 3 * nt);
  const area = new Float32Array(nv);
  for (let t = 0; t < 3 * nt; t += 3) {
    const a = 3 * tri[t], b = 3 * tri[t + 1], c = 3 * tri[t + 2];
    const ux = pos[b] - pos[a], uy = pos[b + 1] - pos[a + 1], uz = pos[b + 2] - pos[a + 2];
    const vx = pos[c] - pos[a], vy = pos[c + 1] - pos[a + 1], vz = pos[c + 2] - pos[a + 2];
    const w = Math.hypot(uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx) / 6;
    area[tri[t]] += w; area[tri[t + 1]] += w; area[tri[t + 2]] += w;
  }
  return {
    vao, bvao, nvao, nv, nt, nb, ne, np, bbox, area,
    k: new Float32Array(buf, off.k, nv), h: new Float32Array(buf, off.h, nv),
    free() {
      [vbo, ibo, lbo].forEach((x) => gl.deleteBuffer(x));
      [vao, bvao, nvao].forEach((x) => gl.deleteVertexArray(x));
    },
  };
}

// Draws one panel: the surface with the look `u` (mode, stripes, angle, range, radius, centre
// depth), then the overlays asked for.
function drawPanel(gl, progs, p, mv, proj, u, overlays) {
  const { surf, lin } = progs;
  gl.useProgram(surf.p);
  gl.uniformMatrix4fv(surf.u.uMV, false, mv);
  gl.uniformMatrix4fv(surf.u.uP, false, proj);
  gl.uniform1i(surf.u.uMode, u.mode);
  gl.uniform1f(surf.u.uStripes, u.stripes);
  gl.uniform1f(surf.u.uAngle, u.angle);
  gl.uniform1f(surf.u.uRange, u.range);
  gl.uniform1f(surf.u.uRadius, u.radius);
  gl.uniform1f(surf.u.uCentreZ, u.centreZ);
  gl.bindVertexArray(p.vao);
  gl.drawElements(gl.TRIANGLES, 3 * p.nt, gl.UNSIGNED_INT, 0);
  if (!overlays.patches && !overlays.net) return;
  gl.useProgram(lin.p);
  gl.uniformMatrix4fv(lin.u.uMV, false, mv);
  gl.uniformMatrix4fv(lin.u.uP, false, proj);
  if (overlays.patches && p.nb) {
    gl.uniform3f(lin.u.uColor, 0.1, 0.1, 0.1);
    gl.bindVertexArray(p.bvao);
    gl.drawArrays(gl.LINES, 0, 2 * p.nb);
  }
  if (overlays.net && p.ne) {
    gl.uniform3f(lin.u.uColor, 1.0, 0.3, 0.2);
    gl.bindVertexArray(p.nvao);
    gl.drawArrays(gl.LINES, 0, 2 * p.ne);
  }
}
