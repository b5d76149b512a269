/* peg3d replay viewer: the browser side of the self-contained replay page that peg-view and the experiments'
   --html flag write (docs/viewer.md). Plain ES2017 script, no modules. It needs the globals THREE (three.js
   r111) and THREE.OrbitControls, inlined before it, and the replay JSON (schema v1) in
   <script id="peg-replay" type="application/json">.

   URL fragment: open the page as replay.html#t=<seconds> (for example #t=12.5) to start paused at that
   instant; changing the fragment later seeks again.

   Keys: space play/pause, left/right one frame back/forward (shift: 10 frames), Home/End first/last frame.

   Script interface, set once the scene is built and first rendered (see docs/viewer.md):
     pegView.ready       true
     pegView.frames      number of recorded frames
     pegView.duration    time of the last frame (s)
     pegView.seek(s)     pauses, moves to the last frame whose time is <= s (within a millionth of a step;
                         clamped to the replay), updates everything and renders before returning; returns
                         the frame index
     pegView.setLayer(name, visible)   shows or hides a layer, keeps its checkbox in sync, renders
     pegView.render()    renders now
   plus, read-only: pegView.frame (current frame), pegView.time (its time, s), pegView.layers (the layer names
   with their visibility), pegView.timing (load timings, ms). */
(function () {
  'use strict';

  var scriptMs = performance.now();  // this script starts running
  var startMs = scriptMs;             // the replay starts loading (set in start())

  var LAYERS = ['obstacles', 'terrain', 'movers', 'agents', 'trails', 'capture', 'collisions', 'apollonius',
    'cone', 'obstacle_vectors', 'arena'];
  var LAYER_LABELS = {
    obstacles: 'Obstacles (spheres, cylinders)',
    terrain: 'Terrain',
    movers: 'Moving obstacles',
    agents: 'Agents and headings',
    trails: 'Trails',
    capture: 'Capture radius and captures',
    collisions: 'Collisions',
    apollonius: 'Apollonius surface',
    cone: 'Optimal cone',
    obstacle_vectors: 'Nearest-obstacle vectors',
    arena: 'Arena box'
  };
  var SPEEDS = [0.25, 0.5, 1, 2, 5, 10, 50];
  // The percept's labels and units, [[label, unit], ...], as the library declares them
  // (<script id="peg-vocabulary">, from game::kObservationEntries).
  var INPUT_LABELS = (function () {
    try {
      var v = JSON.parse(document.getElementById('peg-vocabulary').textContent);
      if (Array.isArray(v.inputs)) return v.inputs;
    } catch (e) { /* no vocabulary: the panel leaves the inputs out */ }
    return [];
  })();
  var PURSUER_COLORS = [0xff5a4f, 0xff9a3c, 0xe0457b, 0xff8c8c, 0xc8553d, 0xffc06a];
  var EVADER_COLORS = [0x4fa3ff, 0x36d1c4, 0x8a7dff, 0x8fd0ff, 0x3d6fe0, 0x5ee08e];
  var OTHER_COLOR = 0xcccccc;
  var TRAIL_POINTS = 4000;   // decimated trail points per agent (plus one for the exact current position)
  var CONE_LENGTH = 6;       // m, slant length of the drawn optimal cone
  var TINY = 1e-4;           // smallest scale ever given to an object (a zero scale makes three.js warn)

  function $(id) { return document.getElementById(id); }

  // A message over the view; `fatal` also hides the playback bar and panel, which cannot work then.
  function showMessage(title, detail, fatal) {
    var box = $('peg-message');
    if (!box) return;
    if (fatal !== false) document.body.classList.add('peg-failed');
    var loading = $('peg-loading');
    if (loading) loading.hidden = true;
    box.textContent = '';
    var h = document.createElement('strong');
    h.textContent = title;
    box.appendChild(h);
    if (detail) {
      var p = document.createElement('p');
      p.textContent = detail;
      box.appendChild(p);
    }
    box.hidden = false;
  }

  function hideMessage() {
    var box = $('peg-message');
    if (box) box.hidden = true;
  }

  // ---------------------------------------------------------------------------------------------------------
  // Decoding

  var BIG_ENDIAN = new Uint8Array(new Uint16Array([1]).buffer)[0] === 0;

  var B64_ALPHABET = 'ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/';
  var B64_LUT = new Uint8Array(65536).fill(255);  // indexed by any UTF-16 code unit
  for (var bi = 0; bi < 64; ++bi) B64_LUT[B64_ALPHABET.charCodeAt(bi)] = bi;

  // Canonical base64 (no whitespace, '=' padding) straight into bytes, about twice as fast as atob plus a
  // copy loop; null when the text is not canonical (then atob, which is more lenient, decides).
  function decodeBase64Fast(s) {
    var len = s.length;
    if (len % 4 !== 0) return null;
    var pad = len > 0 && s.charCodeAt(len - 1) === 61 ? (s.charCodeAt(len - 2) === 61 ? 2 : 1) : 0;
    var out = new Uint8Array(new ArrayBuffer(len / 4 * 3 - pad));
    var full = pad > 0 ? len - 4 : len;
    var bad = 0, i = 0, j = 0;
    for (; i < full; i += 4) {
      var a = B64_LUT[s.charCodeAt(i)], b = B64_LUT[s.charCodeAt(i + 1)];
      var c = B64_LUT[s.charCodeAt(i + 2)], d = B64_LUT[s.charCodeAt(i + 3)];
      bad |= a | b | c | d;
      var v = (a << 18) | (b << 12) | (c << 6) | d;
      out[j++] = v >> 16;
      out[j++] = (v >> 8) & 255;
      out[j++] = v & 255;
    }
    if (pad > 0) {
      var a2 = B64_LUT[s.charCodeAt(i)], b2 = B64_LUT[s.charCodeAt(i + 1)];
      var c2 = pad === 1 ? B64_LUT[s.charCodeAt(i + 2)] : 0;
      bad |= a2 | b2 | c2;
      var v2 = (a2 << 18) | (b2 << 12) | (c2 << 6);
      out[j++] = v2 >> 16;
      if (pad === 1) out[j++] = (v2 >> 8) & 255;
    }
    if (bad & 0xc0) return null;  // a character outside the alphabet (or a misplaced '=')
    return out;
  }

  // The bytes of a base64 string in a fresh ArrayBuffer (so any typed-array view is aligned), a whole number
  // of `width`-byte elements, converted to the host's byte order.
  function decodeBytes(b64, width, key) {
    if (b64 === undefined || b64 === null || b64 === '') return new ArrayBuffer(0);
    if (typeof b64 !== 'string') throw new Error(key + ': expected a base64 string');
    var u8 = decodeBase64Fast(b64);
    if (u8 === null) {
      var bin;
      try {
        bin = atob(b64);
      } catch (e) {
        throw new Error(key + ': not valid base64');
      }
      u8 = new Uint8Array(new ArrayBuffer(bin.length));
      for (var i = 0; i < bin.length; ++i) u8[i] = bin.charCodeAt(i);
    }
    var n = u8.length - u8.length % width;
    if (n !== u8.length) u8 = u8.slice(0, n);  // ignore a ragged tail (slice copies into a fresh buffer)
    if (BIG_ENDIAN && width > 1) {
      for (var j = 0; j < n; j += width) {
        for (var a = j, b = j + width - 1; a < b; ++a, --b) {
          var t = u8[a]; u8[a] = u8[b]; u8[b] = t;
        }
      }
    }
    return u8.buffer;
  }
  function f32(s, key) { return new Float32Array(decodeBytes(s, 4, key)); }
  function f64(s, key) { return new Float64Array(decodeBytes(s, 8, key)); }
  function u32(s, key) { return new Uint32Array(decodeBytes(s, 4, key)); }
  function u8(s, key) { return new Uint8Array(decodeBytes(s, 1, key)); }

  function num(v, fallback) {
    var x = Number(v);
    return (v !== null && v !== '' && isFinite(x)) ? x : fallback;
  }
  function vec3(a, fallback) {
    if (!Array.isArray(a) || a.length < 3) return fallback.slice();
    return [num(a[0], fallback[0]), num(a[1], fallback[1]), num(a[2], fallback[2])];
  }
  function list(v) { return Array.isArray(v) ? v : []; }
  function str(v, fallback) { return (typeof v === 'string' && v !== '') ? v : fallback; }

  // Index of the last element <= x in a sorted array, -1 when none.
  function lastLE(arr, x) {
    var lo = 0, hi = arr.length - 1, ans = -1;
    while (lo <= hi) {
      var mid = (lo + hi) >> 1;
      if (arr[mid] <= x) { ans = mid; lo = mid + 1; } else { hi = mid - 1; }
    }
    return ans;
  }

  function loadReplay() {
    var el = $('peg-replay');
    if (!el) throw new Error('The page holds no replay data.');
    var raw;
    try {
      raw = JSON.parse(el.textContent);
    } catch (e) {
      throw new Error('The replay data is not valid JSON (' + e.message + ').');
    }
    if (!raw || typeof raw !== 'object') throw new Error('The replay data is not a JSON object.');
    if (raw.format !== 'peg3d-replay') throw new Error('This is not a peg3d replay (format: ' + String(raw.format) + ').');
    if (raw.version !== 1) {
      throw new Error('Replay version ' + String(raw.version) + ' is not supported; this viewer reads version 1.');
    }
    var parsedMs = performance.now();

    var R = {};
    R.title = str(raw.title, 'peg3d replay');
    R.subtitle = str(raw.subtitle, '');
    R.dt = num(raw.dt, 0);
    R.captureDistance = Math.max(0, num(raw.capture_distance, 0));

    var times = f64(raw.times_f64, 'times_f64');
    var n = Math.floor(num(raw.frames, times.length));
    if (times.length > 0 && times.length < n) n = times.length;
    if (!(n >= 1)) throw new Error('The replay holds no recorded frames.');
    if (times.length < n) {  // no times: frame k at k dt
      times = new Float64Array(n);
      for (var k = 0; k < n; ++k) times[k] = k * (R.dt > 0 ? R.dt : 1);
    } else if (times.length > n) {
      times = times.slice(0, n);
    }
    R.frames = n;
    R.times = times;

    R.agents = list(raw.agents).map(function (a, i) {
      a = a || {};
      var tr = a.track || {};
      var role = a.role === 'pursuer' || a.role === 'evader' ? a.role : 'agent';
      var key = 'agents[' + i + '].track.';
      return {
        index: i,
        name: str(a.name, role + ' ' + (i + 1)),
        role: role,
        radius: Math.max(0, num(a.radius, 0.2)),
        speed: num(a.speed, NaN),
        pos: f32(tr.position_f32, key + 'position_f32'),
        heading: f32(tr.heading_f32, key + 'heading_f32'),
        active: u8(tr.active_u8, key + 'active_u8'),
        obstacle: f32(tr.obstacle_f32, key + 'obstacle_f32'),
        inputs: f32(tr.inputs_f32, key + 'inputs_f32'),
        action: f32(tr.action_f32, key + 'action_f32'),
        reward: f32(tr.reward_f32, key + 'reward_f32')
      };
    });
    // Labels: the names, made unique when several agents share one.
    var seen = {};
    R.agents.forEach(function (a) { seen[a.name] = (seen[a.name] || 0) + 1; });
    R.agents.forEach(function (a) { a.label = seen[a.name] > 1 ? a.name + ' #' + (a.index + 1) : a.name; });

    var lo = [-1, -1, 0], hi = [1, 1, 2];
    if (raw.arena && Array.isArray(raw.arena.lo) && Array.isArray(raw.arena.hi)) {
      lo = vec3(raw.arena.lo, lo);
      hi = vec3(raw.arena.hi, hi);
    } else {  // no arena: the box around the agents' paths
      var any = false, blo = [Infinity, Infinity, Infinity], bhi = [-Infinity, -Infinity, -Infinity];
      R.agents.forEach(function (a) {
        for (var j = 0; j + 2 < a.pos.length; j += 3) {
          for (var c = 0; c < 3; ++c) {
            var v = a.pos[j + c];
            if (isFinite(v)) { any = true; blo[c] = Math.min(blo[c], v); bhi[c] = Math.max(bhi[c], v); }
          }
        }
      });
      if (any) { lo = blo.map(function (v) { return v - 1; }); hi = bhi.map(function (v) { return v + 1; }); }
    }
    for (var c3 = 0; c3 < 3; ++c3) {
      if (hi[c3] < lo[c3]) { var tt = lo[c3]; lo[c3] = hi[c3]; hi[c3] = tt; }
    }
    R.arena = { lo: lo, hi: hi };

    R.spheres = list(raw.spheres).map(function (s) {
      s = s || {};
      return { center: vec3(s.center, [0, 0, 0]), radius: Math.max(0, num(s.radius, 0)) };
    });
    R.cylinders = list(raw.cylinders).map(function (c) {
      c = c || {};
      return { base: vec3(c.base, [0, 0, 0]), radius: Math.max(0, num(c.radius, 0)), height: Math.max(0, num(c.height, 0)) };
    });
    R.meshes = list(raw.meshes).map(function (m, i) {
      m = m || {};
      var positions = f32(m.positions_f32, 'meshes[' + i + '].positions_f32');
      var indices = u32(m.indices_u32, 'meshes[' + i + '].indices_u32');
      return {
        name: str(m.name, 'mesh ' + (i + 1)),
        triangles: num(m.triangles, indices.length / 3),
        drawnTriangles: num(m.drawn_triangles, indices.length / 3),
        positions: positions,
        indices: indices
      };
    });
    R.movers = list(raw.movers).map(function (m, i) {
      m = m || {};
      var shape = m.shape === 'sphere' || m.shape === 'cylinder' || m.shape === 'box' ? m.shape : 'sphere';
      return {
        shape: shape,
        radius: Math.max(0, num(m.radius, 0)),
        height: Math.max(0, num(m.height, 0)),
        size: vec3(m.size, [0, 0, 0]).map(function (v) { return Math.max(0, v); }),
        dynamic: !!m.dynamic,
        poses: f32(m.poses_f32, 'movers[' + i + '].poses_f32')
      };
    });
    R.poseFrames = u32(raw.pose_frames_u32, 'pose_frames_u32');
    var na = R.agents.length;
    R.pairs = list(raw.pairs).map(function (p, i) {
      p = p || {};
      return {
        pursuer: Math.floor(num(p.pursuer, -1)),
        evader: Math.floor(num(p.evader, -1)),
        apollonius: f32(p.apollonius_f32, 'pairs[' + i + '].apollonius_f32'),
        cone: f32(p.cone_f32, 'pairs[' + i + '].cone_f32')
      };
    }).filter(function (p) {
      return p.pursuer >= 0 && p.pursuer < na && p.evader >= 0 && p.evader < na && p.pursuer !== p.evader;
    });
    var frameOf = function (e) {
      var f = num(e.frame, NaN);
      if (!isFinite(f)) f = isFinite(num(e.time, NaN)) ? Math.max(0, lastLE(times, num(e.time, 0))) : 0;
      return Math.min(n - 1, Math.max(0, Math.floor(f)));
    };
    R.collisions = list(raw.collisions).filter(function (e) { return e && Array.isArray(e.point); }).map(function (e) {
      return {
        frame: frameOf(e),
        time: num(e.time, NaN),
        agent: Math.floor(num(e.agent, -1)),
        kind: str(e.kind, 'obstacle'),
        point: vec3(e.point, [0, 0, 0])
      };
    });
    R.collisions.sort(function (a, b) { return a.frame - b.frame; });  // stable in every current engine
    R.captures = list(raw.captures).filter(function (e) { return !!e; }).map(function (e) {
      return {
        frame: frameOf(e),
        time: num(e.time, NaN),
        pursuer: Math.floor(num(e.pursuer, -1)),
        evader: Math.floor(num(e.evader, -1))
      };
    });
    R.captures.sort(function (a, b) { return a.frame - b.frame; });
    R.timing = { parse_ms: parsedMs - startMs, decode_ms: performance.now() - parsedMs };
    return R;
  }

  // ---------------------------------------------------------------------------------------------------------
  // Track access (every read clamps to what the array holds, so short or missing series never throw)

  function read3(arr, f, out) {
    var count = (arr.length / 3) | 0;
    if (count === 0) return out.set(0, 0, 0);
    var k = 3 * Math.min(f, count - 1);
    return out.set(arr[k], arr[k + 1], arr[k + 2]);
  }
  function readN(arr, stride, f, j) {
    var count = (arr.length / stride) | 0;
    if (count === 0) return NaN;
    return arr[stride * Math.min(f, count - 1) + j];
  }
  function isActive(a, f) {
    if (a.active.length === 0) return true;
    return a.active[Math.min(f, a.active.length - 1)] !== 0;
  }
  function headingDir(a, f, out) {
    var al = readN(a.heading, 2, f, 0), th = readN(a.heading, 2, f, 1);
    if (!isFinite(al) || !isFinite(th)) return out.set(1, 0, 0);
    var s = Math.sin(th);
    return out.set(s * Math.cos(al), s * Math.sin(al), Math.cos(th));
  }
  function finite3(v) { return isFinite(v.x) && isFinite(v.y) && isFinite(v.z); }

  // ---------------------------------------------------------------------------------------------------------
  // The viewer

  function start() {
    if (typeof THREE === 'undefined' || typeof THREE.WebGLRenderer !== 'function') {
      showMessage('The viewer cannot start', 'three.js is missing from this page.');
      return;
    }
    if (typeof THREE.OrbitControls !== 'function') {
      showMessage('The viewer cannot start', 'three.js OrbitControls is missing from this page.');
      return;
    }
    var R;
    startMs = performance.now();
    try {
      R = loadReplay();
    } catch (e) {
      showMessage('This replay cannot be shown', e.message);
      return;
    }
    if (!webglAvailable()) {
      fillHeader(R);
      showMessage('WebGL is not available',
        'This browser (or its current settings) cannot create a WebGL context, so the 3D replay cannot be drawn. ' +
        'Try another browser, or enable hardware acceleration / WebGL.');
      return;
    }
    try {
      new Viewer(R);
    } catch (e) {
      showMessage('The viewer failed to start', String(e && e.message ? e.message : e));
    }
  }

  function webglAvailable() {
    try {
      var c = document.createElement('canvas');
      return !!(window.WebGLRenderingContext && (c.getContext('webgl') || c.getContext('experimental-webgl')));
    } catch (e) {
      return false;
    }
  }

  function fmtNum(x, digits) {
    if (typeof x !== 'number' || !isFinite(x)) return '\u2013';
    var s = x.toFixed(digits);
    return s.charAt(0) === '-' && Number(s) === 0 ? s.slice(1) : s;  // no "-0.000"
  }

  function outcomeText(R) {
    var parts = [];
    var name = function (i) { return R.agents[i] ? R.agents[i].label : 'agent ' + i; };
    if (R.captures.length > 0) {
      R.captures.forEach(function (c) {
        parts.push(name(c.evader) + ' captured by ' + name(c.pursuer) + ' at ' +
          fmtNum(isFinite(c.time) ? c.time : R.times[c.frame], 2) + ' s');
      });
    } else {
      parts.push('no capture');
    }
    parts.push(R.collisions.length + (R.collisions.length === 1 ? ' collision' : ' collisions'));
    parts.push('ended at ' + fmtNum(R.times[R.frames - 1], 2) + ' s (' + R.frames + (R.frames === 1 ? ' frame)' : ' frames)'));
    return parts.join(' \u00b7 ');
  }

  function fillHeader(R) {
    $('peg-title').textContent = R.title;
    $('peg-subtitle').textContent = R.subtitle;
    $('peg-subtitle').hidden = R.subtitle === '';
    $('peg-outcome').textContent = outcomeText(R);
  }

  function Viewer(R) {
    var self = this;
    var N = R.frames;
    var times = R.times;
    var agents = R.agents;
    var tStart = times[0], tEnd = times[N - 1];

    fillHeader(R);

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
      requestRender();
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
      self.gridStep = step;
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

    // --- state
    var state = { frame: 0, frac: 0, playTime: tStart, playing: false, speed: 1, lastTs: null,
      pair: R.pairs.length > 0 ? 0 : -1, agent: agents.length > 0 ? 0 : -1, follow: -1, followPrev: null };
    var dirty = true;
    var panelFrame = -1;
    function requestRender() { dirty = true; }

    // Sample lookup for per-sample series (movers, pairs): the index of the sample in force at frame f and
    // the next one with the interpolation weight.
    var pf = R.poseFrames;
    function sampleAt(count, f, frac) {
      if (count <= 0) return null;
      if (count === 1) return { s: 0, s2: 0, u: 0 };
      var s, s2, u;
      if (count === pf.length) {
        s = Math.max(0, lastLE(pf, f));
        s2 = Math.min(s + 1, count - 1);
        u = s2 > s && pf[s2] > pf[s] ? (f + frac - pf[s]) / (pf[s2] - pf[s]) : 0;
      } else if (count === N) {
        s = f; s2 = Math.min(f + 1, N - 1); u = s2 > s ? frac : 0;
      } else {  // evenly over the frames
        var x = N > 1 ? (f + frac) * (count - 1) / (N - 1) : 0;
        s = Math.min(count - 1, Math.floor(x)); s2 = Math.min(s + 1, count - 1); u = x - s;
      }
      return { s: s, s2: s2, u: Math.min(1, Math.max(0, u)) };
    }

    var qa = new THREE.Quaternion(), qb = new THREE.Quaternion();
    function readQuat(arr, s, out) {
      var o = 7 * s;
      out.set(arr[o + 3], arr[o + 4], arr[o + 5], arr[o + 6]);
      var l = out.length();
      if (!(l > 1e-12) || !isFinite(l)) return out.set(0, 0, 0, 1);
      return out.normalize();
    }

    function updateTrail(a, f) {
      var t = a.trail;
      var c = Math.min(trailM, Math.floor(f / trailK) + 1);
      if (t.patched !== c) {
        if (t.patched >= 0 && t.patched < trailM) {
          t.arr[3 * t.patched] = t.saved[0]; t.arr[3 * t.patched + 1] = t.saved[1]; t.arr[3 * t.patched + 2] = t.saved[2];
        }
        if (c < trailM) { t.saved[0] = t.arr[3 * c]; t.saved[1] = t.arr[3 * c + 1]; t.saved[2] = t.arr[3 * c + 2]; }
        t.patched = c;
      }
      if (finite3(a.cur)) {
        t.arr[3 * c] = a.cur.x; t.arr[3 * c + 1] = a.cur.y; t.arr[3 * c + 2] = a.cur.z;
      }
      t.attr.needsUpdate = true;
      t.geom.setDrawRange(0, c + 1);
    }

    // Poses everything at frame f plus a fraction `frac` (in [0, 1)) towards frame f + 1 (playback only).
    function applyState(f, frac) {
      state.frame = f;
      state.frac = frac;
      var fb = Math.min(f + 1, N - 1);
      var interp = frac > 0 && fb !== f;

      agents.forEach(function (a) {
        var act = isActive(a, f);
        read3(a.pos, f, a.cur);
        headingDir(a, f, a.dir);
        if (interp && act && isActive(a, fb)) {
          read3(a.pos, fb, tmpB);
          if (finite3(tmpB)) a.cur.lerp(tmpB, frac);
          headingDir(a, fb, tmpD);
          a.dir.lerp(tmpD, frac);
        }
        if (!(a.dir.lengthSq() > 1e-12)) headingDir(a, f, a.dir);
        a.dir.normalize();
        a.activeNow = act;
        var ok = finite3(a.cur);
        a.body.visible = ok;
        a.body.position.copy(a.cur);
        a.body.material = act ? a.bodyMat : inactiveMat;
        a.dot.visible = act;
        a.arrow.visible = ok && act;
        a.arrow.position.copy(a.cur);
        a.arrow.setDirection(a.dir);
        if (a.captureSphere) {
          a.captureSphere.visible = ok && act;
          a.captureSphere.position.copy(a.cur);
        }
        updateTrail(a, f);
        read3(a.obstacle, f, tmpE);
        var hasVec = ok && act && finite3(tmpE) && tmpE.lengthSq() > 0;
        a.obstacleLine.visible = hasVec;
        if (hasVec) {
          var o = a.obstacleAttr.array;
          o[0] = a.cur.x; o[1] = a.cur.y; o[2] = a.cur.z;
          o[3] = a.cur.x + tmpE.x; o[4] = a.cur.y + tmpE.y; o[5] = a.cur.z + tmpE.z;
          a.obstacleAttr.needsUpdate = true;
        }
      });

      movers.forEach(function (m) {
        var smp = sampleAt(m.count, f, frac);
        if (!smp) return;
        var o = 7 * smp.s, o2 = 7 * smp.s2, p = m.poses;
        tmpA.set(p[o], p[o + 1], p[o + 2]);
        readQuat(p, smp.s, qa);
        if (smp.u > 0 && smp.s2 !== smp.s) {
          tmpB.set(p[o2], p[o2 + 1], p[o2 + 2]);
          tmpA.lerp(tmpB, smp.u);
          readQuat(p, smp.s2, qb);
          qa.slerp(qb, smp.u);
        }
        placeMover(m, tmpA, qa, finite3(tmpA));
      });
      moverGeom.attributes.position.needsUpdate = true;
      moverGeom.attributes.normal.needsUpdate = true;

      // Pair geometry: the sample in force (no interpolation, so it matches the recorded value).
      apoSphere.visible = false;
      apoPlane.visible = false;
      coneGroup.visible = false;
      var pair = state.pair >= 0 ? R.pairs[state.pair] : null;
      if (pair) {
        var P = agents[pair.pursuer], E = agents[pair.evader];
        var live = P.activeNow && E.activeNow && finite3(P.cur) && finite3(E.cur);
        var sa = sampleAt((pair.apollonius.length / 4) | 0, f, 0);
        if (live && sa) {
          var ap = pair.apollonius, k = 4 * sa.s;
          var r = ap[k + 3];
          tmpA.set(ap[k], ap[k + 1], ap[k + 2]);
          if (finite3(tmpA) && isFinite(r)) {
            if (r > 0) {
              apoSphere.position.copy(tmpA);
              apoSphere.scale.setScalar(r);
              apoSphere.visible = true;
            } else if (r < 0) {
              tmpD.copy(E.cur).sub(P.cur);
              if (!(tmpD.lengthSq() > 1e-18)) tmpD.set(1, 0, 0);
              tmpD.normalize();
              apoPlane.position.copy(tmpA);
              apoPlane.quaternion.setFromUnitVectors(upZ, tmpD);
              apoPlane.visible = true;
            }
          }
        }
        var sc = sampleAt((pair.cone.length / 4) | 0, f, 0);
        if (live && sc) {
          var cn = pair.cone, kc = 4 * sc.s;
          tmpD.set(cn[kc], cn[kc + 1], cn[kc + 2]);
          var half = cn[kc + 3];
          if (finite3(tmpD) && tmpD.lengthSq() > 1e-18 && isFinite(half)) {
            tmpD.normalize();
            half = Math.min(Math.PI, Math.max(0, half));
            var rad = CONE_LENGTH * Math.sin(half), len = CONE_LENGTH * Math.cos(half);
            coneMesh.scale.set(Math.max(TINY, rad), Math.abs(len) < TINY ? (len < 0 ? -TINY : TINY) : len, Math.max(TINY, rad));
            coneGroup.position.copy(P.cur);
            coneGroup.quaternion.setFromUnitVectors(downY, tmpD);
            coneGroup.visible = true;
          }
        }
      }

      if (collisionCross) {
        var nc = lastLE(collisionFrames, f) + 1;
        collisionCross.geometry.setDrawRange(0, 6 * nc);
        collisionDots.geometry.setDrawRange(0, nc);
        collisionCross.visible = collisionDots.visible = nc > 0;
      }
      captureMarks.forEach(function (c) { if (c.obj) c.obj.visible = f >= c.frame; });

      // Camera follow: move the camera by the followed agent's displacement, keep the target on it.
      if (state.follow >= 0) {
        var fa = agents[state.follow];
        if (finite3(fa.cur)) {
          if (!state.followPrev) state.followPrev = controls.target.clone();
          tmpD.copy(fa.cur).sub(state.followPrev);
          camera.position.add(tmpD);
          controls.target.add(tmpD);
          state.followPrev.copy(fa.cur);
          controls.update();
        }
      }
      dirty = true;
    }

    // --- UI
    var ui = {
      play: $('peg-play'), slider: $('peg-slider'), speed: $('peg-speed'), clock: $('peg-clock'),
      barTime: $('peg-time'), frameNo: $('peg-frame'), pair: $('peg-pair'), agent: $('peg-agent'), follow: $('peg-follow'),
      layers: $('peg-layers'), dist: $('peg-dist'), agentInfo: $('peg-agent-info'), events: $('peg-events'),
      legend: $('peg-legend')
    };
    var checkboxes = {};

    function option(sel, value, text) {
      var o = document.createElement('option');
      o.value = String(value);
      o.textContent = text;
      sel.appendChild(o);
      return o;
    }
    function el(tag, cls, text) {
      var e = document.createElement(tag);
      if (cls) e.className = cls;
      if (text !== undefined) e.textContent = text;
      return e;
    }
    function cssColor(c) { return '#' + c.getHexString(); }

    // Legend
    agents.forEach(function (a) {
      var li = el('li');
      var sw = el('span', 'peg-swatch');
      sw.style.background = cssColor(a.color);
      li.appendChild(sw);
      li.appendChild(document.createTextNode(a.label + (a.role !== 'agent' && a.label.indexOf(a.role) < 0 ? ' (' + a.role + ')' : '')));
      ui.legend.appendChild(li);
    });

    // Speed
    SPEEDS.forEach(function (s) { option(ui.speed, s, s + '\u00d7'); });
    ui.speed.value = '1';
    ui.speed.addEventListener('change', function () {
      var s = Number(ui.speed.value);
      state.speed = s > 0 ? s : 1;
    });

    // Slider
    ui.slider.min = '0';
    ui.slider.max = String(N - 1);
    ui.slider.step = '1';
    ui.slider.value = '0';
    ui.slider.disabled = N < 2;
    ui.slider.addEventListener('input', function () {
      var f = Math.min(N - 1, Math.max(0, Math.round(Number(ui.slider.value)) || 0));
      state.playTime = times[f];
      state.lastTs = null;
      applyState(f, 0);
      updatePanel(true);
      renderNow();
    });

    // Play / pause
    ui.play.disabled = N < 2 || !(tEnd > tStart);
    function setPlaying(on) {
      on = !!on && !ui.play.disabled;
      if (on && state.frame >= N - 1) {  // at the end: play from the start
        state.playTime = tStart;
        applyState(0, 0);
        updatePanel(true);
      }
      if (on && !state.playing) state.playTime = times[state.frame] + state.frac * (state.frame < N - 1 ? times[state.frame + 1] - times[state.frame] : 0);
      state.playing = on;
      state.lastTs = null;
      ui.play.textContent = on ? '\u275a\u275a' : '\u25b6';
      ui.play.title = on ? 'Pause (space)' : 'Play (space)';
      ui.play.setAttribute('aria-label', on ? 'Pause' : 'Play');
      if (!on && state.frac !== 0) {  // land exactly on the frame the panel shows
        applyState(state.frame, 0);
        updatePanel(true);
      }
      dirty = true;
    }
    ui.play.addEventListener('click', function () { setPlaying(!state.playing); ui.play.blur(); });

    // Pair selector
    if (R.pairs.length === 0) {
      option(ui.pair, -1, 'no pairs');
      ui.pair.disabled = true;
    } else {
      R.pairs.forEach(function (p, i) { option(ui.pair, i, agents[p.pursuer].label + ' \u2192 ' + agents[p.evader].label); });
    }
    ui.pair.value = String(state.pair);
    ui.pair.addEventListener('change', function () {
      state.pair = Number(ui.pair.value);
      applyState(state.frame, state.frac);
      renderNow();
    });

    // Agent selector
    if (agents.length === 0) {
      option(ui.agent, -1, 'no agents');
      ui.agent.disabled = true;
    } else {
      agents.forEach(function (a, i) { option(ui.agent, i, a.label); });
    }
    ui.agent.value = String(state.agent);
    ui.agent.addEventListener('change', function () {
      state.agent = Number(ui.agent.value);
      buildAgentInfo();
      updatePanel(true);
    });

    // Follow selector
    option(ui.follow, -1, 'none (free orbit)');
    agents.forEach(function (a, i) { option(ui.follow, i, a.label); });
    ui.follow.value = '-1';
    ui.follow.addEventListener('change', function () {
      state.follow = Number(ui.follow.value);
      state.followPrev = null;
      applyState(state.frame, state.frac);
      renderNow();
    });
    $('peg-home').addEventListener('click', function () {
      state.follow = -1;
      state.followPrev = null;
      ui.follow.value = '-1';
      camera.position.copy(centre).add(homeOffset);
      controls.target.copy(centre);
      controls.update();
      renderNow();
      this.blur();
    });
    $('peg-png').addEventListener('click', function () {
      var btn = this;
      btn.blur();
      renderNow();
      if (!renderer.domElement.toBlob) return;
      renderer.domElement.toBlob(function (blob) {
        if (!blob) return;
        var a = document.createElement('a');
        a.href = URL.createObjectURL(blob);
        a.download = 'peg3d-frame-' + state.frame + '.png';
        document.body.appendChild(a);
        a.click();
        document.body.removeChild(a);
        setTimeout(function () { URL.revokeObjectURL(a.href); }, 2000);
      }, 'image/png');
    });
    $('peg-panel-toggle').addEventListener('click', function () {
      document.body.classList.toggle('peg-panel-hidden');
      this.textContent = document.body.classList.contains('peg-panel-hidden') ? 'Panel \u25c2' : 'Panel \u25b8';
      this.blur();
      resize();
    });

    // Layers
    var layerCounts = {
      obstacles: R.spheres.length + R.cylinders.length,
      terrain: R.meshes.length,
      movers: R.movers.length,
      agents: agents.length,
      trails: agents.length,
      capture: agents.filter(function (a) { return a.role === 'pursuer'; }).length + R.captures.length,
      collisions: R.collisions.length,
      apollonius: R.pairs.length,
      cone: R.pairs.length,
      obstacle_vectors: agents.length,
      arena: 1
    };
    LAYERS.forEach(function (name) {
      // The Apollonius sphere of nearly equal speeds is far larger than the arena: shown on request only.
      var on = (name === 'obstacle_vectors' || name === 'apollonius') ? false : name === 'cone' ? R.pairs.length > 0 : true;
      layerOn[name] = on;
      layerGroups[name].visible = on;
      var label = el('label', 'peg-layer');
      var cb = document.createElement('input');
      cb.type = 'checkbox';
      cb.checked = on;
      cb.id = 'peg-layer-' + name;
      cb.setAttribute('data-layer', name);
      cb.addEventListener('change', function () {
        setLayer(name, cb.checked);
        cb.blur();
      });
      checkboxes[name] = cb;
      label.appendChild(cb);
      label.appendChild(document.createTextNode(' ' + LAYER_LABELS[name]));
      if (name !== 'arena') {
        var n = el('span', 'peg-count', String(layerCounts[name]));
        if (name === 'terrain' && drawnTriangles > 0) n.textContent = R.meshes.length + ' \u00b7 ' + drawnTriangles.toLocaleString('en-US') + ' tri';
        label.appendChild(n);
      }
      if (layerCounts[name] === 0) label.classList.add('peg-empty');
      ui.layers.appendChild(label);
    });

    function setLayer(name, visible) {
      if (!Object.prototype.hasOwnProperty.call(layerGroups, name)) {
        throw new Error('pegView.setLayer: unknown layer "' + name + '" (layers: ' + LAYERS.join(', ') + ')');
      }
      var on = !!visible;
      layerOn[name] = on;
      layerGroups[name].visible = on;
      if (checkboxes[name]) checkboxes[name].checked = on;
      renderNow();
    }

    // Distances panel
    var distRows = R.pairs.map(function (p) {
      var tr = el('tr');
      var th = el('th');
      var s1 = el('span', 'peg-swatch'); s1.style.background = cssColor(agents[p.pursuer].color);
      var s2 = el('span', 'peg-swatch'); s2.style.background = cssColor(agents[p.evader].color);
      th.appendChild(s1);
      th.appendChild(document.createTextNode(agents[p.pursuer].label + ' \u2013 '));
      th.appendChild(s2);
      th.appendChild(document.createTextNode(agents[p.evader].label));
      var td = el('td', 'peg-num');
      tr.appendChild(th);
      tr.appendChild(td);
      ui.dist.appendChild(tr);
      return { tr: tr, td: td, p: agents[p.pursuer], e: agents[p.evader] };
    });
    var distNone = el('tr', 'peg-muted');
    distNone.appendChild(el('td', '', R.pairs.length === 0 ? 'no pursuer\u2013evader pairs' : 'no active pair'));
    ui.dist.appendChild(distNone);

    // Agent panel
    var agentCells = null;
    function buildAgentInfo() {
      ui.agentInfo.textContent = '';
      agentCells = null;
      if (state.agent < 0) {
        ui.agentInfo.appendChild(el('p', 'peg-muted', 'no agents'));
        return;
      }
      var a = agents[state.agent];
      var t = el('table', 'peg-table');
      var row = function (label, unit, cls) {
        var tr = el('tr', cls || '');
        tr.appendChild(el('th', '', label));
        var td = el('td', 'peg-num');
        tr.appendChild(td);
        tr.appendChild(el('td', 'peg-unit', unit));
        t.appendChild(tr);
        return td;
      };
      var cells = {};
      cells.status = row('status', '');
      t.appendChild(el('tr', 'peg-sep')).appendChild(el('th', 'peg-subhead', 'fuzzy inputs')).colSpan = 3;
      cells.inputs = INPUT_LABELS.map(function (l) { return row(l[0], l[1]); });
      t.appendChild(el('tr', 'peg-sep')).appendChild(el('th', 'peg-subhead', 'action')).colSpan = 3;
      cells.dAlpha = row('d_alpha', 'rad');
      cells.dTheta = row('d_theta', 'rad');
      t.appendChild(el('tr', 'peg-sep')).appendChild(el('th', 'peg-subhead', 'step')).colSpan = 3;
      cells.reward = row('reward', '');
      ui.agentInfo.appendChild(t);
      agentCells = cells;
      var sw = $('peg-agent-swatch');
      if (sw) sw.style.background = cssColor(a.color);
    }
    buildAgentInfo();

    function lastEventText(f) {
      var nc = lastLE(collisionFrames, f) + 1;
      var parts = [];
      parts.push('collisions so far: ' + nc + ' of ' + R.collisions.length);
      if (nc > 0) {
        var c = R.collisions[nc - 1];
        var who = agents[c.agent] ? agents[c.agent].label : 'agent ' + c.agent;
        parts.push('last: ' + who + ' hit ' + c.kind + ' at ' + fmtNum(isFinite(c.time) ? c.time : times[c.frame], 2) + ' s');
      }
      var caps = R.captures.filter(function (c) { return c.frame <= f; });
      if (caps.length > 0) {
        caps.forEach(function (c) {
          parts.push('captured: ' + (agents[c.evader] ? agents[c.evader].label : c.evader) + ' by ' +
            (agents[c.pursuer] ? agents[c.pursuer].label : c.pursuer) + ' at ' + fmtNum(isFinite(c.time) ? c.time : times[c.frame], 2) + ' s');
        });
      } else if (R.captures.length > 0) {
        parts.push('captures so far: 0 of ' + R.captures.length);
      }
      return parts;
    }

    var eventsKey = '';
    function updatePanel(force) {
      var f = state.frame;
      if (!force && f === panelFrame) return;
      panelFrame = f;
      var clock = fmtNum(times[f], 2) + ' s';
      ui.clock.textContent = 't = ' + clock + ' / ' + fmtNum(tEnd, 2) + ' s';
      ui.frameNo.textContent = 'frame ' + f + ' / ' + (N - 1);
      ui.barTime.textContent = clock + ' \u00b7 ' + f;
      ui.slider.value = String(f);

      var shown = 0;
      distRows.forEach(function (r) {
        var on = isActive(r.e, f);
        r.tr.hidden = !on;
        if (on) {
          shown++;
          read3(r.p.pos, f, tmpA);
          read3(r.e.pos, f, tmpB);
          r.td.textContent = fmtNum(tmpA.distanceTo(tmpB), 2) + ' m';
        }
      });
      distNone.hidden = shown > 0;

      if (agentCells) {
        var a = agents[state.agent];
        var act = isActive(a, f);
        agentCells.status.textContent = act ? 'active' : 'out of the game';
        agentCells.status.parentNode.className = act ? '' : 'peg-out';
        for (var j = 0; j < agentCells.inputs.length; ++j) agentCells.inputs[j].textContent = fmtNum(readN(a.inputs, 6, f, j), j === 0 || j === 3 ? 2 : 3);
        agentCells.dAlpha.textContent = fmtNum(readN(a.action, 2, f, 0), 4);
        agentCells.dTheta.textContent = fmtNum(readN(a.action, 2, f, 1), 4);
        agentCells.reward.textContent = fmtNum(readN(a.reward, 1, f, 0), 4);
      }

      var parts = lastEventText(f);
      var key = parts.join('\n');
      if (key !== eventsKey) {
        eventsKey = key;
        ui.events.textContent = '';
        parts.forEach(function (p) { ui.events.appendChild(el('div', p.indexOf('captured') === 0 ? 'peg-capture' : '', p)); });
      }
    }

    // --- rendering and the loop
    function renderNow() {
      renderer.render(scene, camera);
      dirty = false;
    }
    controls.addEventListener('change', function () {
      if (state.follow >= 0 && state.followPrev) {
        // the user orbits/pans: keep following from wherever the target is now
        state.followPrev.copy(agents[state.follow].cur);
      }
      dirty = true;
    });

    function resize() {
      var w = Math.max(1, host.clientWidth), h = Math.max(1, host.clientHeight);
      renderer.setSize(w, h, true);
      camera.aspect = w / h;
      camera.updateProjectionMatrix();
      renderNow();
    }
    if (typeof ResizeObserver === 'function') {
      new ResizeObserver(function () { resize(); }).observe(host);
    }
    window.addEventListener('resize', resize, false);

    // The last frame whose time is <= t, with a millionth of a step of slack so that a time computed as
    // k * dt (or read back from the panel) finds frame k despite rounding.
    var timeSlack = 1e-6 * (N > 1 && tEnd > tStart ? (tEnd - tStart) / (N - 1) : (R.dt > 0 ? R.dt : 1));
    function frameAtTime(t) {
      return Math.min(N - 1, Math.max(0, lastLE(times, t + timeSlack)));
    }

    function tick(ts) {
      requestAnimationFrame(tick);
      if (state.playing) {
        var dtReal = state.lastTs === null ? 0 : Math.min(0.25, Math.max(0, (ts - state.lastTs) / 1000));
        state.lastTs = ts;
        state.playTime += dtReal * state.speed;
        if (state.playTime >= tEnd) {
          state.playTime = tEnd;
          applyState(N - 1, 0);
          setPlaying(false);
        } else {
          var f = frameAtTime(state.playTime);
          var frac = 0;
          if (f < N - 1 && times[f + 1] > times[f]) frac = Math.min(1, Math.max(0, (state.playTime - times[f]) / (times[f + 1] - times[f])));
          applyState(f, frac);
        }
        updatePanel(false);
      }
      if (dirty) renderNow();
    }

    function seek(seconds) {
      var t = Number(seconds);
      if (!isFinite(t)) throw new TypeError('pegView.seek: expected a number of seconds, got ' + String(seconds));
      setPlaying(false);
      var f = frameAtTime(t);
      state.playTime = times[f];
      applyState(f, 0);
      updatePanel(true);
      renderNow();
      return f;
    }

    function stepFrames(d) {
      setPlaying(false);
      var f = Math.min(N - 1, Math.max(0, state.frame + d));
      state.playTime = times[f];
      applyState(f, 0);
      updatePanel(true);
      renderNow();
    }

    document.addEventListener('keydown', function (ev) {
      if (ev.ctrlKey || ev.metaKey || ev.altKey) return;
      var t = ev.target, tag = t && t.tagName ? t.tagName.toLowerCase() : '';
      if (tag === 'select' || tag === 'textarea' || (tag === 'input' && t.type !== 'checkbox' && t.type !== 'range')) return;
      if (ev.key === ' ' || ev.code === 'Space') {
        ev.preventDefault();
        if (!ev.repeat) setPlaying(!state.playing);
      } else if (tag !== 'input' && (ev.key === 'ArrowRight' || ev.key === 'ArrowLeft')) {
        ev.preventDefault();
        stepFrames((ev.key === 'ArrowRight' ? 1 : -1) * (ev.shiftKey ? 10 : 1));
      } else if (tag !== 'input' && (ev.key === 'Home' || ev.key === 'End')) {
        ev.preventDefault();
        stepFrames(ev.key === 'Home' ? -N : N);
      }
    }, false);
    document.addEventListener('keyup', function (ev) {
      if (ev.key === ' ' || ev.code === 'Space') {
        var tag = ev.target && ev.target.tagName ? ev.target.tagName.toLowerCase() : '';
        if (tag === 'button' || tag === 'input') ev.preventDefault();  // no button click / checkbox toggle
      }
    }, false);

    function seekFromHash() {
      var m = /^#t=([-+0-9.eE]+)$/.exec(location.hash || '');
      if (!m) return false;
      var t = Number(m[1]);
      if (!isFinite(t)) return false;
      seek(t);
      return true;
    }
    window.addEventListener('hashchange', function () { seekFromHash(); }, false);

    // --- first state and render
    var builtMs = performance.now();
    applyState(0, 0);
    updatePanel(true);
    var w0 = Math.max(1, host.clientWidth), h0 = Math.max(1, host.clientHeight);
    renderer.setSize(w0, h0, true);
    camera.aspect = w0 / h0;
    camera.updateProjectionMatrix();
    seekFromHash();
    renderNow();
    // Wait for the GPU to finish the first frame (a one-pixel read) so the timing is honest.
    var gl = renderer.getContext();
    var px = new Uint8Array(4);
    gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, px);
    var renderedMs = performance.now();

    var timing = {
      wait_ms: startMs - scriptMs,
      parse_ms: R.timing.parse_ms,
      decode_ms: R.timing.decode_ms,
      build_ms: builtMs - startMs - R.timing.parse_ms - R.timing.decode_ms,
      first_render_ms: renderedMs - builtMs,
      total_ms: renderedMs - startMs,
      since_navigation_ms: renderedMs
    };
    Object.keys(timing).forEach(function (k) { timing[k] = Math.round(timing[k] * 10) / 10; });

    var api = {
      ready: false,
      frames: N,
      duration: tEnd,
      seek: seek,
      setLayer: setLayer,
      render: function () { renderNow(); },
      timing: timing
    };
    Object.defineProperty(api, 'frame', { get: function () { return state.frame; }, enumerable: true });
    Object.defineProperty(api, 'time', { get: function () { return times[state.frame]; }, enumerable: true });
    Object.defineProperty(api, 'layers', {
      get: function () {
        var o = {};
        LAYERS.forEach(function (n) { o[n] = layerOn[n]; });
        return o;
      },
      enumerable: true
    });
    window.pegView = api;
    api.ready = true;
    document.body.setAttribute('data-peg-ready', 'true');
    document.body.setAttribute('data-peg-timing', JSON.stringify(timing));
    $('peg-loading').hidden = true;
    requestAnimationFrame(tick);
  }

  // Let the page paint its "loading" note before the (possibly long) decode: start after the next frame, or
  // after a short timeout when frames are not produced (a background tab).
  var started = false;
  function startOnce() {
    if (started) return;
    started = true;
    start();
    var loading = $('peg-loading');
    if (loading) loading.hidden = true;
  }
  if (typeof requestAnimationFrame === 'function') {
    requestAnimationFrame(function () { setTimeout(startOnce, 0); });
  }
  setTimeout(startOnce, 100);
})();
