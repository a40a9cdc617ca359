// Hearth recordings (docs/recording-format.md): parsing and random-access replay.
//
// parse(arrayBuffer) walks the chunks once, keeps each frame's byte offsets, and snapshots
// the replayed body state every KEYFRAME frames, so seeking to any frame applies at most
// KEYFRAME frames of body records. Particles, soft-body vertices, joints and contacts are
// whole per frame and decoded when shown.
'use strict';

const Hrec = (() => {
  const KEYFRAME = 32;
  const HEADER_LEN = 16;
  const FLAG_CONTACTS = 1;
  const DEF_BODY = 1, DEF_BODY_REMOVED = 2, DEF_SOFT = 3, DEF_SOFT_REMOVED = 4;
  const SHAPE_SPHERE = 0, SHAPE_BOX = 1, SHAPE_CAPSULE = 2, SHAPE_PLANE = 3;
  const BODY_TYPES = ['static', 'kinematic', 'dynamic'];
  const JOINT_KINDS = { 0: 'ball', 1: 'hinge', 2: 'fixed', 3: 'distance', 4: 'slider', 255: 'other' };
  const COUNTER_NAMES = ['bodies', 'awakeBodies', 'contacts', 'touchingContacts', 'pairsTested',
    'proxiesMoved', 'particles', 'softBodies', 'joints', 'treeHeight'];
  const STEP_HEADER = 16 + 4 * COUNTER_NAMES.length;

  function tag(dv, at) {
    return String.fromCharCode(dv.getUint8(at), dv.getUint8(at + 1), dv.getUint8(at + 2), dv.getUint8(at + 3));
  }

  function f16(h) {
    const s = (h & 0x8000) ? -1 : 1;
    const e = (h >> 10) & 0x1f;
    const m = h & 0x3ff;
    if (e === 0) return s * m * 5.960464477539063e-8;
    if (e === 31) return m ? NaN : s * Infinity;
    return s * (1 + m / 1024) * Math.pow(2, e - 15);
  }

  // Smallest-three rotation in 48 bits (see recording-format.md).
  function unpackQuat(dv, at, out, o) {
    const lo = dv.getUint32(at, true);
    const hi = dv.getUint16(at + 4, true);
    const bits = lo + hi * 4294967296;
    const largest = lo & 3;
    const R = Math.SQRT1_2;
    let sum = 0, k = 0;
    for (let i = 0; i < 4; i++) {
      if (i === largest) continue;
      const q = Math.floor(bits / Math.pow(2, 2 + 15 * k)) % 32768;
      const v = (q / 32767 - 0.5) * 2 * R;
      out[o + i] = v;
      sum += v * v;
      k++;
    }
    out[o + largest] = Math.sqrt(Math.max(0, 1 - sum));
    const n = Math.hypot(out[o], out[o + 1], out[o + 2], out[o + 3]);
    for (let i = 0; i < 4; i++) out[o + i] /= n;
  }

  function readVec3(dv, at) {
    return [dv.getFloat32(at, true), dv.getFloat32(at + 4, true), dv.getFloat32(at + 8, true)];
  }
  function readQuat(dv, at) {
    return [dv.getFloat32(at, true), dv.getFloat32(at + 4, true), dv.getFloat32(at + 8, true), dv.getFloat32(at + 12, true)];
  }

  // Body state while replaying: pose (p, q) and velocities by slot index, awake flags, and
  // the live definitions.
  class State {
    constructor(capacity) {
      this.capacity = 0;
      this.pose = new Float32Array(0);
      this.vel = new Float32Array(0);
      this.awake = new Uint8Array(0);
      this.bodies = new Map(); // slot -> body definition
      this.softs = new Map(); // slot -> soft body definition
      this.frame = -1;
      this.grow(capacity);
    }
    grow(n) {
      if (n <= this.capacity) return;
      const cap = Math.max(n, this.capacity * 2, 64);
      const pose = new Float32Array(cap * 7); pose.set(this.pose); this.pose = pose;
      const vel = new Float32Array(cap * 6); vel.set(this.vel); this.vel = vel;
      const awake = new Uint8Array(cap); awake.set(this.awake); this.awake = awake;
      this.capacity = cap;
    }
    copyFrom(o) {
      this.grow(o.capacity);
      this.pose.fill(0); this.vel.fill(0); this.awake.fill(0);
      this.pose.set(o.pose); this.vel.set(o.vel); this.awake.set(o.awake);
      this.bodies = new Map(o.bodies);
      this.softs = new Map(o.softs);
      this.frame = o.frame;
    }
  }

  function parseDefs(dv, at, end, out) {
    while (at < end) {
      const kind = dv.getUint8(at); at += 1;
      if (kind === DEF_BODY) {
        const d = { kind: 'body', index: dv.getUint32(at, true), generation: dv.getUint32(at + 4, true) };
        d.type = BODY_TYPES[dv.getUint8(at + 8)] || 'unknown';
        d.userData = dv.getBigUint64(at + 9, true).toString();
        d.position = readVec3(dv, at + 17);
        d.rotation = readQuat(dv, at + 29);
        const n = dv.getUint32(at + 45, true);
        at += 49;
        d.shapes = [];
        for (let i = 0; i < n; i++) {
          const k = dv.getUint8(at); at += 1;
          if (k === SHAPE_SPHERE) {
            d.shapes.push({ kind: 'sphere', center: readVec3(dv, at), radius: dv.getFloat32(at + 12, true) }); at += 16;
          } else if (k === SHAPE_BOX) {
            d.shapes.push({ kind: 'box', center: readVec3(dv, at), rotation: readQuat(dv, at + 12), halfExtents: readVec3(dv, at + 28) }); at += 40;
          } else if (k === SHAPE_CAPSULE) {
            d.shapes.push({ kind: 'capsule', a: readVec3(dv, at), b: readVec3(dv, at + 12), radius: dv.getFloat32(at + 24, true) }); at += 28;
          } else if (k === SHAPE_PLANE) {
            d.shapes.push({ kind: 'plane', normal: readVec3(dv, at), offset: dv.getFloat32(at + 12, true) }); at += 16;
          } else {
            throw new Error('unknown shape kind ' + k);
          }
        }
        out.push(d);
      } else if (kind === DEF_BODY_REMOVED) {
        out.push({ kind: 'bodyRemoved', index: dv.getUint32(at, true) }); at += 4;
      } else if (kind === DEF_SOFT) {
        const d = { kind: 'soft', index: dv.getUint32(at, true), generation: dv.getUint32(at + 4, true) };
        d.userData = dv.getBigUint64(at + 8, true).toString();
        d.vertexRadius = dv.getFloat32(at + 16, true);
        d.vertexCount = dv.getUint32(at + 20, true);
        const nt = dv.getUint32(at + 24, true);
        at += 28;
        d.triangles = new Uint32Array(nt * 3);
        for (let i = 0; i < nt * 3; i++) d.triangles[i] = dv.getUint32(at + 4 * i, true);
        at += 12 * nt;
        out.push(d);
      } else if (kind === DEF_SOFT_REMOVED) {
        out.push({ kind: 'softRemoved', index: dv.getUint32(at, true) }); at += 4;
      } else {
        throw new Error('unknown definition record ' + kind);
      }
    }
  }

  // Offsets of a step chunk's sections, without decoding them.
  function indexStep(dv, at, end) {
    const f = {
      step: dv.getUint32(at, true),
      dt: dv.getFloat32(at + 4, true),
      time: dv.getFloat32(at + 8, true),
      stepSeconds: dv.getFloat32(at + 12, true),
      counters: {},
    };
    COUNTER_NAMES.forEach((name, i) => { f.counters[name] = dv.getUint32(at + 16 + 4 * i, true); });
    at += STEP_HEADER;
    f.bodyCount = dv.getUint32(at, true);
    f.bodyAt = at + 4;
    at += 4;
    for (let i = 0; i < f.bodyCount; i++) {
      while (dv.getUint8(at) & 0x80) at++;
      at += 1 + 30;
    }
    f.particleCount = dv.getUint32(at, true);
    f.particleAt = at + 4;
    at += 4 + 14 * f.particleCount;
    f.softCount = dv.getUint32(at, true);
    f.softAt = at + 4;
    at += 4;
    for (let i = 0; i < f.softCount; i++) at += 8 + 12 * dv.getUint32(at + 4, true);
    f.jointCount = dv.getUint32(at, true);
    f.jointAt = at + 4;
    at += 4 + 38 * f.jointCount;
    f.contactCount = dv.getUint32(at, true);
    f.contactAt = at + 4;
    at += 4;
    for (let i = 0; i < f.contactCount; i++) at += 21 + 20 * dv.getUint8(at + 20);
    if (at !== end) throw new Error('step chunk length mismatch at step ' + f.step);
    return f;
  }

  class Recording {
    constructor(buffer) {
      this.buffer = buffer;
      this.dv = new DataView(buffer);
      this.frames = [];
      this.keyframes = [];
      this.truncated = false;
      this.gravity = [0, -9.81, 0];
      this.substeps = 0;
      const dv = this.dv;
      if (buffer.byteLength < HEADER_LEN || tag(dv, 0) + tag(dv, 4) !== 'HEARTHRC') {
        throw new Error('not a Hearth recording (bad magic)');
      }
      this.version = dv.getUint32(8, true);
      if (this.version !== 1) throw new Error('recording format version ' + this.version + ' is not supported');
      this.flags = dv.getUint32(12, true);
      this.hasContacts = (this.flags & FLAG_CONTACTS) !== 0;
      let at = HEADER_LEN;
      let pending = [];
      const state = new State(64);
      while (at < buffer.byteLength) {
        if (buffer.byteLength - at < 8) { this.truncated = true; break; }
        const t = tag(dv, at);
        const len = dv.getUint32(at + 4, true);
        const start = at + 8;
        if (len > buffer.byteLength - start) { this.truncated = true; break; }
        const end = start + len;
        if (t === 'WRLD') {
          this.gravity = readVec3(dv, start);
          this.substeps = dv.getUint32(start + 12, true);
        } else if (t === 'DEFS') {
          parseDefs(dv, start, end, pending);
        } else if (t === 'STEP') {
          const f = indexStep(dv, start, end);
          f.defs = pending;
          pending = [];
          this.frames.push(f);
          this.apply(state, this.frames.length - 1);
          if ((this.frames.length - 1) % KEYFRAME === 0) {
            const snap = new State(state.capacity);
            snap.copyFrom(state);
            this.keyframes.push(snap);
          }
        }
        at = end;
      }
      if (this.frames.length === 0) throw new Error('the recording holds no whole frame');
      this.maxSlot = state.capacity;
      this.state = new State(state.capacity);
      this.state.copyFrom(this.keyframes[0]);
    }

    // Applies frame i's definitions and body records to `state` (which must be at i - 1).
    apply(state, i) {
      const f = this.frames[i];
      const dv = this.dv;
      for (const d of f.defs) {
        if (d.kind === 'body') {
          state.grow(d.index + 1);
          state.bodies.set(d.index, d);
          state.pose.set(d.position, d.index * 7);
          state.pose.set(d.rotation, d.index * 7 + 3);
          state.vel.fill(0, d.index * 6, d.index * 6 + 6);
          state.awake[d.index] = d.type === 'static' ? 0 : 1;
        } else if (d.kind === 'bodyRemoved') {
          state.bodies.delete(d.index);
        } else if (d.kind === 'soft') {
          state.softs.set(d.index, d);
        } else if (d.kind === 'softRemoved') {
          state.softs.delete(d.index);
        }
      }
      let at = f.bodyAt;
      let index = -1;
      for (let n = 0; n < f.bodyCount; n++) {
        let v = 0, shift = 0, b;
        do { b = dv.getUint8(at++); v += (b & 0x7f) * Math.pow(2, shift); shift += 7; } while (b & 0x80);
        index += Math.floor(v / 2);
        state.grow(index + 1);
        state.awake[index] = v & 1;
        const o = index * 7;
        state.pose[o] = dv.getFloat32(at, true);
        state.pose[o + 1] = dv.getFloat32(at + 4, true);
        state.pose[o + 2] = dv.getFloat32(at + 8, true);
        unpackQuat(dv, at + 12, state.pose, o + 3);
        const w = index * 6;
        for (let k = 0; k < 6; k++) state.vel[w + k] = f16(dv.getUint16(at + 18 + 2 * k, true));
        at += 30;
      }
      state.frame = i;
    }

    // The replay state at frame i (the recording's own State object, updated in place).
    seek(i) {
      i = Math.max(0, Math.min(this.frames.length - 1, i | 0));
      const s = this.state;
      const key = Math.floor(i / KEYFRAME);
      if (!(s.frame <= i && s.frame >= key * KEYFRAME)) s.copyFrom(this.keyframes[key]);
      for (let k = s.frame + 1; k <= i; k++) this.apply(s, k);
      return s;
    }

    particles(i) {
      const f = this.frames[i];
      const out = { count: f.particleCount, positions: new Float32Array(3 * f.particleCount), radii: new Float32Array(f.particleCount) };
      for (let k = 0; k < 3 * f.particleCount; k++) out.positions[k] = this.dv.getFloat32(f.particleAt + 4 * k, true);
      const r = f.particleAt + 12 * f.particleCount;
      for (let k = 0; k < f.particleCount; k++) out.radii[k] = f16(this.dv.getUint16(r + 2 * k, true));
      return out;
    }

    softBodies(i) {
      const f = this.frames[i];
      const out = [];
      let at = f.softAt;
      for (let k = 0; k < f.softCount; k++) {
        const index = this.dv.getUint32(at, true);
        const n = this.dv.getUint32(at + 4, true);
        const positions = new Float32Array(3 * n);
        for (let j = 0; j < 3 * n; j++) positions[j] = this.dv.getFloat32(at + 8 + 4 * j, true);
        out.push({ index, positions });
        at += 8 + 12 * n;
      }
      return out;
    }

    joints(i) {
      const f = this.frames[i];
      const dv = this.dv;
      const out = [];
      for (let k = 0; k < f.jointCount; k++) {
        const at = f.jointAt + 38 * k;
        out.push({
          index: dv.getUint32(at, true),
          kind: JOINT_KINDS[dv.getUint8(at + 4)] || 'other',
          broken: dv.getUint8(at + 5) !== 0,
          bodyA: dv.getUint32(at + 6, true),
          bodyB: dv.getUint32(at + 10, true),
          anchorA: readVec3(dv, at + 14),
          anchorB: readVec3(dv, at + 26),
        });
      }
      return out;
    }

    contacts(i) {
      const f = this.frames[i];
      const dv = this.dv;
      const out = [];
      let at = f.contactAt;
      for (let k = 0; k < f.contactCount; k++) {
        const m = { bodyA: dv.getUint32(at, true), bodyB: dv.getUint32(at + 4, true), normal: readVec3(dv, at + 8), points: [] };
        const n = dv.getUint8(at + 20);
        at += 21;
        for (let j = 0; j < n; j++) {
          m.points.push({ point: readVec3(dv, at), separation: dv.getFloat32(at + 12, true), impulse: dv.getFloat32(at + 16, true) });
          at += 20;
        }
        out.push(m);
      }
      return out;
    }
  }

  return { Recording, State, KEYFRAME, f16 };
})();
