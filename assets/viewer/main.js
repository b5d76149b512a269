// Start-up and what binds the parts: start() reads the replay and checks WebGL; Viewer(R) makes the viewer
// `v` (the replay, its times and agents, the playback state, and what buildScene and buildPanels add to it),
// wires resizing, keys and the URL fragment, poses the first frame, and publishes the script interface
// window.pegView (common.js's header).

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

// The viewer of replay R: `v` holds everything the parts share.
function Viewer(R) {
  var N = R.frames, times = R.times, agents = R.agents;
  var tStart = times[0], tEnd = times[N - 1];
  var v = { R: R, N: N, times: times, agents: agents, tStart: tStart, tEnd: tEnd, dirty: true };
  v.state = { frame: 0, frac: 0, playTime: tStart, playing: false, speed: 1, lastTs: null,
    pair: R.pairs.length > 0 ? 0 : -1, agent: agents.length > 0 ? 0 : -1, follow: -1, followPrev: null };
  var state = v.state;

  fillHeader(R);
  buildScene(v);
  buildPanels(v);
  var renderer = v.renderer, camera = v.camera, host = v.host;

  v.controls.addEventListener('change', function () {
    if (state.follow >= 0 && state.followPrev) {
      // the user orbits/pans: keep following from wherever the target is now
      state.followPrev.copy(agents[state.follow].cur);
    }
    v.dirty = true;
  });
  if (typeof ResizeObserver === 'function') {
    new ResizeObserver(function () { resize(v); }).observe(host);
  }
  window.addEventListener('resize', function () { resize(v); }, false);

  document.addEventListener('keydown', function (ev) {
    if (ev.ctrlKey || ev.metaKey || ev.altKey) return;
    var t = ev.target, tag = t && t.tagName ? t.tagName.toLowerCase() : '';
    if (tag === 'select' || tag === 'textarea' || (tag === 'input' && t.type !== 'checkbox' && t.type !== 'range')) return;
    if (ev.key === ' ' || ev.code === 'Space') {
      ev.preventDefault();
      if (!ev.repeat) setPlaying(v, !state.playing);
    } else if (tag !== 'input' && (ev.key === 'ArrowRight' || ev.key === 'ArrowLeft')) {
      ev.preventDefault();
      stepFrames(v, (ev.key === 'ArrowRight' ? 1 : -1) * (ev.shiftKey ? 10 : 1));
    } else if (tag !== 'input' && (ev.key === 'Home' || ev.key === 'End')) {
      ev.preventDefault();
      stepFrames(v, ev.key === 'Home' ? -N : N);
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
    seek(v, t);
    return true;
  }
  window.addEventListener('hashchange', function () { seekFromHash(); }, false);

  // --- first state and render
  var builtMs = performance.now();
  applyState(v, 0, 0);
  updatePanel(v, true);
  var w0 = Math.max(1, host.clientWidth), h0 = Math.max(1, host.clientHeight);
  renderer.setSize(w0, h0, true);
  camera.aspect = w0 / h0;
  camera.updateProjectionMatrix();
  seekFromHash();
  renderNow(v);
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
    seek: function (seconds) { return seek(v, seconds); },
    setLayer: function (name, visible) { setLayer(v, name, visible); },
    render: function () { renderNow(v); },
    timing: timing
  };
  Object.defineProperty(api, 'frame', { get: function () { return state.frame; }, enumerable: true });
  Object.defineProperty(api, 'time', { get: function () { return times[state.frame]; }, enumerable: true });
  Object.defineProperty(api, 'layers', {
    get: function () {
      var o = {};
      LAYERS.forEach(function (n) { o[n] = v.layerOn[n]; });
      return o;
    },
    enumerable: true
  });
  // The sensing layers as drawn now: the selected agent, its rays drawn, its map's cells shown and its image shown
  // (null when none is).
  Object.defineProperty(api, 'sensing', {
    get: function () {
      var a = state.agent >= 0 ? agents[state.agent] : null;
      return { agent: state.agent, rays: v.rayLines.visible ? v.rayLines.geometry.drawRange.count / 2 : 0,
               cells: a && a.mapView ? a.mapView.mesh.count : 0, image: v.imageShown };
    },
    enumerable: true
  });
  window.pegView = api;
  api.ready = true;
  document.body.setAttribute('data-peg-ready', 'true');
  document.body.setAttribute('data-peg-timing', JSON.stringify(timing));
  $('peg-loading').hidden = true;
  requestAnimationFrame(function (ts) { tick(v, ts); });
}

// Fits the renderer and the camera to the view's size, and renders.
function resize(v) {
  var w = Math.max(1, v.host.clientWidth), h = Math.max(1, v.host.clientHeight);
  v.renderer.setSize(w, h, true);
  v.camera.aspect = w / h;
  v.camera.updateProjectionMatrix();
  renderNow(v);
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
