// stiffid's 3D scene viewer: the scene document (JSON, SI, base frame z up) drawn with three.js
// and its orbit controls, both read from this page (no file or address outside it).
const text = (id) => document.getElementById(id).textContent;
const blob = (s) => URL.createObjectURL(new Blob([s], { type: 'text/javascript' }));
const core = blob(text('stiffid-three-core'));
const mod = blob(text('stiffid-three').split('"./three.core.min.js"').join(JSON.stringify(core)));
const orbit = blob(text('stiffid-orbit').split("'three'").join(JSON.stringify(mod)));
const THREE = await import(mod);
const { OrbitControls } = await import(orbit);

for (const root of document.querySelectorAll('.stiffid-scene')) {
  draw(root, JSON.parse(document.getElementById(root.dataset.scene).textContent));
}

function draw(root, scene) {
  const view = root.querySelector('.view');
  const width = view.clientWidth || 900, height = view.clientHeight || 560;
  const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(window.devicePixelRatio || 1);
  renderer.setSize(width, height);
  view.appendChild(renderer.domElement);
  const world = new THREE.Scene();
  world.background = new THREE.Color(0xf4f5f7);
  world.add(new THREE.HemisphereLight(0xffffff, 0x667788, 2.2));
  const sun = new THREE.DirectionalLight(0xffffff, 1.6);
  sun.position.set(3, -4, 6);
  world.add(sun);

  const postures = scene.postures;
  const v3 = (a) => new THREE.Vector3(a[0], a[1], a[2]);
  // The robot: one geometry per link shape, one group per posture.
  const geometries = scene.links.map((l) => l.geometry.map((g) => {
    const b = new THREE.BufferGeometry();
    b.setAttribute('position', new THREE.Float32BufferAttribute(g.positions_m.flat(), 3));
    b.setIndex(g.triangles.flat());
    const flat = b.toNonIndexed();
    flat.computeVertexNormals();
    return flat;
  }));
  const material = (colour, ghost) => new THREE.MeshStandardMaterial({
    color: colour, metalness: 0.1, roughness: 0.65, side: THREE.DoubleSide,
    transparent: ghost, opacity: ghost ? 0.22 : 1, depthWrite: !ghost,
  });
  // Solid and ghosted materials of the robot, the tool and the external axes' parts.
  const materials = {
    robot: [material(0xb8bcc6, false), material(0x8a93a6, true)],
    tool: [material(0xf08c1a, false), material(0xf08c1a, true)],
    axis: [material(0x5f7fa8, false), material(0x5f7fa8, true)],
    obstacle: [false, true].map((ghost) => new THREE.MeshStandardMaterial({
      color: 0x6b8fb3, transparent: true, opacity: ghost ? 0.2 : 0.45, depthWrite: false,
    })),
  };
  // An obstacle's box between its corners, in its own frame (the base frame without frames).
  const obstacleBox = (o) => {
    const s = v3(o.max_m).sub(v3(o.min_m));
    const m = new THREE.Mesh(new THREE.BoxGeometry(s.x, s.y, s.z), materials.obstacle[0]);
    m.position.copy(v3(o.min_m).add(v3(o.max_m)).multiplyScalar(0.5));
    m.userData.kind = 'obstacle';
    return m;
  };
  const axisParts = ['track', 'carriage', 'positioner table'];
  const kind = (l) => (l.part === 'tool' ? 'tool' : axisParts.includes(l.part) ? 'axis' : 'robot');
  const robots = postures.map((p, i) => {
    const g = new THREE.Group();
    // The boxes that move with the external axes, where this posture's values put them.
    for (const o of scene.obstacles.filter((b) => b.frames.length)) {
      const f = o.frames[i];
      const at = new THREE.Group();
      at.position.copy(v3(f.translation_m));
      at.quaternion.set(...f.rotation_xyzw);
      at.add(obstacleBox(o));
      g.add(at);
    }
    scene.links.forEach((l, k) => {
      const f = p.link_frames[k];
      const link = new THREE.Group();
      link.position.copy(v3(f.translation_m));
      link.quaternion.set(...f.rotation_xyzw);
      for (const geo of geometries[k]) {
        const m = new THREE.Mesh(geo, materials[kind(l)][0]);
        m.userData.kind = kind(l);
        link.add(m);
      }
      g.add(link);
    });
    world.add(g);
    return g;
  });

  // The scene's bounds: the robot's shapes in every posture (not only the link frames' origins,
  // which leave out what stands above them), the tool points, the cell and the path.
  const box = new THREE.Box3();
  world.updateMatrixWorld(true);
  for (const g of robots) box.expandByObject(g);
  for (const p of postures) box.expandByPoint(v3(p.tcp_m));
  if (scene.tracker_m) box.expandByPoint(v3(scene.tracker_m));
  if (scene.anchor_m) box.expandByPoint(v3(scene.anchor_m));
  for (const o of scene.obstacles.filter((b) => !b.frames.length)) { box.expandByPoint(v3(o.min_m)); box.expandByPoint(v3(o.max_m)); }
  for (const q of scene.path) box.expandByPoint(v3(q.at_m));
  const size = Math.max(box.getSize(new THREE.Vector3()).length(), 0.5);
  const centre = box.getCenter(new THREE.Vector3());

  // Displacements are drawn magnified: the largest arrow or ellipsoid about a sixth of the scene.
  let largest = 0;
  for (const p of postures) {
    for (const a of p.arrows) for (const d of [a.measured_m, a.predicted_m]) if (d) largest = Math.max(largest, v3(d).length());
    if (p.ellipsoid) largest = Math.max(largest, ...p.ellipsoid.semi_axes_m);
  }
  const gain = largest > 0 ? nice(size / 6 / largest) : 1;

  // The cell.
  const lineMaterial = (colour) => new THREE.LineBasicMaterial({ color: colour });
  const segment = (a, b, colour) => new THREE.Line(new THREE.BufferGeometry().setFromPoints([v3(a), v3(b)]), lineMaterial(colour));
  const ball = (at, radius, colour) => {
    const m = new THREE.Mesh(new THREE.SphereGeometry(radius, 20, 12), new THREE.MeshStandardMaterial({ color: colour }));
    m.position.copy(v3(at));
    return m;
  };
  const floorZ = scene.floor_z_m ?? box.min.z;
  const grid = new THREE.GridHelper(Math.ceil(size), Math.ceil(size) * 4, 0x9aa3b0, 0xd0d5dc);
  grid.rotation.x = Math.PI / 2;
  grid.position.set(centre.x, centre.y, floorZ);
  world.add(grid);
  for (const o of scene.obstacles.filter((b) => !b.frames.length)) world.add(obstacleBox(o));
  if (scene.tracker_m) world.add(ball(scene.tracker_m, 0.06, 0x2b7a2b));
  if (scene.anchor_m) world.add(ball(scene.anchor_m, 0.04, 0x444444));

  // What each posture adds: lines of sight, rope, ellipsoid, arrows.
  const sightColour = (m) => (m < 0 ? 0xd62728 : m < 0.05 ? 0xff9900 : 0x2ca02c);
  const overlays = postures.map((p) => {
    const g = new THREE.Group();
    if (scene.tracker_m) for (const s of p.sights) g.add(segment(scene.tracker_m, s.to_m, sightColour(s.margin_m)));
    if (scene.anchor_m) { g.add(segment(p.loading_point_m, scene.anchor_m, 0x333333)); g.add(ball(p.loading_point_m, 0.02, 0x333333)); }
    if (p.ellipsoid) {
      const e = p.ellipsoid;
      const m = new THREE.Mesh(new THREE.SphereGeometry(1, 32, 16),
        new THREE.MeshStandardMaterial({ color: 0x9467bd, transparent: true, opacity: 0.55, depthWrite: false }));
      const basis = new THREE.Matrix4().makeBasis(v3(e.axes[0]), v3(e.axes[1]), v3(e.axes[2]));
      m.quaternion.setFromRotationMatrix(basis);
      m.scale.set(...e.semi_axes_m.map((s) => Math.max(s * gain, 1e-4)));
      m.position.copy(v3(e.centre_m));
      g.add(m);
    }
    world.add(g);
    return g;
  });
  // Arrows as solid shafts and heads (a line is one pixel wide whatever the zoom), drawn over the
  // bodies, as thick as the scene's size asks.
  const shaft = new THREE.CylinderGeometry(1, 1, 1, 12), head = new THREE.ConeGeometry(1, 1, 16);
  const thickness = size / 400;
  const arrow = (at, d, colour) => {
    const v = v3(d), n = v.length() * gain;
    if (!(n > 0)) return null;
    const m = new THREE.MeshBasicMaterial({ color: colour, depthTest: false, transparent: true });
    const g = new THREE.Group();
    const h = Math.min(0.3 * n, 8 * thickness), r = Math.min(thickness, 0.08 * n);
    const s = new THREE.Mesh(shaft, m), c = new THREE.Mesh(head, m);
    s.scale.set(r, n - h, r);
    s.position.set(0, (n - h) / 2, 0);
    c.scale.set(2.6 * r, h, 2.6 * r);
    c.position.set(0, n - h / 2, 0);
    g.add(s, c);
    g.quaternion.setFromUnitVectors(new THREE.Vector3(0, 1, 0), v.normalize());
    g.position.copy(v3(at));
    g.renderOrder = 11;
    s.renderOrder = c.renderOrder = 11;
    return g;
  };
  const arrows = postures.map((p) => {
    const g = new THREE.Group();
    for (const a of p.arrows) {
      for (const [d, colour] of [[a.measured_m, 0x1f77b4], [a.predicted_m, 0xd62728]]) {
        const drawn = d && arrow(a.at_m, d, colour);
        if (drawn) g.add(drawn);
      }
    }
    world.add(g);
    return g;
  });

  // The path, coloured by its predicted error.
  let errors = null;
  if (scene.path.length > 1) {
    const e = scene.path.map((q) => q.error_m);
    errors = [Math.min(...e), Math.max(...e)];
    const span = errors[1] - errors[0] || 1;
    const colours = scene.path.flatMap((q) => ramp((q.error_m - errors[0]) / span));
    const b = new THREE.BufferGeometry().setFromPoints(scene.path.map((q) => v3(q.at_m)));
    b.setAttribute('color', new THREE.Float32BufferAttribute(colours, 3));
    // Drawn over the bodies: the tool's capsule holds the tool centre point.
    const line = new THREE.Line(b, new THREE.LineBasicMaterial({ vertexColors: true, depthTest: false }));
    line.renderOrder = 10;
    world.add(line);
  }

  // Camera and controls: z up, looking at the scene's centre from the front right.
  const camera = new THREE.PerspectiveCamera(40, width / height, size / 1000, size * 20);
  camera.up.set(0, 0, 1);
  camera.position.copy(centre).add(new THREE.Vector3(1.1, -1.5, 0.8).normalize().multiplyScalar(size * 1.4));
  const controls = new OrbitControls(camera, renderer.domElement);
  controls.target.copy(centre);
  controls.update();

  // The posture selector: one at a time, or all ghosted.
  const select = root.querySelector('select');
  const show = (choice) => {
    const all = choice === 'all';
    robots.forEach((g, i) => {
      const on = all || String(i) === choice;
      g.visible = on;
      g.traverse((m) => { if (m.isMesh) m.material = materials[m.userData.kind][all ? 1 : 0]; });
      overlays[i].visible = !all && on;
      arrows[i].visible = on;
    });
    render();
  };
  select.addEventListener('change', () => show(select.value));

  // The legend and the scale bar.
  const legend = root.querySelector('.legend');
  const rows = [];
  const mm = (x) => `${Number((x * 1e3).toPrecision(3)).toLocaleString('en')} mm`;
  if (largest > 0) rows.push(`displacements and ellipsoids drawn x${gain.toLocaleString('en')}: ${mm(0.1 / gain)} of displacement drawn 100 mm long`);
  const longest = (k) => Math.max(0, ...postures.flatMap((p) => p.arrows.map((a) => (a[k] ? v3(a[k]).length() : 0))));
  if (postures.some((p) => p.arrows.some((a) => a.measured_m))) rows.push(key('#1f77b4', `${scene.arrow_names[0]}, the longest ${mm(longest('measured_m'))}`));
  if (postures.some((p) => p.arrows.some((a) => a.predicted_m))) rows.push(key('#d62728', `${scene.arrow_names[1]}, the longest ${mm(longest('predicted_m'))}`));
  if (postures.some((p) => p.ellipsoid)) rows.push(key('#9467bd', `compliance ellipsoid at the TCP, under ${scene.ellipsoid_force_n.toFixed(0)} N`));
  if (scene.tracker_m) {
    rows.push(key('#2b7a2b', 'tracker; lines of sight by margin:'));
    rows.push(key('#2ca02c', '&ge; 50 mm') + key('#ff9900', '0-50 mm') + key('#d62728', 'blocked'));
  }
  if (scene.anchor_m) rows.push(key('#333333', 'rope from the loading point to the anchor'));
  if (scene.obstacles.length) rows.push(key('#6b8fb3', 'obstacles'));
  const axes = scene.links.filter((l) => kind(l) === 'axis').map((l) => l.name);
  if (axes.length) rows.push(key('#5f7fa8', `external axes: ${axes.join(', ')} at each posture's values`));
  if (errors) rows.push(`path by ${scene.path_error}: <span class="ramp"></span> ${(errors[0] * 1e3).toFixed(3)} to ${(errors[1] * 1e3).toFixed(3)} mm`);
  rows.push(`grid: 0.25 m squares at ${scene.floor_z_m === null ? 'the lowest point' : 'the floor'}, z = ${(floorZ * 1e3).toFixed(0)} mm`);
  legend.innerHTML = rows.map((r) => `<div>${r}</div>`).join('') + scene.notes.map((n) => `<div class="note">${n}</div>`).join('');
  const bar = root.querySelector('.bar'), barText = root.querySelector('.bar-text');
  function render() {
    renderer.render(world, camera);
    const distance = camera.position.distanceTo(controls.target);
    const perMetre = height / (2 * distance * Math.tan((camera.fov * Math.PI) / 360));
    const metres = nice(120 / perMetre);
    bar.style.width = `${metres * perMetre}px`;
    barText.textContent = metres >= 1 ? `${metres} m` : `${Math.round(metres * 1000)} mm`;
  }
  controls.addEventListener('change', render);
  show(select.value);
  root.dataset.ready = 'true';
}

// The nearest of 1, 2, 5 times a power of ten at or below x.
function nice(x) {
  const p = Math.pow(10, Math.floor(Math.log10(x)));
  const m = x / p;
  return (m >= 5 ? 5 : m >= 2 ? 2 : 1) * p;
}

// Blue (0) through green to red (1).
function ramp(t) {
  const c = new THREE.Color();
  c.setHSL((1 - Math.min(Math.max(t, 0), 1)) * 0.66, 0.85, 0.45);
  return [c.r, c.g, c.b];
}

function key(colour, label) {
  return `<span class="key" style="background:${colour}"></span>${label} `;
}
