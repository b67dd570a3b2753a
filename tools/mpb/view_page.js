// view_page.js - the script of the page `mpb view` writes: draws the run's
// bodies with three.js (inlined in the page as #mpb-three), places the moving
// ones at each frame of the chosen stage, and runs the slider and play button.
// Poses come from mpbench (forward kinematics in C): x y z qx qy qz qw per
// moving body per frame, Float32 in base64.
const data = JSON.parse(document.getElementById('mpb-data').textContent);
const threeSource = document.getElementById('mpb-three').textContent;
const THREE = await import(URL.createObjectURL(
  new Blob([threeSource], { type: 'text/javascript' })));

const $ = (id) => document.getElementById(id);

function bytes(b64) {
  const s = atob(b64), out = new Uint8Array(s.length);
  for (let i = 0; i < s.length; i++) out[i] = s.charCodeAt(i);
  return out;
}
const floats = (b64) => new Float32Array(bytes(b64).buffer);
const uints = (b64) => new Uint32Array(bytes(b64).buffer);

// ---- colours ---------------------------------------------------------------
const COLORS = {
  robot: 0xc9ced8, robotStatic: 0x8e97a8, obstacle: 0xc8b89a,
  start: 0x4f86d9, goal: 0x34a853, collision: 0xe53935, trail: 0xf2a900,
  contactObstacle: 0xff7043, seen: 0x8e44ad,
};

// ---- the scene -------------------------------------------------------------
const container = $('view');
const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
renderer.setPixelRatio(window.devicePixelRatio || 1);
container.appendChild(renderer.domElement);
const scene = new THREE.Scene();
scene.background = new THREE.Color(0xf4f6f9);
const camera = new THREE.PerspectiveCamera(45, 1, 0.01, 1000);
camera.up.set(0, 0, 1);
scene.add(new THREE.HemisphereLight(0xffffff, 0x8a8f99, 1.6));
const sun = new THREE.DirectionalLight(0xffffff, 1.6);
sun.position.set(3, -2, 5);
scene.add(sun);
const fill = new THREE.DirectionalLight(0xffffff, 0.5);
fill.position.set(-3, 4, 2);
scene.add(fill);

// ---- geometry, as mpbench's collision world holds it (collision.h) -----------
const meshGeometries = data.meshes.map((m) => {
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.BufferAttribute(floats(m.v), 3));
  g.setIndex(new THREE.BufferAttribute(uints(m.i), 1));
  g.computeVertexNormals();
  return g;
});

function setPose(obj, p, o = 0) {
  obj.position.set(p[o], p[o + 1], p[o + 2]);
  obj.quaternion.set(p[o + 3], p[o + 4], p[o + 5], p[o + 6]);
}

// The three.js geometry of a shape; primitives are centred on their frame,
// cylinders, cones and capsules along z (three.js draws them along y).
function shapeGeometry(s, extent) {
  const d = s.dims;
  let g;
  switch (s.type) {
    case 'box': return new THREE.BoxGeometry(d[0], d[1], d[2]);
    case 'sphere': return new THREE.SphereGeometry(d[0], 32, 16);
    case 'cylinder': g = new THREE.CylinderGeometry(d[0], d[0], d[1], 40); break;
    case 'cone': g = new THREE.ConeGeometry(d[0], d[1], 40); break;
    case 'capsule': g = new THREE.CapsuleGeometry(d[0], d[1], 8, 24); break;
    case 'plane': {
      // a x + b y + c z = d: a square of the scene's size on it.
      g = new THREE.PlaneGeometry(extent, extent);
      const n = new THREE.Vector3(d[0], d[1], d[2]);
      const len = n.length();
      n.normalize();
      g.applyQuaternion(new THREE.Quaternion().setFromUnitVectors(
        new THREE.Vector3(0, 0, 1), n));
      g.translate(n.x * d[3] / len, n.y * d[3] / len, n.z * d[3] / len);
      return g;
    }
    case 'mesh': return meshGeometries[s.mesh];
    default: return new THREE.SphereGeometry(0.01);
  }
  g.rotateX(Math.PI / 2);
  return g;
}

function material(color, opacity = 1, extra = {}) {
  return new THREE.MeshStandardMaterial({
    color, roughness: 0.55, metalness: 0.1, transparent: opacity < 1,
    opacity, depthWrite: opacity >= 1, side: THREE.DoubleSide, ...extra,
  });
}

// A rough size of the world, for planes and the camera.
let extent = 2;
for (const b of data.bodies) {
  for (let k = 0; k < 3; k++) extent = Math.max(extent, 2 * Math.abs(b.pose[k]));
}

// Each body once as a template; copies share its geometries.
const geometries = data.bodies.map((b) => b.shapes.map((s) => shapeGeometry(s, extent)));
function bodyObject(i, mat) {
  const group = new THREE.Group();
  data.bodies[i].shapes.forEach((s, k) => {
    const shapeMat = typeof mat === 'function' ? mat(s) : mat;
    const mesh = new THREE.Mesh(geometries[i][k], shapeMat);
    setPose(mesh, s.offset);
    group.add(mesh);
  });
  group.userData.body = i;
  return group;
}

const robotMat = material(COLORS.robot);
const robotStaticMat = material(COLORS.robotStatic);
const obstacleMat = (s) => s.color
  ? material(new THREE.Color(s.color[0], s.color[1], s.color[2]), s.color[3] < 1 ? s.color[3] : 1)
  : material(COLORS.obstacle);

// The world: bodies that do not move, drawn once.
const world = new THREE.Group();
const sceneGroup = new THREE.Group();
world.add(sceneGroup);
scene.add(world);
const staticObjects = [];
data.bodies.forEach((b, i) => {
  if (b.moves) return;
  const o = bodyObject(i, b.robot ? robotStaticMat : obstacleMat);
  setPose(o, b.pose);
  (b.robot ? world : sceneGroup).add(o);
  staticObjects[i] = o;
});

// What the planner was given instead of the scene (an experiment's seen:,
// such as a sensed octree's cells): its obstacles, over the truth's.
const seenGroup = new THREE.Group();
world.add(seenGroup);
if (data.seen) {
  const seenMat = material(COLORS.seen, 0.45);
  for (const b of data.seen.bodies) {
    const g = new THREE.Group();
    for (const s of b.shapes) {
      const m = new THREE.Mesh(shapeGeometry(s, extent), seenMat);
      setPose(m, s.offset);
      g.add(m);
    }
    setPose(g, b.pose);
    seenGroup.add(g);
  }
  $('seen-key').style.display = 'block';
}

// A robot: one group per moving body, placed from a pose array.
function makeRobot(mat) {
  const g = new THREE.Group();
  g.userData.parts = data.moving.map((i) => {
    const o = bodyObject(i, mat);
    g.add(o);
    return o;
  });
  scene.add(g);
  return g;
}
function placeRobot(robot, poses, frame = 0) {
  const n = data.moving.length;
  robot.userData.parts.forEach((o, m) => setPose(o, poses, 7 * (frame * n + m)));
}

const robot = makeRobot(robotMat);
const startPoses = floats(data.start_poses);
const startRobot = makeRobot(material(COLORS.start, 0.28));
placeRobot(startRobot, startPoses);

// ---- the goal --------------------------------------------------------------
const goalGroup = new THREE.Group();
scene.add(goalGroup);
if (data.goal && data.goal.kind === 'joints') {
  const g = makeRobot(material(COLORS.goal, 0.3));
  placeRobot(g, floats(data.goal.poses));
  scene.remove(g);
  goalGroup.add(g);
} else if (data.goal && data.goal.kind === 'region') {
  // The box the link's point must be in, and a cone around the reference
  // orientation's x axis as wide as the largest rpy tolerance.
  const h = data.goal.half, c = data.goal.center;
  const box = new THREE.Mesh(
    new THREE.BoxGeometry(Math.max(2 * h[0], 0.004), Math.max(2 * h[1], 0.004), Math.max(2 * h[2], 0.004)),
    material(COLORS.goal, 0.45));
  box.position.set(c[0], c[1], c[2]);
  goalGroup.add(box);
  const edges = new THREE.LineSegments(new THREE.EdgesGeometry(box.geometry),
    new THREE.LineBasicMaterial({ color: COLORS.goal }));
  edges.position.copy(box.position);
  goalGroup.add(edges);
  // A 2 cm box is hard to find at the scale of a room: a halo marks it.
  const halo = new THREE.Mesh(new THREE.SphereGeometry(Math.max(3 * Math.max(...h), 0.05), 32, 16),
    material(COLORS.goal, 0.18));
  halo.position.copy(box.position);
  goalGroup.add(halo);
  const tol = Math.min(Math.max(...data.goal.tolerance), Math.PI / 2 - 0.01);
  const len = 0.2;
  const coneGeo = new THREE.ConeGeometry(Math.max(len * Math.tan(tol), 0.004), len, 32, 1, true);
  coneGeo.translate(0, -len / 2, 0);      // apex at the origin, opening along -y
  coneGeo.rotateZ(Math.PI / 2);           // ... along +x
  const cone = new THREE.Mesh(coneGeo, material(COLORS.goal, 0.35));
  cone.position.set(c[0], c[1], c[2]);
  const [r, p, y] = data.goal.rpy;
  cone.quaternion.setFromEuler(new THREE.Euler(r, p, y, 'ZYX'));
  goalGroup.add(cone);
  const axis = new THREE.ArrowHelper(new THREE.Vector3(1, 0, 0).applyQuaternion(cone.quaternion),
    cone.position, len * 1.3, COLORS.goal, 0.03, 0.015);
  goalGroup.add(axis);
}

// ---- the floor ---------------------------------------------------------------
const grid = new THREE.GridHelper(extent * 2, 20, 0xb0b7c3, 0xd5dae3);
grid.rotateX(Math.PI / 2);
// The planar world's prisms stand on z = 0 halfway: the floor goes under them.
if (data.format === 'planar') grid.position.z = -new THREE.Box3().setFromObject(sceneGroup).getSize(new THREE.Vector3()).z / 2;
scene.add(grid);

// ---- stages ------------------------------------------------------------------
const stages = data.stages.map((s) => ({
  ...s,
  poseArray: floats(s.poses),
  frameAt: floats(s.frame_at),
  collisionPoses: s.collision ? floats(s.collision.poses) : null,
}));
let stage = stages[0];
let frame = 0;
const collisionGroup = new THREE.Group();
scene.add(collisionGroup);
let trail = null;

// The end effector: the last moving robot body.
const tipIndex = data.moving.length - 1;

// The configuration where the verifier found the collision: the robot there,
// its body in contact solid red, the others see-through (solid when the
// slider is on that frame, in place of the robot), and the obstacle it
// touches tinted red and outlined, so that the arm stays visible inside it.
const contactParts = [];
const ghostMat = material(COLORS.collision, 0.16);
const redMat = material(COLORS.collision, 1, { emissive: 0x7a0000 });
const contactObstacleMat = material(COLORS.contactObstacle, 0.5, { emissive: 0x401000 });
function highlightContact() {
  for (const o of staticObjects) {
    if (!o) continue;
    o.traverse((m) => { if (m.userData.orig) { m.material = m.userData.orig; delete m.userData.orig; } });
    for (const e of o.children.filter((c) => c.userData.outline)) o.remove(e);
  }
  collisionGroup.clear();
  contactParts.length = 0;
  if (!stage.collision) return;
  const [a, b] = stage.collision.bodies;
  const c = makeRobot(ghostMat);
  scene.remove(c);
  placeRobot(c, stage.collisionPoses);
  c.userData.parts.forEach((o) => {
    const touching = o.userData.body === a || o.userData.body === b;
    o.traverse((m) => { if (m.isMesh) m.material = touching ? redMat : ghostMat; });
    if (!touching) contactParts.push(o);
    else {
      // A halo around the body in contact, to find it among the others.
      const sphere = new THREE.Box3().setFromObject(o).getBoundingSphere(new THREE.Sphere());
      const halo = new THREE.Mesh(new THREE.SphereGeometry(Math.max(sphere.radius * 1.6, 0.04), 32, 16),
        material(COLORS.collision, 0.22));
      halo.position.copy(sphere.center);
      collisionGroup.add(halo);
    }
  });
  collisionGroup.add(c);
  for (const i of [a, b]) {
    const o = staticObjects[i];
    if (!o) continue;
    for (const m of [...o.children]) {
      if (!m.isMesh) continue;
      m.userData.orig = m.material;
      m.material = contactObstacleMat;
      const edges = new THREE.LineSegments(new THREE.EdgesGeometry(m.geometry, 30),
        new THREE.LineBasicMaterial({ color: COLORS.collision }));
      edges.position.copy(m.position);
      edges.quaternion.copy(m.quaternion);
      edges.userData.outline = true;
      o.add(edges);
    }
  }
}

function makeTrail() {
  if (trail) scene.remove(trail);
  const n = data.moving.length, pts = [];
  for (let f = 0; f < stage.frames; f++) {
    const o = 7 * (f * n + tipIndex);
    pts.push(new THREE.Vector3(stage.poseArray[o], stage.poseArray[o + 1], stage.poseArray[o + 2]));
  }
  trail = new THREE.Line(new THREE.BufferGeometry().setFromPoints(pts),
    new THREE.LineBasicMaterial({ color: COLORS.trail }));
  trail.visible = $('show-trail').checked;
  scene.add(trail);
}

function describe(s) {
  const el = $('verdict');
  el.className = 'verdict ' + (s.valid ? 'ok' : 'bad');
  el.textContent = '';
  const head = document.createElement('b');
  head.textContent = s.valid ? 'valid' : 'verdict: ' + s.verdict;
  el.appendChild(head);
  const lines = [];
  if (!s.valid && s.detail) lines.push(s.detail);
  if (s.collision) {
    const [a, b] = s.collision.bodies;
    if (a >= 0) lines.push(data.bodies[a].name + ' touches ' + data.bodies[b].name);
    if (s.collision.certified)
      lines.push('at s=' + s.collision.s.toPrecision(17) + ' of segment ' + s.segment +
        ', found by the certified check (the segment proved free up to it)');
    else
      lines.push('at s=' + s.collision.s.toFixed(4) + ' of segment ' + s.segment +
        ', sampled every ' + data.resolution + ' rad' + (data.resolution_known ? '' : ' (assumed)'));
    lines.push('configuration: [' + s.collision.q.map((x) => x.toFixed(6)).join(', ') + ']');
  }
  lines.push(s.waypoints ? s.waypoints + ' waypoints' : 'no waypoints to draw');
  for (const t of lines) {
    const d = document.createElement('div');
    d.textContent = t;
    el.appendChild(d);
  }
  $('to-failure').disabled = s.fail_frame < 0;
}

function setStage(i) {
  stage = stages[i];
  const slider = $('slider');
  slider.max = Math.max(stage.frames - 1, 0);
  describe(stage);
  highlightContact();
  makeTrail();
  setFrame(stage.fail_frame >= 0 ? stage.fail_frame : 0);
  applyVisibility();
}

function setFrame(f) {
  frame = Math.max(0, Math.min(f, stage.frames - 1));
  $('slider').value = frame;
  robot.visible = stage.frames > 0;
  if (stage.frames > 0) placeRobot(robot, stage.poseArray, frame);
  // On the frame of the collision, the red robot stands in for the robot.
  const atCollision = !!stage.collision && frame === stage.fail_frame &&
    $('show-collision').checked;
  if (atCollision) robot.visible = false;
  for (const o of contactParts)
    o.traverse((m) => { if (m.isMesh) m.material = atCollision ? robotMat : ghostMat; });
  const at = stage.frames > 0 ? stage.frameAt[frame] : 0;
  $('frame').textContent = stage.frames === 0 ? 'no waypoints to draw' :
    'frame ' + (frame + 1) + '/' + stage.frames +
    ', waypoint ' + (Number.isInteger(at) ? at : at.toFixed(2)) + ' of ' + (stage.waypoints - 1);
  render();
}

function applyVisibility() {
  startRobot.visible = $('show-start').checked;
  goalGroup.visible = $('show-goal').checked;
  collisionGroup.visible = $('show-collision').checked;
  setFrame(frame);
  if (trail) trail.visible = $('show-trail').checked;
  sceneGroup.visible = $('show-scene').checked;
  seenGroup.visible = $('show-seen').checked;
  render();
}

// ---- the page around the view --------------------------------------------------
const run = data.run;
$('title').textContent = 'Run ' + run.id + ': ' + run.planner + ' on ' + run.place;
$('subtitle').textContent = 'experiment ' + run.experiment + ' (' + run.experiment_id +
  '), repetition ' + run.repetition + ', ' + (run.success === 1 ? 'success' : run.success === 0 ? 'no success' : 'not finished');
const runInfo = [
  ['status', run.status], ['verdict', run.verdict || '-'],
  ['time', run.time_total == null ? '-' : run.time_total.toFixed(4) + ' s'],
  ['planner', run.planner_id || '-'], ['message', run.message || '-'],
];
if (data.seen) {
  const sn = data.seen;
  runInfo.push(['planned on', sn.how || 'what was seen'],
    ['on what was seen', sn.success === 1 ? 'success'
      : sn.success === 0 ? 'no success (' + (sn.detail || sn.verdict) + ')' : '-']);
}
for (const [k, v] of runInfo) {
  const d = document.createElement('div');
  const b = document.createElement('b');
  b.textContent = k + ': ';
  d.appendChild(b);
  d.appendChild(document.createTextNode(v));
  $('run').appendChild(d);
}
stages.forEach((s, i) => {
  const o = document.createElement('option');
  o.value = i;
  o.textContent = s.name + (s.valid ? '' : ' (' + s.verdict + ')');
  $('stage').appendChild(o);
});
// Open the first stage that failed, if any: that is what one comes to see.
const firstBad = Math.max(0, stages.findIndex((s) => !s.valid));
$('stage').value = firstBad;
$('stage').addEventListener('change', (e) => setStage(Number(e.target.value)));
$('slider').addEventListener('input', (e) => { stop(); setFrame(Number(e.target.value)); });
for (const id of ['show-start', 'show-goal', 'show-collision', 'show-trail', 'show-scene',
  'show-seen'])
  $(id).addEventListener('change', applyVisibility);
$('to-failure').addEventListener('click', () => { stop(); setFrame(stage.fail_frame); });

let playing = null;
function stop() {
  if (playing) cancelAnimationFrame(playing);
  playing = null;
  $('play').innerHTML = '&#9654; Play';
}
$('play').addEventListener('click', () => {
  if (playing) return stop();
  if (frame >= stage.frames - 1) setFrame(0);
  $('play').innerHTML = '&#10074;&#10074; Pause';
  const perSecond = Math.max(30, stage.frames / 8);   // a whole stage in 8 s at most
  let last = performance.now(), acc = 0;
  const step = (now) => {
    acc += (now - last) / 1000 * perSecond;
    last = now;
    if (acc >= 1) {
      setFrame(frame + Math.floor(acc));
      acc -= Math.floor(acc);
    }
    if (frame >= stage.frames - 1) return stop();
    playing = requestAnimationFrame(step);
  };
  playing = requestAnimationFrame(step);
});

// ---- camera: fit the robot's reach and what it touches; drag to orbit ----------
const target = new THREE.Vector3();
let radius = 2, azimuth = -2.6, elevation = 0.85;
function fitCamera() {
  const box = new THREE.Box3();
  for (const g of [robot, startRobot, collisionGroup, goalGroup]) box.expandByObject(g);
  data.bodies.forEach((b, i) => { if (b.robot && staticObjects[i]) box.expandByObject(staticObjects[i]); });
  if (box.isEmpty()) box.expandByObject(world);
  const size = box.getSize(new THREE.Vector3());
  box.getCenter(target);
  radius = Math.max(size.length() * 1.1, 0.5);
}
function placeCamera() {
  camera.position.set(
    target.x + radius * Math.cos(elevation) * Math.cos(azimuth),
    target.y + radius * Math.cos(elevation) * Math.sin(azimuth),
    target.z + radius * Math.sin(elevation));
  camera.lookAt(target);
}
function render() {
  placeCamera();
  renderer.render(scene, camera);
}
function resize() {
  const w = container.clientWidth, h = container.clientHeight;
  renderer.setSize(w, h, false);
  camera.aspect = w / Math.max(h, 1);
  camera.updateProjectionMatrix();
  render();
}
window.addEventListener('resize', resize);
let drag = null;
renderer.domElement.addEventListener('contextmenu', (e) => e.preventDefault());
renderer.domElement.addEventListener('pointerdown', (e) => {
  drag = { x: e.clientX, y: e.clientY, pan: e.shiftKey || e.button === 2 };
  renderer.domElement.setPointerCapture(e.pointerId);
});
renderer.domElement.addEventListener('pointerup', () => { drag = null; });
renderer.domElement.addEventListener('pointermove', (e) => {
  if (!drag) return;
  const dx = e.clientX - drag.x, dy = e.clientY - drag.y;
  drag.x = e.clientX;
  drag.y = e.clientY;
  if (drag.pan) {
    const right = new THREE.Vector3().setFromMatrixColumn(camera.matrix, 0);
    const up = new THREE.Vector3().setFromMatrixColumn(camera.matrix, 1);
    const k = radius / container.clientHeight;
    target.addScaledVector(right, -dx * k).addScaledVector(up, dy * k);
  } else {
    azimuth -= dx * 0.008;
    elevation = Math.max(-1.5, Math.min(1.5, elevation + dy * 0.008));
  }
  render();
});
renderer.domElement.addEventListener('wheel', (e) => {
  e.preventDefault();
  radius *= Math.exp(e.deltaY * 0.001);
  render();
}, { passive: false });

setStage(firstBad);
fitCamera();
resize();
// For tests and scripts: the page is drawn, and its frames can be set.
window.mpbView = { ready: true, setFrame, setStage, get frame() { return frame; }, stages: stages.length };
document.body.dataset.ready = '1';
