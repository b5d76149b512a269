// Time: posing every object of the scene at a frame (applyState), rendering, and playback (play, pause,
// seek, step) over the recorded times. Every function takes the viewer `v` (main.js).

// Sample lookup for per-sample series (movers, pairs): the index of the sample in force at frame f and
// the next one with the interpolation weight.
function sampleAt(v, count, f, frac) {
  var pf = v.R.poseFrames, N = v.N;
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

function readQuat(arr, s, out) {
  var o = 7 * s;
  out.set(arr[o + 3], arr[o + 4], arr[o + 5], arr[o + 6]);
  var l = out.length();
  if (!(l > 1e-12) || !isFinite(l)) return out.set(0, 0, 0, 1);
  return out.normalize();
}

function updateTrail(v, a, f) {
  var trailM = v.trailM, trailK = v.trailK;
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

// The selected agent's rays at frame f, drawn from the pose of the frame its readings were taken at (a lidar
// with a period of several steps keeps its readings in between), as sense::Lidar::rays_at aims them: x the
// heading, y level and to its left, z = x cross y.
function updateRays(v, a, f) {
  var lines = v.rayLines, li = a ? a.lidar : null;
  lines.visible = false;
  if (!li || !isActive(a, f)) return;
  var sf = Math.min(li.scanFrame[f], v.N - 1), n = li.rays;
  var o = v.tmpA, x = v.tmpB, z = v.tmpE;
  read3(a.pos, sf, o);
  headingDir(a, sf, x);
  var al = readN(a.heading, 2, sf, 0);
  if (!finite3(o) || !isFinite(al)) return;
  var yx = -Math.sin(al), yy = Math.cos(al);  // y = (-sin alpha, cos alpha, 0)
  z.set(x.y * 0 - x.z * yy, x.z * yx - x.x * 0, x.x * yy - x.y * yx);
  var pos = lines.geometry.attributes.position.array, col = lines.geometry.attributes.color.array;
  for (var k = 0; k < n; ++k) {
    var fx = li.frame[3 * k], fy = li.frame[3 * k + 1], fz = li.frame[3 * k + 2];
    var dx = fx * x.x + fy * yx + fz * z.x, dy = fx * x.y + fy * yy + fz * z.y, dz = fx * x.z + fz * z.z;
    var len = Math.sqrt(dx * dx + dy * dy + dz * dz) || 1, r = li.ranges[f * n + k] / len;
    var echo = li.echo[f * n + k] !== 0, j = 6 * k;
    pos[j] = o.x; pos[j + 1] = o.y; pos[j + 2] = o.z;
    pos[j + 3] = o.x + dx * r; pos[j + 4] = o.y + dy * r; pos[j + 5] = o.z + dz * r;
    col[j] = col[j + 3] = echo ? 1.0 : 0.35;
    col[j + 1] = col[j + 4] = echo ? 0.85 : 0.4;
    col[j + 2] = col[j + 5] = echo ? 0.3 : 0.45;
  }
  lines.geometry.attributes.position.needsUpdate = true;
  lines.geometry.attributes.color.needsUpdate = true;
  lines.geometry.setDrawRange(0, 2 * n);
  lines.visible = true;
}

// Agent a's own map at frame f: its flips up to f applied to the instanced cubes (from the start again when
// seeking back). A cell that becomes free gives its instance to the last one.
function updateMap(a, f) {
  var m = a.map, mv = a.mapView;
  if (mv.applied > 0 && m.frames[mv.applied - 1] > f) {
    mv.applied = 0;
    mv.slot.clear();
    mv.cell.length = 0;
    mv.mesh.count = 0;
  }
  var changed = false, res = m.resolution;
  while (mv.applied < m.frames.length && m.frames[mv.applied] <= f) {
    var k = mv.applied++, cx = m.centres[3 * k], cy = m.centres[3 * k + 1], cz = m.centres[3 * k + 2];
    var key = Math.floor(cx / res) + ',' + Math.floor(cy / res) + ',' + Math.floor(cz / res);  // centres lie mid-cell
    var at = mv.slot.get(key);
    if (m.occupied[k] !== 0) {
      if (at !== undefined || mv.cell.length >= mv.mesh.instanceMatrix.count) continue;
      mv.matrix.makeTranslation(cx, cy, cz);
      mv.mesh.setMatrixAt(mv.cell.length, mv.matrix);
      mv.slot.set(key, mv.cell.length);
      mv.cell.push(key);
    } else {
      if (at === undefined) continue;
      var last = mv.cell.length - 1;
      if (at !== last) {
        mv.mesh.getMatrixAt(last, mv.matrix);
        mv.mesh.setMatrixAt(at, mv.matrix);
        mv.cell[at] = mv.cell[last];
        mv.slot.set(mv.cell[at], at);
      }
      mv.cell.pop();
      mv.slot.delete(key);
    }
    changed = true;
  }
  mv.mesh.count = mv.cell.length;
  if (changed) mv.mesh.instanceMatrix.needsUpdate = true;
}

// The selected agent's first image at frame f (the reading in force then), in the image overlay when the images
// layer is on: near pixels bright, far ones dark, pixels without an echo in dark blue.
function updateImage(v, f) {
  var sel = v.state.agent >= 0 ? v.agents[v.state.agent] : null;
  var im = sel && sel.images.length > 0 ? sel.images[0] : null;
  var box = v.imageBox;
  v.imageShown = null;
  if (!box) return;
  box.hidden = !(im && v.layerOn.images);
  if (box.hidden) return;
  var canvas = v.imageCanvas, n = im.rows * im.columns;
  if (canvas.width !== im.columns || canvas.height !== im.rows) {
    canvas.width = im.columns;
    canvas.height = im.rows;
    v.imageData = null;
  }
  var ctx = canvas.getContext('2d');
  if (!v.imageData) v.imageData = ctx.createImageData(im.columns, im.rows);
  var px = v.imageData.data, span = im.high - im.low;
  for (var k = 0; k < n; ++k) {
    var j = 4 * k;
    if (im.echo[f * n + k] === 0) {
      px[j] = 18; px[j + 1] = 26; px[j + 2] = 58;
    } else {
      var g = Math.round(255 * (1 - Math.min(1, Math.max(0, (im.values[f * n + k] - im.low) / span))));
      px[j] = g; px[j + 1] = g; px[j + 2] = g;
    }
    px[j + 3] = 255;
  }
  ctx.putImageData(v.imageData, 0, 0);
  var taken = Math.min(im.scanFrame[f], v.N - 1);
  v.imageCaption.textContent = sel.label + ' \u00b7 ' + im.sensor + ' ' + im.columns + '\u00d7' + im.rows + ' \u00b7 ' +
    fmtNum(im.low, 0) + '\u2013' + fmtNum(im.high, 0) + ' ' + im.unit + ' \u00b7 taken at ' + fmtNum(v.times[taken], 2) + ' s';
  v.imageShown = { agent: v.state.agent, sensor: im.sensor, rows: im.rows, columns: im.columns, frame: taken };
}

function updateSensing(v, f) {
  var sel = v.state.agent >= 0 ? v.agents[v.state.agent] : null;
  updateRays(v, sel, f);
  updateImage(v, f);
  v.agents.forEach(function (a) {
    if (!a.mapView) return;
    a.mapView.mesh.visible = a === sel;
    if (a === sel) updateMap(a, f);
  });
}

// Poses everything at frame f plus a fraction `frac` (in [0, 1)) towards frame f + 1 (playback only).
// An agent's sight at frame f: the line to its estimate of its opponent, the ghost there while the opponent is
// hidden, and its field of view along its heading.
var SIGHT_UP = new THREE.Vector3(0, -1, 0);
function updateSight(v, a, f, on) {
  var s = a.sight, opp = s.opponent[f];
  var known = on && opp < v.agents.length;
  var est = v.tmpE.set(s.estimate[3 * f], s.estimate[3 * f + 1], s.estimate[3 * f + 2]);
  known = known && finite3(est);
  var seen = s.visible[f] === 1;
  a.sightLine.visible = known;
  a.ghost.visible = known && !seen;
  if (known) {
    var o = a.sightAttr.array;
    o[0] = a.cur.x; o[1] = a.cur.y; o[2] = a.cur.z;
    o[3] = est.x; o[4] = est.y; o[5] = est.z;
    a.sightAttr.needsUpdate = true;
    a.sightLine.material = seen ? a.seenMat : a.hiddenMat;
    if (!seen) a.sightLine.computeLineDistances();
    a.ghost.position.copy(est);
    a.ghost.scale.setScalar(Math.max(0.05, v.agents[opp].radius));
  }
  if (a.fovCone) {
    a.fovCone.visible = on;
    a.fovCone.position.copy(a.cur);
    a.fovCone.quaternion.setFromUnitVectors(SIGHT_UP, a.dir);
  }
}

function applyState(v, f, frac) {
  var R = v.R, N = v.N, agents = v.agents, movers = v.movers, state = v.state;
  var camera = v.camera, controls = v.controls, coneMesh = v.coneMesh, coneGroup = v.coneGroup;
  var apoSphere = v.apoSphere, apoPlane = v.apoPlane, collisionCross = v.collisionCross, collisionDots = v.collisionDots;
  var tmpA = v.tmpA, tmpB = v.tmpB, tmpD = v.tmpD, tmpE = v.tmpE, qa = v.qa, qb = v.qb;
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
    a.body.material = act ? a.bodyMat : v.inactiveMat;
    a.dot.visible = act;
    a.arrow.visible = ok && act;
    a.arrow.position.copy(a.cur);
    a.arrow.setDirection(a.dir);
    if (a.captureSphere) {
      a.captureSphere.visible = ok && act;
      a.captureSphere.position.copy(a.cur);
    }
    updateTrail(v, a, f);
    read3(a.obstacle, f, tmpE);
    var hasVec = ok && act && finite3(tmpE) && tmpE.lengthSq() > 0;
    a.obstacleLine.visible = hasVec;
    if (hasVec) {
      var o = a.obstacleAttr.array;
      o[0] = a.cur.x; o[1] = a.cur.y; o[2] = a.cur.z;
      o[3] = a.cur.x + tmpE.x; o[4] = a.cur.y + tmpE.y; o[5] = a.cur.z + tmpE.z;
      a.obstacleAttr.needsUpdate = true;
    }
    if (a.sight) updateSight(v, a, f, ok && act);
  });

  movers.forEach(function (m) {
    var smp = sampleAt(v, m.count, f, frac);
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
    v.placeMover(m, tmpA, qa, finite3(tmpA));
  });
  v.moverGeom.attributes.position.needsUpdate = true;
  v.moverGeom.attributes.normal.needsUpdate = true;

  // Pair geometry: the sample in force (no interpolation, so it matches the recorded value).
  apoSphere.visible = false;
  apoPlane.visible = false;
  coneGroup.visible = false;
  var pair = state.pair >= 0 ? R.pairs[state.pair] : null;
  if (pair) {
    var P = agents[pair.pursuer], E = agents[pair.evader];
    var live = P.activeNow && E.activeNow && finite3(P.cur) && finite3(E.cur);
    var sa = sampleAt(v, (pair.apollonius.length / 4) | 0, f, 0);
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
          apoPlane.quaternion.setFromUnitVectors(v.upZ, tmpD);
          apoPlane.visible = true;
        }
      }
    }
    var sc = sampleAt(v, (pair.cone.length / 4) | 0, f, 0);
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
        coneGroup.quaternion.setFromUnitVectors(v.downY, tmpD);
        coneGroup.visible = true;
      }
    }
  }

  updateSensing(v, f);

  if (collisionCross) {
    var nc = lastLE(v.collisionFrames, f) + 1;
    collisionCross.geometry.setDrawRange(0, 6 * nc);
    collisionDots.geometry.setDrawRange(0, nc);
    collisionCross.visible = collisionDots.visible = nc > 0;
  }
  v.captureMarks.forEach(function (c) { if (c.obj) c.obj.visible = f >= c.frame; });

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
  v.dirty = true;
}

function renderNow(v) {
  v.renderer.render(v.scene, v.camera);
  v.dirty = false;
}

// The last frame whose time is <= t, with a millionth of a step of slack so that a time computed as
// k * dt (or read back from the panel) finds frame k despite rounding.
function frameAtTime(v, t) {
  var N = v.N, tStart = v.tStart, tEnd = v.tEnd;
  var timeSlack = 1e-6 * (N > 1 && tEnd > tStart ? (tEnd - tStart) / (N - 1) : (v.R.dt > 0 ? v.R.dt : 1));
  return Math.min(N - 1, Math.max(0, lastLE(v.times, t + timeSlack)));
}

// Starts or stops playback; at the end, play starts over.
function setPlaying(v, on) {
  var state = v.state, ui = v.ui, N = v.N, times = v.times;
  on = !!on && !ui.play.disabled;
  if (on && state.frame >= N - 1) {  // at the end: play from the start
    state.playTime = v.tStart;
    applyState(v, 0, 0);
    updatePanel(v, true);
  }
  if (on && !state.playing) state.playTime = times[state.frame] + state.frac * (state.frame < N - 1 ? times[state.frame + 1] - times[state.frame] : 0);
  state.playing = on;
  state.lastTs = null;
  ui.play.textContent = on ? '\u275a\u275a' : '\u25b6';
  ui.play.title = on ? 'Pause (space)' : 'Play (space)';
  ui.play.setAttribute('aria-label', on ? 'Pause' : 'Play');
  if (!on && state.frac !== 0) {  // land exactly on the frame the panel shows
    applyState(v, state.frame, 0);
    updatePanel(v, true);
  }
  v.dirty = true;
}

// The animation loop: advances playback by the real time since the last frame, renders when needed.
function tick(v, ts) {
  requestAnimationFrame(function (next) { tick(v, next); });
  var state = v.state, N = v.N, times = v.times, tEnd = v.tEnd;
  if (state.playing) {
    var dtReal = state.lastTs === null ? 0 : Math.min(0.25, Math.max(0, (ts - state.lastTs) / 1000));
    state.lastTs = ts;
    state.playTime += dtReal * state.speed;
    if (state.playTime >= tEnd) {
      state.playTime = tEnd;
      applyState(v, N - 1, 0);
      setPlaying(v, false);
    } else {
      var f = frameAtTime(v, state.playTime);
      var frac = 0;
      if (f < N - 1 && times[f + 1] > times[f]) frac = Math.min(1, Math.max(0, (state.playTime - times[f]) / (times[f + 1] - times[f])));
      applyState(v, f, frac);
    }
    updatePanel(v, false);
  }
  if (v.dirty) renderNow(v);
}

function seek(v, seconds) {
  var t = Number(seconds);
  if (!isFinite(t)) throw new TypeError('pegView.seek: expected a number of seconds, got ' + String(seconds));
  setPlaying(v, false);
  var f = frameAtTime(v, t);
  v.state.playTime = v.times[f];
  applyState(v, f, 0);
  updatePanel(v, true);
  renderNow(v);
  return f;
}

function stepFrames(v, d) {
  setPlaying(v, false);
  var f = Math.min(v.N - 1, Math.max(0, v.state.frame + d));
  v.state.playTime = v.times[f];
  applyState(v, f, 0);
  updatePanel(v, true);
  renderNow(v);
}
