// The replay's data: its JSON read and its base64 arrays decoded into typed arrays (loadReplay), safe reads of
// the per-frame tracks, and the header's text.

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


// An agent's lidar (rays in its sensor's frame, every frame's readings), or null when it has none or the data
// do not fit together.
function readLidar(li, key, frames) {
  if (!li || typeof li !== 'object') return null;
  var n = Math.floor(num(li.rays, 0));
  var out = {
    rays: n,
    range: Math.max(0, num(li.range, 0)),
    frame: f32(li.frame_f32, key + 'frame_f32'),
    ranges: f32(li.ranges_f32, key + 'ranges_f32'),
    echo: u8(li.echo_u8, key + 'echo_u8'),
    scanFrame: u32(li.scan_frame_u32, key + 'scan_frame_u32')
  };
  var ok = n > 0 && out.frame.length === 3 * n && out.ranges.length >= n * frames && out.echo.length >= n * frames &&
    out.scanFrame.length >= frames;
  return ok ? out : null;
}
// An agent's images: every sensor layer of the agent that holds an `image` (rows x columns of every frame's values,
// row-major from the top left, their echoes, the frame each was taken at), in the agent's order; a layer whose data
// do not fit together is left out.
function readImages(a, key, frames) {
  var out = [];
  Object.keys(a).forEach(function (name) {
    var im = a[name] && typeof a[name] === 'object' ? a[name].image : null;
    if (!im || typeof im !== 'object') return;
    var k = key + name + '.image.';
    var rows = Math.floor(num(im.rows, 0)), columns = Math.floor(num(im.columns, 0));
    var img = {
      sensor: name, rows: rows, columns: columns, unit: str(im.unit, ''),
      low: num(im.low, 0), high: num(im.high, 1),
      values: f32(im.values_f32, k + 'values_f32'),
      echo: u8(im.echo_u8, k + 'echo_u8'),
      scanFrame: u32(im.scan_frame_u32, k + 'scan_frame_u32')
    };
    var n = rows * columns;
    if (n > 0 && img.high > img.low && img.values.length >= n * frames && img.echo.length >= n * frames &&
        img.scanFrame.length >= frames) {
      out.push(img);
    }
  });
  return out;
}
// An agent's limited sight (every frame's opponent, whether it saw it, where it took it to be), or null when its
// sight is not limited or the data do not fit together.
function readSight(si, key, frames) {
  if (!si || typeof si !== 'object') return null;
  var out = {
    fov: Math.min(360, Math.max(0, num(si.fov, 360))),
    range: Math.max(0, num(si.range, 0)),
    opponent: u32(si.opponent_u32, key + 'opponent_u32'),
    visible: u8(si.visible_u8, key + 'visible_u8'),
    estimate: f32(si.estimate_f32, key + 'estimate_f32')
  };
  var ok = out.opponent.length >= frames && out.visible.length >= frames && out.estimate.length >= 3 * frames;
  return ok ? out : null;
}
// An agent's own map as it grows: cells occupied at frame 0, then each change of occupancy, in frame order.
function readMap(m, key) {
  if (!m || typeof m !== 'object') return null;
  var out = {
    resolution: Math.max(1e-3, num(m.resolution, 0.25)),
    frames: u32(m.flip_frames_u32, key + 'flip_frames_u32'),
    centres: f32(m.flip_centres_f32, key + 'flip_centres_f32'),
    occupied: u8(m.flip_occupied_u8, key + 'flip_occupied_u8')
  };
  var k = out.frames.length;
  return out.centres.length === 3 * k && out.occupied.length === k ? out : null;
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
      reward: f32(tr.reward_f32, key + 'reward_f32'),
      lidar: readLidar(a.lidar, 'agents[' + i + '].lidar.', n),
      map: readMap(a.map, 'agents[' + i + '].map.'),
      sight: readSight(a.sight, 'agents[' + i + '].sight.', n),
      images: readImages(a, 'agents[' + i + '].', n)
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
