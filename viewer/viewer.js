// The viewer's page logic: loading, camera, building each frame's scene, picking, the
// timeline, the chart, and a small test hook (window.hearthViewer) for tests/viewer/.
'use strict';

(() => {
  const $ = (id) => document.getElementById(id);
  const { M } = HRender;
  const canvas = $('canvas');
  const chart = $('chart');
  const FOV = 45 * Math.PI / 180;
  let renderer = null;
  let rec = null;
  let frame = 0;
  let playing = false;
  let speed = 1;
  let selected = -1; // body slot
  let sceneRadius = 10;
  const cam = { target: [0, 0, 0], dist: 10, yaw: 0.7, pitch: 0.45 };
  let dirty = true;

  function setStatus(text) { $('status').textContent = text; }

  try {
    renderer = new HRender.Renderer(canvas);
  } catch (e) {
    setStatus('Cannot draw: ' + e.message);
  }

  // Body colours: static bodies grey; others a golden-ratio hue sequence over the slot index
  // (hue = fract(slot * 0.618034), saturation 0.6, value 0.95; kinematic saturation 0.3).
  // Sleeping bodies are drawn dimmer and bluer when sleep colouring is on.
  function hsv(h, s, v) {
    const i = Math.floor(h * 6), f = h * 6 - i;
    const p = v * (1 - s), q = v * (1 - f * s), t = v * (1 - (1 - f) * s);
    return [[v, t, p], [q, v, p], [p, v, t], [p, q, v], [t, p, v], [v, p, q]][i % 6];
  }
  function baseColor(slot, type) {
    if (type === 'static') return [0.56, 0.57, 0.6];
    const h = (slot * 0.618033988749895) % 1;
    return hsv(h, type === 'kinematic' ? 0.3 : 0.6, 0.95);
  }
  function bodyColor(slot, type, awake) {
    const c = baseColor(slot, type);
    if (type !== 'static' && !awake && $('show-sleep').checked) {
      return [c[0] * 0.35 + 0.12, c[1] * 0.35 + 0.14, c[2] * 0.35 + 0.28];
    }
    return c;
  }

  // ------------------------------------------------------------------------- camera
  function eye() {
    const c = Math.cos(cam.pitch);
    return [cam.target[0] + cam.dist * c * Math.sin(cam.yaw), cam.target[1] + cam.dist * Math.sin(cam.pitch),
      cam.target[2] + cam.dist * c * Math.cos(cam.yaw)];
  }
  function viewProj() {
    const aspect = Math.max(1e-3, canvas.clientWidth / Math.max(1, canvas.clientHeight));
    const proj = M.perspective(FOV, aspect, cam.dist * 0.01, cam.dist * 50 + sceneRadius * 4);
    return M.mul(proj, M.lookAt(eye(), cam.target, [0, 1, 0]));
  }

  // Frames what the recording shows (bodies but planes, soft bodies, particles) over five
  // frames spread through it, ignoring the farthest 2 % on each axis (a body that flies off).
  function fitCamera() {
    const pts = [[], [], []];
    const n = rec.frames.length - 1;
    for (const i of new Set([0, n >> 2, n >> 1, (3 * n) >> 2, n])) {
      const s = rec.seek(i);
      for (const [slot, d] of s.bodies) {
        if (d.shapes.length === 0 || d.shapes.some((sh) => sh.kind === 'plane')) continue;
        for (let k = 0; k < 3; k++) pts[k].push(s.pose[slot * 7 + k]);
      }
      for (const sb of rec.softBodies(i)) {
        for (let j = 0; j < sb.positions.length; j++) pts[j % 3].push(sb.positions[j]);
      }
      const p = rec.particles(i);
      for (let j = 0; j < p.positions.length; j++) pts[j % 3].push(p.positions[j]);
    }
    const lo = [-5, -5, -5], hi = [5, 5, 5];
    if (pts[0].length > 0) {
      for (let k = 0; k < 3; k++) {
        const a = Float64Array.from(pts[k]).sort();
        lo[k] = a[Math.floor(0.02 * (a.length - 1))] - 0.5;
        hi[k] = a[Math.ceil(0.98 * (a.length - 1))] + 0.5;
      }
    }
    cam.target = [0, 1, 2].map((k) => 0.5 * (lo[k] + hi[k]));
    sceneRadius = Math.max(1, 0.5 * Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]));
    cam.dist = sceneRadius / Math.sin(FOV / 2) * 0.95;
    cam.yaw = 0.7;
    cam.pitch = 0.45;
  }

  // ------------------------------------------------------------------------- scene
  function pushLine(lines, a, b, c) { lines.push(a[0], a[1], a[2], c[0], c[1], c[2], b[0], b[1], b[2], c[0], c[1], c[2]); }
  function pushBox(lines, lo, hi, c) {
    const p = (x, y, z) => [x ? hi[0] : lo[0], y ? hi[1] : lo[1], z ? hi[2] : lo[2]];
    for (let a = 0; a < 2; a++) for (let b = 0; b < 2; b++) {
      pushLine(lines, p(0, a, b), p(1, a, b), c);
      pushLine(lines, p(a, 0, b), p(a, 1, b), c);
      pushLine(lines, p(a, b, 0), p(a, b, 1), c);
    }
  }
  function shapeAabb(sh, p, q) {
    const tp = (v) => { const r = M.rotate(q, v); return [r[0] + p[0], r[1] + p[1], r[2] + p[2]]; };
    if (sh.kind === 'sphere') {
      const c = tp(sh.center);
      return [c.map((x) => x - sh.radius), c.map((x) => x + sh.radius)];
    }
    if (sh.kind === 'capsule') {
      const a = tp(sh.a), b = tp(sh.b);
      return [a.map((x, k) => Math.min(x, b[k]) - sh.radius), a.map((x, k) => Math.max(x, b[k]) + sh.radius)];
    }
    if (sh.kind === 'box') {
      const c = tp(sh.center);
      const r = M.qmul(q, sh.rotation);
      const ext = [0, 0, 0];
      for (let k = 0; k < 3; k++) {
        const axis = [0, 0, 0]; axis[k] = sh.halfExtents[k];
        const w = M.rotate(r, axis);
        for (let j = 0; j < 3; j++) ext[j] += Math.abs(w[j]);
      }
      return [c.map((x, k) => x - ext[k]), c.map((x, k) => x + ext[k])];
    }
    return null;
  }

  function buildScene() {
    const s = rec.seek(frame);
    const inst = { sphere: [], box: [], cylinder: [] };
    const planes = [], lines = [], points = [];
    const tmp = new Float32Array(16);
    const put = (kind, p, q, scale, color, pick) => {
      M.trs(tmp, 0, p, q, scale);
      const a = inst[kind];
      for (let k = 0; k < 16; k++) a.push(tmp[k]);
      a.push(color[0], color[1], color[2], 1, pick[0], pick[1], pick[2], 1);
    };
    const showAabbs = $('show-aabbs').checked;
    for (const [slot, d] of s.bodies) {
      const o = slot * 7;
      const p = [s.pose[o], s.pose[o + 1], s.pose[o + 2]];
      const q = [s.pose[o + 3], s.pose[o + 4], s.pose[o + 5], s.pose[o + 6]];
      const color = bodyColor(slot, d.type, s.awake[slot]);
      const id = slot + 1;
      const pick = [(id & 255) / 255, ((id >> 8) & 255) / 255, ((id >> 16) & 255) / 255];
      const tp = (v) => { const r = M.rotate(q, v); return [r[0] + p[0], r[1] + p[1], r[2] + p[2]]; };
      for (const sh of d.shapes) {
        if (sh.kind === 'sphere') {
          put('sphere', tp(sh.center), q, [sh.radius, sh.radius, sh.radius], color, pick);
        } else if (sh.kind === 'box') {
          put('box', tp(sh.center), M.qmul(q, sh.rotation), sh.halfExtents, color, pick);
        } else if (sh.kind === 'capsule') {
          const a = tp(sh.a), b = tp(sh.b);
          const r = [sh.radius, sh.radius, sh.radius];
          put('sphere', a, q, r, color, pick);
          put('sphere', b, q, r, color, pick);
          const axis = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
          const len = Math.hypot(axis[0], axis[1], axis[2]);
          if (len > 1e-6) {
            put('cylinder', [(a[0] + b[0]) / 2, (a[1] + b[1]) / 2, (a[2] + b[2]) / 2],
              M.fromY(axis.map((x) => x / len)), [sh.radius, len, sh.radius], color, pick);
          }
        } else if (sh.kind === 'plane') {
          const ln = Math.hypot(sh.normal[0], sh.normal[1], sh.normal[2]);
          const n = M.rotate(q, sh.normal.map((x) => x / ln));
          const offset = sh.offset / ln + n[0] * p[0] + n[1] * p[1] + n[2] * p[2];
          // A large square of the plane, centred under the camera's target.
          const t = cam.target;
          const dist = n[0] * t[0] + n[1] * t[1] + n[2] * t[2] - offset;
          const c = [t[0] - dist * n[0], t[1] - dist * n[1], t[2] - dist * n[2]];
          const r = M.fromY(n);
          const size = Math.max(50, 6 * sceneRadius);
          const model = new Float32Array(16);
          M.trs(model, 0, c, r, [size, 1, size]);
          planes.push({ model, u: M.rotate(r, [1, 0, 0]), v: M.rotate(r, [0, 0, 1]) });
        }
        if (showAabbs || slot === selected) {
          const bb = shapeAabb(sh, p, q);
          if (bb) pushBox(lines, bb[0], bb[1], slot === selected ? [1, 0.9, 0.2] : [0.35, 0.85, 0.45]);
        }
      }
    }
    // Soft bodies.
    const softs = [];
    for (const sb of rec.softBodies(frame)) {
      const d = s.softs.get(sb.index);
      if (!d) continue;
      const normals = new Float32Array(sb.positions.length);
      const P = sb.positions, T = d.triangles;
      for (let t = 0; t < T.length; t += 3) {
        const a = 3 * T[t], b = 3 * T[t + 1], c = 3 * T[t + 2];
        const e1 = [P[b] - P[a], P[b + 1] - P[a + 1], P[b + 2] - P[a + 2]];
        const e2 = [P[c] - P[a], P[c + 1] - P[a + 1], P[c + 2] - P[a + 2]];
        const n = [e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]];
        for (const v of [a, b, c]) { normals[v] += n[0]; normals[v + 1] += n[1]; normals[v + 2] += n[2]; }
      }
      softs.push({ slot: sb.index, positions: P, normals, triangles: T, color: hsv((0.08 + sb.index * 0.31) % 1, 0.45, 0.95) });
    }
    // Particles.
    const part = rec.particles(frame);
    for (let i = 0; i < part.count; i++) {
      points.push(part.positions[3 * i], part.positions[3 * i + 1], part.positions[3 * i + 2], Math.max(part.radii[i], 0.01), 1.0, 0.62, 0.25);
    }
    // Joints: anchor to anchor, and each body's centre to its anchor.
    if ($('show-joints').checked) {
      for (const j of rec.joints(frame)) {
        const c = j.broken ? [0.9, 0.2, 0.2] : [0.95, 0.85, 0.3];
        pushLine(lines, j.anchorA, j.anchorB, c);
        for (const [b, anchor] of [[j.bodyA, j.anchorA], [j.bodyB, j.anchorB]]) {
          if (b !== 0xffffffff && s.bodies.has(b)) pushLine(lines, [s.pose[7 * b], s.pose[7 * b + 1], s.pose[7 * b + 2]], anchor, [0.6, 0.6, 0.65]);
        }
        points.push(...j.anchorA, 0.04, 0.95, 0.85, 0.3, ...j.anchorB, 0.04, 0.95, 0.85, 0.3);
      }
    }
    // Contacts: points and normals (length grows with the normal impulse).
    if ($('show-contacts').checked && rec.hasContacts) {
      for (const m of rec.contacts(frame)) {
        for (const pt of m.points) {
          const len = 0.15 + Math.min(0.6, 0.02 * Math.sqrt(Math.max(0, pt.impulse)));
          const tip = [pt.point[0] + len * m.normal[0], pt.point[1] + len * m.normal[1], pt.point[2] + len * m.normal[2]];
          pushLine(lines, pt.point, tip, [0.95, 0.3, 0.3]);
          points.push(...pt.point, 0.03, 0.95, 0.25, 0.25);
        }
      }
    }
    const vp = viewProj();
    const light = [0.45, 0.8, 0.4];
    const ll = Math.hypot(...light);
    return {
      viewProj: new Float32Array(vp),
      light: light.map((x) => x / ll),
      pixelsPerUnit: canvas.height / (2 * Math.tan(FOV / 2)),
      instances: { sphere: new Float32Array(inst.sphere), box: new Float32Array(inst.box), cylinder: new Float32Array(inst.cylinder) },
      planes, softs, lines: new Float32Array(lines), points: new Float32Array(points),
    };
  }

  function render() {
    if (!rec || !renderer) return;
    renderer.draw(buildScene(), false);
    dirty = false;
  }

  // ------------------------------------------------------------------------- info panels
  const fmt = (v, d = 3) => v.toFixed(d);
  const vec = (a) => '(' + a.map((x) => fmt(x)).join(', ') + ')';

  function updateInfo() {
    if (!rec) return;
    const f = rec.frames[frame];
    const c = f.counters;
    $('frame-label').textContent = `frame ${frame} / ${rec.frames.length - 1} · t = ${fmt(f.time)} s`;
    $('timeline').value = String(frame);
    $('frame-info').textContent =
      `step         ${f.step}\n` +
      `dt           ${fmt(f.dt * 1000, 2)} ms\n` +
      `step time    ${fmt(f.stepSeconds * 1000, 3)} ms\n` +
      `bodies       ${c.bodies} (${c.awakeBodies} awake)\n` +
      `contacts     ${c.contacts} (${c.touchingContacts} touching)\n` +
      `pairs tested ${c.pairsTested}\n` +
      `particles    ${c.particles}\n` +
      `soft bodies  ${c.softBodies}\n` +
      `joints       ${c.joints}\n` +
      `tree height  ${c.treeHeight}`;
    const s = rec.state;
    const d = selected >= 0 ? s.bodies.get(selected) : null;
    if (!d) {
      $('body-info').textContent = selected >= 0 ? `body ${selected} does not exist in this frame` : 'click a body';
      return;
    }
    const v = Array.from(s.vel.subarray(6 * selected, 6 * selected + 3));
    const w = Array.from(s.vel.subarray(6 * selected + 3, 6 * selected + 6));
    const p = Array.from(s.pose.subarray(7 * selected, 7 * selected + 3));
    $('body-info').textContent =
      `id           {index ${d.index}, generation ${d.generation}}\n` +
      `type         ${d.type}\n` +
      `user_data    ${d.userData}\n` +
      `state        ${d.type === 'static' ? 'static' : (s.awake[selected] ? 'awake' : 'asleep')}\n` +
      `position     ${vec(p)}\n` +
      `velocity     ${vec(v)} |v| ${fmt(Math.hypot(...v))} m/s\n` +
      `angular vel. ${vec(w)} rad/s\n` +
      `shapes       ${d.shapes.map((x) => x.kind).join(', ') || 'none'}`;
  }

  // ------------------------------------------------------------------------- chart
  function drawChart() {
    const dpr = window.devicePixelRatio || 1;
    chart.width = Math.round(chart.clientWidth * dpr);
    chart.height = Math.round(chart.clientHeight * dpr);
    const g = chart.getContext('2d');
    g.setTransform(dpr, 0, 0, dpr, 0, 0);
    const W = chart.clientWidth, H = chart.clientHeight;
    g.fillStyle = '#1b1e23';
    g.fillRect(0, 0, W, H);
    if (!rec) return;
    const n = rec.frames.length;
    const series = [
      { name: 'step time (ms)', color: '#f0a35e', get: (f) => f.stepSeconds * 1000 },
      { name: 'awake bodies', color: '#6fb3f2', get: (f) => f.counters.awakeBodies },
      { name: 'touching contacts', color: '#7fd48a', get: (f) => f.counters.touchingContacts },
    ];
    const x = (i) => (n <= 1 ? 0 : (i / (n - 1)) * (W - 1));
    let legendX = 6;
    g.font = '11px system-ui, sans-serif';
    for (const sr of series) {
      let max = 0;
      for (const f of rec.frames) max = Math.max(max, sr.get(f));
      g.strokeStyle = sr.color;
      g.lineWidth = 1.2;
      g.beginPath();
      rec.frames.forEach((f, i) => {
        const y = H - 4 - (max > 0 ? sr.get(f) / max : 0) * (H - 20);
        if (i === 0) g.moveTo(x(i), y); else g.lineTo(x(i), y);
      });
      g.stroke();
      const label = `${sr.name}: max ${max < 10 ? max.toFixed(3) : Math.round(max)}`;
      g.fillStyle = sr.color;
      g.fillText(label, legendX, 12);
      legendX += g.measureText(label).width + 16;
    }
    g.strokeStyle = '#ffffff';
    g.lineWidth = 1;
    g.beginPath();
    g.moveTo(x(frame) + 0.5, 0);
    g.lineTo(x(frame) + 0.5, H);
    g.stroke();
  }

  // ------------------------------------------------------------------------- frames
  function setFrame(i) {
    if (!rec) return;
    frame = Math.max(0, Math.min(rec.frames.length - 1, i | 0));
    rec.seek(frame);
    updateInfo();
    render();
    drawChart();
  }

  let last = 0, acc = 0;
  function tick(t) {
    if (rec && playing) {
      acc += Math.min(0.25, (t - last) / 1000) * speed;
      let advanced = false;
      while (frame < rec.frames.length - 1) {
        const dt = rec.frames[frame + 1].dt || 1 / 60;
        if (acc < dt) break;
        acc -= dt;
        frame++;
        advanced = true;
      }
      if (frame >= rec.frames.length - 1) { playing = false; $('play').textContent = 'play'; }
      if (advanced) setFrame(frame);
    } else if (dirty) {
      render();
    }
    last = t;
    requestAnimationFrame(tick);
  }
  requestAnimationFrame(tick);

  function togglePlay() {
    if (!rec) return;
    if (!playing && frame >= rec.frames.length - 1) setFrame(0);
    playing = !playing;
    acc = 0;
    $('play').textContent = playing ? 'pause' : 'play';
  }

  // ------------------------------------------------------------------------- loading
  function load(buffer, name) {
    try {
      rec = new Hrec.Recording(buffer);
    } catch (e) {
      setStatus('Cannot open ' + name + ': ' + e.message);
      api.error = e.message;
      return false;
    }
    api.error = null;
    $('file-name').textContent = `${name} · ${(buffer.byteLength / 1024).toFixed(0)} KiB · ${rec.frames.length} frames`;
    setStatus(rec.truncated ? 'truncated: shows every whole step' : '');
    $('drop-hint').classList.add('hidden');
    $('timeline').max = String(rec.frames.length - 1);
    $('show-contacts').disabled = !rec.hasContacts;
    selected = -1;
    playing = false;
    $('play').textContent = 'play';
    fitCamera();
    setFrame(0);
    api.ready = true;
    return true;
  }

  function loadUrl(url) {
    setStatus('loading ' + url + ' …');
    return fetch(url)
      .then((r) => { if (!r.ok) throw new Error(r.status + ' ' + r.statusText); return r.arrayBuffer(); })
      .then((b) => load(b, url.split('/').pop()))
      .catch((e) => { setStatus('Cannot load ' + url + ': ' + e.message); api.error = e.message; });
  }

  $('file-input').addEventListener('change', (e) => {
    const f = e.target.files[0];
    if (f) f.arrayBuffer().then((b) => load(b, f.name));
  });
  window.addEventListener('dragover', (e) => { e.preventDefault(); });
  window.addEventListener('drop', (e) => {
    e.preventDefault();
    const f = e.dataTransfer.files[0];
    if (f) f.arrayBuffer().then((b) => load(b, f.name));
  });

  // ------------------------------------------------------------------------- input
  $('timeline').addEventListener('input', (e) => setFrame(+e.target.value));
  $('first').onclick = () => setFrame(0);
  $('last').onclick = () => setFrame(rec ? rec.frames.length - 1 : 0);
  $('back').onclick = () => setFrame(frame - 1);
  $('forward').onclick = () => setFrame(frame + 1);
  $('play').onclick = togglePlay;
  $('speed').onchange = (e) => { speed = +e.target.value; };
  for (const id of ['show-contacts', 'show-aabbs', 'show-joints', 'show-sleep']) $(id).onchange = () => render();
  window.addEventListener('keydown', (e) => {
    if (e.target.tagName === 'INPUT' && e.target.type !== 'checkbox' && e.target.type !== 'range') return;
    if (e.key === ' ') { togglePlay(); e.preventDefault(); }
    else if (e.key === 'ArrowLeft') { setFrame(frame - 1); e.preventDefault(); }
    else if (e.key === 'ArrowRight') { setFrame(frame + 1); e.preventDefault(); }
    else if (e.key === 'Home') setFrame(0);
    else if (e.key === 'End' && rec) setFrame(rec.frames.length - 1);
  });
  const scrub = (e) => {
    if (!rec) return;
    const r = chart.getBoundingClientRect();
    setFrame(Math.round(((e.clientX - r.left) / r.width) * (rec.frames.length - 1)));
  };
  chart.addEventListener('mousedown', (e) => { scrub(e); const move = (m) => scrub(m); window.addEventListener('mousemove', move); window.addEventListener('mouseup', () => window.removeEventListener('mousemove', move), { once: true }); });

  let drag = null;
  canvas.addEventListener('contextmenu', (e) => e.preventDefault());
  canvas.addEventListener('mousedown', (e) => { drag = { x: e.clientX, y: e.clientY, moved: false, pan: e.button === 2 || e.shiftKey }; });
  window.addEventListener('mousemove', (e) => {
    if (!drag) return;
    const dx = e.clientX - drag.x, dy = e.clientY - drag.y;
    if (Math.abs(dx) + Math.abs(dy) > 2) drag.moved = true;
    if (!drag.moved) return;
    drag.x = e.clientX; drag.y = e.clientY;
    if (drag.pan) {
      const s = cam.dist * 0.0015;
      const right = [Math.cos(cam.yaw), 0, -Math.sin(cam.yaw)];
      const up = [-Math.sin(cam.pitch) * Math.sin(cam.yaw), Math.cos(cam.pitch), -Math.sin(cam.pitch) * Math.cos(cam.yaw)];
      for (let k = 0; k < 3; k++) cam.target[k] += (-dx * right[k] + dy * up[k]) * s;
    } else {
      cam.yaw -= dx * 0.006;
      cam.pitch = Math.max(-1.5, Math.min(1.5, cam.pitch + dy * 0.006));
    }
    render();
  });
  window.addEventListener('mouseup', (e) => {
    if (drag && !drag.moved && e.button === 0) pickAt(e.clientX, e.clientY);
    drag = null;
  });
  canvas.addEventListener('wheel', (e) => { e.preventDefault(); cam.dist *= Math.exp(e.deltaY * 0.001); render(); }, { passive: false });
  window.addEventListener('resize', () => { render(); drawChart(); });

  function pickAt(clientX, clientY) {
    if (!rec || !renderer) return -1;
    const r = canvas.getBoundingClientRect();
    const dpr = canvas.width / r.width;
    renderer.draw(buildScene(), true);
    const id = renderer.readPick((clientX - r.left) * dpr, (clientY - r.top) * dpr);
    selected = id - 1;
    updateInfo();
    render();
    return selected;
  }

  // ------------------------------------------------------------------------- test hook
  // Used by tests/viewer/viewer_test.js: the page's own camera, so a test can project a body's
  // recorded position to the pixel where it must appear.
  const api = {
    ready: false,
    error: null,
    frameCount: () => (rec ? rec.frames.length : 0),
    frame: () => frame,
    setFrame: (i) => setFrame(i),
    camera: () => {
      const r = canvas.getBoundingClientRect();
      return { viewProj: viewProj(), left: r.left, top: r.top, width: r.width, height: r.height };
    },
    selected: () => selected,
    loadUrl,
  };
  window.hearthViewer = api;

  const param = new URLSearchParams(location.search).get('file');
  if (param) loadUrl(param);
  drawChart();
})();
