// The side panel and the controls: legend, speed, the frame slider, play/pause, the pair, agent and camera
// selectors, the layers' checkboxes (setLayer), the distances, the selected agent's inputs and actions, and the
// events so far (updatePanel, for the frame shown). Every function takes the viewer `v` (main.js).

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

function buildPanels(v) {
  var R = v.R, N = v.N, agents = v.agents, times = v.times, state = v.state;
  var tStart = v.tStart, tEnd = v.tEnd, camera = v.camera, controls = v.controls, renderer = v.renderer;
  var centre = v.centre, homeOffset = v.homeOffset, layerGroups = v.layerGroups, layerOn = v.layerOn;
  var drawnTriangles = v.drawnTriangles;
  // --- UI
  var ui = v.ui = {
    play: $('peg-play'), slider: $('peg-slider'), speed: $('peg-speed'), clock: $('peg-clock'),
    barTime: $('peg-time'), frameNo: $('peg-frame'), pair: $('peg-pair'), agent: $('peg-agent'), follow: $('peg-follow'),
    layers: $('peg-layers'), dist: $('peg-dist'), agentInfo: $('peg-agent-info'), events: $('peg-events'),
    legend: $('peg-legend')
  };
  var checkboxes = v.checkboxes = {};

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
    applyState(v, f, 0);
    updatePanel(v, true);
    renderNow(v);
  });

  // Play / pause
  ui.play.disabled = N < 2 || !(tEnd > tStart);
  ui.play.addEventListener('click', function () { setPlaying(v, !state.playing); ui.play.blur(); });

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
    applyState(v, state.frame, state.frac);
    renderNow(v);
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
    buildAgentInfo(v);
    updatePanel(v, true);
    applyState(v, state.frame, state.frac);  // the sensing layer draws the selected agent's rays and map
    renderNow(v);
  });

  // Follow selector
  option(ui.follow, -1, 'none (free orbit)');
  agents.forEach(function (a, i) { option(ui.follow, i, a.label); });
  ui.follow.value = '-1';
  ui.follow.addEventListener('change', function () {
    state.follow = Number(ui.follow.value);
    state.followPrev = null;
    applyState(v, state.frame, state.frac);
    renderNow(v);
  });
  $('peg-home').addEventListener('click', function () {
    state.follow = -1;
    state.followPrev = null;
    ui.follow.value = '-1';
    camera.position.copy(centre).add(homeOffset);
    controls.target.copy(centre);
    controls.update();
    renderNow(v);
    this.blur();
  });
  $('peg-png').addEventListener('click', function () {
    var btn = this;
    btn.blur();
    renderNow(v);
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
    resize(v);
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
    sensing: agents.filter(function (a) { return a.lidar; }).length,
    images: agents.filter(function (a) { return a.images.length > 0; }).length,
    sight: agents.filter(function (a) { return a.sight; }).length,
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
      setLayer(v, name, cb.checked);
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


  // Distances panel
  v.distRows = R.pairs.map(function (p) {
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
  v.distNone = distNone;
  distNone.appendChild(el('td', '', R.pairs.length === 0 ? 'no pursuer\u2013evader pairs' : 'no active pair'));
  ui.dist.appendChild(distNone);

  v.agentCells = null;
  v.eventsKey = '';
  v.panelFrame = -1;
  buildAgentInfo(v);
}

function setLayer(v, name, visible) {
  var layerGroups = v.layerGroups;
  if (!Object.prototype.hasOwnProperty.call(layerGroups, name)) {
    throw new Error('pegView.setLayer: unknown layer "' + name + '" (layers: ' + LAYERS.join(', ') + ')');
  }
  var on = !!visible;
  v.layerOn[name] = on;
  layerGroups[name].visible = on;
  if (v.checkboxes[name]) v.checkboxes[name].checked = on;
  if (name === 'images') updateImage(v, v.state.frame);  // a panel over the view, not in the scene
  renderNow(v);
}

// Agent panel
function buildAgentInfo(v) {
  var ui = v.ui, state = v.state, agents = v.agents;
  ui.agentInfo.textContent = '';
  v.agentCells = null;
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
  v.agentCells = cells;
  var sw = $('peg-agent-swatch');
  if (sw) sw.style.background = cssColor(a.color);
}

function lastEventText(v, f) {
  var R = v.R, agents = v.agents, times = v.times;
  var nc = lastLE(v.collisionFrames, f) + 1;
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

function updatePanel(v, force) {
  var ui = v.ui, state = v.state, agents = v.agents, times = v.times, N = v.N, tmpA = v.tmpA, tmpB = v.tmpB;
  var agentCells = v.agentCells;
  var f = state.frame;
  if (!force && f === v.panelFrame) return;
  v.panelFrame = f;
  var clock = fmtNum(times[f], 2) + ' s';
  ui.clock.textContent = 't = ' + clock + ' / ' + fmtNum(v.tEnd, 2) + ' s';
  ui.frameNo.textContent = 'frame ' + f + ' / ' + (N - 1);
  ui.barTime.textContent = clock + ' \u00b7 ' + f;
  ui.slider.value = String(f);

  var shown = 0;
  v.distRows.forEach(function (r) {
    var on = isActive(r.e, f);
    r.tr.hidden = !on;
    if (on) {
      shown++;
      read3(r.p.pos, f, tmpA);
      read3(r.e.pos, f, tmpB);
      r.td.textContent = fmtNum(tmpA.distanceTo(tmpB), 2) + ' m';
    }
  });
  v.distNone.hidden = shown > 0;

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

  var parts = lastEventText(v, f);
  var key = parts.join('\n');
  if (key !== v.eventsKey) {
    v.eventsKey = key;
    ui.events.textContent = '';
    parts.forEach(function (p) { ui.events.appendChild(el('div', p.indexOf('captured') === 0 ? 'peg-capture' : '', p)); });
  }
}
