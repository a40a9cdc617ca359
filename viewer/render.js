// WebGL2 drawing for the viewer: instanced lit meshes (spheres, boxes, capsule cylinders),
// soft-body triangle meshes, ground planes, particles as point sprites, debug lines, and an
// id buffer for picking. Plain WebGL2, no dependencies.
'use strict';

const HRender = (() => {
  const M = {
    // Column-major 4x4 matrices, as WebGL wants them.
    perspective(fovy, aspect, near, far) {
      const f = 1 / Math.tan(fovy / 2), nf = 1 / (near - far);
      return [f / aspect, 0, 0, 0, 0, f, 0, 0, 0, 0, (far + near) * nf, -1, 0, 0, 2 * far * near * nf, 0];
    },
    lookAt(eye, target, up) {
      let zx = eye[0] - target[0], zy = eye[1] - target[1], zz = eye[2] - target[2];
      let l = Math.hypot(zx, zy, zz); zx /= l; zy /= l; zz /= l;
      let xx = up[1] * zz - up[2] * zy, xy = up[2] * zx - up[0] * zz, xz = up[0] * zy - up[1] * zx;
      l = Math.hypot(xx, xy, xz); xx /= l; xy /= l; xz /= l;
      const yx = zy * xz - zz * xy, yy = zz * xx - zx * xz, yz = zx * xy - zy * xx;
      return [xx, yx, zx, 0, xy, yy, zy, 0, xz, yz, zz, 0,
        -(xx * eye[0] + xy * eye[1] + xz * eye[2]), -(yx * eye[0] + yy * eye[1] + yz * eye[2]),
        -(zx * eye[0] + zy * eye[1] + zz * eye[2]), 1];
    },
    mul(a, b) {
      const o = new Array(16);
      for (let c = 0; c < 4; c++) for (let r = 0; r < 4; r++) {
        o[c * 4 + r] = a[r] * b[c * 4] + a[4 + r] * b[c * 4 + 1] + a[8 + r] * b[c * 4 + 2] + a[12 + r] * b[c * 4 + 3];
      }
      return o;
    },
    // p' = q * v (quaternion [x, y, z, w]).
    rotate(q, v) {
      const [x, y, z, w] = q;
      const tx = 2 * (y * v[2] - z * v[1]), ty = 2 * (z * v[0] - x * v[2]), tz = 2 * (x * v[1] - y * v[0]);
      return [v[0] + w * tx + (y * tz - z * ty), v[1] + w * ty + (z * tx - x * tz), v[2] + w * tz + (x * ty - y * tx)];
    },
    qmul(a, b) {
      return [a[3] * b[0] + a[0] * b[3] + a[1] * b[2] - a[2] * b[1],
        a[3] * b[1] - a[0] * b[2] + a[1] * b[3] + a[2] * b[0],
        a[3] * b[2] + a[0] * b[1] - a[1] * b[0] + a[2] * b[3],
        a[3] * b[3] - a[0] * b[0] - a[1] * b[1] - a[2] * b[2]];
    },
    // Rotation taking +Y to the unit vector d.
    fromY(d) {
      const dot = d[1];
      if (dot < -0.999999) return [1, 0, 0, 0];
      const ax = [d[2], 0, -d[0]]; // Y x d
      const q = [ax[0], ax[1], ax[2], 1 + dot];
      const l = Math.hypot(q[0], q[1], q[2], q[3]);
      return q.map((c) => c / l);
    },
    // Writes a column-major T * R * S matrix into out[o..o+16].
    trs(out, o, p, q, s) {
      const [x, y, z, w] = q;
      const x2 = x + x, y2 = y + y, z2 = z + z;
      const xx = x * x2, xy = x * y2, xz = x * z2, yy = y * y2, yz = y * z2, zz = z * z2;
      const wx = w * x2, wy = w * y2, wz = w * z2;
      out[o] = (1 - (yy + zz)) * s[0]; out[o + 1] = (xy + wz) * s[0]; out[o + 2] = (xz - wy) * s[0]; out[o + 3] = 0;
      out[o + 4] = (xy - wz) * s[1]; out[o + 5] = (1 - (xx + zz)) * s[1]; out[o + 6] = (yz + wx) * s[1]; out[o + 7] = 0;
      out[o + 8] = (xz + wy) * s[2]; out[o + 9] = (yz - wx) * s[2]; out[o + 10] = (1 - (xx + yy)) * s[2]; out[o + 11] = 0;
      out[o + 12] = p[0]; out[o + 13] = p[1]; out[o + 14] = p[2]; out[o + 15] = 1;
    },
  };

  const LIT_VS = `#version 300 es
    layout(location=0) in vec3 a_pos;
    layout(location=1) in vec3 a_normal;
    layout(location=2) in mat4 a_model;
    layout(location=6) in vec4 a_color;
    layout(location=7) in vec4 a_pick;
    uniform mat4 u_viewProj;
    out vec3 v_normal;
    out vec4 v_color;
    out vec4 v_pick;
    void main() {
      vec4 world = a_model * vec4(a_pos, 1.0);
      v_normal = mat3(a_model) * a_normal;
      v_color = a_color;
      v_pick = a_pick;
      gl_Position = u_viewProj * world;
    }`;
  // Lighting scales the colour by one factor, so a body's hue and saturation survive it.
  const LIT_FS = `#version 300 es
    precision highp float;
    in vec3 v_normal;
    in vec4 v_color;
    in vec4 v_pick;
    uniform vec3 u_light;
    uniform int u_picking;
    out vec4 o_color;
    void main() {
      if (u_picking == 1) { o_color = v_pick; return; }
      vec3 n = normalize(v_normal);
      if (!gl_FrontFacing) n = -n;
      float k = 0.38 + 0.62 * max(dot(n, u_light), 0.0);
      o_color = vec4(v_color.rgb * k, 1.0);
    }`;
  const PLANE_VS = `#version 300 es
    layout(location=0) in vec3 a_pos;
    uniform mat4 u_viewProj;
    uniform mat4 u_model;
    out vec3 v_world;
    void main() {
      vec4 w = u_model * vec4(a_pos, 1.0);
      v_world = w.xyz;
      gl_Position = u_viewProj * w;
    }`;
  const PLANE_FS = `#version 300 es
    precision highp float;
    in vec3 v_world;
    uniform vec3 u_u;
    uniform vec3 u_v;
    uniform int u_picking;
    out vec4 o_color;
    void main() {
      if (u_picking == 1) { o_color = vec4(0.0); return; }
      vec2 c = floor(vec2(dot(v_world, u_u), dot(v_world, u_v)));
      float checker = mod(c.x + c.y, 2.0);
      o_color = vec4(vec3(0.50 + 0.05 * checker), 1.0);
    }`;
  const LINE_VS = `#version 300 es
    layout(location=0) in vec3 a_pos;
    layout(location=1) in vec3 a_color;
    uniform mat4 u_viewProj;
    out vec3 v_color;
    void main() { v_color = a_color; gl_Position = u_viewProj * vec4(a_pos, 1.0); }`;
  const LINE_FS = `#version 300 es
    precision highp float;
    in vec3 v_color;
    out vec4 o_color;
    void main() { o_color = vec4(v_color, 1.0); }`;
  const POINT_VS = `#version 300 es
    layout(location=0) in vec3 a_pos;
    layout(location=1) in float a_radius;
    layout(location=2) in vec3 a_color;
    uniform mat4 u_viewProj;
    uniform float u_pixelsPerUnit;
    out vec3 v_color;
    void main() {
      gl_Position = u_viewProj * vec4(a_pos, 1.0);
      gl_PointSize = clamp(2.0 * a_radius * u_pixelsPerUnit / gl_Position.w, 2.0, 64.0);
      v_color = a_color;
    }`;
  const POINT_FS = `#version 300 es
    precision highp float;
    in vec3 v_color;
    out vec4 o_color;
    void main() {
      vec2 d = gl_PointCoord * 2.0 - 1.0;
      float r2 = dot(d, d);
      if (r2 > 1.0) discard;
      o_color = vec4(v_color * (0.55 + 0.45 * sqrt(1.0 - r2)), 1.0);
    }`;

  function compile(gl, vs, fs) {
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
    const n = gl.getProgramParameter(p, gl.ACTIVE_UNIFORMS);
    for (let i = 0; i < n; i++) {
      const name = gl.getActiveUniform(p, i).name;
      u[name] = gl.getUniformLocation(p, name);
    }
    return { program: p, u };
  }

  // Meshes: positions and normals interleaved, with indices.
  function sphereMesh(rings, segments) {
    const v = [], idx = [];
    for (let r = 0; r <= rings; r++) {
      const th = Math.PI * r / rings;
      for (let s = 0; s <= segments; s++) {
        const ph = 2 * Math.PI * s / segments;
        const n = [Math.sin(th) * Math.cos(ph), Math.cos(th), Math.sin(th) * Math.sin(ph)];
        v.push(n[0], n[1], n[2], n[0], n[1], n[2]);
      }
    }
    for (let r = 0; r < rings; r++) for (let s = 0; s < segments; s++) {
      const a = r * (segments + 1) + s, b = a + segments + 1;
      idx.push(a, b, a + 1, a + 1, b, b + 1);
    }
    return { v, idx };
  }
  function boxMesh() {
    const v = [], idx = [];
    const faces = [[0, 1], [0, -1], [1, 1], [1, -1], [2, 1], [2, -1]];
    for (const [axis, sign] of faces) {
      const n = [0, 0, 0]; n[axis] = sign;
      const u = [0, 0, 0]; u[(axis + 1) % 3] = 1;
      const w = [0, 0, 0]; w[(axis + 2) % 3] = 1;
      const base = v.length / 6;
      for (const [a, b] of [[-1, -1], [1, -1], [1, 1], [-1, 1]]) {
        v.push(n[0] + a * u[0] + b * w[0], n[1] + a * u[1] + b * w[1], n[2] + a * u[2] + b * w[2], n[0], n[1], n[2]);
      }
      idx.push(base, base + 1, base + 2, base, base + 2, base + 3);
    }
    return { v, idx };
  }
  function cylinderMesh(segments) {
    const v = [], idx = [];
    for (let s = 0; s <= segments; s++) {
      const ph = 2 * Math.PI * s / segments;
      const c = Math.cos(ph), sn = Math.sin(ph);
      v.push(c, -0.5, sn, c, 0, sn, c, 0.5, sn, c, 0, sn);
    }
    for (let s = 0; s < segments; s++) {
      const a = 2 * s;
      idx.push(a, a + 1, a + 2, a + 2, a + 1, a + 3);
    }
    return { v, idx };
  }

  class Renderer {
    constructor(canvas) {
      const gl = canvas.getContext('webgl2', { antialias: true, preserveDrawingBuffer: true });
      if (!gl) throw new Error('WebGL2 is not available in this browser');
      this.gl = gl;
      this.canvas = canvas;
      this.lit = compile(gl, LIT_VS, LIT_FS);
      this.plane = compile(gl, PLANE_VS, PLANE_FS);
      this.line = compile(gl, LINE_VS, LINE_FS);
      this.point = compile(gl, POINT_VS, POINT_FS);
      this.meshes = {};
      for (const [name, m] of [['sphere', sphereMesh(12, 20)], ['box', boxMesh()], ['cylinder', cylinderMesh(24)]]) {
        this.meshes[name] = this.makeMesh(m);
      }
      this.quad = this.makeMesh({ v: [-1, 0, -1, 0, 1, 0, 1, 0, -1, 0, 1, 0, 1, 0, 1, 0, 1, 0, -1, 0, 1, 0, 1, 0], idx: [0, 2, 1, 0, 3, 2] });
      this.dyn = {};
      this.pickFb = null;
    }

    makeMesh(m) {
      const gl = this.gl;
      const vao = gl.createVertexArray();
      gl.bindVertexArray(vao);
      const vb = gl.createBuffer();
      gl.bindBuffer(gl.ARRAY_BUFFER, vb);
      gl.bufferData(gl.ARRAY_BUFFER, new Float32Array(m.v), gl.STATIC_DRAW);
      gl.enableVertexAttribArray(0);
      gl.vertexAttribPointer(0, 3, gl.FLOAT, false, 24, 0);
      gl.enableVertexAttribArray(1);
      gl.vertexAttribPointer(1, 3, gl.FLOAT, false, 24, 12);
      const ib = gl.createBuffer();
      gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, ib);
      gl.bufferData(gl.ELEMENT_ARRAY_BUFFER, new Uint16Array(m.idx), gl.STATIC_DRAW);
      // Per-instance model matrix (locations 2..5), colour (6) and pick id (7).
      const inst = gl.createBuffer();
      gl.bindBuffer(gl.ARRAY_BUFFER, inst);
      for (let c = 0; c < 4; c++) {
        gl.enableVertexAttribArray(2 + c);
        gl.vertexAttribPointer(2 + c, 4, gl.FLOAT, false, 96, 16 * c);
        gl.vertexAttribDivisor(2 + c, 1);
      }
      gl.enableVertexAttribArray(6);
      gl.vertexAttribPointer(6, 4, gl.FLOAT, false, 96, 64);
      gl.vertexAttribDivisor(6, 1);
      gl.enableVertexAttribArray(7);
      gl.vertexAttribPointer(7, 4, gl.FLOAT, false, 96, 80);
      gl.vertexAttribDivisor(7, 1);
      gl.bindVertexArray(null);
      return { vao, count: m.idx.length, inst, capacity: 0 };
    }

    // A dynamic vertex buffer for lines or points, grown as needed.
    dynamic(name, layout) {
      if (this.dyn[name]) return this.dyn[name];
      const gl = this.gl;
      const vao = gl.createVertexArray();
      gl.bindVertexArray(vao);
      const buf = gl.createBuffer();
      gl.bindBuffer(gl.ARRAY_BUFFER, buf);
      const stride = layout.reduce((a, n) => a + n, 0) * 4;
      let off = 0;
      layout.forEach((n, i) => {
        gl.enableVertexAttribArray(i);
        gl.vertexAttribPointer(i, n, gl.FLOAT, false, stride, off);
        off += 4 * n;
      });
      gl.bindVertexArray(null);
      this.dyn[name] = { vao, buf, floats: stride / 4 };
      return this.dyn[name];
    }

    resize() {
      const c = this.canvas;
      const dpr = window.devicePixelRatio || 1;
      const w = Math.max(1, Math.round(c.clientWidth * dpr)), h = Math.max(1, Math.round(c.clientHeight * dpr));
      if (c.width !== w || c.height !== h) { c.width = w; c.height = h; }
    }

    // scene: { viewProj, light, pixelsPerUnit, instances: {sphere|box|cylinder: Float32Array(24 per instance)},
    //          planes: [{model, u, v}], softs: [{positions, normals, triangles, color}],
    //          lines: Float32Array (x y z r g b per vertex), points: Float32Array (x y z radius r g b) }
    draw(scene, picking) {
      const gl = this.gl;
      this.resize();
      if (picking) {
        this.ensurePickTarget();
        gl.bindFramebuffer(gl.FRAMEBUFFER, this.pickFb);
      } else {
        gl.bindFramebuffer(gl.FRAMEBUFFER, null);
      }
      gl.viewport(0, 0, this.canvas.width, this.canvas.height);
      if (picking) gl.clearColor(0, 0, 0, 0); else gl.clearColor(0.13, 0.15, 0.18, 1);
      gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
      gl.enable(gl.DEPTH_TEST);
      gl.disable(gl.CULL_FACE);
      // Planes.
      gl.useProgram(this.plane.program);
      gl.uniformMatrix4fv(this.plane.u.u_viewProj, false, scene.viewProj);
      gl.uniform1i(this.plane.u.u_picking, picking ? 1 : 0);
      for (const p of scene.planes) {
        gl.uniformMatrix4fv(this.plane.u.u_model, false, p.model);
        gl.uniform3fv(this.plane.u.u_u, p.u);
        gl.uniform3fv(this.plane.u.u_v, p.v);
        gl.bindVertexArray(this.quad.vao);
        gl.drawElements(gl.TRIANGLES, this.quad.count, gl.UNSIGNED_SHORT, 0);
      }
      // Instanced shapes.
      gl.useProgram(this.lit.program);
      gl.uniformMatrix4fv(this.lit.u.u_viewProj, false, scene.viewProj);
      gl.uniform3fv(this.lit.u.u_light, scene.light);
      gl.uniform1i(this.lit.u.u_picking, picking ? 1 : 0);
      for (const name of ['sphere', 'box', 'cylinder']) {
        const data = scene.instances[name];
        const n = data.length / 24;
        if (n === 0) continue;
        const mesh = this.meshes[name];
        gl.bindBuffer(gl.ARRAY_BUFFER, mesh.inst);
        gl.bufferData(gl.ARRAY_BUFFER, data, gl.DYNAMIC_DRAW);
        gl.bindVertexArray(mesh.vao);
        gl.drawElementsInstanced(gl.TRIANGLES, mesh.count, gl.UNSIGNED_SHORT, 0, n);
      }
      // Soft bodies: non-instanced, the instance attributes held constant.
      for (const s of scene.softs) {
        const d = this.dynamic('soft' + s.slot, [3, 3]);
        gl.bindVertexArray(d.vao);
        gl.bindBuffer(gl.ARRAY_BUFFER, d.buf);
        const n = s.positions.length / 3;
        const inter = new Float32Array(6 * n);
        for (let i = 0; i < n; i++) {
          inter.set(s.positions.subarray(3 * i, 3 * i + 3), 6 * i);
          inter.set(s.normals.subarray(3 * i, 3 * i + 3), 6 * i + 3);
        }
        gl.bufferData(gl.ARRAY_BUFFER, inter, gl.DYNAMIC_DRAW);
        if (!d.ib) d.ib = gl.createBuffer();
        gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, d.ib);
        gl.bufferData(gl.ELEMENT_ARRAY_BUFFER, s.triangles, gl.DYNAMIC_DRAW);
        const id = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1];
        for (let c = 0; c < 4; c++) { gl.disableVertexAttribArray(2 + c); gl.vertexAttrib4f(2 + c, id[4 * c], id[4 * c + 1], id[4 * c + 2], id[4 * c + 3]); }
        gl.disableVertexAttribArray(6); gl.vertexAttrib4f(6, s.color[0], s.color[1], s.color[2], 1);
        gl.disableVertexAttribArray(7); gl.vertexAttrib4f(7, 0, 0, 0, 0);
        gl.drawElements(gl.TRIANGLES, s.triangles.length, gl.UNSIGNED_INT, 0);
      }
      if (!picking) {
        // Lines, drawn over everything else only where not hidden.
        if (scene.lines.length) {
          const d = this.dynamic('lines', [3, 3]);
          gl.useProgram(this.line.program);
          gl.uniformMatrix4fv(this.line.u.u_viewProj, false, scene.viewProj);
          gl.bindVertexArray(d.vao);
          gl.bindBuffer(gl.ARRAY_BUFFER, d.buf);
          gl.bufferData(gl.ARRAY_BUFFER, scene.lines, gl.DYNAMIC_DRAW);
          gl.drawArrays(gl.LINES, 0, scene.lines.length / 6);
        }
        if (scene.points.length) {
          const d = this.dynamic('points', [3, 1, 3]);
          gl.useProgram(this.point.program);
          gl.uniformMatrix4fv(this.point.u.u_viewProj, false, scene.viewProj);
          gl.uniform1f(this.point.u.u_pixelsPerUnit, scene.pixelsPerUnit);
          gl.bindVertexArray(d.vao);
          gl.bindBuffer(gl.ARRAY_BUFFER, d.buf);
          gl.bufferData(gl.ARRAY_BUFFER, scene.points, gl.DYNAMIC_DRAW);
          gl.drawArrays(gl.POINTS, 0, scene.points.length / 7);
        }
      }
      gl.bindVertexArray(null);
      gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    }

    ensurePickTarget() {
      const gl = this.gl;
      const w = this.canvas.width, h = this.canvas.height;
      if (this.pickFb && this.pickW === w && this.pickH === h) return;
      if (!this.pickFb) {
        this.pickFb = gl.createFramebuffer();
        this.pickTex = gl.createRenderbuffer();
        this.pickDepth = gl.createRenderbuffer();
      }
      gl.bindRenderbuffer(gl.RENDERBUFFER, this.pickTex);
      gl.renderbufferStorage(gl.RENDERBUFFER, gl.RGBA8, w, h);
      gl.bindRenderbuffer(gl.RENDERBUFFER, this.pickDepth);
      gl.renderbufferStorage(gl.RENDERBUFFER, gl.DEPTH_COMPONENT24, w, h);
      gl.bindFramebuffer(gl.FRAMEBUFFER, this.pickFb);
      gl.framebufferRenderbuffer(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.RENDERBUFFER, this.pickTex);
      gl.framebufferRenderbuffer(gl.FRAMEBUFFER, gl.DEPTH_ATTACHMENT, gl.RENDERBUFFER, this.pickDepth);
      gl.bindFramebuffer(gl.FRAMEBUFFER, null);
      this.pickW = w; this.pickH = h;
    }

    // The pick id (0 = nothing) at canvas pixel (x, y) from the top left, after draw(scene, true).
    readPick(x, y) {
      const gl = this.gl;
      const px = new Uint8Array(4);
      gl.bindFramebuffer(gl.FRAMEBUFFER, this.pickFb);
      gl.readPixels(Math.floor(x), this.canvas.height - 1 - Math.floor(y), 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, px);
      gl.bindFramebuffer(gl.FRAMEBUFFER, null);
      return px[0] + 256 * px[1] + 65536 * px[2];
    }
  }

  return { Renderer, M };
})();
