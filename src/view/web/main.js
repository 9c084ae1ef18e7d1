// Browser viewer for one scenesmith scene directory, served by `scenesmith view DIR`.
//
// The server exposes the scene directory under `scene/`; this page reads
//   scene/export/scene.glb  meshes: one node per object, extras {id, category, kind, asset, hold,
//                           mass_kg}, children are the object's links `<id>/<link>`;
//   scene/scene.json        support relations and rooms (floor polygons);
//   scene/metrics.json      optional evaluation metrics.
// Frames: scenesmith's world frame W is Z-up, glTF's frame G is Y-up, and the exporter maps
// p_G = (x, z, -y). Everything in this file that comes from scene.json goes through `gltfFromWorld`.
//
// `window.scenesmithViewer` is the hook test/screenshot.mjs drives; see `api` below.

import * as THREE from 'three';
import { GLTFLoader } from 'three/examples/jsm/loaders/GLTFLoader.js';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';

// Relative, so the page works under any prefix the server mounts it at.
const SCENE_BASE = 'scene/';
const GLB_PATH = 'export/scene.glb';
// Magenta does not occur in the generated materials, so the test can count highlight pixels.
const HIGHLIGHT_COLOR = 0xff00ff;
const BACKGROUND_COLOR = 0xdde3ea;
// Walls are cut at this height (metres above the floor) so the default view sees into rooms.
const WALL_CUT_HEIGHT_M = 1.0;
// Keeps what lies below WALL_CUT_HEIGHT_M (glTF y is up).
const WALL_CUT_PLANE = new THREE.Plane(new THREE.Vector3(0, -1, 0), WALL_CUT_HEIGHT_M);
// A pointer that moves further than this between down and up was orbiting, not clicking.
const CLICK_SLOP_PX = 4;
// Camera looks from the -y side of the world (+z in glTF), a little from +x, about 54° down.
const VIEW_DIRECTION_G = new THREE.Vector3(0.4, 1.5, 1.0).normalize();
// Display order of kinds; kinds not listed follow alphabetically.
const KIND_ORDER = ['architecture', 'furniture', 'wall', 'ceiling', 'manipuland'];

/** Test and scripting hook. Methods throw on unknown ids. */
const api = {
  ready: false,
  error: null,
  objects: [],
  selected: null,
  focusedRoom: null,
  screenPoint,
  pick,
  setKindVisible,
  focusRoom,
  describe,
  view,
};
window.scenesmithViewer = api;

const viewer = {
  renderer: null,
  camera: null,
  controls: null,
  scene: new THREE.Scene(),
  /** The glTF scene graph (child of `scene`). */
  sceneRoot: null,
  /** id -> Object3D of the object node (the node carrying extras.id). */
  objectNodes: new Map(),
  /** id -> object record of scene.json (absent when scene.json is missing). */
  records: new Map(),
  rooms: [],
  raycaster: new THREE.Raycaster(),
  highlight: { id: null, savedMaterials: new Map(), box: null },
  highlightMaterial: makeHighlightMaterial([]),
  /** The same for cut walls, so a picked room is not drawn taller than it was. */
  highlightCutMaterial: makeHighlightMaterial([WALL_CUT_PLANE]),
};

main();

// Magenta that still shows the shape: green stays exactly 0 under any light, red and blue never
// drop below the emissive part, which is what the test's colour check relies on.
function makeHighlightMaterial(clippingPlanes) {
  return new THREE.MeshLambertMaterial({
    color: HIGHLIGHT_COLOR, emissive: HIGHLIGHT_COLOR, emissiveIntensity: 0.45, clippingPlanes,
  });
}

async function main() {
  try {
    setUpRenderer();
    // The small JSON files first, so metrics show even when the GLB is missing.
    const [sceneJson, metrics] = await Promise.all([fetchJson('scene.json'), fetchJson('metrics.json')]);
    showMetrics(metrics);
    indexRecords(sceneJson);
    await addGltf(await fetchGlb());
    buildKindToggles();
    buildRoomSelector();
    showSceneTitle(sceneJson);
    frameBox(new THREE.Box3().setFromObject(viewer.sceneRoot));
    api.ready = true;
  } catch (err) {
    // The page is the only place this error is reported: the status line and `api.error`.
    api.error = err.message;
    setStatus(err.message, true);
  }
}

// ---------------------------------------------------------------- loading

async function fetchGlb() {
  const response = await fetch(SCENE_BASE + GLB_PATH);
  if (response.status === 404) {
    throw new Error(`no ${GLB_PATH}: run scenesmith export DIR --formats glb`);
  }
  if (!response.ok) {
    throw new Error(`${GLB_PATH}: HTTP ${response.status}`);
  }
  return response.arrayBuffer();
}

/** A scene-directory JSON file, or null when the server has none (404). */
async function fetchJson(path) {
  const response = await fetch(SCENE_BASE + path);
  if (response.status === 404) return null;
  if (!response.ok) throw new Error(`${path}: HTTP ${response.status}`);
  try {
    return await response.json();
  } catch (err) {
    throw new Error(`${path}: not valid JSON (${err.message})`);
  }
}

function indexRecords(sceneJson) {
  if (!sceneJson) return;
  for (const record of sceneJson.objects ?? []) viewer.records.set(record.id, record);
  viewer.rooms = sceneJson.rooms ?? [];
}

async function addGltf(arrayBuffer) {
  let gltf;
  try {
    gltf = await new GLTFLoader().parseAsync(arrayBuffer, '');
  } catch (err) {
    throw new Error(`${GLB_PATH}: cannot parse (${err.message ?? err})`);
  }
  viewer.sceneRoot = gltf.scene;
  viewer.scene.add(gltf.scene);
  gltf.scene.traverse((node) => {
    const id = node.userData.id;
    if (typeof id === 'string' && !viewer.objectNodes.has(id)) viewer.objectNodes.set(id, node);
  });
  api.objects = [...viewer.objectNodes.keys()];
  prepareWallCut(gltf);
}

/**
 * Gives the walls of every architecture object a clipping plane at WALL_CUT_HEIGHT_M; the
 * "cut walls" checkbox switches clipping on and off for the whole renderer.
 */
function prepareWallCut(gltf) {
  for (const node of viewer.objectNodes.values()) {
    if (node.userData.kind !== 'architecture') continue;
    node.traverse((child) => {
      // GLTFLoader strips '/' from names, so read the link name from the original glTF node.
      if (!child.isMesh || linkName(gltf, child) !== 'walls') return;
      child.userData.cutAway = true;
      child.material = child.material.clone();
      child.material.clippingPlanes = [WALL_CUT_PLANE];
      // Without caps a cut wall is an open shell; drawing both sides keeps it looking solid.
      child.material.side = THREE.DoubleSide;
    });
  }
}

/** The `<link>` part of the glTF node name `<id>/<link>` that produced `object` (or its parent). */
function linkName(gltf, object) {
  for (let o = object; o; o = o.parent) {
    const nodeIndex = gltf.parser.associations.get(o)?.nodes;
    const name = nodeIndex === undefined ? undefined : gltf.parser.json.nodes[nodeIndex]?.name;
    if (typeof name === 'string' && name.includes('/')) return name.slice(name.lastIndexOf('/') + 1);
  }
  return null;
}

// ---------------------------------------------------------------- rendering and camera

function setUpRenderer() {
  const container = document.getElementById('viewport');
  const renderer = new THREE.WebGLRenderer({ antialias: true });
  renderer.setPixelRatio(window.devicePixelRatio);
  renderer.localClippingEnabled = true;
  container.appendChild(renderer.domElement);
  viewer.renderer = renderer;

  viewer.scene.background = new THREE.Color(BACKGROUND_COLOR);
  viewer.scene.add(new THREE.HemisphereLight(0xffffff, 0x8a8070, 2.2));
  const sun = new THREE.DirectionalLight(0xffffff, 1.6);
  sun.position.set(3, 10, 6);
  viewer.scene.add(sun);

  viewer.camera = new THREE.PerspectiveCamera(45, 1, 0.05, 500);
  viewer.controls = new OrbitControls(viewer.camera, renderer.domElement);
  // Render on demand rather than every frame: a static scene costs nothing while idle.
  viewer.controls.addEventListener('change', render);

  new ResizeObserver(() => resize(container)).observe(container);
  resize(container);
  listenForClicks(renderer.domElement);
  document.getElementById('cut-walls').addEventListener('change', (event) => {
    renderer.localClippingEnabled = event.target.checked;
    render();
  });
}

function resize(container) {
  const width = Math.max(1, container.clientWidth);
  const height = Math.max(1, container.clientHeight);
  viewer.renderer.setSize(width, height);
  viewer.camera.aspect = width / height;
  viewer.camera.updateProjectionMatrix();
  render();
}

function render() {
  viewer.highlight.box?.update();
  viewer.renderer.render(viewer.scene, viewer.camera);
}

/** Points the camera at `box` from VIEW_DIRECTION_G, close enough that the box fills the view. */
function frameBox(box) {
  if (box.isEmpty()) return;
  const camera = viewer.camera;
  const sphere = box.getBoundingSphere(new THREE.Sphere());
  const radius = Math.max(sphere.radius, 0.5);
  // The narrower of the two fields of view decides the distance.
  const halfFovY = THREE.MathUtils.degToRad(camera.fov / 2);
  const halfFov = Math.min(halfFovY, Math.atan(Math.tan(halfFovY) * camera.aspect));
  // The bounding sphere over-estimates a flat room; 0.9 keeps its corners just inside.
  const distance = (0.9 * radius) / Math.sin(halfFov);
  camera.position.copy(sphere.center).addScaledVector(VIEW_DIRECTION_G, distance);
  camera.near = distance / 100;
  camera.far = distance * 10;
  camera.updateProjectionMatrix();
  viewer.controls.target.copy(sphere.center);
  viewer.controls.update();
  render();
}

// ---------------------------------------------------------------- picking

function listenForClicks(canvas) {
  let down = null;
  canvas.addEventListener('pointerdown', (event) => {
    down = { x: event.clientX, y: event.clientY };
  });
  canvas.addEventListener('pointerup', (event) => {
    if (!down || event.button !== 0 || !api.ready) return;
    const moved = Math.hypot(event.clientX - down.x, event.clientY - down.y);
    down = null;
    if (moved > CLICK_SLOP_PX) return;
    const hit = firstVisibleHit(event.clientX, event.clientY);
    select(hit ? hit.id : null);
  });
  window.addEventListener('keydown', (event) => {
    if (event.key === 'Escape') select(null);
  });
}

/** The nearest visible object under a CSS-pixel position, as {id, point} or null. */
function firstVisibleHit(clientX, clientY) {
  const rect = viewer.renderer.domElement.getBoundingClientRect();
  const ndc = new THREE.Vector2(
    ((clientX - rect.left) / rect.width) * 2 - 1,
    -((clientY - rect.top) / rect.height) * 2 + 1,
  );
  viewer.raycaster.setFromCamera(ndc, viewer.camera);
  // The raycaster ignores `visible` and clipping, so both are filtered here.
  for (const hit of viewer.raycaster.intersectObject(viewer.sceneRoot, true)) {
    if (!isShown(hit.object)) continue;
    if (hit.object.userData.cutAway && viewer.renderer.localClippingEnabled
        && hit.point.y > WALL_CUT_HEIGHT_M) continue;
    const id = owningObjectId(hit.object);
    if (id !== null) return { id, point: hit.point };
  }
  return null;
}

function isShown(object) {
  for (let o = object; o; o = o.parent) if (!o.visible) return false;
  return true;
}

/** The id of the nearest ancestor carrying extras.id: the object a link mesh belongs to. */
function owningObjectId(object) {
  for (let o = object; o; o = o.parent) {
    if (typeof o.userData.id === 'string') return o.userData.id;
  }
  return null;
}

function select(id) {
  clearHighlight();
  api.selected = id;
  if (id !== null) addHighlight(id);
  showInfo(id);
  render();
}

function addHighlight(id) {
  const node = viewer.objectNodes.get(id);
  // Materials are shared between meshes, so swap the mesh's material rather than editing it.
  node.traverse((child) => {
    if (!child.isMesh) return;
    viewer.highlight.savedMaterials.set(child, child.material);
    child.material = child.userData.cutAway ? viewer.highlightCutMaterial : viewer.highlightMaterial;
  });
  // The box shows through everything, so an object inside a drawer can still be found.
  const box = new THREE.BoxHelper(node, HIGHLIGHT_COLOR);
  box.material.depthTest = false;
  box.renderOrder = 1;
  viewer.scene.add(box);
  viewer.highlight.id = id;
  viewer.highlight.box = box;
}

function clearHighlight() {
  const highlight = viewer.highlight;
  for (const [mesh, material] of highlight.savedMaterials) mesh.material = material;
  highlight.savedMaterials.clear();
  if (highlight.box) {
    viewer.scene.remove(highlight.box);
    highlight.box.geometry.dispose();
    highlight.box.material.dispose();
  }
  highlight.box = null;
  highlight.id = null;
}

// ---------------------------------------------------------------- panel

function setStatus(text, isError = false) {
  const status = document.getElementById('status');
  status.textContent = text;
  status.classList.toggle('error', isError);
}

function showSceneTitle(sceneJson) {
  const name = sceneJson?.package_name;
  if (name) document.title = `${name} · scenesmith view`;
  const prompt = sceneJson?.provenance?.prompt;
  // Counted as metrics.json counts them: architecture (floors and walls) is not an object there.
  const objects = [...viewer.objectNodes.values()].filter((n) => n.userData.kind !== 'architecture');
  const summary = `${objects.length} objects, ${viewer.rooms.length} rooms`;
  setStatus(prompt ? `${name ?? ''}: ${prompt} (${summary})` : summary);
}

/**
 * Objects, COL and STB first, then every other top-level section that has a `percent` (or, for
 * navigability, a `ratio`), so new metrics show up without a change here.
 */
function showMetrics(metrics) {
  const rows = [];
  if (!metrics) {
    rows.push(['no metrics', 'run scenesmith eval DIR']);
  } else {
    if (metrics.counts?.total !== undefined) rows.push(['objects', String(metrics.counts.total)]);
    for (const [key, section] of orderedSections(metrics)) {
      rows.push([key.toUpperCase().replace('_', ' '), formatSection(section)]);
    }
  }
  const body = document.createElement('tbody');
  for (const [label, value] of rows) {
    const tr = body.insertRow();
    const th = document.createElement('th');
    th.textContent = label;
    tr.appendChild(th);
    tr.insertCell().textContent = value;
  }
  document.getElementById('metrics').replaceChildren(body);
}

function orderedSections(metrics) {
  const first = ['col', 'stb'];
  const skip = new Set(['version', 'counts']);
  const rest = Object.keys(metrics).filter((k) => !first.includes(k) && !skip.has(k));
  return [...first, ...rest]
    .filter((key) => key in metrics)
    // A null section is a metric that was not run (e.g. STB without physics): keep it visible.
    .filter((key) => metrics[key] === null || typeof metrics[key]?.percent === 'number'
      || typeof metrics[key]?.ratio === 'number')
    .map((key) => [key, metrics[key]]);
}

function formatSection(section) {
  if (section === null) return 'not run';
  if (typeof section.percent === 'number') return `${section.percent.toFixed(1)} %`;
  return section.ratio.toFixed(2);
}

function showInfo(id) {
  const info = document.getElementById('info');
  if (id === null) {
    const hint = document.createElement('dd');
    hint.className = 'hint';
    hint.textContent = 'click an object';
    info.replaceChildren(hint);
    return;
  }
  const d = describe(id);
  const mass = typeof d.mass_kg === 'number' ? `${d.mass_kg.toFixed(2)} kg` : '—';
  const fields = [
    ['id', d.id], ['category', d.category], ['kind', d.kind], ['room', d.room ?? '—'],
    ['mass', mass], ['hold', d.hold ?? '—'], ['support', formatSupport(d.support)],
    ['asset', d.asset ?? '—'],
  ];
  const children = [];
  for (const [label, value] of fields) {
    const dt = document.createElement('dt');
    dt.textContent = label;
    const dd = document.createElement('dd');
    dd.dataset.field = label;
    dd.textContent = value;
    children.push(dt, dd);
  }
  info.replaceChildren(...children);
}

function formatSupport(support) {
  if (!support) return viewer.records.size ? '—' : 'unknown (no scene.json)';
  switch (support.type) {
    case 'object':
      return `on ${support.parent}` + (support.surface ? ` (${support.surface})` : '');
    case 'floor':
      return `floor of ${support.room ?? '?'}`;
    case 'wall':
      return `wall ${support.wall ?? ''}`.trim();
    case 'ceiling':
      return `ceiling of ${support.room ?? '?'}`;
    default:
      return support.type;
  }
}

function buildKindToggles() {
  const counts = new Map();
  for (const node of viewer.objectNodes.values()) {
    const kind = node.userData.kind ?? 'unknown';
    counts.set(kind, (counts.get(kind) ?? 0) + 1);
  }
  const rank = (kind) => (KIND_ORDER.includes(kind) ? KIND_ORDER.indexOf(kind) : KIND_ORDER.length);
  const kinds = [...counts.keys()].sort((a, b) => rank(a) - rank(b) || a.localeCompare(b));
  const container = document.getElementById('kinds');
  container.replaceChildren(...kinds.map((kind) => {
    const label = document.createElement('label');
    label.className = 'option';
    const box = document.createElement('input');
    box.type = 'checkbox';
    box.checked = true;
    box.dataset.kind = kind;
    box.addEventListener('change', () => setKindVisible(kind, box.checked));
    const count = document.createElement('span');
    count.className = 'count';
    count.textContent = ` (${counts.get(kind)})`;
    label.append(box, ` ${kind}`, count);
    return label;
  }));
}

function buildRoomSelector() {
  const select = document.getElementById('rooms');
  for (const room of viewer.rooms) {
    const option = document.createElement('option');
    option.value = room.id;
    option.textContent = room.label ? `${room.label} (${room.id})` : room.id;
    select.appendChild(option);
  }
  select.addEventListener('change', () => {
    if (select.value) focusRoom(select.value);
    else showWholeScene();
  });
}

function showWholeScene() {
  api.focusedRoom = null;
  frameBox(new THREE.Box3().setFromObject(viewer.sceneRoot));
}

// ---------------------------------------------------------------- test hook

/**
 * A CSS-pixel point (page coordinates) where a click lands on object `id`, or null when the
 * object is hidden. Tries the bounding-box centre, then the centres of its meshes, then a sample
 * of its vertices; `hit` says whether a ray through the point really reaches the object first.
 */
function screenPoint(id) {
  const node = nodeOf(id);
  if (!isShown(node)) return null;
  const candidates = candidatePoints(node);
  let fallback = null;
  for (const p_G of candidates) {
    const css = cssFromWorld(p_G);
    if (!css) continue;
    fallback ??= css;
    if (document.elementFromPoint(css.x, css.y) !== viewer.renderer.domElement) continue;
    if (firstVisibleHit(css.x, css.y)?.id === id) return { ...css, hit: true };
  }
  return fallback ? { ...fallback, hit: false } : null;
}

function candidatePoints(node) {
  const points = [new THREE.Box3().setFromObject(node).getCenter(new THREE.Vector3())];
  const meshes = [];
  node.traverse((child) => { if (child.isMesh) meshes.push(child); });
  for (const mesh of meshes) {
    points.push(new THREE.Box3().setFromObject(mesh).getCenter(new THREE.Vector3()));
  }
  const SAMPLES_PER_MESH = 64;
  for (const mesh of meshes) {
    const position = mesh.geometry.attributes.position;
    const stride = Math.max(1, Math.floor(position.count / SAMPLES_PER_MESH));
    for (let i = 0; i < position.count; i += stride) {
      points.push(new THREE.Vector3().fromBufferAttribute(position, i).applyMatrix4(mesh.matrixWorld));
    }
  }
  return points;
}

/** Page CSS pixels of a glTF-frame point, or null when it is behind the camera or off screen. */
function cssFromWorld(p_G) {
  const ndc = p_G.clone().project(viewer.camera);
  if (Math.abs(ndc.x) > 0.98 || Math.abs(ndc.y) > 0.98 || ndc.z > 1 || ndc.z < -1) return null;
  const rect = viewer.renderer.domElement.getBoundingClientRect();
  return {
    x: rect.left + ((ndc.x + 1) / 2) * rect.width,
    y: rect.top + ((1 - ndc.y) / 2) * rect.height,
  };
}

/** Selects `id` as a click would; `pick(null)` clears the selection. */
function pick(id) {
  if (id !== null) nodeOf(id);
  select(id);
}

function setKindVisible(kind, visible) {
  for (const node of viewer.objectNodes.values()) {
    if ((node.userData.kind ?? 'unknown') === kind) node.visible = visible;
  }
  const box = document.querySelector(`#kinds input[data-kind="${CSS.escape(kind)}"]`);
  if (box) box.checked = visible;
  // A hidden object cannot stay selected: its highlight box would float over nothing.
  if (api.selected !== null && !isShown(viewer.objectNodes.get(api.selected))) select(null);
  else render();
}

/** Frames room `roomId` (its floor polygon up to its wall height). */
function focusRoom(roomId) {
  const room = viewer.rooms.find((r) => r.id === roomId);
  if (!room) throw new Error(`unknown room ${roomId}`);
  const box = new THREE.Box3();
  for (const [x, y] of room.floor_polygon) {
    box.expandByPoint(gltfFromWorld(x, y, 0));
    box.expandByPoint(gltfFromWorld(x, y, room.wall_height ?? 2.5));
  }
  api.focusedRoom = roomId;
  document.getElementById('rooms').value = roomId;
  frameBox(box);
}

/** Scene frame (Z-up) to glTF frame (Y-up), as the exporter writes it. */
function gltfFromWorld(x, y, z) {
  return new THREE.Vector3(x, z, -y);
}

function describe(id) {
  const node = nodeOf(id);
  const extras = node.userData;
  const record = viewer.records.get(id);
  return {
    id,
    category: extras.category ?? record?.category ?? null,
    kind: extras.kind ?? record?.kind ?? null,
    room: record?.room ?? null,
    asset: extras.asset ?? record?.asset ?? null,
    hold: extras.hold ?? null,
    mass_kg: extras.mass_kg ?? null,
    support: record?.support ?? null,
  };
}

/** Camera position and orbit target in the glTF frame (Y-up), metres. */
function view() {
  return {
    position: viewer.camera.position.toArray(),
    target: viewer.controls.target.toArray(),
  };
}

function nodeOf(id) {
  const node = viewer.objectNodes.get(id);
  if (!node) throw new Error(`unknown object ${id}`);
  return node;
}
