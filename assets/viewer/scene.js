// The three.js scene of a replay: renderer, camera and lights, one group per layer (LAYERS), and every object
// the frames pose: the arena, the obstacles and terrain, the movers (one buffer placed on the CPU), the agents
// (bodies, headings, trails, capture spheres, obstacle vectors), collision and capture marks, the chosen
// pair's Apollonius surface and optimal cone. buildScene(v) fills the viewer `v` (main.js) with them.

function buildScene(v) {
  var R = v.R, N = v.N, agents = v.agents;

  // --- colours
  var np = 0, ne = 0;
  agents.forEach(function (a) {
    var hex = a.role === 'pursuer' ? PURSUER_COLORS[np++ % PURSUER_COLORS.length]
      : a.role === 'evader' ? EVADER_COLORS[ne++ % EVADER_COLORS.length] : OTHER_COLOR;
    a.color = new THREE.Color(hex);
  });

  // --- renderer, scene, camera
  var host = $('peg-canvas-host');
  var renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(Math.min(window.devicePixelRatio || 1, 2));
  renderer.setClearColor(0x1c1f23, 1);
  host.appendChild(renderer.domElement);
  renderer.domElement.addEventListener('webglcontextlost', function (ev) {
    ev.preventDefault();
    showMessage('The WebGL context was lost', 'Reload the page to draw the replay again.', false);
  }, false);
  renderer.domElement.addEventListener('webglcontextrestored', function () {
    hideMessage();
    document.body.classList.remove('peg-failed');
    v.dirty = true;
  }, false);

  var scene = new THREE.Scene();
  scene.background = new THREE.Color(0x1c1f23);

  var lo = new THREE.Vector3().fromArray(R.arena.lo), hi = new THREE.Vector3().fromArray(R.arena.hi);
  var centre = lo.clone().add(hi).multiplyScalar(0.5);
  var extent = hi.clone().sub(lo);
  var diag = Math.max(extent.length(), 1);

  var camera = new THREE.PerspectiveCamera(45, 1, diag / 2000, diag * 60);
  camera.up.set(0, 0, 1);
  var homeOffset = new THREE.Vector3(-0.5, -1.0, 0.6).normalize().multiplyScalar(diag * 1.3);
  camera.position.copy(centre).add(homeOffset);
  camera.lookAt(centre);

  var controls = new THREE.OrbitControls(camera, renderer.domElement);
  controls.target.copy(centre);
  controls.enableKeys = false;         // the page's keys drive the replay
  controls.screenSpacePanning = true;
  controls.update();

  var hemi = new THREE.HemisphereLight(0xdfe8f2, 0x3b3329, 0.6);
  hemi.position.set(0, 0, 1);
  scene.add(hemi);
  var sun = new THREE.DirectionalLight(0xffffff, 0.6);
  sun.position.copy(centre).add(new THREE.Vector3(0.45, -0.6, 1).normalize().multiplyScalar(diag));
  sun.target.position.copy(centre);
  scene.add(sun);
  scene.add(sun.target);

  // --- layers: one group each; a layer's visibility is its group's, data-driven visibility lives below it
  var layerGroups = {};
  var layerOn = {};
  LAYERS.forEach(function (name) {
    var g = new THREE.Group();
    g.name = 'layer:' + name;
    layerGroups[name] = g;
    scene.add(g);
  });

  var unitSphere = new THREE.SphereBufferGeometry(1, 32, 20);
  var unitCylinder = new THREE.CylinderBufferGeometry(1, 1, 1, 40, 1, false);
  unitCylinder.rotateX(Math.PI / 2);     // axis along z, centred
  var unitCylinderBase = unitCylinder.clone();
  unitCylinderBase.translate(0, 0, 0.5); // axis along z, base disc centre at the origin
  var clampScale = function (v) { return Math.max(TINY, v); };

  // --- arena: box edges and a floor grid
  (function () {
    var box = new THREE.BoxBufferGeometry(Math.max(extent.x, TINY), Math.max(extent.y, TINY), Math.max(extent.z, TINY));
    var edges = new THREE.LineSegments(new THREE.EdgesGeometry(box), new THREE.LineBasicMaterial({ color: 0x8fa3b8 }));
    edges.position.copy(centre);
    layerGroups.arena.add(edges);
    var span = Math.max(extent.x, extent.y);
    var steps = [0.5, 1, 2, 5, 10, 20, 50, 100, 200, 500, 1000];
    var step = steps[steps.length - 1];
    for (var i = 0; i < steps.length; ++i) { if (span / steps[i] <= 24) { step = steps[i]; break; } }
    var pts = [];
    var z = lo.z;
    for (var x = Math.ceil(lo.x / step) * step; x <= hi.x + 1e-9; x += step) { pts.push(x, lo.y, z, x, hi.y, z); }
    for (var y = Math.ceil(lo.y / step) * step; y <= hi.y + 1e-9; y += step) { pts.push(lo.x, y, z, hi.x, y, z); }
    if (pts.length > 0) {
      var g = new THREE.BufferGeometry();
      g.setAttribute('position', new THREE.Float32BufferAttribute(pts, 3));
      var grid = new THREE.LineSegments(g, new THREE.LineBasicMaterial({ color: 0x3a424c, transparent: true, opacity: 0.8 }));
      layerGroups.arena.add(grid);
    }
  })();

  // --- static obstacles
  var obstacleMat = new THREE.MeshPhongMaterial({ color: 0x8593a0, shininess: 18 });
  R.spheres.forEach(function (s) {
    if (!(s.radius > 0)) return;
    var m = new THREE.Mesh(unitSphere, obstacleMat);
    m.position.fromArray(s.center);
    m.scale.setScalar(s.radius);
    layerGroups.obstacles.add(m);
  });
  R.cylinders.forEach(function (c) {
    if (!(c.radius > 0) || !(c.height > 0)) return;
    var m = new THREE.Mesh(unitCylinderBase, obstacleMat);
    m.position.fromArray(c.base);
    m.scale.set(c.radius, c.radius, c.height);
    layerGroups.obstacles.add(m);
  });

  // --- terrain meshes
  var terrainMat = new THREE.MeshLambertMaterial({ color: 0x7d6a4f, side: THREE.DoubleSide });
  var drawnTriangles = 0;
  R.meshes.forEach(function (m) {
    var nv = (m.positions.length / 3) | 0;
    if (nv < 3) return;
    var g = new THREE.BufferGeometry();
    g.setAttribute('position', new THREE.BufferAttribute(m.positions.length === nv * 3 ? m.positions : m.positions.slice(0, nv * 3), 3));
    if (m.indices.length >= 3) {
      var ni = m.indices.length - m.indices.length % 3;
      var idx = ni === m.indices.length ? m.indices : m.indices.slice(0, ni);
      var bad = false;
      for (var i = 0; i < idx.length; ++i) { if (idx[i] >= nv) { bad = true; break; } }
      if (bad) return;  // indices outside the vertices: not drawable
      g.setIndex(new THREE.BufferAttribute(idx, 1));
      drawnTriangles += ni / 3;
    } else {
      drawnTriangles += Math.floor(nv / 3);
    }
    g.computeVertexNormals();
    var mesh = new THREE.Mesh(g, terrainMat);
    mesh.name = m.name;
    layerGroups.terrain.add(mesh);
  });

  // --- moving obstacles
  var moverMat = new THREE.MeshPhongMaterial({ color: 0xa77bd6, shininess: 25 });
  // Every mover's vertices in one buffer, placed on the CPU each frame: one draw call however many movers
  // there are (software WebGL spends tens of microseconds per draw or instance; a JavaScript loop over the
  // vertices costs less).
  var moverTemplates = {
    sphere: new THREE.SphereBufferGeometry(1, 16, 10),
    cylinder: unitCylinder,
    box: new THREE.BoxBufferGeometry(1, 1, 1)
  };
  var moverVertices = 0, moverIndices = 0;
  var movers = R.movers.map(function (m) {
    var kind = m.shape === 'box' || m.shape === 'cylinder' ? m.shape : 'sphere';
    var scale = new THREE.Vector3(1, 1, 1);
    if (kind === 'box') {
      scale.set(Math.max(m.size[0], TINY), Math.max(m.size[1], TINY), Math.max(m.size[2], TINY));
    } else if (kind === 'cylinder') {
      scale.set(clampScale(m.radius), clampScale(m.radius), clampScale(m.height));
    } else {
      scale.setScalar(clampScale(m.radius));
    }
    var t = moverTemplates[kind];
    var entry = { template: t, first: moverVertices, scale: scale, poses: m.poses, count: (m.poses.length / 7) | 0 };
    moverVertices += t.attributes.position.count;
    moverIndices += t.index.count;
    return entry;
  });
  var moverPos = new Float32Array(3 * moverVertices), moverNrm = new Float32Array(3 * moverVertices);
  var moverIdx = moverVertices > 65535 ? new Uint32Array(moverIndices) : new Uint16Array(moverIndices);
  (function () {
    var k = 0;
    movers.forEach(function (m) {
      var idx = m.template.index.array;
      for (var i = 0; i < idx.length; ++i) moverIdx[k++] = idx[i] + m.first;
    });
  })();
  var moverGeom = new THREE.BufferGeometry();
  moverGeom.setAttribute('position', new THREE.BufferAttribute(moverPos, 3).setUsage(THREE.DynamicDrawUsage));
  moverGeom.setAttribute('normal', new THREE.BufferAttribute(moverNrm, 3).setUsage(THREE.DynamicDrawUsage));
  moverGeom.setIndex(new THREE.BufferAttribute(moverIdx, 1));
  var moverMesh = new THREE.Mesh(moverGeom, moverMat);
  moverMesh.frustumCulled = false;  // the movers spread over the arena and move
  layerGroups.movers.add(moverMesh);
  var moverMatrix = new THREE.Matrix4(), hiddenScale = new THREE.Vector3(TINY, TINY, TINY);
  // Writes mover m's vertices at its pose (normals rotated only: the shapes' scalings keep their face
  // directions); a mover without a finite pose shrinks out of sight.
  function placeMover(m, position, quaternion, visible) {
    moverMatrix.compose(position, quaternion, visible ? m.scale : hiddenScale);
    var e = moverMatrix.elements;
    var tp = m.template.attributes.position.array, tn = m.template.attributes.normal.array;
    var qx = quaternion.x, qy = quaternion.y, qz = quaternion.z, qw = quaternion.w;
    for (var i = 0, o = 3 * m.first; i < tp.length; i += 3, o += 3) {
      var x = tp[i], y = tp[i + 1], z = tp[i + 2];
      moverPos[o] = e[0] * x + e[4] * y + e[8] * z + e[12];
      moverPos[o + 1] = e[1] * x + e[5] * y + e[9] * z + e[13];
      moverPos[o + 2] = e[2] * x + e[6] * y + e[10] * z + e[14];
      // n' = q n q*, expanded
      var nx = tn[i], ny = tn[i + 1], nz = tn[i + 2];
      var ix = qw * nx + qy * nz - qz * ny, iy = qw * ny + qz * nx - qx * nz;
      var iz = qw * nz + qx * ny - qy * nx, iw = -qx * nx - qy * ny - qz * nz;
      moverNrm[o] = ix * qw + iw * -qx + iy * -qz - iz * -qy;
      moverNrm[o + 1] = iy * qw + iw * -qy + iz * -qx - ix * -qz;
      moverNrm[o + 2] = iz * qw + iw * -qz + ix * -qy - iy * -qx;
    }
  }
  var origin = new THREE.Vector3(), identity = new THREE.Quaternion();
  movers.forEach(function (m) { placeMover(m, origin, identity, false); });

  // --- agents: body, screen-size dot, heading arrow, trail, capture sphere, obstacle vector
  var maxRadius = agents.reduce(function (r, a) { return Math.max(r, a.radius); }, 0);
  var trailK = Math.max(1, Math.ceil(N / TRAIL_POINTS));
  var trailM = Math.floor((N - 1) / trailK) + 1;
  var tmpA = new THREE.Vector3(), tmpB = new THREE.Vector3(), tmpD = new THREE.Vector3(), tmpE = new THREE.Vector3();
  var inactiveMat = new THREE.MeshPhongMaterial({ color: 0x6b7078, transparent: true, opacity: 0.35, depthWrite: false });
  var captureMat = new THREE.MeshBasicMaterial({ color: 0xff7a6b, transparent: true, opacity: 0.1, depthWrite: false });
  var captureWireMat = new THREE.MeshBasicMaterial({ color: 0xff7a6b, wireframe: true, transparent: true, opacity: 0.12, depthWrite: false });

  agents.forEach(function (a) {
    a.cur = new THREE.Vector3();
    a.dir = new THREE.Vector3(1, 0, 0);
    a.activeNow = true;
    a.bodyMat = new THREE.MeshPhongMaterial({ color: a.color, shininess: 40 });
    a.body = new THREE.Mesh(unitSphere, a.bodyMat);
    a.body.scale.setScalar(clampScale(a.radius));
    var dotGeom = new THREE.BufferGeometry();
    dotGeom.setAttribute('position', new THREE.Float32BufferAttribute([0, 0, 0], 3));
    a.dot = new THREE.Points(dotGeom, new THREE.PointsMaterial({ color: a.color, size: 6, sizeAttenuation: false }));
    a.dot.frustumCulled = false;
    a.body.add(a.dot);
    layerGroups.agents.add(a.body);
    var arrowLen = Math.max(1.2, 4 * a.radius);
    a.arrow = new THREE.ArrowHelper(new THREE.Vector3(1, 0, 0), new THREE.Vector3(), arrowLen,
      a.color.clone().lerp(new THREE.Color(0xffffff), 0.35).getHex(), 0.28 * arrowLen, 0.13 * arrowLen);
    layerGroups.agents.add(a.arrow);

    // Trail: decimated whole path (every trailK-th frame) plus a spare slot; the slot just after the last
    // decimated point at or before the current frame is overwritten by the exact current position.
    var arr = new Float32Array((trailM + 1) * 3);
    for (var j = 0; j < trailM; ++j) {
      read3(a.pos, j * trailK, tmpA);
      if (!finite3(tmpA)) tmpA.set(0, 0, 0);
      arr[3 * j] = tmpA.x; arr[3 * j + 1] = tmpA.y; arr[3 * j + 2] = tmpA.z;
    }
    arr[3 * trailM] = arr[3 * trailM - 3]; arr[3 * trailM + 1] = arr[3 * trailM - 2]; arr[3 * trailM + 2] = arr[3 * trailM - 1];
    var attr = new THREE.BufferAttribute(arr, 3);
    attr.setUsage(THREE.DynamicDrawUsage);
    var tg = new THREE.BufferGeometry();
    tg.setAttribute('position', attr);
    tg.setDrawRange(0, 1);
    var line = new THREE.Line(tg, new THREE.LineBasicMaterial({ color: a.color, transparent: true, opacity: 0.85 }));
    line.frustumCulled = false;
    layerGroups.trails.add(line);
    a.trail = { arr: arr, attr: attr, geom: tg, patched: -1, saved: [0, 0, 0] };

    if (a.role === 'pursuer' && R.captureDistance > 0) {
      a.captureSphere = new THREE.Mesh(unitSphere, captureMat);
      a.captureSphere.scale.setScalar(R.captureDistance);
      var wire = new THREE.Mesh(new THREE.SphereBufferGeometry(1, 16, 10), captureWireMat);
      a.captureSphere.add(wire);
      layerGroups.capture.add(a.captureSphere);
    }

    var og = new THREE.BufferGeometry();
    var oattr = new THREE.BufferAttribute(new Float32Array(6), 3);
    oattr.setUsage(THREE.DynamicDrawUsage);
    og.setAttribute('position', oattr);
    a.obstacleLine = new THREE.Line(og, new THREE.LineBasicMaterial({ color: a.color.clone().lerp(new THREE.Color(0xffffaa), 0.6) }));
    a.obstacleLine.frustumCulled = false;
    a.obstacleAttr = oattr;
    layerGroups.obstacle_vectors.add(a.obstacleLine);
  });

  // --- sight: for each agent with limited sight, the line to where it takes its opponent to be (green while it
  // sees it, red dashed while hidden), the ghost of a hidden opponent at its estimate, and its field of view as a
  // cone 3 m long about its heading (below 180 degrees)
  var seenMat = new THREE.LineBasicMaterial({ color: 0x5ee08e });
  var hiddenMat = new THREE.LineDashedMaterial({ color: 0xff5a4f, dashSize: 0.4, gapSize: 0.3 });
  agents.forEach(function (a) {
    if (!a.sight) return;
    var g = new THREE.BufferGeometry();
    var attr = new THREE.BufferAttribute(new Float32Array(6), 3);
    attr.setUsage(THREE.DynamicDrawUsage);
    g.setAttribute('position', attr);
    a.sightLine = new THREE.Line(g, seenMat);
    a.sightLine.frustumCulled = false;
    a.sightAttr = attr;
    a.seenMat = seenMat;
    a.hiddenMat = hiddenMat;
    layerGroups.sight.add(a.sightLine);
    a.ghost = new THREE.Mesh(new THREE.SphereBufferGeometry(1, 12, 8), new THREE.MeshBasicMaterial({
      color: 0xffffff, wireframe: true, transparent: true, opacity: 0.6, depthWrite: false }));
    a.ghost.visible = false;
    layerGroups.sight.add(a.ghost);
    if (a.sight.fov < 180) {
      var half = a.sight.fov * Math.PI / 360, len = 3;
      var cone = new THREE.ConeBufferGeometry(len * Math.tan(half), len, 24, 1, true);
      cone.translate(0, -len / 2, 0);  // apex at the origin, opening along -y
      a.fovCone = new THREE.Mesh(cone, new THREE.MeshBasicMaterial({ color: a.color, transparent: true, opacity: 0.12,
        side: THREE.DoubleSide, depthWrite: false }));
      layerGroups.sight.add(a.fovCone);
    }
  });

  // --- sensing: the selected agent's rays (echoes bright, rays that met nothing dim) and each sensing agent's
  // own map, its occupied cells as instanced cubes that appear and vanish as the flips say (timeline.js)
  var mostRays = agents.reduce(function (r, a) { return Math.max(r, a.lidar ? a.lidar.rays : 0); }, 0);
  var rayPos = new THREE.BufferAttribute(new Float32Array(Math.max(1, mostRays) * 6), 3);
  var rayCol = new THREE.BufferAttribute(new Float32Array(Math.max(1, mostRays) * 6), 3);
  rayPos.setUsage(THREE.DynamicDrawUsage);
  rayCol.setUsage(THREE.DynamicDrawUsage);
  var rayGeom = new THREE.BufferGeometry();
  rayGeom.setAttribute('position', rayPos);
  rayGeom.setAttribute('color', rayCol);
  rayGeom.setDrawRange(0, 0);
  var rayLines = new THREE.LineSegments(rayGeom, new THREE.LineBasicMaterial({
    vertexColors: THREE.VertexColors, transparent: true, opacity: 0.8 }));
  rayLines.frustumCulled = false;
  rayLines.visible = false;
  layerGroups.sensing.add(rayLines);
  agents.forEach(function (a) {
    if (!a.map) return;
    var cells = 0;  // at most every cell that ever becomes occupied is shown at once
    for (var k = 0; k < a.map.occupied.length; ++k) cells += a.map.occupied[k];
    var box = new THREE.BoxBufferGeometry(a.map.resolution, a.map.resolution, a.map.resolution);
    var mesh = new THREE.InstancedMesh(box, new THREE.MeshPhongMaterial({
      color: a.color.clone().lerp(new THREE.Color(0xffffff), 0.25), transparent: true, opacity: 0.55 }), Math.max(1, cells));
    mesh.count = 0;
    mesh.frustumCulled = false;
    mesh.visible = false;
    layerGroups.sensing.add(mesh);
    // applied: flips shown so far; slot: cell -> instance; cell: instance -> cell
    a.mapView = { mesh: mesh, applied: 0, slot: new Map(), cell: [], matrix: new THREE.Matrix4() };
  });

  // --- collisions: crosses and screen-size dots, in frame order, shown through a draw range
  var collisionFrames = new Float64Array(R.collisions.map(function (c) { return c.frame; }));
  var collisionCross = null, collisionDots = null;
  if (R.collisions.length > 0) {
    var h = Math.max(0.25, 1.2 * maxRadius);
    var cross = new Float32Array(R.collisions.length * 18);
    var dots = new Float32Array(R.collisions.length * 3);
    R.collisions.forEach(function (c, i) {
      var p = c.point, o = 18 * i;
      var segs = [[h, 0, 0], [0, h, 0], [0, 0, h]];
      for (var s = 0; s < 3; ++s) {
        for (var q = 0; q < 3; ++q) {
          cross[o + 6 * s + q] = p[q] - segs[s][q];
          cross[o + 6 * s + 3 + q] = p[q] + segs[s][q];
        }
      }
      dots[3 * i] = p[0]; dots[3 * i + 1] = p[1]; dots[3 * i + 2] = p[2];
    });
    var cg = new THREE.BufferGeometry();
    cg.setAttribute('position', new THREE.BufferAttribute(cross, 3));
    collisionCross = new THREE.LineSegments(cg, new THREE.LineBasicMaterial({ color: 0xffe94d }));
    collisionCross.frustumCulled = false;
    var dg = new THREE.BufferGeometry();
    dg.setAttribute('position', new THREE.BufferAttribute(dots, 3));
    collisionDots = new THREE.Points(dg, new THREE.PointsMaterial({ color: 0xffe94d, size: 7, sizeAttenuation: false }));
    collisionDots.frustumCulled = false;
    layerGroups.collisions.add(collisionCross);
    layerGroups.collisions.add(collisionDots);
  }

  // --- captures: a gold sphere of the capture radius at the evader and the P-E segment, from their frame on
  var captureMarks = R.captures.map(function (c) {
    var g = new THREE.Group();
    var e = agents[c.evader], p = agents[c.pursuer];
    if (e) read3(e.pos, c.frame, tmpA); else tmpA.set(NaN, NaN, NaN);
    if (!finite3(tmpA)) return { frame: c.frame, obj: null };
    g.position.copy(tmpA);
    var r = R.captureDistance > 0 ? R.captureDistance : Math.max(0.3, 2 * maxRadius);
    var s = new THREE.Mesh(new THREE.SphereBufferGeometry(1, 24, 14),
      new THREE.MeshBasicMaterial({ color: 0xffd23f, wireframe: true, transparent: true, opacity: 0.7, depthWrite: false }));
    s.scale.setScalar(r);
    g.add(s);
    var dg2 = new THREE.BufferGeometry();
    dg2.setAttribute('position', new THREE.Float32BufferAttribute([0, 0, 0], 3));
    var dot = new THREE.Points(dg2, new THREE.PointsMaterial({ color: 0xffd23f, size: 11, sizeAttenuation: false }));
    dot.frustumCulled = false;
    g.add(dot);
    if (p) {
      read3(p.pos, c.frame, tmpB);
      if (finite3(tmpB)) {
        tmpB.sub(tmpA);
        var lg = new THREE.BufferGeometry();
        lg.setAttribute('position', new THREE.Float32BufferAttribute([0, 0, 0, tmpB.x, tmpB.y, tmpB.z], 3));
        var l = new THREE.Line(lg, new THREE.LineBasicMaterial({ color: 0xffd23f }));
        l.frustumCulled = false;
        g.add(l);
      }
    }
    g.visible = false;
    layerGroups.capture.add(g);
    return { frame: c.frame, obj: g };
  });

  // --- Apollonius surface and optimal cone of the chosen pair
  var planeSize = diag * 1.2;
  var apoColor = 0x6cf2a0;
  var apoSphere = new THREE.Mesh(new THREE.SphereBufferGeometry(1, 32, 16),
    new THREE.MeshBasicMaterial({ color: apoColor, wireframe: true, transparent: true, opacity: 0.22, depthWrite: false }));
  apoSphere.visible = false;
  layerGroups.apollonius.add(apoSphere);
  var planeGeom = new THREE.PlaneBufferGeometry(1, 1, 8, 8);
  var apoPlane = new THREE.Mesh(planeGeom, new THREE.MeshBasicMaterial({
    color: apoColor, transparent: true, opacity: 0.14, side: THREE.DoubleSide, depthWrite: false }));
  apoPlane.add(new THREE.LineSegments(new THREE.EdgesGeometry(planeGeom),
    new THREE.LineBasicMaterial({ color: apoColor, transparent: true, opacity: 0.6 })));
  apoPlane.scale.set(planeSize, planeSize, 1);
  apoPlane.visible = false;
  layerGroups.apollonius.add(apoPlane);

  var coneColor = 0xffb347;
  var coneGroup = new THREE.Group();
  var coneGeom = new THREE.ConeBufferGeometry(1, 1, 48, 1, true);
  coneGeom.translate(0, -0.5, 0);  // apex at the origin, opening along -y, base disc at y = -1
  var coneMesh = new THREE.Mesh(coneGeom, new THREE.MeshBasicMaterial({
    color: coneColor, transparent: true, opacity: 0.18, side: THREE.DoubleSide, depthWrite: false }));
  var rimPts = [];
  for (var ri = 0; ri < 64; ++ri) {
    var ang = 2 * Math.PI * ri / 64;
    rimPts.push(Math.cos(ang), -1, Math.sin(ang));
  }
  var rimGeom = new THREE.BufferGeometry();
  rimGeom.setAttribute('position', new THREE.Float32BufferAttribute(rimPts, 3));
  coneMesh.add(new THREE.LineLoop(rimGeom, new THREE.LineBasicMaterial({ color: coneColor, transparent: true, opacity: 0.7 })));
  coneGroup.add(coneMesh);
  var axisGeom = new THREE.BufferGeometry();
  axisGeom.setAttribute('position', new THREE.Float32BufferAttribute([0, 0, 0, 0, -CONE_LENGTH, 0], 3));
  coneGroup.add(new THREE.Line(axisGeom, new THREE.LineBasicMaterial({ color: coneColor })));
  coneGroup.visible = false;
  layerGroups.cone.add(coneGroup);
  var downY = new THREE.Vector3(0, -1, 0), upZ = new THREE.Vector3(0, 0, 1);

  v.host = host;
  v.renderer = renderer;
  v.scene = scene;
  v.camera = camera;
  v.controls = controls;
  v.centre = centre;
  v.homeOffset = homeOffset;
  v.layerGroups = layerGroups;
  v.layerOn = layerOn;
  v.drawnTriangles = drawnTriangles;
  v.movers = movers;
  v.moverGeom = moverGeom;
  v.placeMover = placeMover;
  v.trailK = trailK;
  v.trailM = trailM;
  v.inactiveMat = inactiveMat;
  v.collisionFrames = collisionFrames;
  v.collisionCross = collisionCross;
  v.collisionDots = collisionDots;
  v.captureMarks = captureMarks;
  v.apoSphere = apoSphere;
  v.apoPlane = apoPlane;
  v.coneGroup = coneGroup;
  v.rayLines = rayLines;
  // The images layer: a picture over the view (its group in the scene stays empty), drawn by updateImage.
  v.imageBox = $('peg-image');
  v.imageCanvas = $('peg-image-canvas');
  v.imageCaption = $('peg-image-caption');
  v.imageData = null;
  v.imageShown = null;
  v.coneMesh = coneMesh;
  v.downY = downY;
  v.upZ = upZ;
  // Scratch for posing a frame and for the panel (never kept between calls).
  v.tmpA = tmpA;
  v.tmpB = tmpB;
  v.tmpD = tmpD;
  v.tmpE = tmpE;
  v.qa = new THREE.Quaternion();
  v.qb = new THREE.Quaternion();
}
