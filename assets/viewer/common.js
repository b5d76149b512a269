/* peg3d replay viewer: the browser side of the self-contained replay page that peg-view and the experiments'
   --html flag write (docs/viewer.md). Plain ES2017, in files by concern that the page inlines in this order
   inside one function scope (view/viewer_html.cpp): common.js (constants, messages, small helpers),
   replay.js (reading the replay's data), scene.js (the three.js scene), timeline.js (posing a frame,
   playback, seeking), panels.js (the side panel and controls), main.js (start-up, keys, the script
   interface). It needs the globals THREE (three.js r111) and THREE.OrbitControls, inlined before it, the
   replay JSON (schema v1) in <script id="peg-replay" type="application/json"> and the library's labels in
   <script id="peg-vocabulary" type="application/json">.

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
   with their visibility), pegView.timing (load timings, ms), pegView.sensing (the selected agent, its rays
   drawn, its own map's cells shown, and the image shown: its sensor, size and the frame it was taken at). */

var scriptMs = performance.now();  // this script starts running
var startMs = scriptMs;             // the replay starts loading (set in start())

var LAYERS = ['obstacles', 'terrain', 'movers', 'agents', 'trails', 'capture', 'collisions', 'apollonius',
  'cone', 'obstacle_vectors', 'sensing', 'images', 'sight', 'arena'];
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
  sensing: 'Selected agent\'s rays and own map',
  images: 'Selected agent\'s images (depth camera)',
  sight: 'Lines of sight (seen / hidden), fields of view, last-seen ghosts',
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


function fmtNum(x, digits) {
  if (typeof x !== 'number' || !isFinite(x)) return '\u2013';
  var s = x.toFixed(digits);
  return s.charAt(0) === '-' && Number(s) === 0 ? s.slice(1) : s;  // no "-0.000"
}


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
