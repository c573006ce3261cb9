// The arphysics testbed page: loads testbed.wasm (plain exported functions, no
// bindings generator), draws the draw list on a canvas, and forwards the mouse.
// Modes (query string): none: interactive; ?check=1: runs every scene a fixed
// number of frames without animation, compares each hash with the native one,
// tests the error paths, writes the results into the DOM (#check, and
// #check-status = PASS or FAIL) for scripts/testbed-check.sh; ?scene=NAME&frames=N:
// loads NAME, steps N frames and pauses (for screenshots).
'use strict';

const E = { NO_SCENE: -1, NOT_LOADED: -2, ENGINE: -3, OUTSIDE: -4, FULL: -5, NOT_DRAGGABLE: -6,
  NO_HISTORY: -7, MISMATCH: -8, BAD_INPUT: -9 };
const DEFAULT_SUBSTEPS = 4;
const params = new URLSearchParams(location.search);
const $ = (id) => document.getElementById(id);

let wasm = null;       // the instance's exports
let trapped = false;   // the module trapped: it is dead
let info = null;       // scene list (tb_info)
let native = null;     // native-hashes.json
const consoleErrors = [];

// Errors anywhere on the page are recorded (the check fails on any).
const origError = console.error.bind(console);
console.error = (...a) => { consoleErrors.push(a.join(' ')); origError(...a); };
window.addEventListener('error', (e) => consoleErrors.push(String(e.message)));
window.addEventListener('unhandledrejection', (e) => consoleErrors.push(String(e.reason)));

function showTrap(err) {
  trapped = true;
  const t = $('trap');
  t.style.display = 'block';
  t.textContent = 'The wasm module trapped (a panic or a bug inside it): ' + err +
    '. The simulation is stopped; reload the page.';
}

// Calls an export; a trap (WebAssembly.RuntimeError) is caught and reported.
function call(name, ...args) {
  if (trapped) throw new Error('module trapped');
  try {
    return wasm[name](...args);
  } catch (e) {
    if (e instanceof WebAssembly.RuntimeError) showTrap(e.message);
    throw e;
  }
}

const decoder = new TextDecoder();
function text(ptr, len) {
  return decoder.decode(new Uint8Array(wasm.memory.buffer, ptr, len));
}
function lastError() { return text(call('tb_error_ptr'), call('tb_error_len')); }
function hex(hi, lo) {
  return (hi >>> 0).toString(16).padStart(8, '0') + (lo >>> 0).toString(16).padStart(8, '0');
}
function stateHash() { return hex(call('tb_hash_hi'), call('tb_hash_lo')); }

async function instantiate() {
  const resp = await fetch('testbed.wasm');
  if (!resp.ok) throw new Error('testbed.wasm: HTTP ' + resp.status + ' (run scripts/testbed.sh)');
  const { instance } = await WebAssembly.instantiate(await resp.arrayBuffer(), {});
  return instance.exports;
}

// ---- State of the interactive page ----
let scene = 0;
let substeps = DEFAULT_SUBSTEPS;
let playing = true;
let rate = 60;
let acc = 0;
let lastT = null;
const stepTimes = [];
let view = [-20, -1, 20, 20];   // x0, y0, x1, y1 (m)
let nativeNote = null;          // the last comparison with native: {frame, ok}
let dragging = false;
let loadedSubsteps = DEFAULT_SUBSTEPS; // the count the scene was loaded with
const stepStamps = [];          // performance.now() of recent steps (the rate)

function message(s) { $('message').textContent = s || ''; }

function load(index) {
  const r = call('tb_load', index, substeps);
  if (r < 0) { message('cannot load: ' + lastError()); return false; }
  scene = index;
  loadedSubsteps = substeps;
  stepStamps.length = 0;
  const sc = info.scenes[index];
  view = sc.view.slice();
  nativeNote = null;
  stepTimes.length = 0;
  $('about').textContent = sc.about;
  $('scene').value = String(index);
  $('rb').textContent = '–';
  message('');
  updatePanel();
  return true;
}

function nativeHash(name, frame) {
  const s = native && native.scenes[name];
  return s ? s.hashes[String(frame)] : undefined;
}

function stepOnce() {
  const t0 = performance.now();
  const r = call('tb_step', 1);
  const ms = performance.now() - t0;
  if (r < 0) { message('step failed: ' + lastError()); playing = false; return; }
  stepTimes.push(ms);
  if (stepTimes.length > 30) stepTimes.shift();
  stepStamps.push(t0);
  while (stepStamps.length > 0 && t0 - stepStamps[0] > 1000) stepStamps.shift();
  // Compare with native at its checkpoints, for an untouched run at 4 sub-steps.
  const frame = call('tb_frame');
  const want = nativeHash(info.scenes[scene].name, frame);
  if (want !== undefined && loadedSubsteps === DEFAULT_SUBSTEPS && call('tb_interacted') === 0) {
    nativeNote = { frame, want, got: stateHash() };
  }
}

function updatePanel() {
  const frame = call('tb_frame');
  $('frame').textContent = frame;
  const avg = stepTimes.length ? stepTimes.reduce((a, b) => a + b, 0) / stepTimes.length : 0;
  $('ms').textContent = stepTimes.length ? avg.toFixed(2) + ' ms' : '–';
  $('bodies').textContent = call('tb_body_count');
  $('contacts').textContent = call('tb_contact_count');
  $('joints').textContent = call('tb_joint_count');
  $('substepsnow').textContent = call('tb_substeps');
  // Steps in the last second: the rate the page keeps up (the selected one
  // unless a step takes longer than a frame allows).
  $('steprate').textContent = playing ? stepStamps.length + ' steps/s (target ' + rate + ')' : 'paused';
  const sl = call('tb_sensor_events');
  if (sl >= 0) {
    const ev = JSON.parse(text(call('tb_text_ptr'), sl));
    $('sensors').textContent = ev.begin + ' begin, ' + ev.end + ' end';
    $('sensorlog').textContent = ev.log.slice().reverse().map(([f, b, s, v]) =>
      'frame ' + f + ': body #' + v + (b ? ' entered' : ' left') + ' sensor #' + s).join('\n');
  }
  $('hash').textContent = stateHash() + ' @ frame ' + frame;
  const noteLen = call('tb_scene_note');
  if (noteLen > 0 && !$('message').textContent) message(text(call('tb_text_ptr'), noteLen));
  const n = $('native');
  n.className = '';
  if (!native) {
    $('nativehash').textContent = '–';
    n.textContent = 'no native-hashes.json (run scripts/testbed.sh)';
  } else if (loadedSubsteps !== DEFAULT_SUBSTEPS) {
    $('nativehash').textContent = '–';
    n.textContent = 'n/a: native hashes are for 4 sub-steps';
  } else if (call('tb_interacted') !== 0) {
    $('nativehash').textContent = '–';
    n.textContent = 'n/a: you changed the world (spawn, drag or sub-steps)';
  } else if (nativeNote) {
    $('nativehash').textContent = nativeNote.want + ' @ frame ' + nativeNote.frame;
    const ok = nativeNote.want === nativeNote.got;
    n.className = ok ? 'ok' : 'bad';
    n.textContent = ok ? 'same bits as native ✓ (frame ' + nativeNote.frame + ')'
      : 'DIFFERS from native ✗ (frame ' + nativeNote.frame + ': ' + nativeNote.got + ')';
  } else {
    $('nativehash').textContent = '–';
    n.textContent = 'native hashes every 60 frames: wait…';
  }
}

// ---- Drawing ----
const canvas = $('view');
const ctx = canvas.getContext('2d');

function fit() {
  const [x0, y0, x1, y1] = view;
  const s = Math.min(canvas.width / (x1 - x0), canvas.height / (y1 - y0));
  const cx = (x0 + x1) / 2, cy = (y0 + y1) / 2;
  return { s, ox: canvas.width / 2 - cx * s, oy: canvas.height / 2 + cy * s };
}
function toWorld(px, py) {
  const f = fit();
  return [(px - f.ox) / f.s, (f.oy - py) / f.s];
}

const FILL = ['#f2b134', '#4f9dd9', '#9c6ade', '#7a7a7a'];
function draw() {
  const count = call('tb_draw');
  if (count < 0) return;
  const ptr = call('tb_draw_ptr');
  const stride = info.stride;
  const d = new Float32Array(wasm.memory.buffer, ptr, count * stride);
  const f = fit();
  ctx.setTransform(1, 0, 0, 1, 0, 0);
  ctx.clearRect(0, 0, canvas.width, canvas.height);
  ctx.setTransform(f.s, 0, 0, -f.s, f.ox, f.oy);
  ctx.lineWidth = 1 / f.s;
  ctx.lineJoin = 'round';
  ctx.lineCap = 'round';
  for (let i = 0; i < count; i++) {
    const o = i * stride;
    const kind = d[o], flags = d[o + 1], x = d[o + 2], y = d[o + 3], a = d[o + 4], r = d[o + 5], n = d[o + 6];
    const isStatic = flags & 1, held = flags & 4, sensor = flags & 8;
    const fill = sensor ? 'rgba(79, 157, 217, 0.25)' : isStatic ? '#9aa0a6' : (flags & 2) ? '#6cc4a1' : FILL[kind] || '#ccc';
    ctx.fillStyle = held ? '#e8505b' : fill;
    ctx.strokeStyle = '#333';
    if (kind === 0) {
      ctx.beginPath();
      ctx.arc(x, y, r, 0, 2 * Math.PI);
      ctx.fill(); ctx.stroke();
      ctx.beginPath(); ctx.moveTo(x, y); ctx.lineTo(x + r * Math.cos(a), y + r * Math.sin(a)); ctx.stroke();
    } else if (kind === 1 || kind === 2) {
      ctx.beginPath();
      ctx.moveTo(d[o + 8], d[o + 9]);
      for (let k = 1; k < n; k++) ctx.lineTo(d[o + 8 + 2 * k], d[o + 9 + 2 * k]);
      ctx.closePath();
      if (r > 0) {
        // A rounded polygon or a capsule: its core, widened by the radius.
        ctx.save();
        ctx.lineWidth = 2 * r + 2 / f.s; ctx.strokeStyle = '#333'; ctx.stroke();
        ctx.lineWidth = 2 * r; ctx.strokeStyle = ctx.fillStyle; ctx.stroke();
        ctx.restore();
        if (n > 2) ctx.fill();
      } else {
        ctx.fill(); ctx.stroke();
      }
    } else if (kind === 3) {
      ctx.save(); ctx.lineWidth = 3 / f.s; ctx.strokeStyle = '#555';
      ctx.beginPath(); ctx.moveTo(d[o + 8], d[o + 9]); ctx.lineTo(d[o + 10], d[o + 11]); ctx.stroke();
      ctx.restore();
    } else if (kind === 5) {
      ctx.save(); ctx.lineWidth = 1.5 / f.s; ctx.strokeStyle = '#2e7d32';
      ctx.beginPath(); ctx.moveTo(d[o + 8], d[o + 9]); ctx.lineTo(d[o + 10], d[o + 11]); ctx.stroke();
      ctx.fillStyle = '#2e7d32'; ctx.fillRect(d[o + 8] - 2 / f.s, d[o + 9] - 2 / f.s, 4 / f.s, 4 / f.s);
      ctx.restore();
    } else if (kind === 4) {
      ctx.save(); ctx.lineWidth = 2 / f.s; ctx.strokeStyle = '#e8505b'; ctx.setLineDash([6 / f.s, 4 / f.s]);
      ctx.beginPath(); ctx.moveTo(d[o + 8], d[o + 9]); ctx.lineTo(d[o + 10], d[o + 11]); ctx.stroke();
      ctx.restore();
    }
  }
}

// ---- Interactive loop ----
function frameLoop(t) {
  if (trapped) return;
  try {
    if (playing && lastT !== null) {
      acc += Math.min(0.1, (t - lastT) / 1000) * rate;
      let n = 0;
      while (acc >= 1 && n < 4 && playing) { stepOnce(); acc -= 1; n++; }
      if (n === 4) acc = 0;
    }
    lastT = t;
    draw();
    updatePanel();
  } catch (e) {
    if (!trapped) { console.error(e); playing = false; }
    return;
  }
  requestAnimationFrame(frameLoop);
}

function setupUi() {
  const sel = $('scene');
  info.scenes.forEach((s, i) => {
    const o = document.createElement('option');
    o.value = String(i); o.textContent = s.name;
    sel.appendChild(o);
  });
  sel.addEventListener('change', () => load(Number(sel.value)));
  $('play').addEventListener('click', () => { playing = !playing; $('play').textContent = playing ? 'pause' : 'play'; });
  $('step').addEventListener('click', () => { playing = false; $('play').textContent = 'play'; stepOnce(); });
  $('reset').addEventListener('click', () => load(scene));
  $('substeps').addEventListener('change', () => {
    const v = Number($('substeps').value);
    if (!(v >= 1 && v <= info.max_substeps)) { message('sub-steps must be 1 to ' + info.max_substeps); return; }
    substeps = v;
    // The running world changes from the next frame (recorded: rollback replays it).
    if (call('tb_set_substeps', v) < 0) message('sub-steps: ' + lastError());
  });
  $('rate').addEventListener('change', () => { rate = Number($('rate').value); });
  $('rollback').addEventListener('click', () => {
    const r = call('tb_rollback');
    if (r < 0) { $('rb').textContent = '✗ ' + lastError(); return; }
    const before = hex(call('tb_rollback_hash', 1), call('tb_rollback_hash', 0));
    const after = hex(call('tb_rollback_hash', 3), call('tb_rollback_hash', 2));
    $('rb').textContent = 'rewound ' + r + ' frames, re-simulated: ' + (before === after ? '✓ same hash' : '✗ ' + after);
  });
  const pos = (e) => { const b = canvas.getBoundingClientRect(); return toWorld((e.clientX - b.left) * canvas.width / b.width, (e.clientY - b.top) * canvas.height / b.height); };
  canvas.addEventListener('pointerdown', (e) => {
    const [x, y] = pos(e);
    const r = call('tb_drag_begin', x, y);
    if (r === 0) { dragging = true; canvas.setPointerCapture(e.pointerId); message(''); return; }
    const why = lastError();
    if (r === E.NOT_DRAGGABLE && why.startsWith('no body')) {
      // Empty space: a click spawns.
      const s = call('tb_spawn', Number($('spawnkind').value), x, y);
      message(s < 0 ? 'cannot spawn: ' + lastError() : '');
    } else {
      // A static body (or no room for the drag joint): said on the page, nothing else.
      message(r === E.NOT_DRAGGABLE ? 'not draggable: ' + why : why);
    }
  });
  canvas.addEventListener('pointermove', (e) => { if (dragging) { const [x, y] = pos(e); call('tb_drag_move', x, y); } });
  const end = () => { if (dragging) { dragging = false; call('tb_drag_end'); } };
  canvas.addEventListener('pointerup', end);
  canvas.addEventListener('pointercancel', end);
  canvas.addEventListener('wheel', (e) => {
    e.preventDefault();
    const [x, y] = pos(e);
    const k = e.deltaY > 0 ? 1.15 : 1 / 1.15;
    view = [x + (view[0] - x) * k, y + (view[1] - y) * k, x + (view[2] - x) * k, y + (view[3] - y) * k];
  }, { passive: false });
}

// ---- Check mode ----
function hashAfter(index, frames, actions) {
  if (call('tb_load', index, DEFAULT_SUBSTEPS) < 0) throw new Error('load: ' + lastError());
  actions && actions();
  if (frames > 0 && call('tb_step', frames) < 0) throw new Error('step: ' + lastError());
  return stateHash();
}

async function runCheck() {
  const out = [];
  let failed = 0;
  const line = (ok, s) => { out.push((ok ? 'ok   ' : 'FAIL ') + s); if (!ok) failed++; $('check').textContent = out.join('\n'); };
  const pause = () => new Promise((r) => setTimeout(r, 0));
  if (!native) line(false, 'native-hashes.json missing');
  // Every scene: its hash after check_frames frames against native, then a rollback.
  for (let i = 0; i < info.scenes.length; i++) {
    const sc = info.scenes[i];
    await pause();
    try {
      if (call('tb_load', i, DEFAULT_SUBSTEPS) < 0) throw new Error('load: ' + lastError());
      // (No timing here: under headless Chromium's virtual time the clock stands still.)
      let done = 0;
      while (done < sc.check_frames) {
        const r = call('tb_step', Math.min(60, sc.check_frames - done));
        if (r < 0) throw new Error('step: ' + lastError());
        done += r;
      }
      const got = stateHash();
      const want = nativeHash(sc.name, sc.check_frames);
      line(got === want, `scene ${sc.name}: frame ${sc.check_frames} hash ${got} native ${want} ` +
        `(${call('tb_body_count')} bodies, ${call('tb_contact_count')} contacts)`);
      const rb = call('tb_rollback');
      line(rb > 0, `scene ${sc.name}: rollback of ${rb} frames ` +
        (rb > 0 ? 're-simulated to the same hash' : lastError()));
      if (i === 0) { scene = 0; view = sc.view.slice(); draw(); }
    } catch (e) {
      if (trapped) { line(false, `scene ${sc.name}: TRAP ${e.message}`); break; }
      line(false, `scene ${sc.name}: ${e.message}`);
    }
  }
  await pause();
  if (!trapped) {
    try {
      // Bad input: the page says so and the module keeps running.
      let r = call('tb_load', 9999, DEFAULT_SUBSTEPS);
      line(r === E.NO_SCENE, `no such scene -> ${r} (${lastError()})`);
      r = call('tb_load', 0, 0);
      line(r === E.BAD_INPUT, `0 sub-steps -> ${r} (${lastError()})`);
      const ground = info.scenes.findIndex((s) => s.name === 'pyramid_20');
      call('tb_load', ground, DEFAULT_SUBSTEPS);
      r = call('tb_spawn', 0, 5000, 0);
      line(r === E.OUTSIDE, `spawn outside the bounds -> ${r} (${lastError()})`);
      r = call('tb_spawn', 0, NaN, 1);
      line(r === E.BAD_INPUT, `spawn at NaN -> ${r} (${lastError()})`);
      r = call('tb_drag_begin', 0, -1);
      line(r === E.NOT_DRAGGABLE && lastError().includes('static'), `drag on the static ground -> ${r} (${lastError()})`);
      r = call('tb_drag_begin', 0, 300);
      line(r === E.NOT_DRAGGABLE, `drag on nothing -> ${r} (${lastError()})`);
      let spawned = 0;
      for (; spawned < 1000; spawned++) { r = call('tb_spawn', 1, -60 + spawned * 0.9 % 120, 30 + Math.floor(spawned / 130) * 2); if (r < 0) break; }
      line(r === E.FULL, `fill the world: ${spawned} spawned, then -> ${r} (${lastError()})`);
      r = call('tb_step', 5);
      line(r === 5, `a full world still steps -> ${r}`);
      // The same input replayed gives the same hash; rollback through input too.
      const play = () => {
        call('tb_step', 20);
        call('tb_spawn', 0, -3, 12); call('tb_spawn', 1, 3, 14);
        if (call('tb_drag_begin', 0, 19.5) !== 0) throw new Error('drag_begin on the pyramid top: ' + lastError());
        for (let k = 0; k < 40; k++) { call('tb_drag_move', -4 + k * 0.2, 22 + k * 0.05); call('tb_step', 1); }
        call('tb_drag_end');
        call('tb_spawn', 0, 6, 10);
      };
      const h1 = hashAfter(ground, 10, play);
      const h2 = hashAfter(ground, 10, play);
      line(h1 === h2, `same input, same hash: ${h1} ${h2}`);
      r = call('tb_rollback');
      line(r > 0, `rollback through spawns and a drag: ${r > 0 ? r + ' frames, same hash' : lastError()}`);
      // The scripted drag (a drag, a throw, sub-step changes, a spawn) played
      // through the page's controls: the same hash as the native build.
      const sc = info.script;
      const si = info.scenes.findIndex((x) => x.name === sc.scene);
      if (call('tb_load', si, DEFAULT_SUBSTEPS) < 0) throw new Error('script load: ' + lastError());
      for (const a of sc.actions) {
        let rr = 0;
        switch (a[0]) {
          case 'step': rr = call('tb_step', a[1]); break;
          case 'begin': rr = call('tb_drag_begin', a[1], a[2]); break;
          case 'move': rr = call('tb_drag_move', a[1], a[2]); break;
          case 'end': rr = call('tb_drag_end'); break;
          case 'spawn': rr = call('tb_spawn', a[1], a[2], a[3]); break;
          case 'substeps': rr = call('tb_set_substeps', a[1]); break;
          default: throw new Error('script: unknown action ' + a[0]);
        }
        if (rr < 0) throw new Error('script: ' + a[0] + ': ' + lastError());
      }
      const sh = stateHash();
      const want = native && native.script && native.script.hash;
      line(sh === want && call('tb_frame') === native.script.frames,
        `scripted drag on ${sc.scene} (${sc.actions.length} actions, ${call('tb_frame')} frames, a throw, ` +
        `sub-steps 4→8→4): hash ${sh} native ${want}`);
      r = call('tb_rollback');
      line(r > 0, `rollback through the scripted drag: ${r > 0 ? r + ' frames, same hash' : lastError()}`);
      // The sensors scene reports its events on the page.
      const sens = info.scenes.findIndex((x) => x.name === 'sensors');
      call('tb_load', sens, DEFAULT_SUBSTEPS);
      call('tb_step', 240);
      const evLen = call('tb_sensor_events'); // (writes the text buffer: read its pointer after)
      const ev = JSON.parse(text(call('tb_text_ptr'), evLen));
      line(ev.begin > 0 && ev.end > 0 && ev.log.length > 0,
        `sensors: ${ev.begin} begin and ${ev.end} end events in 240 frames`);
      const live = stateHash();
      // A trap is caught and reported: a second instance is made to trap.
      const saved = wasm;
      wasm = await instantiate();
      let caught = false;
      try { call('tb_debug_trap'); } catch (e) { caught = e instanceof WebAssembly.RuntimeError; }
      line(caught && trapped && $('trap').style.display === 'block', 'a trap is detected and shown');
      // Back to the live instance for the rest.
      wasm = saved; trapped = false; $('trap').style.display = 'none';
      line(stateHash() === live, 'the first instance still runs after the other trapped');
    } catch (e) {
      line(false, 'error paths: ' + e.message);
    }
  }
  line(consoleErrors.length === 0, `console errors: ${consoleErrors.length}` + (consoleErrors.length ? ': ' + consoleErrors.join(' | ') : ''));
  // Draw the first scene for the screenshot.
  try { call('tb_load', 0, DEFAULT_SUBSTEPS); call('tb_step', 240); view = info.scenes[0].view.slice(); draw(); updatePanel(); } catch (e) { /* reported above */ }
  const status = document.createElement('div');
  status.id = 'check-status';
  status.textContent = failed === 0 ? 'PASS' : 'FAIL ' + failed;
  document.body.appendChild(status);
}

async function main() {
  try {
    wasm = await instantiate();
  } catch (e) {
    message('cannot load the wasm module: ' + e.message);
    console.error('testbed.wasm: ' + e.message);
    return;
  }
  try {
    const r = await fetch('native-hashes.json');
    if (r.ok) native = await r.json();
  } catch (e) { /* shown in the panel */ }
  const len = call('tb_info');
  info = JSON.parse(text(call('tb_text_ptr'), len));
  setupUi();
  if (params.has('check')) {
    playing = false;
    await runCheck();
    return;
  }
  const want = params.get('scene');
  let index = 0;
  if (want !== null) {
    index = info.scenes.findIndex((s) => s.name === want);
    if (index < 0) { message('no scene named "' + want + '": showing ' + info.scenes[0].name); index = 0; }
  }
  load(index);
  const frames = Number(params.get('frames') || 0);
  if (frames > 0) {
    playing = false; $('play').textContent = 'play';
    for (let k = 0; k < frames; k++) stepOnce();
  }
  requestAnimationFrame(frameLoop);
}

main();
