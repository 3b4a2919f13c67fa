// The motiongraph studio: a three.js view of the character and panels for clips, the distance
// matrix and its transitions, per-tag statistics, path drawing and interactive steering, all
// talking to `motiongraph serve`'s JSON API (src/studio/studio_api.h). window.studio exposes
// the state for the browser test (tests/js/studio_browser.mjs).
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { Figure, PLANTED_COLOUR } from './figure.js';

const $ = (id) => document.getElementById(id);

async function request(method, path, body) {
  const response = await fetch(path, {
    method,
    headers: body ? { 'Content-Type': 'application/json' } : {},
    body: body ? JSON.stringify(body) : undefined,
  });
  const data = await response.json();
  if (!response.ok) throw new Error(data.error || `${method} ${path}: HTTP ${response.status}`);
  return data;
}
const get = (path) => request('GET', path);
const post = (path, body) => request('POST', path, body);

// --- the scene ---------------------------------------------------------------------------
const canvas = $('canvas');
const renderer = new THREE.WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
renderer.shadowMap.enabled = true;
renderer.shadowMap.type = THREE.PCFSoftShadowMap;
const scene = new THREE.Scene();
const BACKGROUND = 0xdfe6ee;
scene.background = new THREE.Color(BACKGROUND);
const camera = new THREE.PerspectiveCamera(45, 1, 0.05, 400);
camera.position.set(2.5, 2.2, 5.5);
const controls = new OrbitControls(camera, canvas);
controls.target.set(0, 0.9, 0);
controls.update();
scene.add(new THREE.HemisphereLight(0xffffff, 0x8090a0, 1.4));
const sun = new THREE.DirectionalLight(0xffffff, 2.2);
sun.position.set(3, 8, 4);
sun.castShadow = true;
sun.shadow.mapSize.set(1024, 1024);
Object.assign(sun.shadow.camera, { left: -4, right: 4, top: 4, bottom: -4, near: 0.5, far: 30 });
scene.add(sun, sun.target);
const ground = new THREE.Mesh(new THREE.PlaneGeometry(400, 400),
  new THREE.MeshStandardMaterial({ color: 0xc9ced3, roughness: 0.95 }));
ground.rotation.x = -Math.PI / 2;
ground.receiveShadow = true;
scene.add(ground);
const grid = new THREE.GridHelper(400, 400, 0x6d7680, 0x8d969f);
grid.position.y = 0.002;
scene.add(grid);
const overlays = new THREE.Group();  // path and trails
scene.add(overlays);

const TAG_COLOURS = [0x2b7bd8, 0xd83b2b, 0x2ba84a, 0x9b4fd0, 0xd8a52b, 0x2bb8c8, 0x777777];
const tagColour = (tag) => (tag && state.tags.includes(tag)
  ? TAG_COLOURS[state.tags.indexOf(tag) % TAG_COLOURS.length] : 0x333333);

// --- state -------------------------------------------------------------------------------
const state = {
  ready: false, error: null, summary: null, tags: [], joints: [], clips: [], transitions: [],
  mode: 'idle',                  // clip, result, steer, poses
  track: null,                   // {fps, frames: [flat positions], loop, contacts}
  markFeet: true,                // draw planted foot joints (the API's "contacts")
  time: 0, playing: false, speed: 1,
  frameIndex: 0, framesShown: 0, root: [0, 0, 0],
  selectedTransition: -1, poses: null,
  path: { points: [], tags: [] }, pathResult: null, drawing: false,
  ticket: 0,                     // bumped by each thing the user turns to: a result asked before it is dropped
  synthesizing: 0,               // the ticket of the path synthesis under way (0: none)
  steer: null,                   // {session, buffer, inFlight, heading, tag, received, lastStepMs}
  result: null,
};
let figure = null;
let second = null;               // the arrival pose beside a transition's departure

function ensureFigure(joints) {
  if (figure && figure.joints.length === joints.length) return;
  if (figure) scene.remove(figure.group);
  if (second) scene.remove(second.group);
  figure = new Figure(joints);
  second = new Figure(joints, 0x3c8fd8);
  second.group.visible = false;
  scene.add(figure.group, second.group);
}

function setResultLink(id) {
  state.result = id;
  const params = new URLSearchParams();
  if ($('root-motion').checked) params.set('root_motion', '1');
  if ($('no-figure').checked) params.set('figure', '0');
  const query = params.toString() ? `?${params}` : '';
  for (const [link, ext] of [['download', 'bvh'], ['download-glb', 'glb'], ['download-gltf', 'gltf'],
    ['download-fbx', 'fbx']]) {
    const a = $(link);
    a.href = `/api/results/${id}.${ext}${query}`;
    a.download = `motiongraph-${id}.${ext}`;
    a.hidden = false;
  }
  $('root-motion-label').hidden = false;
  $('no-figure-label').hidden = false;
}

// The user turned to something else: a path or walk still being made is not played when it comes.
function turnedTo() {
  state.ticket += 1;
  $('synthesize').disabled = false;  // a synthesis under way is now dropped when it comes: another may start
  return state.ticket;
}
// The transition picked on the matrix, and its info, once the view shows something else.
function dropTransition() {
  if (state.selectedTransition < 0) return;
  state.selectedTransition = -1;
  $('transition-info').textContent = '';
  drawTransitions();
}

function play(track, mode) {
  stopSteering();
  if (mode !== 'poses') dropTransition();
  // The clip's doubts say what is wrong with a clip as read, not with a result.
  if (mode !== 'clip') $('clip-doubts').textContent = '';
  state.track = track;
  state.mode = mode;
  state.time = 0;
  state.playing = true;
  second.group.visible = false;
  figure.offset.set(0, 0, 0);
  $('scrub').max = String(track.frames.length - 1);
  $('play').textContent = 'Pause';
}

// --- clips -------------------------------------------------------------------------------
// `ticket`: turnedTo()'s when the clip was asked for; a clip whose frames come after the user has
// turned to something else is not played.
async function loadClip(index, ticket = state.ticket) {
  const clip = state.clips[index];
  // What looks wrong with the clip as read (its size, floor, feet or clock), as info says it.
  $('clip-doubts').textContent = clip.doubts.length ? `Looks wrong as read: ${clip.doubts.join('; ')}.` : '';
  const frames = [];
  let joints = null;
  let contacts = null;
  for (let from = 0; from < clip.frames; from += 600) {
    const part = await get(`/api/clips/${index}/frames?from=${from}&count=${Math.min(600, clip.frames - from)}`);
    joints = part.joints;
    frames.push(...part.positions);
    if (part.contacts) {
      if (!contacts) contacts = { ...part.contacts, planted: [] };
      contacts.planted.push(...part.contacts.planted);
    }
  }
  if (ticket !== state.ticket) return;
  ensureFigure(joints);
  setDrawing(false);
  play({ fps: state.summary.fps, frames, loop: true, label: `clip ${clip.name}`, contacts }, 'clip');
  chaseCamera([2.5, 1.3, 5]);
  state.clipIndex = index;
}

$('clip-select').addEventListener('change', (e) => {
  const ticket = turnedTo();
  loadClip(Number(e.target.value), ticket).catch((err) => {
    if (ticket === state.ticket) $('clip-doubts').textContent = `error: ${err.message}`;
  });
});
$('play').addEventListener('click', () => {
  if (state.mode === 'steer') return;  // (disabled while steering: the session plays as it is steered)
  // At the end of a motion that does not loop, Play plays it again from its first frame.
  if (!state.playing && state.track && !state.track.loop && state.time >= state.track.frames.length - 1) {
    state.time = 0;
  }
  state.playing = !state.playing;
  $('play').textContent = state.playing ? 'Pause' : 'Play';
});
$('speed').addEventListener('change', (e) => { state.speed = Number(e.target.value); });
$('scrub').addEventListener('input', (e) => {
  state.time = Number(e.target.value);
  state.playing = false;
  $('play').textContent = 'Play';
});

// --- the distance matrix and transitions ---------------------------------------------------
const overlay = $('matrix-overlay');
const MATRIX_PX = 300;
// Where the transition's D lies on the matrix: the pair of frames it was measured on (a
// bridge's blend leaves earlier and lands later than that).
function transitionPoint(t) {
  const span = state.summary.matrix.side * state.summary.matrix.block;
  return [(t.window_to_frame + 0.5) / span * MATRIX_PX, (t.window_from_frame + 0.5) / span * MATRIX_PX];
}
function drawTransitions() {
  overlay.width = MATRIX_PX;
  overlay.height = MATRIX_PX;
  const g = overlay.getContext('2d');
  g.clearRect(0, 0, MATRIX_PX, MATRIX_PX);
  state.transitions.forEach((t, i) => {
    const [x, y] = transitionPoint(t);
    g.beginPath();
    g.arc(x, y, i === state.selectedTransition ? 5 : 2.5, 0, 2 * Math.PI);
    g.fillStyle = i === state.selectedTransition ? '#ffffff' : '#ff2a2a';
    g.fill();
    if (i === state.selectedTransition) { g.strokeStyle = '#000'; g.stroke(); }
  });
}
overlay.addEventListener('click', (e) => {
  const r = overlay.getBoundingClientRect();
  const x = (e.clientX - r.left) * MATRIX_PX / r.width;
  const y = (e.clientY - r.top) * MATRIX_PX / r.height;
  let best = -1;
  let bestD = 64;
  state.transitions.forEach((t, i) => {
    const [tx, ty] = transitionPoint(t);
    const d = (tx - x) ** 2 + (ty - y) ** 2;
    if (d < bestD) { bestD = d; best = i; }
  });
  if (best >= 0) {
    const ticket = turnedTo();
    selectTransition(best, ticket).catch((err) => {
      if (ticket === state.ticket) $('transition-info').textContent = `error: ${err.message}`;
    });
  }
});
// A database frame as a frame of the clip named (the clip selector's and scrubber's numbering, from 1).
function clipFrame(name, frame) {
  const clip = state.clips.find((c) => c.name === name);
  return clip ? frame - clip.first_frame + 1 : frame;
}

async function selectTransition(index, ticket = state.ticket) {
  const poses = await get(`/api/transitions/${index}/poses`);
  if (ticket !== state.ticket) return;  // the user turned to something else meanwhile
  stopSteering();
  ensureFigure(poses.joints);
  state.selectedTransition = index;
  state.poses = poses;
  state.mode = 'poses';
  state.track = { fps: poses.fps, frames: poses.from.positions, loop: true, label: `transition ${index}`,
    contacts: poses.from.contacts };
  state.time = 0;
  state.playing = true;
  $('play').textContent = 'Pause';
  figure.offset.set(-0.6, 0, 0);
  second.offset.set(0.6, 0, 0);
  setDrawing(false);
  chaseCamera([0, 0.6, 4]);
  second.group.visible = true;
  const t = state.transitions[index];
  const moved = t.window_from_frame !== t.from_frame || t.window_to_frame !== t.to_frame;
  $('transition-info').textContent = `transition ${index}: `
    + `${t.from_clip} frame ${clipFrame(t.from_clip, t.window_from_frame)} (orange) -> `
    + `${t.to_clip} frame ${clipFrame(t.to_clip, t.window_to_frame)} (blue), D = ${t.distance.toFixed(3)}, `
    + `blended over ${t.blend_frames} frames`
    + (moved ? ` (from frame ${clipFrame(t.from_clip, t.from_frame)} to frame ${clipFrame(t.to_clip, t.to_frame)}, `
      + 'centred on these)' : '')
    + (t.bridge ? ', a bridge' : '');
  drawTransitions();
}

// --- path drawing and synthesis ------------------------------------------------------------
const raycaster = new THREE.Raycaster();
const floorPlane = new THREE.Plane(new THREE.Vector3(0, 1, 0), 0);
function groundPoint(e) {
  const r = canvas.getBoundingClientRect();
  const ndc = new THREE.Vector2(((e.clientX - r.left) / r.width) * 2 - 1, -((e.clientY - r.top) / r.height) * 2 + 1);
  raycaster.setFromCamera(ndc, camera);
  const hit = new THREE.Vector3();
  return raycaster.ray.intersectPlane(floorPlane, hit) ? hit : null;
}
function pathSegments() {
  const { points, tags } = state.path;
  const arc = [0];
  for (let i = 1; i < points.length; ++i) {
    arc.push(arc[i - 1] + Math.hypot(points[i][0] - points[i - 1][0], points[i][1] - points[i - 1][1]));
  }
  const segments = [];
  for (let i = 1; i < points.length; ++i) {
    const tag = tags[i];
    if (!tag) continue;
    const last = segments[segments.length - 1];
    if (last && last.tag === tag && last.to_m === arc[i - 1]) last.to_m = arc[i];
    else segments.push({ from_m: arc[i - 1], to_m: arc[i], tag });
  }
  return segments;
}
// A flat ribbon along floor points [[x, z], ...] (WebGL lines are one pixel wide).
const ribbonGeometry = new THREE.BoxGeometry(1, 1, 1);
const ribbonMaterials = new Map();
function ribbonPiece([ax, az], [bx, bz], colour, y, width) {
  if (!ribbonMaterials.has(colour)) ribbonMaterials.set(colour, new THREE.MeshBasicMaterial({ color: colour }));
  const piece = new THREE.Mesh(ribbonGeometry, ribbonMaterials.get(colour));
  piece.position.set((ax + bx) / 2, y, (az + bz) / 2);
  piece.rotation.y = -Math.atan2(bz - az, bx - ax);
  piece.scale.set(Math.hypot(bx - ax, bz - az) + width, 0.004, width);
  return piece;
}
function line(points, colour, y = 0.01, width = 0.06) {
  const group = new THREE.Group();
  for (let i = 1; i < points.length; ++i) group.add(ribbonPiece(points[i - 1], points[i], colour, y, width));
  return group;
}
function drawPath() {
  overlays.clear();
  const { points, tags } = state.path;
  for (let i = 1; i < points.length; ++i) overlays.add(line([points[i - 1], points[i]], tagColour(tags[i]), 0.012));
  if (state.pathResult) overlays.add(line(state.pathResult.roots, 0x111111, 0.02, 0.03));
}
let stroking = false;
canvas.addEventListener('pointerdown', (e) => {
  if (!state.drawing) return;
  const p = groundPoint(e);
  if (!p) return;
  stroking = true;
  canvas.setPointerCapture(e.pointerId);
  const tag = $('path-tag').value;
  if (state.path.points.length === 0) { state.path.points.push([p.x, p.z]); state.path.tags.push(tag); }
  else addPathPoint(p, tag, 0.05);
});
const MAX_PATH_M = 200;  // the API's longest path (studio_api.h)
function pathLength() {
  const { points } = state.path;
  let length = 0;
  for (let i = 1; i < points.length; ++i) {
    length += Math.hypot(points[i][0] - points[i - 1][0], points[i][1] - points[i - 1][1]);
  }
  return length;
}
function addPathPoint(p, tag, spacing) {
  const last = state.path.points[state.path.points.length - 1];
  if (Math.hypot(p.x - last[0], p.z - last[1]) < spacing) return;
  state.path.points.push([p.x, p.z]);
  state.path.tags.push(tag);
  drawPath();
  const length = pathLength();
  $('path-info').textContent = `drawn: ${length.toFixed(1)} m`
    + (length > MAX_PATH_M ? ` (over the ${MAX_PATH_M} m a path may be: Clear and draw a shorter one)` : '');
}
canvas.addEventListener('pointermove', (e) => {
  if (!state.drawing || !stroking) return;
  // Dragged off the view (onto the panel), the stroke adds no points out of sight.
  const r = canvas.getBoundingClientRect();
  if (e.clientX < r.left || e.clientX > r.right || e.clientY < r.top || e.clientY > r.bottom) return;
  const p = groundPoint(e);
  if (p) addPathPoint(p, $('path-tag').value, 0.25);
});
canvas.addEventListener('pointerup', () => { stroking = false; });
function setDrawing(on) {
  state.drawing = on;
  controls.enabled = !on;
  $('draw').classList.toggle('active', on);
  $('draw').textContent = on ? 'Drawing (click to stop)' : 'Draw a path';
  if (on) {  // look straight down on the origin so the whole view is ground
    turnedTo();
    stopSteering();
    dropTransition();
    state.playing = false;
    camera.position.set(0, 24, 0.01);
    controls.target.set(0, 0, 0);
    controls.update();
  }
}
$('draw').addEventListener('click', () => setDrawing(!state.drawing));
$('clear-path').addEventListener('click', () => {
  turnedTo();
  state.path = { points: [], tags: [] };
  state.pathResult = null;
  drawPath();
  $('path-info').textContent = '';
  $('path-warnings').textContent = '';
});
$('synthesize').addEventListener('click', async () => {
  // One at a time (the button is disabled meanwhile), unless the user moved on from it.
  if (state.synthesizing && state.synthesizing === state.ticket) return;
  if (state.path.points.length < 2) { $('path-info').textContent = 'draw a path first'; return; }
  setDrawing(false);
  const ticket = turnedTo();
  state.synthesizing = ticket;
  $('synthesize').disabled = true;
  $('path-info').textContent = 'synthesizing...';
  $('path-warnings').textContent = '';
  try {
    const result = await post('/api/path',
      { points: state.path.points, segments: pathSegments(), cleanup: $('cleanup').checked,
        edit_path: $('edit-path').checked, rest_at_end: $('rest-at-end').checked });
    if (ticket !== state.ticket) {  // the user went on to something else meanwhile: not played
      if ($('path-info').textContent === 'synthesizing...') {
        $('path-info').textContent = state.path.points.length ? 'the synthesis came after you moved on: not shown' : '';
      }
      return;
    }
    result.roots = result.positions.map((f) => [f[0], f[2]]);
    state.pathResult = result;
    drawPath();
    ensureFigure(state.joints);
    play({ fps: result.fps, frames: result.positions, loop: false, label: 'path', contacts: result.contacts },
      'result');
    chaseCamera([0, 6, 7]);  // high, so the path shows beside the figure
    setResultLink(result.result);
    $('path-info').textContent = `${result.path_length_m.toFixed(1)} m, ${result.frames} frames `
      + `(${(result.frames / result.fps).toFixed(1)} s): deviation mean ${result.mean_deviation_m.toFixed(2)} m, `
      + `max ${result.max_deviation_m.toFixed(2)} m${result.reached_end ? ''
        : ` (end not reached: ${result.arc_covered_m.toFixed(1)} m along it, ${result.end_distance_m.toFixed(1)} m from its end)`}`
      + (result.path_edit.edited ? ` (bent onto the path; as the graph played it `
        + `${result.graph_mean_deviation_m.toFixed(2)} m, max ${result.graph_max_deviation_m.toFixed(2)} m)`
        : result.path_edit.undone ? ' (as the graph played it: bent onto the path, it went further off)' : '')
      + `, tags matched ${(100 * result.tag_match).toFixed(0)} %${segmentMatches(result)}; ${result.transitions} transitions `
      + `(${result.transitions_per_second.toFixed(2)}/s${result.bridges ? `, ${result.bridges} bridge${result.bridges === 1 ? '' : 's'}` : ''}); `
      + footSlideText(result)
      + (result.rest ? `; at rest from ${result.rest.at_s.toFixed(1)} s at the end of ${result.rest.clip}, `
        + `${result.end_distance_m.toFixed(2)} m from the path's end` : '');
    // What the CLI's path warns of: a segment's type the graph can hardly play, what the motion
    // falls short of (the end not reached, dawdling, further off the path than the retries look
    // for, a motion type missed).
    $('path-warnings').textContent = result.warnings.map((s) => `\u26a0 ${s}.`).join(' ');
  } catch (err) {
    if (ticket === state.ticket) $('path-info').textContent = `error: ${err.message}`;
    else if ($('path-info').textContent === 'synthesizing...') $('path-info').textContent = '';
  } finally {
    if (state.synthesizing === ticket) {
      state.synthesizing = 0;
      $('synthesize').disabled = false;
    }
  }
});

// Each segment's type and how much of the motion in it carries it, when there are two or more
// (one is the total), and any type the graph plays in no frame: " (walk 100 %, run 0 %: not in
// the graph)".
function segmentMatches(result) {
  const segments = result.segments || [];
  const parts = segments.map((s) => `${s.tag} ${s.tag_match === null ? 'no frames'
    : `${(100 * s.tag_match).toFixed(0)} %`}${s.graph_frames === 0 ? ': not in the graph' : ''}`);
  return parts.length > 1 || segments.some((s) => s.graph_frames === 0) ? ` (${parts.join(', ')})` : '';
}

// How much a result's planted feet slide, beside the clips it was cut from.
function footSlideText(result) {
  const fs = result.foot_slide;
  if (!fs || fs.error) return `foot slide not measured${fs ? `: ${fs.error}` : ''}`;
  const times = [];
  if (fs.ratio.mean_mps !== null) times.push(`${fs.ratio.mean_mps.toFixed(2)}x the capture`);
  const same = fs.same_frames;
  if (same && !same.error && same.ratio !== null) times.push(`${same.ratio.toFixed(2)}x on the frames played`);
  return `feet slide ${fs.mean_mps.toFixed(3)} m/s${times.length ? ` (${times.join('; ')})` : ''}, ${result.cleanup ? 'cleaned up' : 'as played'}`;
}

// --- steering ------------------------------------------------------------------------------
const keys = new Set();
const STEER_KEYS = ['KeyW', 'KeyA', 'KeyS', 'KeyD', 'ArrowUp', 'ArrowDown', 'ArrowLeft', 'ArrowRight', 'KeyJ', 'KeyX'];
const MOVE_KEYS = STEER_KEYS.filter((k) => k !== 'KeyX');
// Fields that take typed keys keep them (a select, the scrubber's arrows); a checkbox or button
// clicked while steering does not take the steering keys away.
const TYPED_INPUTS = new Set(['text', 'number', 'range', 'search', 'email', 'url', 'password']);
window.addEventListener('keydown', (e) => {
  if (e.target instanceof HTMLSelectElement || e.target instanceof HTMLTextAreaElement
    || (e.target instanceof HTMLInputElement && TYPED_INPUTS.has(e.target.type))) return;
  keys.add(e.code);
  if (state.steer && /^Digit[0-9]$/.test(e.code)) {
    const d = Number(e.code.slice(5));
    state.steer.chosenTag = d === 0 ? '' : (state.tags[d - 1] || state.steer.chosenTag);
  }
  // X: come to rest; moving again takes it back (once it stands, it starts off, unless for good).
  if (state.steer && e.code === 'KeyX') state.steer.rest = true;
  else if (state.steer && MOVE_KEYS.includes(e.code) && !state.steer.restForGood) state.steer.rest = false;
  if (state.steer && STEER_KEYS.includes(e.code)) e.preventDefault();
});
window.addEventListener('keyup', (e) => keys.delete(e.code));
window.addEventListener('blur', () => keys.clear());

const has = (tag) => state.tags.includes(tag);
const DIAGONAL_RELEASE_MS = 150;
function steerInput() {
  const s = state.steer;
  let dx = (keys.has('KeyD') || keys.has('ArrowRight') ? 1 : 0) - (keys.has('KeyA') || keys.has('ArrowLeft') ? 1 : 0);
  let dz = (keys.has('KeyS') || keys.has('ArrowDown') ? 1 : 0) - (keys.has('KeyW') || keys.has('ArrowUp') ? 1 : 0);
  let run = keys.has('ShiftLeft') || keys.has('ShiftRight');
  let jump = keys.has('KeyJ');
  const pads = navigator.getGamepads ? [...navigator.getGamepads()].filter(Boolean) : [];
  if (pads.length) {
    const pad = pads[0];
    if (pad.axes.length >= 2 && Math.hypot(pad.axes[0], pad.axes[1]) > 0.3) { dx = pad.axes[0]; dz = pad.axes[1]; }
    jump ||= Boolean(pad.buttons[0]?.pressed);
    run ||= (pad.buttons[7]?.value ?? 0) > 0.5;
    if (pad.buttons[1]?.pressed) s.rest = true;
    s.gamepad = pad.id;
  }
  // A diagonal held (W and D) and let go: hands lift the two keys a few tens of milliseconds apart,
  // and the one left alone that long must not turn the character onto its axis.
  const now = performance.now();
  const diagonal = dx !== 0 && dz !== 0;
  if (diagonal) s.diagonalAt = now;
  const leavingDiagonal = !diagonal && s.diagonalAt !== undefined && now - s.diagonalAt < DIAGONAL_RELEASE_MS;
  if ((dx !== 0 || dz !== 0) && !leavingDiagonal) {  // relative to where the camera looks: W is away from it
    const look = new THREE.Vector3();
    camera.getWorldDirection(look);
    const view = Math.atan2(look.x, -look.z);
    const bearing = ((view + Math.atan2(dx, -dz)) * 180) / Math.PI;
    s.heading = Math.round((((bearing % 360) + 540) % 360) - 180);
  }
  let tag = s.chosenTag;
  if (run && has('run')) tag = 'run';
  if (jump && has('jump')) tag = 'jump';
  s.tag = tag;
  return { heading_deg: s.heading, tag, rest: Boolean(s.rest) };
}

// `ticket`: turnedTo()'s when it was asked for; a session that comes after the user has turned to
// something else (drawing, a clip) is not steered (the server lets it go unstepped).
async function startSteering(ticket = state.ticket) {
  const tag = has('walk') ? 'walk' : '';
  const session = await post('/api/steer/sessions', { heading_deg: 0, tag, cleanup: $('cleanup').checked });
  if (ticket !== state.ticket) return;
  ensureFigure(session.joints);
  state.track = null;
  state.mode = 'steer';
  state.playing = true;
  figure.offset.set(0, 0, 0);
  second.group.visible = false;
  overlays.clear();
  // buffer: the frames received and not yet shown; planted: their rows of the contacts.
  state.steer = { session: session.session, buffer: [], planted: [], contacts: null, inFlight: false, heading: 0,
    tag, chosenTag: tag, rest: false, restS: null, restClip: null, resting: false, restForGood: false, lastStart: null,
    canRest: session.can_rest,
    received: 0, played: 0, clock: 0, fps: session.fps, lastStepMs: 0, trailEnd: null };
  setResultLink(session.result);
  setDrawing(false);
  $('steer-warnings').textContent = '';
  showSteerWarnings(session.warnings);
  chaseCamera([0, 1.6, 5]);  // from the south, looking north
  dropTransition();
  $('steer').textContent = 'Stop steering';
  $('play').disabled = true;
  $('play').textContent = 'Pause';
  canvas.focus();
  requestSteps();
}
function stopSteering() {
  if (!state.steer) return;
  state.steer = null;
  if (state.mode === 'steer') state.mode = 'idle';
  $('steer').textContent = 'Start steering';
  $('play').disabled = false;
  state.playing = false;
  $('play').textContent = 'Play';
}
$('steer').addEventListener('click', () => {
  if (state.steer) { stopSteering(); return; }
  const ticket = turnedTo();
  // The server's reason (all sessions in use, ...) in the steering line, where a step's error goes.
  startSteering(ticket).catch((err) => {
    if (ticket === state.ticket) $('steer-info').textContent = `error: ${err.message}`;
  });
});

// What the session's controls asked that the graph cannot give (a motion type it can hardly
// play, rest where no clip ends standing still), each said once by the server: kept under the
// steering line until steering starts again.
function showSteerWarnings(warnings) {
  if (!warnings.length) return;
  const shown = $('steer-warnings').textContent;
  $('steer-warnings').textContent = [shown, ...warnings.map((w) => `\u26a0 ${w}.`)].filter(Boolean).join(' ');
}

// Keeps about 0.4 s of motion ahead of playback, so input shows within a fraction of a second.
async function requestSteps() {
  const s = state.steer;
  if (!s || s.inFlight || s.buffer.length > 0.4 * s.fps) return;
  s.inFlight = true;
  const input = steerInput();
  const started = performance.now();
  try {
    const step = await post(`/api/steer/sessions/${s.session}/step`, { ...input, min_frames: 8 });
    s.lastStepMs = performance.now() - started;
    s.buffer.push(...step.positions);
    s.contacts = step.contacts;  // its joints; the rows go with the frames
    s.planted.push(...(step.contacts ? step.contacts.planted : step.positions.map(() => null)));
    s.received += step.frames;
    s.transitionsPerSecond = step.session_transitions_per_second;
    s.bridges = step.session_bridges;
    s.restS = step.rest_s;
    s.restClip = step.rest_clip;
    s.resting = step.resting;
    s.restForGood = step.rest_for_good;
    if (step.starts && step.starts.length) s.lastStart = step.starts[step.starts.length - 1];
    showSteerWarnings(step.warnings);
  } catch (err) {
    $('steer-info').textContent = `error: ${err.message}`;
    stopSteering();
    return;
  } finally {
    s.inFlight = false;
  }
}

// --- random walk ---------------------------------------------------------------------------
$('random-walk').addEventListener('click', async () => {
  const nodes = state.summary.statistics.nodes;
  const seed = Math.floor(Math.random() * 1e6);
  const ticket = turnedTo();
  let walk;
  try {
    walk = await post('/api/walk', {
      from: seed % nodes, to: (seed * 7919) % nodes, min_frames: 300, cost: 'random', seed,
      cleanup: $('cleanup').checked });
  } catch (err) {
    if (ticket === state.ticket) $('walk-info').textContent = `error: ${err.message}`;
    return;
  }
  if (ticket !== state.ticket) return;  // the user went on to something else meanwhile
  $('walk-info').textContent = `${walk.frames} frames, ${walk.transitions} transitions; ${footSlideText(walk)}`;
  ensureFigure(walk.joints);
  setDrawing(false);
  play({ fps: walk.fps, frames: walk.positions, loop: false, label: 'graph walk', contacts: walk.contacts },
    'result');
  chaseCamera([2, 1.6, 5]);
  setResultLink(walk.result);
});

// --- the loop ------------------------------------------------------------------------------
const clock = new THREE.Clock();
let lastRoot = null;
function resize() {
  const w = canvas.clientWidth;
  const h = canvas.clientHeight;
  if (canvas.width !== Math.floor(w * devicePixelRatio) || canvas.height !== Math.floor(h * devicePixelRatio)) {
    renderer.setPixelRatio(devicePixelRatio);
    renderer.setSize(w, h, false);
    camera.aspect = w / h;
    camera.updateProjectionMatrix();
  }
}
// On the next frame shown, puts the camera at `offset` from the root, looking at it (the
// follow keeps that offset).
let chaseOffset = null;
function chaseCamera(offset) { chaseOffset = offset; }
function follow(root) {
  if (state.drawing) return;
  const at = new THREE.Vector3(root[0], 0.9, root[2]);
  if (chaseOffset) {
    controls.target.copy(at);
    camera.position.set(at.x + chaseOffset[0], at.y + chaseOffset[1], at.z + chaseOffset[2]);
    chaseOffset = null;
    lastRoot = null;
  }
  if (lastRoot && state.mode !== 'poses') {
    const delta = at.clone().sub(lastRoot);
    if (delta.length() < 3) { camera.position.add(delta); controls.target.add(delta); }
    else { camera.position.add(at.clone().sub(controls.target)); controls.target.copy(at); }
  }
  lastRoot = at;
  sun.position.set(root[0] + 3, 8, root[2] + 4);
  sun.target.position.set(root[0], 0, root[2]);
}
function showFrame(flat) {
  figure.setPose(flat);
  state.root = [flat[0], flat[1], flat[2]];
  state.framesShown += 1;
  follow(state.root);
}
// Draws the foot joints planted in `row` (a row of contacts.planted) when marking is on.
function markFeet(fig, contacts, row) {
  if (state.markFeet && contacts && row) fig.setPlanted(contacts.joint_indices, row);
  else fig.setPlanted(null, null);
}
$('mark-feet').addEventListener('change', (e) => { state.markFeet = e.target.checked; });
for (const box of ['root-motion', 'no-figure']) {
  $(box).addEventListener('change', () => { if (state.result !== null) setResultLink(state.result); });
}

function tick() {
  const dt = Math.min(clock.getDelta(), 0.25);  // real time down to 4 frames a second
  resize();
  if (state.mode === 'steer' && state.steer) {
    const s = state.steer;
    steerInput();
    s.clock += dt * s.fps;
    while (s.clock >= 1 && s.buffer.length > 1) { s.buffer.shift(); s.planted.shift(); s.clock -= 1; s.played += 1; }
    if (s.buffer.length <= 1) s.clock = Math.min(s.clock, 1);
    if (s.buffer.length) {
      showFrame(s.buffer[0]);
      markFeet(figure, s.contacts, s.planted[0]);
      const here = [state.root[0], state.root[2]];
      const last = s.trailEnd;
      if (!last) s.trailEnd = here;
      else if (Math.hypot(here[0] - last[0], here[1] - last[1]) > 0.15) {  // the root's track
        overlays.add(ribbonPiece(last, here, 0x111111, 0.015, 0.03));
        s.trailEnd = here;
        if (overlays.children.length > 400) overlays.remove(overlays.children[0]);
      }
    }
    requestSteps();
    let rest = '';
    if (s.resting && s.played / s.fps < s.restS) {
      rest = `coming to rest at the end of ${s.restClip}, standing from ${s.restS.toFixed(1)} s; `;
    } else if (s.resting) {
      rest = `at rest since ${s.restS.toFixed(1)} s, at the end of ${s.restClip}`
        + (s.restForGood ? ', for good (the graph has no way on from there: Stop steering and start again); '
          : ' (move to start off); ');
    } else if (s.rest) {
      rest = s.canRest ? 'coming to rest; ' : 'asked to rest, but no clip of this graph ends standing still; ';
    } else if (s.lastStart && s.played / s.fps < s.lastStart.at_s + 3) {
      rest = s.lastStart.under_way ? `rest taken back: going on into ${s.lastStart.clip}; `
        : `starting off from rest into ${s.lastStart.clip}; `;
    }
    $('steer-info').textContent = `${rest}heading ${s.heading.toFixed(0)} deg, ${s.tag || 'any'}; `
      + `${s.received} frames received, step ${s.lastStepMs.toFixed(0)} ms, `
      + `${(s.transitionsPerSecond || 0).toFixed(2)} transitions/s${s.bridges ? ` (${s.bridges} bridge${s.bridges === 1 ? '' : 's'})` : ''}`
      + `${s.gamepad ? `; gamepad ${s.gamepad}` : ''}`;
  } else if (state.track && figure) {
    const n = state.track.frames.length;
    if (state.playing) state.time += dt * state.track.fps * state.speed;
    if (state.track.loop) state.time %= n;
    else if (state.time > n - 1) { state.time = n - 1; state.playing = false; $('play').textContent = 'Play'; }
    const f = Math.max(0, Math.min(n - 1, Math.floor(state.time)));
    state.frameIndex = f;
    showFrame(state.track.frames[f]);
    markFeet(figure, state.track.contacts, state.track.contacts?.planted[f]);
    if (state.mode === 'poses' && state.poses) {
      second.setPose(state.poses.to.positions[f]);
      markFeet(second, state.poses.to.contacts, state.poses.to.contacts?.planted[f]);
    }
    $('scrub').value = String(f);
    $('frame-label').textContent = `${state.track.label}: frame ${f + 1} / ${n}`;
  }
  $('hud').textContent = `${state.mode}  root (${state.root.map((v) => v.toFixed(2)).join(', ')})`;
  controls.update();
  renderer.render(scene, camera);
  requestAnimationFrame(tick);
}

// --- start ---------------------------------------------------------------------------------
async function start() {
  const [summary, clips, transitions] = await Promise.all([get('/api/summary'), get('/api/clips'), get('/api/transitions')]);
  Object.assign(state, { summary, clips, transitions, tags: summary.tags });
  $('summary').textContent = `${summary.graph}: ${summary.clips} clips, ${summary.frames} frames at ${summary.fps} fps; `
    + `${summary.statistics.nodes} nodes, ${summary.statistics.edges} edges, `
    + `${summary.statistics.transitions} transitions`;
  $('clip-select').innerHTML = clips.map((c) => `<option value="${c.index}">${c.doubts.length ? '\u26a0 ' : ''}`
    + `${c.name} (${c.frames} frames, kept ${Math.round((100 * c.kept_frames) / c.frames)} %; `
    + `${c.tags.join(', ') || 'no tag'}${c.mirror_of ? `; mirror image of ${c.mirror_of}` : ''})</option>`).join('');
  // A type the graph plays in no frame (its frames pruned away) says so: a path asking for it
  // cannot follow it.
  const absent = new Set(summary.statistics.tags.filter((t) => t.frames === 0).map((t) => t.name));
  // The colours the drawn path takes for each motion type asked along it.
  const hex = (colour) => `#${colour.toString(16).padStart(6, '0')}`;
  $('path-key').innerHTML = ['', ...summary.tags].map((t) => `<span><i style="background:${hex(tagColour(t))}"></i>`
    + `${t || 'any'}</span>`).join('');
  $('path-tag').innerHTML = ['<option value="">any</option>',
    ...summary.tags.map((t) => `<option value="${t}"${t === 'walk' ? ' selected' : ''}>${t}`
      + `${absent.has(t) ? ' (not in the graph)' : ''}</option>`)].join('');
  const modifierNote = 'a modifier: says how a motion goes (turn, stop, ...), not what it is; its frames live in '
    + 'the motion types\' regions and need no connected region (SCC) of their own';
  const rows = summary.statistics.tags.map((t) => `<tr${t.modifier ? ` class="modifier" title="${modifierNote}"` : ''}>`
    + `<th>${t.name}${t.modifier ? '*' : ''}</th><td>${t.database_frames}</td>`
    + `<td>${t.frames}</td><td>${t.nodes}</td><td>${t.edges}</td><td>${t.largest_component_nodes}</td></tr>`);
  $('tag-stats').innerHTML = '<tr><th>tag</th><th>db frames</th><th>graph frames</th><th>nodes</th>'
    + `<th>edges</th><th>largest SCC</th></tr>${rows.join('')}`;
  $('tag-stats-note').textContent = summary.statistics.tags.some((t) => t.modifier) ? `* ${modifierNote}.` : '';
  $('matrix-img').src = '/api/matrix.png';
  drawTransitions();
  const first = await get('/api/clips/0/frames?count=1');
  state.joints = first.joints;
  ensureFigure(first.joints);
  await loadClip(0);
  state.ready = true;
}

// Hooks for the browser test.
window.studio = {
  state,
  // The figure's bounding box on the page (CSS pixels), from its joints.
  figureScreenBox() {
    const r = canvas.getBoundingClientRect();
    const box = { left: Infinity, top: Infinity, right: -Infinity, bottom: -Infinity };
    for (const p of figure.points) {
      const v = p.clone().project(camera);
      const x = r.left + ((v.x + 1) / 2) * r.width;
      const y = r.top + ((1 - v.y) / 2) * r.height;
      box.left = Math.min(box.left, x); box.right = Math.max(box.right, x);
      box.top = Math.min(box.top, y); box.bottom = Math.max(box.bottom, y);
    }
    return box;
  },
  setFigureVisible(visible) { figure.group.visible = visible; },
  // The planted marks on the figure now: the frame shown, the foot joints of the contacts
  // played and, per joint, its sphere's colour and whether its floor disc is shown.
  plantedMarks() {
    const contacts = state.mode === 'steer' ? state.steer?.contacts : state.track?.contacts;
    const indices = contacts ? contacts.joint_indices : [];
    return { mode: state.mode, frame: state.frameIndex, clip: state.clipIndex, plantedColour: PLANTED_COLOUR,
      indices, marks: figure.plantedMarks(indices) };
  },
  transitionClientPoint(index) {
    const r = overlay.getBoundingClientRect();
    const [x, y] = transitionPoint(state.transitions[index]);
    return { x: r.left + (x * r.width) / MATRIX_PX, y: r.top + (y * r.height) / MATRIX_PX };
  },
};

requestAnimationFrame(tick);
start().catch((err) => {
  state.error = err.message;
  $('summary').textContent = `error: ${err.message}`;
});
