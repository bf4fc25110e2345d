// urdflint web page: the robot in 3D (three.js, served from /static/vendor/three).
// Draws the check answer's "scene" (urdflint/outputs/scene.py): every shape already placed
// in the world (ROS: z up, metres), meshes decoded from base64, each link's centre of mass
// as a marker and its inertia as the uniform box of the same mass and inertia (Gazebo's
// "View > Inertia"), the joint axes as arrows, links with findings in their severity's
// colour. The robot comes first: visuals in their own colours (or a neutral grey), the
// camera framed on them; the overlays (centres of mass, inertia boxes, joint axes, finding
// colours) show for the selected link only, unless the reader asks for those of every
// flagged link or of every link. A mobile base's support polygon (from the answer's
// "statics") is drawn on the ground with the projection of the whole robot's centre of mass,
// in green (it stands), amber (a tilt under 10 degrees tips it) or red (it falls), when the
// "support polygon" box is ticked. Renders on demand (after a change), never in a loop.
// Events on document: urdflint:results {scene, statics, started} -> draw; urdflint:select {link}
// -> highlight; a click on a link sends urdflint:select {link, from: "scene"}.
// three.js loads on the first check (or when the form is sent), not with the page.

const COLOURS = { error: "#d92d20", warning: "#dc6803", info: "#1570ef" };
const PLAIN = "#b7bec9"; // a visual without a colour of its own
const COLLISION = "#0e9384";
const INERTIA = "#7a5af8";
const COM = "#101828";
const AXIS = "#3e4fd8";
const SUPPORT = { stands: "#079455", close: "#dc6803", falls: "#d92d20" }; // by the stability margin
const TIPS = 10; // degrees: a base that a smaller tilt tips over is close to tipping
// "stand": the collision geometry of a link with no visual, shown in its place
const GROUPS = ["visual", "stand", "collision", "inertia", "com", "axes", "support"];
const OVERLAYS = ["com", "inertia", "axes", "findings"];
const FILLS = 6; // inertia boxes past which only their edges are drawn (the selected one's filled)
const MARKER = 0.009; // a centre of mass's radius per metre from the camera: ~5 px, always
const $ = (id) => document.getElementById(id);

// every material the view makes, by kind; warm() draws one of each before the answer comes
const MATERIALS = {
  solid: (T, more) => new T.MeshPhongMaterial({ flatShading: true, side: T.DoubleSide, shininess: 25, ...more }),
  // a collision that is its visual tints it evenly instead of fighting it for depth
  seeThrough: (T, more) => MATERIALS.solid(T, { transparent: true, depthWrite: false, polygonOffset: true, polygonOffsetFactor: -1, polygonOffsetUnits: -1, ...more }),
  fill: (T, more) => new T.MeshBasicMaterial({ transparent: true, depthWrite: false, polygonOffset: true, polygonOffsetFactor: -2, polygonOffsetUnits: -2, ...more }),
  marker: (T, more) => new T.MeshBasicMaterial({ depthTest: false, ...more }),
  edges: (T, more) => new T.LineBasicMaterial(more),
  dashed: (T, more) => new T.LineDashedMaterial(more),
};

let loading = null; // the three.js import, once
let view = null; // {THREE, renderer, scene, camera, controls, ...}; null when there is no WebGL
let current = null; // the drawn robot: {groups, links: Map(name -> {objects, com, marks}), size}
// overlays: "selected" (the selected link's only), "flagged" (also every link with a
// finding of their kind), "all"; com, inertia, axes, findings: which overlays there are
const show = { visual: true, collision: false, overlays: "selected", com: true, inertia: true, axes: true, findings: true, support: false };

function three() {
  if (!loading) {
    loading = Promise.all([
      import("./vendor/three/three.module.min.js"),
      import("./vendor/three/OrbitControls.js"),
    ]).then(([THREE, orbit]) => ({ THREE, OrbitControls: orbit.OrbitControls }));
  }
  return loading;
}

function state(name, note) {
  const box = $("view");
  box.dataset.state = name;
  box.querySelectorAll(".view-note").forEach((p) => p.remove());
  if (note) box.append(Object.assign(document.createElement("p"), { className: "view-note muted", textContent: note }));
}

let gpu = null; // {software}: what the browser's WebGL 2 runs on, probed once; false: none

function webgl2() {
  if (gpu === null) {
    try {
      const probe = document.createElement("canvas").getContext("webgl2");
      const named = probe && probe.getExtension("WEBGL_debug_renderer_info");
      const name = probe ? String(probe.getParameter(named ? named.UNMASKED_RENDERER_WEBGL : probe.RENDERER)) : "";
      gpu = probe ? { software: /swiftshader|llvmpipe|softpipe|software/i.test(name) } : false;
      if (probe) probe.getExtension("WEBGL_lose_context")?.loseContext();
    } catch (ignored) {
      gpu = false;
    }
  }
  return !!gpu;
}

function setUp(lib) {
  const { THREE, OrbitControls } = lib;
  const box = $("view");
  // software GL (SwiftShader, llvmpipe) spends most of a frame on multisampling: off there
  const renderer = new THREE.WebGLRenderer({ antialias: !(gpu && gpu.software) });
  renderer.setPixelRatio(Math.min(window.devicePixelRatio || 1, 2));
  renderer.setClearColor("#f8fafc");
  renderer.domElement.className = "view-canvas";
  box.append(renderer.domElement);
  const camera = new THREE.PerspectiveCamera(40, 1, 0.001, 1000);
  camera.up.set(0, 0, 1);
  const controls = new OrbitControls(camera, renderer.domElement);
  const scene = new THREE.Scene();
  scene.add(new THREE.HemisphereLight("#ffffff", "#8a94a6", 2.2));
  const sun = new THREE.DirectionalLight("#ffffff", 1.6);
  sun.position.set(0.4, -0.6, 1);
  camera.add(sun);
  scene.add(camera);
  view = { THREE, renderer, camera, controls, scene, raycaster: new THREE.Raycaster() };
  controls.addEventListener("change", draw);
  controls.addEventListener("start", () => { if (current) current.framed = false; });
  new ResizeObserver(resize).observe(box);
  pickOnClick(renderer.domElement);
  resize();
}

function warm() {
  // while the server works, draw one of each material with each vertex layout the robot
  // will use (primitives: position, normal, uv; meshes: position only). Software GL builds
  // its shaders and pipelines at the first draw of each: about 1.5 s for a robot, paid here
  const { THREE, renderer, scene, camera } = view;
  const group = new THREE.Group();
  const box = new THREE.BoxGeometry(0.01, 0.01, 0.01);
  const bare = new THREE.BufferGeometry().setAttribute("position", box.getAttribute("position"));
  bare.setIndex(box.getIndex());
  const lines = new THREE.EdgesGeometry(box);
  const add = (object) => { object.frustumCulled = false; group.add(object); };
  for (const kind of ["solid", "seeThrough"]) {
    add(new THREE.Mesh(box, MATERIALS[kind](THREE)));
    add(new THREE.Mesh(bare, MATERIALS[kind](THREE)));
  }
  add(new THREE.Mesh(box, MATERIALS.fill(THREE)));
  add(new THREE.Mesh(box, MATERIALS.marker(THREE)));
  add(new THREE.LineSegments(lines, MATERIALS.edges(THREE)));
  add(new THREE.LineSegments(lines, MATERIALS.dashed(THREE)).computeLineDistances());
  for (const helper of [new THREE.ArrowHelper(), new THREE.GridHelper(0.01, 2), new THREE.Box3Helper(new THREE.Box3(new THREE.Vector3(), new THREE.Vector3(0.01, 0.01, 0.01)))]) {
    helper.traverse((o) => { o.frustumCulled = false; });
    group.add(helper);
  }
  scene.add(group);
  camera.position.set(0.05, -0.05, 0.05);
  camera.lookAt(0, 0, 0);
  view.warm = renderer.compileAsync(scene, camera).catch(() => {}).then(() => {
    renderer.render(scene, camera);
    scene.remove(group);
  });
  view.warmGroup = group; // kept: its materials hold the compiled programs
}

function prepare() {
  // the form was sent: load three.js and set the view up now, not after the answer
  if (!webgl2()) return;
  three().then((lib) => {
    if (!view) {
      setUp(lib);
      warm();
    }
  }).catch(() => {});
}

function resize() {
  if (!view) return;
  const box = $("view");
  const width = Math.max(1, box.clientWidth);
  const height = Math.max(1, box.clientHeight);
  view.renderer.setSize(width, height, false);
  view.camera.aspect = width / height;
  view.camera.updateProjectionMatrix();
  if (current && current.framed) frame(); // untouched since framed: framed again, to fit
  else draw();
}

function draw() {
  if (!view || !current) return;
  for (const marker of [...current.groups.com.children, ...current.groups.support.children]) {
    if (marker.userData.marker) marker.scale.setScalar(view.camera.position.distanceTo(marker.position) * MARKER);
  }
  view.renderer.render(view.scene, view.camera);
}

// -- building the robot -----------------------------------------------------------------------

function bytes(text) {
  const raw = atob(text);
  const out = new Uint8Array(raw.length);
  for (let i = 0; i < raw.length; i++) out[i] = raw.charCodeAt(i);
  return out.buffer;
}

function meshGeometries(THREE, meshes) {
  return meshes.map((m) => {
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute("position", new THREE.BufferAttribute(new Float32Array(bytes(m.positions)), 3));
    const index = m.index === "u32" ? new Uint32Array(bytes(m.indices)) : new Uint16Array(bytes(m.indices));
    geometry.setIndex(new THREE.BufferAttribute(index, 1));
    geometry.computeBoundingSphere();
    return geometry;
  });
}

function primitive(THREE, shape, meshes) {
  // the shape's geometry in its own frame (three's cylinders stand along y, URDF's along z)
  if (shape.kind === "box") return new THREE.BoxGeometry(...shape.size);
  if (shape.kind === "sphere") return new THREE.SphereGeometry(shape.radius, 24, 16);
  if (shape.kind === "cylinder") return new THREE.CylinderGeometry(shape.radius, shape.radius, shape.length, 28).rotateX(Math.PI / 2);
  if (shape.kind === "capsule") return new THREE.CapsuleGeometry(shape.radius, shape.length, 8, 20).rotateX(Math.PI / 2);
  if (shape.kind === "mesh" && Number.isInteger(shape.mesh)) return meshes[shape.mesh] || null;
  return null;
}

function place(object, at) {
  object.position.set(at[0], at[1], at[2]);
  object.quaternion.set(at[3], at[4], at[5], at[6]);
  return object;
}

function tinted(entry) {
  // a link in its worst finding's colour: when finding colours are on and it is in scope
  return !!(show.findings && entry.link.severity && inScope(entry, "findings"));
}

function inScope(entry, kind, chosenOnly) {
  // whether an overlay of this kind shows for this link: the selected link has them all;
  // "flagged" adds the links with findings of that kind (inertia findings for the box and
  // the centre of mass, the joint's for its axis, any for the colour); "all", every link.
  // chosenOnly: by the scope the reader chose, whatever is selected
  const link = entry.link;
  if (!chosenOnly && current && current.selected === link.name) return true;
  if (show.overlays === "all") return true;
  if (show.overlays !== "flagged") return false;
  if (kind === "com" || kind === "inertia") return !!link.inertia_severity;
  if (kind === "axes") return !!(entry.joint && entry.joint.severity);
  return !!link.severity;
}

function addShapes(robot, link, tag, meshes) {
  // a link's visuals, or its collisions: in the "collision" group, or in the "stand" group
  // (drawn like the visuals are) when the link has no visual to show
  const { THREE } = view;
  const entry = robot.links.get(link.name);
  const group = tag === "collision" && !entry.objects.length ? "stand" : tag;
  for (const shape of link[tag]) {
    const geometry = primitive(THREE, shape, meshes);
    if (!geometry || !Array.isArray(shape.at)) continue;
    const rgba = tag === "visual" && Array.isArray(shape.rgba) ? shape.rgba : null;
    const own = rgba ? new THREE.Color().setRGB(rgba[0], rgba[1], rgba[2], THREE.SRGBColorSpace) : null;
    const material = tag === "collision"
      ? MATERIALS.seeThrough(THREE, { color: COLLISION, opacity: 0.45 })
      : MATERIALS.solid(THREE, { color: own || PLAIN, transparent: !!rgba && rgba[3] < 1, opacity: rgba ? Math.max(0.15, rgba[3]) : 1 });
    material.userData = { own, tag };
    const mesh = place(new THREE.Mesh(geometry, material), shape.at);
    mesh.userData.link = link.name;
    robot.groups[group].add(mesh);
    entry.objects.push(mesh);
  }
}

function addInertia(robot, link) {
  const { THREE } = view;
  const inertial = link.inertial;
  if (!inertial || !Array.isArray(inertial.com)) return;
  const colour = link.inertia_severity ? COLOURS[link.inertia_severity] : null;
  const box = inertial.box;
  if (box && box.size.some((v) => v > 0)) {
    const size = box.size.map((v) => Math.max(v, 1e-6));
    const geometry = new THREE.BoxGeometry(...size);
    // front faces only: seen from inside (a box 1000x too large holds the camera), a box
    // is its edges, not a tint over everything
    const fill = new THREE.Mesh(geometry, MATERIALS.fill(THREE, { color: colour || INERTIA, opacity: colour ? 0.22 : 0.14 }));
    fill.material.userData = { flagged: colour, plain: INERTIA };
    const edges = new THREE.LineSegments(new THREE.EdgesGeometry(geometry), box.valid
      ? MATERIALS.edges(THREE, { color: colour || INERTIA })
      : MATERIALS.dashed(THREE, { color: colour || COLOURS.error, dashSize: robot.size / 80, gapSize: robot.size / 120 }));
    edges.material.userData = { flagged: colour, plain: box.valid ? INERTIA : COLOURS.error };
    robot.marks.push(fill.material, edges.material);
    if (!box.valid) edges.computeLineDistances();
    const group = place(new THREE.Group(), box.at);
    group.add(fill, edges);
    fill.userData.link = link.name;
    fill.userData.overlay = true;
    robot.groups.inertia.add(group);
    robot.links.get(link.name).objects.push(fill);
    robot.links.get(link.name).marks.inertia = group;
    robot.links.get(link.name).marks.fill = fill;
  }
  const marker = new THREE.Group(); // unit spheres, scaled to a constant size on screen
  marker.userData.marker = true;
  const dot = new THREE.Mesh(new THREE.SphereGeometry(1, 16, 12), MATERIALS.marker(THREE, { color: colour || COM }));
  dot.material.userData = { flagged: colour, plain: COM };
  robot.marks.push(dot.material);
  const halo = new THREE.Mesh(new THREE.SphereGeometry(1.45, 16, 12), MATERIALS.marker(THREE, { color: "#ffffff" }));
  halo.renderOrder = 10;
  dot.renderOrder = 11;
  dot.userData.link = link.name;
  marker.add(halo, dot);
  marker.position.set(...inertial.com);
  robot.groups.com.add(marker);
  robot.links.get(link.name).com = marker.position.clone();
  robot.links.get(link.name).marks.com = marker;
}

function addAxes(robot, joints) {
  // each joint's axis, an overlay of its child link
  const { THREE } = view;
  const length = robot.size / 9;
  for (const joint of joints) {
    const child = robot.links.get(joint.child);
    if (!joint.axis || !child) continue;
    const colour = joint.severity ? COLOURS[joint.severity] : AXIS;
    const arrow = new THREE.ArrowHelper(new THREE.Vector3(...joint.axis.direction),
      new THREE.Vector3(...joint.axis.origin), length, colour, length * 0.28, length * 0.14);
    for (const material of [arrow.line.material, arrow.cone.material]) {
      material.userData = { flagged: joint.severity ? colour : null, plain: AXIS };
      robot.marks.push(material);
    }
    arrow.line.material.depthTest = arrow.cone.material.depthTest = false;
    arrow.renderOrder = 11;
    robot.groups.axes.add(arrow);
    child.marks.axes = arrow;
    child.joint = joint;
  }
}

function bounds(THREE, robot, links) {
  // what the camera frames: the robot as it looks, its visuals (and the collisions of links
  // without one); never the inertia boxes (a tensor 1000x too large must not shrink the
  // robot to a dot) nor the collision geometry. Without either: the link frames and the
  // centres of mass
  const box = new THREE.Box3();
  box.expandByObject(robot.groups.visual);
  box.expandByObject(robot.groups.stand);
  if (box.isEmpty()) {
    for (const link of links) {
      if (Array.isArray(link.at)) box.expandByPoint(new THREE.Vector3(...link.at.slice(0, 3)));
      if (link.inertial && Array.isArray(link.inertial.com)) box.expandByPoint(new THREE.Vector3(...link.inertial.com));
    }
  }
  if (box.isEmpty()) box.set(new THREE.Vector3(-0.1, -0.1, -0.1), new THREE.Vector3(0.1, 0.1, 0.1));
  const size = box.getSize(new THREE.Vector3());
  if (size.length() < 0.05) box.expandByScalar(0.05);
  return box;
}

function baseOf(statics) {
  // the answer's mobile base with a support polygon: {support, stance, kind}, or null
  const sections = statics && Array.isArray(statics.sections) ? statics.sections : [];
  const found = sections.find((s) => s && s.name === "base");
  const data = found && found.data;
  const support = data && data.mobile ? data.support : null;
  if (!support || !Array.isArray(support.polygon) || support.polygon.length < 2) return null;
  const stance = data.given || data.zero;
  if (!stance || !Array.isArray(stance.com)) return null;
  const tilt = stance.tipping_angle_deg;
  const kind = stance.margin_mm < 0 ? "falls" : typeof tilt === "number" && tilt < TIPS ? "close" : "stands";
  return { support, stance, kind };
}

function addSupport(robot, base) {
  // the support polygon on the ground (its edge and a light fill) and the whole robot's
  // centre of mass over it (a dot on the ground, a dashed line down from the centre of
  // mass), drawn over the robot: the polygon is under the base
  const { THREE } = view;
  robot.supportPoints = [];
  if (!base) return;
  const colour = SUPPORT[base.kind];
  const z = base.support.ground;
  const corners = base.support.polygon.map(([x, y]) => new THREE.Vector3(x, y, z));
  const group = robot.groups.support;
  const edge = new THREE.LineLoop(new THREE.BufferGeometry().setFromPoints(corners), MATERIALS.edges(THREE, { color: colour, depthTest: false }));
  edge.renderOrder = 12;
  group.add(edge);
  if (corners.length >= 3) {
    const shape = new THREE.Shape(corners.map((p) => new THREE.Vector2(p.x, p.y)));
    const fill = new THREE.Mesh(new THREE.ShapeGeometry(shape), MATERIALS.fill(THREE, { color: colour, opacity: 0.3, depthTest: false }));
    fill.position.z = z;
    fill.renderOrder = 11;
    group.add(fill);
  }
  const [x, y, height] = base.stance.com;
  const drop = new THREE.Line(new THREE.BufferGeometry().setFromPoints([new THREE.Vector3(x, y, height), new THREE.Vector3(x, y, z)]),
    MATERIALS.dashed(THREE, { color: colour, depthTest: false, dashSize: robot.size / 60, gapSize: robot.size / 90 }));
  drop.computeLineDistances();
  drop.renderOrder = 12;
  const marker = new THREE.Group();
  marker.userData.marker = true;
  const halo = new THREE.Mesh(new THREE.SphereGeometry(1.45, 16, 12), MATERIALS.marker(THREE, { color: "#ffffff" }));
  const dot = new THREE.Mesh(new THREE.SphereGeometry(1, 16, 12), MATERIALS.marker(THREE, { color: colour }));
  halo.renderOrder = 12;
  dot.renderOrder = 13;
  marker.add(halo, dot);
  marker.position.set(x, y, z);
  group.add(drop, marker);
  robot.supportPoints = [...corners, marker.position.clone()];
}

function build(data, statics) {
  const { THREE, scene } = view;
  if (current) dispose(current);
  const root = new THREE.Group();
  const robot = { root, groups: {}, links: new Map(), size: 1, selected: null, outline: null, marks: [] };
  for (const name of GROUPS) {
    robot.groups[name] = new THREE.Group();
    root.add(robot.groups[name]);
  }
  const links = Array.isArray(data.links) ? data.links : [];
  for (const link of links) robot.links.set(link.name, { link, objects: [], com: null, marks: {} });
  const meshes = meshGeometries(THREE, Array.isArray(data.meshes) ? data.meshes : []);
  for (const link of links) {
    addShapes(robot, link, "visual", meshes);
    addShapes(robot, link, "collision", meshes);
  }
  robot.box = bounds(THREE, robot, links);
  robot.size = Math.max(robot.box.getSize(new THREE.Vector3()).length(), 0.05);
  for (const link of links) addInertia(robot, link);
  addAxes(robot, Array.isArray(data.joints) ? data.joints : []);
  const floor = new THREE.GridHelper(robot.size * 2, 20, "#c9ced6", "#e4e7ec");
  floor.rotation.x = Math.PI / 2;
  floor.position.set(...robot.box.getCenter(new THREE.Vector3()).toArray().slice(0, 2), robot.box.min.z);
  root.add(floor);
  addSupport(robot, baseOf(statics));
  scene.add(root);
  current = robot;
  robot.points = outlinePoints(THREE, robot);
  applyShown();
  frame();
}

function dispose(robot) {
  view.scene.remove(robot.root);
  robot.root.traverse((object) => {
    if (object.geometry) object.geometry.dispose();
    if (object.material) [].concat(object.material).forEach((m) => m.dispose());
  });
}

function corners(THREE, box) {
  return Array.from({ length: 8 }, (_, i) => new THREE.Vector3(
    i & 1 ? box.max.x : box.min.x, i & 2 ? box.max.y : box.min.y, i & 4 ? box.max.z : box.min.z));
}

function outlinePoints(THREE, robot) {
  // what framing fits into the view: the corners of each visual's box (of each stand-in
  // collision's), tighter than the corners of the box around them all
  const points = [];
  for (const group of [robot.groups.visual, robot.groups.stand]) {
    for (const object of group.children) {
      const box = new THREE.Box3().setFromObject(object);
      if (!box.isEmpty()) points.push(...corners(THREE, box));
    }
  }
  return points.length ? points : corners(THREE, robot.box);
}

function framedPoints(THREE) {
  // the robot's visuals; with the overlays the reader asked for every flagged link (or
  // every link), their centres of mass and the inertia boxes up to 4 times the robot's size
  // (a box 30x its link's, a tensor 1000x too large, shows whole around the robot; one of a
  // tensor in g mm^2, 10^6x, would shrink the robot to a dot and is left to reach past)
  const points = current.points.slice();
  if (show.support) points.push(...current.supportPoints);
  if (show.overlays === "selected") return points;
  const limit = current.size * 4;
  for (const entry of current.links.values()) {
    if (show.com && entry.com && inScope(entry, "com", true)) points.push(entry.com);
    const group = entry.marks.inertia;
    if (show.inertia && group && inScope(entry, "inertia", true)) {
      const box = new THREE.Box3().setFromObject(group);
      if (!box.isEmpty() && box.getSize(new THREE.Vector3()).length() <= limit) points.push(...corners(THREE, box));
    }
  }
  return points;
}

function frame() {
  // the whole robot as large as the view allows (a small margin around), seen from the
  // front right and a little above: the distance at which every point fits, the target
  // moved so that the picture is centred
  const { THREE, camera, controls } = view;
  const direction = new THREE.Vector3(0.55, -1, 0.5).normalize();
  const forward = direction.clone().negate();
  const right = new THREE.Vector3().crossVectors(forward, camera.up).normalize();
  const up = new THREE.Vector3().crossVectors(right, forward);
  const tanV = Math.tan((camera.fov * Math.PI) / 360) * 0.9;
  const tanH = tanV * camera.aspect;
  const points = framedPoints(THREE);
  const centre = new THREE.Box3().setFromPoints(points).getCenter(new THREE.Vector3());
  const q = new THREE.Vector3();
  let distance = 0;
  for (let round = 0; round < 4; round++) {
    distance = 0;
    for (const p of points) {
      q.subVectors(p, centre);
      const z = q.dot(forward);
      distance = Math.max(distance, Math.abs(q.dot(right)) / tanH - z, Math.abs(q.dot(up)) / tanV - z);
    }
    distance = Math.max(distance, current.size * 0.3, 0.05);
    if (round === 3) break;
    const span = [Infinity, -Infinity, Infinity, -Infinity];
    for (const p of points) {
      q.subVectors(p, centre);
      const depth = distance + q.dot(forward);
      const x = q.dot(right) / depth;
      const y = q.dot(up) / depth;
      span[0] = Math.min(span[0], x); span[1] = Math.max(span[1], x);
      span[2] = Math.min(span[2], y); span[3] = Math.max(span[3], y);
    }
    centre.addScaledVector(right, ((span[0] + span[1]) / 2) * distance);
    centre.addScaledVector(up, ((span[2] + span[3]) / 2) * distance);
  }
  camera.position.copy(centre).addScaledVector(direction, distance);
  camera.near = distance / 200;
  camera.far = distance * 200;
  camera.updateProjectionMatrix();
  controls.target.copy(centre);
  controls.update();
  current.framed = true;
  draw();
}

// -- showing, picking, selecting -----------------------------------------------------------

function setShown(name, value, quiet) {
  show[name] = value;
  const box = document.querySelector(`[data-show="${name}"]`);
  if (box && box.type === "checkbox") box.checked = value;
  else if (box) box.value = value;
  if (!quiet) applyShown();
}

function applyShown() {
  // the groups' toggles, each link's overlays by scope, the colours
  if (!current) return;
  for (const name of GROUPS) current.groups[name].visible = name === "stand" ? show.visual || show.collision : show[name];
  const counts = { com: 0, inertia: 0, axes: 0, findings: 0 };
  for (const entry of current.links.values()) {
    const { link, objects, marks } = entry;
    for (const kind of ["com", "inertia", "axes"]) {
      if (!marks[kind]) continue;
      marks[kind].visible = inScope(entry, kind);
      if (marks[kind].visible && show[kind]) counts[kind] += 1;
    }
    const tint = tinted(entry);
    if (tint) counts.findings += 1;
    for (const object of objects) {
      const data = object.material.userData || {};
      if (data.tag === "visual") object.material.color.set(tint ? COLOURS[link.severity] : data.own || PLAIN);
      if (data.tag === "collision") object.material.color.set(tint ? COLOURS[link.severity] : COLLISION);
    }
  }
  // many boxes filled would hide the robot behind their tint: past FILLS, their edges only
  for (const entry of current.links.values()) {
    if (entry.marks.fill) entry.marks.fill.visible = counts.inertia <= FILLS || current.selected === entry.link.name;
  }
  // how many of each overlay are drawn (for tests and the curious)
  $("view").dataset.overlays = OVERLAYS.map((kind) => `${kind} ${counts[kind]}`).join(", ");
  for (const material of current.marks) {
    const { flagged, plain } = material.userData;
    material.color.set(show.findings && flagged ? flagged : plain);
  }
  highlight();
  draw();
}

function highlight() {
  // the selected link glows and gets a dark frame around what is shown of it
  const { THREE } = view;
  if (current.outline) {
    current.root.remove(current.outline);
    current.outline.geometry.dispose();
    current.outline = null;
  }
  for (const { objects } of current.links.values()) {
    for (const object of objects) if (object.material.emissive) object.material.emissive.set("#000000");
  }
  const picked = current.selected && current.links.get(current.selected);
  if (!picked) return;
  const box = new THREE.Box3();
  for (const object of picked.objects) {
    if (object.material.emissive) object.material.emissive.set("#3a3f4c");
    if (shown(object) && !object.userData.overlay) box.expandByObject(object);
  }
  if (picked.com && show.com) box.expandByPoint(picked.com);
  if (box.isEmpty() && Array.isArray(picked.link.at)) box.expandByPoint(new THREE.Vector3(...picked.link.at.slice(0, 3)));
  box.expandByScalar(current.size / 150);
  current.outline = new THREE.Box3Helper(box, "#101828");
  current.root.add(current.outline);
}

function select(name, from) {
  if (!current) return;
  current.selected = name && current.links.has(name) ? name : null;
  $("view").dataset.selected = current.selected || "";
  applyShown(); // the selected link's overlays, and the highlight
  if (current.selected && from !== "scene") {
    // turn to the link, keeping the distance
    const target = current.outline ? current.outline.box.getCenter(new view.THREE.Vector3()) : null;
    if (target) {
      current.framed = false;
      view.camera.position.add(target.clone().sub(view.controls.target));
      view.controls.target.copy(target);
      view.controls.update();
    }
  }
  draw();
}

function shown(object) {
  for (let up = object; up; up = up.parent) if (!up.visible) return false;
  return true;
}

function visibleHit(hit) {
  return hit.object.isMesh && hit.object.userData.link && shown(hit.object);
}

function pickOnClick(canvas) {
  let down = null;
  canvas.addEventListener("pointerdown", (event) => { down = [event.clientX, event.clientY]; });
  canvas.addEventListener("pointerup", (event) => {
    if (!down || !current || Math.hypot(event.clientX - down[0], event.clientY - down[1]) > 5) return;
    const rect = canvas.getBoundingClientRect();
    const ndc = new view.THREE.Vector2(((event.clientX - rect.left) / rect.width) * 2 - 1,
      -((event.clientY - rect.top) / rect.height) * 2 + 1);
    view.raycaster.setFromCamera(ndc, view.camera);
    const hits = view.raycaster.intersectObject(current.root, true).filter(visibleHit);
    const solid = hits.find((h) => !h.object.material.transparent) || hits[0];
    const name = solid ? solid.object.userData.link : null;
    document.dispatchEvent(new CustomEvent("urdflint:select", { detail: { link: name, from: "scene" } }));
  });
}

// -- the answer -------------------------------------------------------------------------------

function offerSupport(base) {
  // the "support polygon" box is offered for a mobile base whose polygon is known
  const box = document.querySelector("[data-show='support']");
  const label = $("support-toggle");
  if (label.dataset.title === undefined) label.dataset.title = label.title;
  box.disabled = !base;
  label.title = base ? label.dataset.title : "No support polygon: not a mobile base, or its stance is not judged (see the statics)";
}

async function results(detail) {
  const data = detail && detail.scene;
  offerSupport(baseOf(detail && detail.statics));
  const notes = $("view-notes");
  notes.hidden = true;
  if (!data || !Array.isArray(data.links) || !data.links.length) {
    if (current) { dispose(current); current = null; }
    state("none", "No 3D view: the file is not a usable robot (see the findings), or it has over 2000 links.");
    return;
  }
  if (!view && !webgl2()) {
    state("unavailable", "No 3D view: this browser offers no WebGL 2. The tree and the findings have everything it would show.");
    return;
  }
  state("loading", "Drawing…");
  const phases = []; // "step ms" from the answer on: what the time went to
  const mark = (step) => phases.push(`${step} ${Math.round(performance.now() - (detail.started || 0))}`);
  try {
    const lib = await three();
    if (!view) {
      setUp(lib);
      warm();
    }
    await view.warm;
    mark("ready");
    resize(); // the results just appeared: the canvas takes its size before the first frame
    build(data, detail.statics);
    mark("built");
  } catch (problem) {
    state("error", `The 3D view could not be drawn (${problem && problem.message ? problem.message : problem}).`);
    return;
  }
  const missing = data.links.flatMap((l) => [...l.visual, ...l.collision]).filter((s) => s.kind === "mesh" && s.missing);
  const texts = [...(Array.isArray(data.notes) ? data.notes : [])];
  if (missing.length) texts.push(`${missing.length} mesh${missing.length === 1 ? " is" : "es are"} not shown (not found or not readable: see the C findings).`);
  notes.textContent = texts.join(" ");
  notes.hidden = !texts.length;
  await new Promise((done) => requestAnimationFrame(() => requestAnimationFrame(done)));
  state("ready");
  const box = $("view");
  box.dataset.links = String(data.links.length);
  box.dataset.support = current.supportPoints.length ? baseOf(detail.statics).kind : "none";
  box.dataset.triangles = String((data.meshes || []).reduce((n, m) => n + (m.triangles || 0), 0));
  mark("shown");
  box.dataset.phases = phases.join(", ");
  if (typeof detail.started === "number") box.dataset.renderedMs = String(Math.round(performance.now() - detail.started));
}

function project(point) {
  const v = point.clone().project(view.camera);
  const rect = view.renderer.domElement.getBoundingClientRect();
  return { x: rect.left + ((v.x + 1) / 2) * rect.width, y: rect.top + ((1 - v.y) / 2) * rect.height, inside: Math.abs(v.x) <= 1 && Math.abs(v.y) <= 1 };
}

// where things are on the screen (CSS pixels in the viewport), for tests and curious users
window.urdflintView = Object.freeze({
  where(link, what) {
    const found = current && current.links.get(link);
    if (!found) return null;
    if (what === "com") return found.com ? project(found.com) : null;
    const target = what === "inertia" ? found.objects.find((o) => o.material.type === "MeshBasicMaterial") : found.objects[0];
    if (!target) return null;
    return project(new view.THREE.Box3().setFromObject(target).getCenter(new view.THREE.Vector3()));
  },
  support() {
    // the support polygon's corners and the centre of mass's ground point, on the screen
    if (!current || !current.supportPoints.length) return null;
    const points = current.supportPoints.map(project);
    return { corners: points.slice(0, -1), com: points[points.length - 1], shown: show.support };
  },
});

document.addEventListener("urdflint:results", (event) => { results(event.detail); });
document.addEventListener("urdflint:select", (event) => select(event.detail.link, event.detail.from));
// the toggles keep their state from one check to the next
document.querySelectorAll("[data-show]").forEach((box) => box.addEventListener("change", () => {
  setShown(box.dataset.show, box.type === "checkbox" ? box.checked : box.value);
  // a camera the reader has not moved frames what is shown now
  if (current && current.framed && ["overlays", "com", "inertia", "support"].includes(box.dataset.show)) frame();
}));
$("view-reset").addEventListener("click", () => {
  if (!current) return;
  frame();
});
$("check-form").addEventListener("submit", prepare);
$("fix").addEventListener("click", prepare);
state("empty", "Check a robot to see it here: drag to orbit, scroll to zoom, click a link to select it.");
