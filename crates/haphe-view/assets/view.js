// The haphe view: the scene's meshes, the device point, the proxy, the force and the
// contact, live over a WebSocket or replayed from a trace. World frame, metres, z up.

import * as THREE from 'three';
import { OrbitControls } from 'three/addons/OrbitControls.js';
import { Chart } from '/chart.js';

const CHART_SECONDS = 5;
const $ = (id) => document.getElementById(id);

// What the page shows now; tests read it.
const state = {
  ready: false, info: null, frame: null, frames: 0, sent: 0, connected: false,
  replay: null, drawn: {}, others: [], shapes: {},
};
window.haphe = state;

const info = await (await fetch('/info')).json();
state.info = info;
const meshes = decodeMeshes(await (await fetch('/mesh.bin')).arrayBuffer());
$('title').textContent = info.title;

// Scene, camera, controls.
const canvas = $('scene');
const renderer = new THREE.WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
renderer.setPixelRatio(window.devicePixelRatio);
const scene = new THREE.Scene();
scene.background = new THREE.Color(0x1d2126);
scene.add(new THREE.HemisphereLight(0xdde6f0, 0x2a2622, 1.2));
const sun = new THREE.DirectionalLight(0xffffff, 1.6);
sun.position.set(1, -1.5, 2.5);
scene.add(sun);

const [lo, hi] = info.bounds ?? [[-0.1, -0.1, -0.1], [0.1, 0.1, 0.1]];
const centre = new THREE.Vector3((lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2);
const size = Math.max(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2], 1e-3);
const camera = new THREE.PerspectiveCamera(40, 1, size * 1e-3, size * 100);
camera.up.set(0, 0, 1);
camera.position.copy(centre).add(new THREE.Vector3(0.55, -1.6, 0.9).multiplyScalar(size * 1.15));
const controls = new OrbitControls(camera, canvas);
controls.target.copy(centre);
controls.update();

const grid = new THREE.GridHelper(size * 3, 30, 0x3b424b, 0x2b3138);
grid.rotation.x = Math.PI / 2;
grid.position.set(centre.x, centre.y, lo[2]);
scene.add(grid);
// The grid's scale: 30 cells over three times the scene's size.
{
  const cell = (size * 3) / 30;
  document.getElementById('grid-scale').textContent =
    cell >= 1 ? `1 cell = ${+cell.toPrecision(3)} m` : `1 cell = ${+(cell * 1e3).toPrecision(3)} mm`;
}

// The objects: flat-shaded, tinted by the force while touched. Each keeps its positions,
// triangles and the triangle of each face index (what frames name) for the contact.
const objects = new Map();
function geometryOf(positions, triangles) {
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.BufferAttribute(positions, 3));
  geometry.setIndex(new THREE.BufferAttribute(triangles, 1));
  geometry.computeVertexNormals();
  return geometry;
}
function bySourceOf(source) {
  const bySource = new Map();
  source.forEach((s, i) => bySource.set(s, i));
  return bySource;
}
for (const m of meshes) {
  const geometry = geometryOf(m.positions, m.triangles);
  const material = new THREE.MeshStandardMaterial({
    color: 0x8fa3b8, flatShading: true, roughness: 0.7, metalness: 0.05,
    transparent: true, opacity: 0.92, side: THREE.DoubleSide,
  });
  const mesh = new THREE.Mesh(geometry, material);
  mesh.quaternion.set(m.rotation[0], m.rotation[1], m.rotation[2], m.rotation[3]);
  mesh.position.set(m.translation[0], m.translation[1], m.translation[2]);
  mesh.updateMatrixWorld();
  scene.add(mesh);
  objects.set(m.id, {
    mesh, material, positions: m.positions, triangles: m.triangles, bySource: bySourceOf(m.source),
  });
}

// Device point, proxy, the line between them, force arrow, contact triangle and normal.
// The proxy is the tool's centre: a tool of radius tool_radius is drawn as a sphere of
// that radius (with a faint halo of the marker's size when it is smaller than the marker,
// so that it can be found); a point tool as the marker.
const r = size * 0.012;
const tool = info.tool_radius ?? 0;
const hipMark = new THREE.Mesh(new THREE.SphereGeometry(r, 20, 12),
  new THREE.MeshBasicMaterial({ color: 0xff8c1a, depthTest: false, transparent: true, opacity: 0.9 }));
const proxyMark = new THREE.Mesh(new THREE.SphereGeometry(tool > 0 ? tool : r, 32, 20),
  new THREE.MeshStandardMaterial({ color: 0x3ddc84 }));
if (tool > 0 && tool < r) {
  proxyMark.add(new THREE.Mesh(new THREE.SphereGeometry(r, 20, 12),
    new THREE.MeshBasicMaterial({ color: 0x3ddc84, transparent: true, opacity: 0.25, depthWrite: false })));
}
state.tool = { radius: tool, drawn: proxyMark.geometry.parameters.radius };
const toolText = tool > 0 ? `; tool: a sphere of radius ${+(tool * 1e3).toPrecision(3)} mm` : '';
hipMark.renderOrder = 10;
const link = new THREE.Line(new THREE.BufferGeometry().setFromPoints([centre, centre]),
  new THREE.LineBasicMaterial({ color: 0xffffff, depthTest: false, transparent: true }));
link.renderOrder = 9;
const forceArrow = new THREE.ArrowHelper(new THREE.Vector3(0, 0, 1), centre, size * 0.3, 0xff4d4d);
const normalArrow = new THREE.ArrowHelper(new THREE.Vector3(0, 0, 1), centre, size * 0.12, 0x33d6ff);
const triGeometry = new THREE.BufferGeometry();
triGeometry.setAttribute('position', new THREE.BufferAttribute(new Float32Array(9), 3));
const contactTri = new THREE.Mesh(triGeometry, new THREE.MeshBasicMaterial({
  color: 0xffe14d, side: THREE.DoubleSide, polygonOffset: true, polygonOffsetFactor: -4,
  polygonOffsetUnits: -4,
}));
for (const o of [hipMark, proxyMark, link, forceArrow, normalArrow, contactTri]) {
  o.visible = false;
  scene.add(o);
}
const maxForce = 3.3;

// The scene's force effects, info.effects: [{ effect, place: { kind, ... } }]. A viscosity
// in a box is that box, translucent, with its edges; one inside an object tints the object;
// a spring's anchor is a marker; the others act everywhere or in contact and are named in
// the panel. state.effects says what was drawn, world frame.
const effectColour = 0xb07cff;
state.effects = [];
const effectNames = [];
for (const e of info.effects ?? []) {
  const p = e.place;
  let drawn = null;
  let where = '';
  if (p.kind === 'box') {
    const sides = [0, 1, 2].map((k) => Math.max(p.max[k] - p.min[k], size * 1e-4));
    const geometry = new THREE.BoxGeometry(sides[0], sides[1], sides[2]);
    const box = new THREE.Mesh(geometry, new THREE.MeshBasicMaterial({
      color: effectColour, transparent: true, opacity: 0.2, depthWrite: false, side: THREE.DoubleSide,
    }));
    box.add(new THREE.LineSegments(new THREE.EdgesGeometry(geometry),
      new THREE.LineBasicMaterial({ color: effectColour })));
    box.position.set(...[0, 1, 2].map((k) => (p.min[k] + p.max[k]) / 2));
    scene.add(box);
    box.updateMatrixWorld(true);
    const bounds = new THREE.Box3().setFromObject(box);
    drawn = { min: bounds.min.toArray(), max: bounds.max.toArray() };
    where = ' in the box';
  } else if (p.kind === 'object') {
    const o = objects.get(p.id);
    if (o) {
      o.material.color.setHex(effectColour);
      drawn = { id: p.id, colour: o.material.color.getHex() };
    }
    where = ` inside ${info.objects.find((x) => x.id === p.id)?.name ?? `object ${p.id}`}`;
  } else if (p.kind === 'point') {
    // Seen through the objects, as the device point is: an anchor may lie inside one.
    const marker = new THREE.Mesh(new THREE.OctahedronGeometry(r * 0.9),
      new THREE.MeshBasicMaterial({ color: effectColour, depthTest: false, transparent: true }));
    marker.renderOrder = 10;
    marker.position.set(p.at[0], p.at[1], p.at[2]);
    scene.add(marker);
    drawn = { at: marker.position.toArray() };
    where = ' to the marker';
  }
  state.effects.push({ effect: e.effect, kind: p.kind, drawn });
  effectNames.push(e.effect + where);
}
$('effects').textContent = effectNames.length ? effectNames.join(', ') : '–';

// The other devices of a run of several (two hands): each one's device point, its tool (a
// sphere of its radius, or the marker for a point) and the line between them, in a colour
// of its own, made when a frame first carries it.
const otherColours = [0x4da6ff, 0xd86bff, 0xffd24d];
const others = [];
function otherTool(i, radius) {
  if (!others[i]) {
    const colour = otherColours[i % otherColours.length];
    const hip = new THREE.Mesh(new THREE.SphereGeometry(r, 20, 12),
      new THREE.MeshBasicMaterial({ color: colour, depthTest: false, transparent: true, opacity: 0.9 }));
    hip.renderOrder = 10;
    const proxy = new THREE.Mesh(new THREE.SphereGeometry(radius > 0 ? radius : r, 32, 20),
      new THREE.MeshStandardMaterial({ color: colour }));
    const line = new THREE.Line(new THREE.BufferGeometry().setFromPoints([centre, centre]),
      new THREE.LineBasicMaterial({ color: 0xffffff, depthTest: false, transparent: true }));
    line.renderOrder = 9;
    for (const o of [hip, proxy, line]) scene.add(o);
    others[i] = { hip, proxy, line };
  }
  return others[i];
}

// f.others: [{ hip, proxy, force, tool_radius, contact }], one per other device.
function showOthers(list) {
  state.others = (list ?? []).map((o, i) => {
    const m = otherTool(i, o.tool_radius);
    const hip = new THREE.Vector3(...o.hip), proxy = new THREE.Vector3(...o.proxy);
    m.hip.position.copy(hip);
    m.proxy.position.copy(proxy);
    m.line.geometry.setFromPoints([hip, proxy]);
    return { proxy: [...o.proxy], drawn: m.proxy.geometry.parameters.radius, contact: o.contact };
  });
}

// The objects moved by script, where the frame's tick had them: poses [{ id, rotation
// [x, y, z, w], translation [x, y, z] }]. state.drawn[id] is where each mesh is drawn.
function place(poses) {
  for (const p of poses ?? []) {
    const o = objects.get(p.id);
    if (!o) continue;
    o.mesh.quaternion.set(p.rotation[0], p.rotation[1], p.rotation[2], p.rotation[3]);
    o.mesh.position.set(p.translation[0], p.translation[1], p.translation[2]);
    o.mesh.updateMatrixWorld();
    state.drawn[p.id] = { rotation: [...p.rotation], translation: [...p.translation] };
  }
}

function show(f) {
  // f: { hip, proxy, force, object, triangle, penetration, sticking, status, max_force, poses }
  place(f.poses);
  showOthers(f.others);
  const hip = new THREE.Vector3(...f.hip), proxy = new THREE.Vector3(...f.proxy);
  hipMark.position.copy(hip);
  proxyMark.position.copy(proxy);
  hipMark.visible = proxyMark.visible = true;
  link.geometry.setFromPoints([hip, proxy]);
  link.visible = true;
  const force = new THREE.Vector3(...f.force);
  const magnitude = force.length();
  if (magnitude > 1e-6) {
    forceArrow.position.copy(proxy);
    forceArrow.setDirection(force.clone().normalize());
    const length = size * 0.35 * Math.min(1, magnitude / maxForce) + r;
    forceArrow.setLength(length, Math.min(length * 0.35, r * 3), r * 1.6);
    forceArrow.visible = true;
  } else {
    forceArrow.visible = false;
  }
  for (const o of objects.values()) o.material.emissive.setRGB(0, 0, 0);
  const o = f.object != null ? objects.get(f.object) : undefined;
  const t = o && f.triangle != null ? o.bySource.get(f.triangle) : undefined;
  if (o && t !== undefined) {
    const shade = Math.min(1, magnitude / maxForce);
    o.material.emissive.setRGB(0.3 * shade, 0.05 * shade, 0);
    const p = triGeometry.attributes.position;
    const corners = [];
    for (let k = 0; k < 3; k++) {
      const v = o.triangles[3 * t + k];
      const c = new THREE.Vector3(o.positions[3 * v], o.positions[3 * v + 1], o.positions[3 * v + 2])
        .applyMatrix4(o.mesh.matrixWorld);
      corners.push(c);
      p.setXYZ(k, c.x, c.y, c.z);
    }
    p.needsUpdate = true;
    triGeometry.computeBoundingSphere();
    const n = new THREE.Vector3().subVectors(corners[1], corners[0])
      .cross(new THREE.Vector3().subVectors(corners[2], corners[0])).normalize();
    normalArrow.position.copy(corners[0]).add(corners[1]).add(corners[2]).multiplyScalar(1 / 3);
    normalArrow.setDirection(n);
    contactTri.visible = normalArrow.visible = true;
    state.normal = n.toArray();
  } else {
    contactTri.visible = normalArrow.visible = false;
    state.normal = null;
  }
  const status = $('status');
  status.textContent = f.status + (f.sticking ? ' (sticking)' : '');
  status.className = f.sticking ? 'sticking' : f.object != null ? 'contact' : 'free';
  const name = o ? info.objects.find((x) => x.id === f.object)?.name ?? `object ${f.object}` : '–';
  $('touch').textContent = o ? `${name}, triangle ${f.triangle}` : '–';
  $('force').textContent = `${magnitude.toFixed(3)} N`;
  $('pen').textContent = `${(f.penetration * 1000).toFixed(3)} mm`;
}

// Live: frames over the WebSocket; the pointer moves the mouse device.
const chart = new Chart($('chart'), CHART_SECONDS);
let socket = null;
if (info.mode === 'live') {
  $('device').textContent = `${info.device} at ${info.rate_hz} Hz${toolText}`;
  $('help').textContent = info.mouse
    ? 'Move the pointer to move the device point (orange) on a plane facing you; the wheel ' +
      'moves it in depth (W/S keys too). Drag to orbit, right-drag to pan, Shift+wheel to zoom.'
    : 'Drag to orbit, right-drag to pan, wheel to zoom.';
  socket = new WebSocket(`ws://${location.host}/ws`);
  socket.binaryType = 'arraybuffer';
  socket.onopen = () => { state.connected = true; };
  socket.onclose = () => { state.connected = false; $('status').textContent = 'disconnected'; };
  socket.onmessage = (event) => {
    if (event.data instanceof ArrayBuffer) { reshape(event.data); return; }
    const f = JSON.parse(event.data);
    state.frame = f;
    state.frames += 1;
    if (target === null) target = new THREE.Vector3(...f.hip);
    chart.push(f.t, f.max_force, f.max_penetration * 1000);
    $('tick').textContent = `${f.tick}${f.ended ? ' (ended)' : ''}`;
    $('rate').textContent = f.rate_hz ? `${f.rate_hz.toFixed(0)} Hz` : '–';
    const c = f.compute_us;
    $('compute').textContent = f.rate_hz
      ? `${c[0].toFixed(1)} / ${c[1].toFixed(1)} / ${c[2].toFixed(1)} µs` : '–';
  };
}

// The mouse device: a plane through the device point facing the camera.
let target = null;
let pending = false;
const raycaster = new THREE.Raycaster();
function send() {
  if (!socket || socket.readyState !== WebSocket.OPEN || target === null) return;
  if (pending) return;
  pending = true;
  requestAnimationFrame(() => {
    pending = false;
    socket.send(JSON.stringify({ hip: target.toArray() }));
    state.sent += 1;
  });
}
function facing() {
  return camera.getWorldDirection(new THREE.Vector3());
}
if (info.mouse) {
  canvas.addEventListener('pointermove', (event) => {
    if (event.buttons !== 0 || target === null) return;
    const rect = canvas.getBoundingClientRect();
    const ndc = new THREE.Vector2(
      ((event.clientX - rect.left) / rect.width) * 2 - 1,
      -((event.clientY - rect.top) / rect.height) * 2 + 1);
    raycaster.setFromCamera(ndc, camera);
    const plane = new THREE.Plane().setFromNormalAndCoplanarPoint(facing(), target);
    const hit = raycaster.ray.intersectPlane(plane, new THREE.Vector3());
    if (hit) { target.copy(hit); send(); }
  });
  const depth = (steps) => {
    if (target === null) return;
    target.addScaledVector(facing(), steps * size * 0.01);
    send();
  };
  window.addEventListener('wheel', (event) => {
    if (event.shiftKey) return; // the controls zoom
    event.preventDefault();
    event.stopImmediatePropagation();
    depth(-Math.sign(event.deltaY) * Math.min(5, Math.abs(event.deltaY) / 40));
  }, { capture: true, passive: false });
  window.addEventListener('keydown', (event) => {
    if (event.key === 'w' || event.key === 'W') depth(1);
    if (event.key === 's' || event.key === 'S') depth(-1);
  });
  // Shift+wheel zooms: OrbitControls sees only those wheels.
}

// Replay: the whole trace at once; play, pause, speed and the scrubber.
let replay = null;
if (info.mode === 'replay') {
  const rows = new Float32Array(await (await fetch('/trace.bin')).arrayBuffer());
  const n = info.trace_rows, k = info.row_values;
  // The moving objects' poses per row (see `encode_poses`), when the scene has motions.
  const poses = info.moving.length
    ? new Float32Array(await (await fetch('/poses.bin')).arrayBuffer()) : null;
  replay = { rows, n, k, poses, index: 0, time: rows[0], playing: true };
  state.replay = { index: 0, last: n - 1, atEnd: false };
  $('replay').hidden = false;
  $('device').textContent = `replay of ${n} ticks${toolText}`;
  $('help').textContent = 'Drag to orbit, right-drag to pan, wheel to zoom.';
  $('scrub').max = String(n - 1);
  $('play').onclick = () => {
    if (replay.index >= n - 1) { replay.index = 0; replay.time = rows[0]; }
    replay.playing = !replay.playing;
  };
  $('scrub').oninput = (event) => {
    replay.index = Number(event.target.value);
    replay.time = rows[replay.index * k];
  };
}
function posesAt(i) {
  const { poses } = replay, m = info.pose_values;
  if (!poses) return [];
  return info.moving.map((id, j) => {
    const o = (i * info.moving.length + j) * m;
    return { id, rotation: Array.from(poses.subarray(o, o + 4)), translation: Array.from(poses.subarray(o + 4, o + 7)) };
  });
}
function rowAt(i) {
  const { rows, k } = replay, o = i * k;
  return {
    poses: posesAt(i),
    t: rows[o], hip: [rows[o + 1], rows[o + 2], rows[o + 3]],
    proxy: [rows[o + 4], rows[o + 5], rows[o + 6]], force: [rows[o + 7], rows[o + 8], rows[o + 9]],
    object: rows[o + 10] < 0 ? null : rows[o + 10], triangle: rows[o + 11] < 0 ? null : rows[o + 11],
    status: info.statuses[rows[o + 12]] ?? '?', penetration: rows[o + 13], sticking: rows[o + 14] > 0,
  };
}
function stepReplay(dt) {
  const { rows, n, k } = replay;
  if (replay.playing) {
    replay.time += dt * Number($('speed').value);
    let i = replay.index;
    while (i + 1 < n && rows[(i + 1) * k] <= replay.time) i++;
    replay.index = i;
    if (i >= n - 1) replay.playing = false;
  }
  const f = rowAt(replay.index);
  show(f);
  $('play').textContent = replay.playing ? 'Pause' : 'Play';
  $('scrub').value = String(replay.index);
  $('clock').textContent = `tick ${replay.index + 1} / ${n}, t = ${f.t.toFixed(4)} s`;
  $('tick').textContent = String(replay.index);
  state.replay = { index: replay.index, last: n - 1, atEnd: replay.index === n - 1 };
  // The chart: the last seconds up to now, at most ~600 points.
  const from = f.t - CHART_SECONDS;
  let first = replay.index;
  while (first > 0 && rows[(first - 1) * k] >= from) first--;
  const stride = Math.max(1, Math.floor((replay.index - first) / 600));
  const points = [];
  for (let i = first; i <= replay.index; i += stride) {
    const o = i * k;
    points.push([rows[o], Math.hypot(rows[o + 7], rows[o + 8], rows[o + 9]), rows[o + 13] * 1000]);
  }
  chart.replace(points);
}

// A new version of an object whose shape changes, in one of two binary messages (see
// haphe_view::encode_vertices and encode_mesh), little-endian, object frame:
// - 'HPD1' (a deformation): id (u32), version (u64), vertex count (u32), positions (3 f32
//   each); the triangles stay;
// - 'HPM1' (a cut): id (u32), version (u64), vertex count (u32), triangle count (u32),
//   positions (3 f32 each), triangles (3 u32 each), face indices (u32 each); the object's
//   geometry is replaced (the old one disposed).
// state.shapes[id] says which version is drawn, how many arrived, and the mesh's vertex
// and triangle counts; state.drawnMesh(id) the counts of the geometry drawn, and
// state.vertex(id, i) where vertex i is drawn (object frame).
function reshape(buffer) {
  const view = new DataView(buffer);
  if (view.byteLength < 20) return;
  const magic = view.getUint32(0, true);
  const id = view.getUint32(4, true);
  const version = Number(view.getBigUint64(8, true));
  const n = view.getUint32(16, true);
  const o = objects.get(id);
  if (!o) return;
  if (magic === 0x31445048) {
    const attribute = o.mesh.geometry.attributes.position;
    if (attribute.count !== n || view.byteLength !== 20 + 12 * n) return;
    attribute.array.set(new Float32Array(buffer, 20, 3 * n));
    attribute.needsUpdate = true;
    o.mesh.geometry.computeVertexNormals();
    o.mesh.geometry.computeBoundingSphere();
    o.positions = attribute.array;
  } else if (magic === 0x314d5048 && view.byteLength >= 24) {
    const t = view.getUint32(20, true);
    if (view.byteLength !== 24 + 12 * n + 16 * t) return;
    const positions = new Float32Array(buffer, 24, 3 * n);
    const triangles = new Uint32Array(buffer, 24 + 12 * n, 3 * t);
    const source = new Uint32Array(buffer, 24 + 12 * n + 12 * t, t);
    const old = o.mesh.geometry;
    o.mesh.geometry = geometryOf(positions, triangles);
    old.dispose();
    Object.assign(o, { positions, triangles, bySource: bySourceOf(source) });
  } else {
    return;
  }
  const seen = state.shapes[id];
  state.shapes[id] = {
    version, updates: (seen?.updates ?? 0) + 1,
    vertices: o.positions.length / 3, triangles: o.triangles.length / 3,
  };
}
// The geometry drawn for an object now: its vertex and triangle counts.
state.drawnMesh = (id) => {
  const g = objects.get(id)?.mesh.geometry;
  return g ? { vertices: g.attributes.position.count, triangles: g.index.count / 3 } : null;
};
state.vertex = (id, i) => {
  const a = objects.get(id)?.mesh.geometry.attributes.position;
  return a ? [a.getX(i), a.getY(i), a.getZ(i)] : null;
};

// Where a world point is on the page, CSS pixels (for tests and tools driving the page).
state.project = (x, y, z) => {
  const p = new THREE.Vector3(x, y, z).project(camera);
  const rect = canvas.getBoundingClientRect();
  return [rect.left + (p.x + 1) / 2 * rect.width, rect.top + (1 - p.y) / 2 * rect.height];
};

// Render loop.
function resize() {
  const w = canvas.clientWidth, h = canvas.clientHeight;
  if (canvas.width !== Math.floor(w * renderer.getPixelRatio()) ||
      canvas.height !== Math.floor(h * renderer.getPixelRatio())) {
    renderer.setSize(w, h, false);
    camera.aspect = w / Math.max(h, 1);
    camera.updateProjectionMatrix();
  }
}
let previous = performance.now();
function animate(now) {
  const dt = Math.min(0.1, (now - previous) / 1000);
  previous = now;
  resize();
  if (replay) stepReplay(dt);
  else if (state.frame) show(state.frame);
  chart.draw();
  renderer.render(scene, camera);
  state.ready = true;
  requestAnimationFrame(animate);
}
requestAnimationFrame(animate);

// The binary mesh message of the server (see `Model::encode`).
function decodeMeshes(buffer) {
  const view = new DataView(buffer);
  if (view.getUint32(0, true) !== 0x31565048) throw new Error('not a haphe mesh message');
  const count = view.getUint32(4, true);
  let at = 8;
  const out = [];
  for (let i = 0; i < count; i++) {
    const id = view.getUint32(at, true), nv = view.getUint32(at + 4, true);
    const nt = view.getUint32(at + 8, true);
    at += 12;
    const pose = new Float32Array(buffer.slice(at, at + 28));
    at += 28;
    const positions = new Float32Array(buffer, at, nv * 3);
    at += nv * 12;
    const triangles = new Uint32Array(buffer, at, nt * 3);
    at += nt * 12;
    const source = new Uint32Array(buffer, at, nt);
    at += nt * 4;
    out.push({ id, positions, triangles, source, rotation: pose.slice(0, 4), translation: pose.slice(4, 7) });
  }
  return out;
}
