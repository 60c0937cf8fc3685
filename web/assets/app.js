// The experimenter's page of `freeplay serve --web` (schema: docs/web.md). Plain JS, no dependencies.
'use strict';
(() => {
  const token = new URLSearchParams(location.search).get('token') || '';
  const freezeAt = parseFloat(new URLSearchParams(location.search).get('freeze') || 'NaN');
  const pictures = new URLSearchParams(location.search).get('pictures') !== '0';  // 0: footprint polygons only
  const picture = {};
  const withToken = (path) => token ? `${path}${path.includes('?') ? '&' : '?'}token=${encodeURIComponent(token)}` : path;
  const $ = (id) => document.getElementById(id);
  const canvas = $('tray');
  const ctx = canvas.getContext('2d');
  const seatColour = { purple: '#9b59d0', yellow: '#e8c21c' };
  const presets = ['Hello!', 'Your turn!', 'Well done!', 'Where shall I put it?', 'Let us play together', 'Goodbye!'];
  let scene = null, state = null, zones = [], events = [], background = null, backgroundVersion = -1;
  let drag = null, clickMode = null, frozen = false, drawPending = false, cameraVersion = 0;
  const timelines = {};
  window.__latencies = [];
  window.__frames = 0;
  window.__events = events;

  const W = () => scene ? scene.screen.width_m : 0.6;
  const H = () => scene ? scene.screen.height_m : 0.335;
  const toPx = (x, y) => [x / W() * canvas.width, -y / H() * canvas.height];
  const toTray = (px, py) => [px / canvas.width * W(), -py / canvas.height * H()];
  const mmss = (s) => `${Math.floor(s / 60)}:${String(Math.floor(s % 60)).padStart(2, '0')}`;

  async function send(command) {
    const r = await fetch(withToken('/api/command'), { method: 'POST', headers: { 'Content-Type': 'application/json' },
                                                      body: JSON.stringify(command) });
    const body = await r.json().catch(() => ({}));
    if (!r.ok) { log({ t: state ? state.t : 0, source: 'page', type: 'refused', data: { status: r.status, error: body.error } }); }
    return { status: r.status, body };
  }
  window.__send = send;

  function log(e) {
    events.push(e);
    const li = document.createElement('li');
    li.textContent = `${e.t.toFixed(1)} ${e.source} ${e.type} ${e.data ? JSON.stringify(e.data) : ''}`;
    const list = $('events');
    list.prepend(li);
    while (list.children.length > 200) list.lastChild.remove();
  }

  function itemAt(x, y) {
    if (!state || !scene) return null;
    let best = null;
    for (const it of state.items) {
      if (!it.visible) continue;
      const spec = scene.items.find((s) => s.name === it.name);
      const d = Math.hypot(it.x - x, it.y - y);
      if (d < spec.box_side_m / 2 && (!best || it.z > best.z)) best = it;
    }
    return best;
  }

  function polygon(points, ox, oy, theta) {
    ctx.beginPath();
    points.forEach(([px, py], i) => {
      const x = ox + px * Math.cos(theta) - py * Math.sin(theta), y = oy + px * Math.sin(theta) + py * Math.cos(theta);
      const [cx, cy] = toPx(x, y);
      if (i === 0) ctx.moveTo(cx, cy); else ctx.lineTo(cx, cy);
    });
    ctx.closePath();
  }

  function dot(x, y, r, fill, stroke) {
    const [cx, cy] = toPx(x, y);
    ctx.beginPath();
    ctx.arc(cx, cy, r, 0, 2 * Math.PI);
    if (fill) { ctx.fillStyle = fill; ctx.fill(); }
    if (stroke) { ctx.strokeStyle = stroke; ctx.lineWidth = 2; ctx.stroke(); }
  }

  function cross(x, y, colour) {
    const [cx, cy] = toPx(x, y);
    ctx.strokeStyle = colour; ctx.lineWidth = 2;
    ctx.beginPath(); ctx.moveTo(cx - 9, cy); ctx.lineTo(cx + 9, cy); ctx.moveTo(cx, cy - 9); ctx.lineTo(cx, cy + 9); ctx.stroke();
  }

  function draw() {
    drawPending = false;
    ctx.fillStyle = '#000';
    ctx.fillRect(0, 0, canvas.width, canvas.height);
    if (!state || !scene) return;
    if (background) ctx.drawImage(background, 0, 0, canvas.width, canvas.height);
    for (const z of zones) {
      polygon(z.polygon, 0, 0, 0);
      ctx.strokeStyle = z.colour === 'white' ? '#ddd' : z.colour; ctx.lineWidth = 2; ctx.setLineDash([6, 4]); ctx.stroke();
      ctx.setLineDash([]);
    }
    const items = [...state.items].sort((a, b) => a.z - b.z);
    for (const it of items) {
      if (!it.visible) continue;
      const spec = scene.items.find((s) => s.name === it.name);
      const [cx, cy] = toPx(it.x, it.y);
      const img = picture[it.name];
      if (pictures && img && img.complete) {  // the game's picture, rotated as on the screen (θ is CCW in sandtray)
        const side = spec.box_side_m / W() * canvas.width;
        ctx.save(); ctx.translate(cx, cy); ctx.rotate(-it.theta); ctx.drawImage(img, -side / 2, -side / 2, side, side); ctx.restore();
        if (it.holder !== 'none') {
          polygon(spec.polygon, it.x, it.y, it.theta);
          ctx.strokeStyle = it.holder === 'robot' ? '#3fa9f5' : '#fff'; ctx.lineWidth = 3; ctx.stroke();
        }
        continue;
      }
      polygon(spec.polygon, it.x, it.y, it.theta);
      ctx.fillStyle = `rgba(${spec.colour.join(',')},0.92)`; ctx.fill();
      ctx.strokeStyle = it.holder === 'robot' ? '#3fa9f5' : it.holder === 'finger' ? '#fff' : '#222';
      ctx.lineWidth = it.holder === 'none' ? 1 : 3; ctx.stroke();
      ctx.fillStyle = '#111'; ctx.font = '12px sans-serif'; ctx.textAlign = 'center';
      ctx.fillText(spec.label, cx, cy + 4);
    }
    for (const c of state.children || []) {
      for (const f of state.touches) if (c.fingers.includes(f.finger)) dot(f.x, f.y, 9, seatColour[c.seat], '#fff');
      if (c.gaze_point && c.gaze_point[2] < 0.05 && ['tray', 'item'].includes(c.gaze)) dot(c.gaze_point[0], c.gaze_point[1], 5, null, seatColour[c.seat]);
    }
    const rc = state.robot_control;
    if (state.robot) {
      if (state.robot.hand) dot(state.robot.hand[0], state.robot.hand[1], 11, 'rgba(63,169,245,0.35)', '#3fa9f5');
      if (state.robot.finger) dot(state.robot.finger[0], state.robot.finger[1], 7, '#3fa9f5', '#fff');
      const g = state.robot.gaze_point;
      if (g && g[2] < 0.05) cross(g[0], g[1], '#3fa9f5');
    }
    if (rc && rc.reach) {  // the arm_reach disc: where the robot can move items
      const [cx, cy] = toPx(rc.reach.centre[0], rc.reach.centre[1]);
      ctx.beginPath(); ctx.arc(cx, cy, rc.reach.radius / W() * canvas.width, 0, 2 * Math.PI);
      ctx.strokeStyle = 'rgba(63,169,245,0.6)'; ctx.lineWidth = 1; ctx.setLineDash([2, 6]); ctx.stroke(); ctx.setLineDash([]);
    }
    if (rc && rc.move) { const [x, y] = rc.move.target; cross(x, y, '#f0c040'); }
    if (drag) {
      const spec = scene.items.find((s) => s.name === drag.item);
      polygon(spec.polygon, drag.x, drag.y, 0);
      ctx.strokeStyle = '#f0c040'; ctx.lineWidth = 2; ctx.setLineDash([4, 3]); ctx.stroke(); ctx.setLineDash([]);
    }
  }
  const schedule = () => { if (!drawPending) { drawPending = true; requestAnimationFrame(draw); } };

  function updatePanels() {
    $('stage').textContent = state.stage;
    $('clock').textContent = mmss(state.t || 0);
    $('freeplay').textContent = state.freeplay_t >= 0 ? mmss(state.freeplay_t) : '–';
    const rc = state.robot_control;
    if (rc) {
      for (const r of document.querySelectorAll('input[name=mode]')) r.checked = r.value === rc.mode;
      $('proposal').textContent = rc.proposal
        ? `${rc.proposal.actions.map((a) => a.action + (a.item ? ' ' + a.item : '')).join(', ')} in ${rc.proposal.remaining_s.toFixed(1)} s`
        : 'none';
      $('robot-status').textContent = (rc.move ? `moving ${rc.move.item} (${rc.move.by})` : 'idle') +
        (rc.last_said ? ` · said “${rc.last_said}”` : '');
    }
    if (state.components) components(state.components);
    if (state.experiment) {
      const e = state.experiment;
      $('experiment-status').textContent = `${e.file} · ${e.markers.length} markers` +
        (e.social_engagement ? ` · social engagement ${e.social_engagement}` : '') + (e.finalised ? ' · finalised' : '');
    }
    for (const c of state.children || []) {
      const t = timelines[c.seat] || (timelines[c.seat] = makeTimeline(c.seat));
      t.info.textContent = `gaze ${c.gaze}${c.speaking ? ' · speaking' : ''} · fingers ${c.fingers.length}` +
        (c.coded ? ` · coded ${c.coded.task} / ${c.coded.social} / ${c.coded.attitude}` : '');
      t.samples.push({ gaze: c.gaze, speaking: c.speaking, touching: c.fingers.length > 0, coded: c.coded });
      if (t.samples.length > 600) t.samples.shift();
      drawTimeline(t);
    }
  }

  const gazeColour = { tray: '#5a9', item: '#7c5', partner: '#e85', robot: '#3fa9f5', away: '#666', experimenter: '#a5a' };
  // The coder's ground truth (simulation only), one row per PInSoRo axis.
  const codedColour = {
    task: { goaloriented: '#4caf50', aimless: '#c0ca33', adultseeking: '#ff9800', noplay: '#757575' },
    social: { solitary: '#607d8b', onlooker: '#90a4ae', parallel: '#29b6f6', associative: '#7e57c2', cooperative: '#ec407a' },
    attitude: { prosocial: '#66bb6a', adversarial: '#e53935', assertive: '#ffb300', frustrated: '#8d6e63', passive: '#9e9e9e' },
  };
  function makeTimeline(seat) {
    const div = document.createElement('div');
    div.className = 'child';
    div.innerHTML = `<b class="seat-${seat}">${seat}</b> <span class="small"></span><canvas width="600" height="72"></canvas>` +
      '<div class="small">rows: gaze · speech · touch · coded task · social · attitude</div>';
    $('children').append(div);
    return { info: div.querySelector('span'), canvas: div.querySelector('canvas'), samples: [] };
  }
  function drawTimeline(t) {
    const c = t.canvas.getContext('2d');
    c.clearRect(0, 0, t.canvas.width, t.canvas.height);
    t.samples.forEach((s, i) => {
      const x = t.canvas.width - t.samples.length + i;
      c.fillStyle = gazeColour[s.gaze] || '#444'; c.fillRect(x, 0, 1, 12);
      if (s.speaking) { c.fillStyle = '#eee'; c.fillRect(x, 12, 1, 12); }
      if (s.touching) { c.fillStyle = '#c94'; c.fillRect(x, 24, 1, 12); }
      if (s.coded) {
        ['task', 'social', 'attitude'].forEach((axis, k) => {
          c.fillStyle = codedColour[axis][s.coded[axis]] || '#444'; c.fillRect(x, 36 + 12 * k, 1, 12);
        });
      }
    });
  }

  // The experiment manager's status panel: every component, with start/stop where it has one.
  function components(c) {
    const rows = [['game', c.game, null], ['robot side', c.robot, 'robot'], ['recorder', c.recorder, 'recorder'],
                  ['cameras', c.cameras, 'cameras']];
    for (const [label, status, name] of rows) {
      let row = document.querySelector(`#components [data-component="${label}"]`);
      if (!row) {
        row = document.createElement('div');
        row.className = 'row'; row.dataset.component = label;
        row.innerHTML = `<span class="label">${label}</span> <span class="chip"></span> <span class="small"></span>`;
        if (name) {
          for (const action of ['start', 'stop']) {
            const b = document.createElement('button');
            b.textContent = action; b.dataset.componentAction = `${name}:${action}`;
            b.onclick = () => send({ type: 'component', name, action });
            row.append(b);
          }
        }
        $('components').append(row);
      }
      row.hidden = !status;
      if (!status) continue;
      row.querySelector('.chip').textContent = status.state;
      row.querySelector('.small').textContent =
        name === 'recorder' ? `${status.messages} messages · paused ${status.paused_s.toFixed(0)} s` :
        name === 'cameras' ? status.names.join(', ') : name === 'robot' ? status.mode : status.stage;
      for (const b of row.querySelectorAll('button')) {
        b.disabled = (name === 'cameras' && status.state === 'none') ||
          b.textContent === (['running', 'recording'].includes(status.state) ? 'start' : 'stop');
      }
    }
  }

  function participants() {
    const seats = scene.robot ? ['purple'] : ['purple', 'yellow'];
    $('participants').innerHTML = seats.map((seat) => `<fieldset data-seat="${seat}"><legend class="seat-${seat}">${seat} child</legend>
      <div class="row">Gender <select name="gender"><option>female</option><option>male</option></select>
      Age <input name="age" type="number" min="3" max="8" value="6"></div>
      <div class="row">Tablet <select name="tablet_familiarity"><option value="na">not known</option>
        <option value="0">not familiar</option><option value="1">somewhat</option><option value="2">familiar</option></select></div>
      </fieldset>`).join('');
    document.querySelector('select[name=condition]').value = scene.robot ? 'childrobot' : 'childchild';
  }

  function onFrame(frame) {
    window.__frames++;
    if (frame.tick_unix_ms) window.__latencies.push(Date.now() - frame.tick_unix_ms);
    if (frame.zones) zones = frame.zones;
    for (const e of frame.events || []) log(e);
    if (frozen) return;
    state = { ...state, ...frame };
    window.__state = state;
    if (frame.background_version !== undefined && frame.background_version !== backgroundVersion) {
      backgroundVersion = frame.background_version;
      const img = new Image();
      img.onload = () => { background = img; window.__backgroundVersion = backgroundVersion; schedule(); };
      img.src = withToken(`/api/background.jpg?v=${backgroundVersion}`);
    }
    const cam = frame.camera;
    $('camera-img').hidden = !cam;
    if (cam && cam.version > 0 && cam.version !== cameraVersion) {
      cameraVersion = cam.version;
      $('camera-img').src = withToken(`/api/camera.jpg?v=${cam.version}`);
    }
    if (!isNaN(freezeAt) && state.t >= freezeAt) { frozen = true; window.__frozenAt = state.t; }
    updatePanels();
    schedule();
  }

  function connect() {
    const ws = new WebSocket(withToken(`ws://${location.host}/ws`));
    ws.onopen = () => { $('link').textContent = 'live'; $('link').classList.remove('down'); };
    ws.onmessage = (m) => onFrame(JSON.parse(m.data));
    ws.onclose = () => { $('link').textContent = 'disconnected'; $('link').classList.add('down'); setTimeout(connect, 1000); };
  }

  function pointer(ev) {
    const r = canvas.getBoundingClientRect();
    return toTray((ev.clientX - r.left) / r.width * canvas.width, (ev.clientY - r.top) / r.height * canvas.height);
  }
  canvas.addEventListener('pointerdown', (ev) => {
    const [x, y] = pointer(ev);
    if (clickMode) {
      send(clickMode === 'point' ? { type: 'point_at', x, y } : { type: 'look_at', x, y, z: 0 });
      clickMode = null;
      for (const b of document.querySelectorAll('.armed')) b.classList.remove('armed');
      return;
    }
    const it = itemAt(x, y);
    if (it) { drag = { item: it.name, x, y }; canvas.setPointerCapture(ev.pointerId); schedule(); }
  });
  canvas.addEventListener('pointermove', (ev) => { if (drag) { [drag.x, drag.y] = pointer(ev); schedule(); } });
  canvas.addEventListener('pointerup', (ev) => {
    if (!drag) return;
    const [x, y] = pointer(ev);
    const item = drag.item;
    drag = null;
    schedule();
    send({ type: 'move', item, x: Math.min(Math.max(x, 0), W()), y: Math.min(Math.max(y, -H()), 0) });
  });

  for (const r of document.querySelectorAll('input[name=mode]')) r.addEventListener('change', () => send({ type: 'mode', mode: r.value }));
  $('accept').onclick = () => send({ type: 'sparc', decision: 'accept' });
  $('veto').onclick = () => send({ type: 'sparc', decision: 'veto' });
  $('set-timeout').onclick = () => send({ type: 'sparc_timeout', seconds: parseFloat($('sparc-timeout').value) });
  $('say').onclick = () => { if ($('say-text').value) send({ type: 'say', text: $('say-text').value }); };
  for (const p of presets) {
    const b = document.createElement('button');
    b.textContent = p; b.onclick = () => send({ type: 'say', text: p });
    $('presets').append(b);
  }
  for (const b of document.querySelectorAll('[data-look]')) b.onclick = () => send({ type: 'look_at', child: b.dataset.look });
  $('look-click').onclick = (ev) => { clickMode = 'look'; ev.target.classList.add('armed'); };
  $('point-click').onclick = (ev) => { clickMode = 'point'; ev.target.classList.add('armed'); };
  $('stop').onclick = () => send({ type: 'stop' });
  for (const b of document.querySelectorAll('[data-signal]')) b.onclick = () => send({ type: 'signal', name: b.dataset.signal });
  for (const b of document.querySelectorAll('[data-marker]')) {
    b.onclick = () => send({ type: 'marker', kind: b.dataset.marker, text: $('marker-text').value });
  }
  for (let i = 1; i <= 5; ++i) {
    const b = document.createElement('button');
    b.textContent = i; b.dataset.likert = i; b.onclick = () => send({ type: 'likert', social_engagement: i });
    $('likert').append(b);
  }
  $('finalise').onclick = () => send({ type: 'finalise' });
  $('camera').onchange = () => send({ type: 'camera', name: $('camera').value });
  $('demographics').addEventListener('submit', async (ev) => {
    ev.preventDefault();
    await send({ type: 'condition', condition: document.querySelector('select[name=condition]').value });
    const command = { type: 'demographics' };
    for (const f of document.querySelectorAll('#participants fieldset')) {
      command[f.dataset.seat] = { age: parseInt(f.querySelector('[name=age]').value, 10),
                                  gender: f.querySelector('[name=gender]').value,
                                  tablet_familiarity: f.querySelector('[name=tablet_familiarity]').value };
    }
    window.__demographics = await send(command);
  });

  fetch(withToken('/api/scene')).then((r) => r.json()).then((s) => {
    scene = s;
    window.__scene = s;
    if (pictures) {
      for (const item of s.items) {
        const img = new Image();
        img.onload = schedule;
        img.src = withToken(`/api/item/${item.name}.png`);
        picture[item.name] = img;
      }
    }
    $('scenario').textContent = `${s.scenario} (${s.condition})`;
    $('cap').textContent = mmss(s.protocol.freeplay_cap_s);
    if (!s.robot) $('robot-panel').style.display = 'none';
    for (const b of document.querySelectorAll('[data-look]')) if (!s.seats.includes(b.dataset.look)) b.style.display = 'none';
    participants();
    connect();
  });
})();
