// The experimenter's page in a real browser (Debian chromium, headless, via puppeteer-core): it loads without console
// errors, shows the ten items where the simulation has them, a drag makes the simulated robot move the item to the
// drop point, the demographics form writes experiment.yaml, protocol and marker buttons reach the session, two pages
// see the same session, bad requests and wrong tokens get 4xx, and the tray matches the expected picture.
// Usage: node browser_test.mjs FREEPLAY SCENARIO OUTDIR EXPECTED_DIR (run by run_browser_test.sh).
import puppeteer from 'puppeteer-core';
import WebSocket from 'ws';
import { spawn } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import readline from 'node:readline';

const [freeplay, scenario, out, expectedDir] = process.argv.slice(2);
const token = 'browser-test-token-0123456789';
const session = path.join(out, 'session');
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));
const failures = [];
function check(ok, what, detail = '') {
  console.log(`${ok ? 'ok  ' : 'FAIL'} ${what}${detail ? ': ' + detail : ''}`);
  if (!ok) failures.push(what);
}
async function until(what, f, timeoutMs = 30000) {
  const end = Date.now() + timeoutMs;
  for (;;) {
    const v = await f();
    if (v) return v;
    if (Date.now() > end) throw new Error(`timed out waiting for ${what}`);
    await sleep(100);
  }
}
// A minimal Foxglove client: subscribes to every channel and decodes /tf, the background, the joints and the camera.
function foxglove(url) {
  return new Promise((resolve, reject) => {
    const ws = new WebSocket(url, ['foxglove.websocket.v1']);
    const result = { protocol: '', serverInfo: false, topics: [], tfSchema: '', tf: [], links: new Set(), joints: 0, png: false, camera: false };
    const channels = {};
    const timer = setTimeout(() => { ws.close(); reject(new Error('no Foxglove messages')); }, 15000);
    ws.on('open', () => { result.protocol = ws.protocol; });
    ws.on('message', (data, binary) => {
      if (!binary) {
        const m = JSON.parse(data.toString());
        if (m.op === 'serverInfo') result.serverInfo = true;
        if (m.op === 'advertise') {
          for (const c of m.channels) { channels[c.id] = c; result.topics.push(c.topic); }
          result.tfSchema = m.channels.find((c) => c.topic === '/tf').schema;
          ws.send(JSON.stringify({ op: 'subscribe', subscriptions: m.channels.map((c) => ({ id: 100 + c.id, channelId: c.id })) }));
        }
        return;
      }
      const b = Buffer.from(data);
      if (b[0] !== 1) return;
      const topic = channels[b.readUInt32LE(1) - 100].topic;
      let o = 13;
      const str = () => { const n = b.readUInt32LE(o); o += 4; const v = b.toString('utf8', o, o + n); o += n; return v; };
      if (topic === '/tf') {  // one game broadcaster (sandtray → an item or a touch) or the Nao's links (robot_state_publisher)
        const count = b.readUInt32LE(o); o += 4;
        const frames = [];
        for (let i = 0; i < count; ++i) {
          o += 12; const parent = str(); const child = str();
          const x = b.readDoubleLE(o), y = b.readDoubleLE(o + 8); o += 7 * 8;
          frames.push({ parent, child, x, y });
        }
        if (frames.length === 1 && frames[0].parent === 'sandtray') {
          if (!result.tf.some((t) => t.child === frames[0].child)) result.tf.push(frames[0]);
        } else {
          for (const f of frames) result.links.add(f.child);
        }
      }
      if (topic === '/env_camera/qhd/image_color/compressed') {  // the scenario's stage camera, at its rate
        o += 12; const frame = str(); const format = str(); const n = b.readUInt32LE(o);
        result.camera = frame === 'env_camera_rgb_optical_frame' && format === 'jpeg' && b[o + 4] === 0xff && b[o + 5] === 0xd8 && n > 1000;
      }
      if (topic === '/joint_states') {
        o += 12; str(); result.joints = b.readUInt32LE(o);
      }
      if (topic === '/sandtray/background/image/compressed') {
        o += 12; str(); const format = str(); const n = b.readUInt32LE(o);
        result.png = format === 'rgba8; png compressed bgr8' && b[o + 4] === 0x89 && b[o + 5] === 0x50 && n > 1000;
      }
      if (result.tf.length >= 10 && result.png && result.links.size && result.joints && result.camera) { clearTimeout(timer); ws.close(); resolve(result); }
    });
    ws.on('error', reject);
  });
}
const readText = (file) => (fs.existsSync(file) ? fs.readFileSync(file, 'utf8') : '');

// Greetings 6 s and a 1 s tutorial: free play starts at t = 7 s; the frozen page keeps the tray at t = 7.5 s.
fs.rmSync(session, { recursive: true, force: true });
const server = spawn(freeplay, ['serve', scenario, '--web', '0', '--web-token', token, '--web-out', session,
                                '--web-mode', 'wizard', '--seed', '7', '--set', 'protocol.greeting_s=6',
                                '--set', 'protocol.tutorial_s=1', '--set', 'protocol.freeplay_cap_s=120',
                                '--set', 'protocol.debriefing_s=1', '--web-no-linger',
                                '--set', 'cameras=[{name: env_camera, rate_hz: 1, width: 320, height: 180}]'],
                     { stdio: ['ignore', 'pipe', 'inherit'] });
const firstLine = await new Promise((resolve, reject) => {
  readline.createInterface({ input: server.stdout }).once('line', resolve);
  server.once('exit', (code) => reject(new Error(`freeplay serve exited with ${code}`)));
});
const base = firstLine.replace(/^web: /, '').replace(/\/\?token=.*$/, '');
const api = (p) => `${base}${p}${p.includes('?') ? '&' : '?'}token=${token}`;
const post = (body, url = api('/api/command')) => fetch(url, { method: 'POST', body: typeof body === 'string' ? body : JSON.stringify(body) });
let browser;
try {
  // ---- bad requests and tokens (before free play: robot actions are refused with 409) ----------------------------
  check((await fetch(`${base}/`)).status === 401, 'the page without the token is refused (401)');
  check((await fetch(`${base}/?token=wrong-wrong-wrong-wrong`)).status === 401, 'a wrong token is refused (401)');
  check((await post({ type: 'stop' }, `${base}/api/command?token=nope`)).status === 401, 'a command with a wrong token is refused (401)');
  let r = await post('{"type": "move", "item": ');
  check(r.status === 400 && (await r.json()).error.includes('not JSON'), 'malformed JSON gets 400 with a message');
  r = await post({ type: 'move', item: 'zebra', x: 5, y: -0.1 });
  const outOfRange = await r.json();
  check(r.status === 400 && outOfRange.error.includes("'x' = 5 is out of range"), 'an off-screen drop gets 400', outOfRange.error);
  r = await post({ type: 'move', item: 'unicorn', x: 0.3, y: -0.1 });
  check(r.status === 400 && (await r.json()).error.includes('zebra'), 'an unknown item gets 400 naming the items');
  r = await post({ type: 'move', item: 'zebra', x: 0.3, y: -0.1 });
  check(r.status === 409, 'a move outside free play gets 409', `${r.status}`);
  // The scenario camera renders (llvmpipe, on every core) only from the Foxglove check on: the latency figures are
  // taken without it first, then with it.
  check((await post({ type: 'component', name: 'cameras', action: 'stop' })).status === 202, 'the cameras can be paused before free play');

  browser = await puppeteer.launch({ executablePath: process.env.FREEPLAY_CHROMIUM, headless: 'new',
                                     args: ['--no-sandbox', '--disable-gpu', '--disable-dev-shm-usage', '--font-render-hinting=none',
                                            // two pages live side by side: neither is a throttled background tab
                                            '--disable-background-timer-throttling', '--disable-renderer-backgrounding',
                                            '--disable-backgrounding-occluded-windows'] });
  const open = async (query) => {
    const page = await browser.newPage();
    await page.setViewport({ width: 1280, height: 860, deviceScaleFactor: 1 });
    page.errors = [];
    page.on('console', (m) => { if (m.type() === 'error') page.errors.push(m.text()); });
    page.on('pageerror', (e) => page.errors.push(String(e)));
    await page.goto(`${base}/?token=${token}${query}`, { waitUntil: 'load' });
    return page;
  };
  const page = await open('');
  const frozen = await open('&freeze=7.5&pictures=0');  // footprints in item colours: checked pixel by pixel

  // ---- the tray picture at t = 7.5 s against the expected one -------------------------------------------------
  await frozen.waitForFunction(() => window.__frozenAt !== undefined && window.__backgroundVersion === window.__state.background_version,
                               { timeout: 60000 });
  await sleep(300);
  const tray = path.join(out, 'tray.png');
  await (await frozen.$('#tray')).screenshot({ path: tray });
  const expected = path.join(expectedDir, 'tray.png');
  if (!fs.existsSync(expected) || process.env.FREEPLAY_UPDATE_EXPECTED === '1') {
    fs.mkdirSync(expectedDir, { recursive: true });
    fs.copyFileSync(tray, expected);
    console.log(`note: wrote the expected picture ${expected}`);
  }
  const diff = await frozen.evaluate(async (a, b) => {
    const load = (src) => new Promise((res) => { const i = new Image(); i.onload = () => res(i); i.src = src; });
    const [x, y] = await Promise.all([load(a), load(b)]);
    const pixels = (img) => {
      const c = document.createElement('canvas'); c.width = x.width; c.height = x.height;
      const g = c.getContext('2d'); g.drawImage(img, 0, 0, x.width, x.height);
      return g.getImageData(0, 0, x.width, x.height).data;
    };
    const p = pixels(x), q = pixels(y);
    let sum = 0, far = 0;
    for (let i = 0; i < p.length; i += 4) {
      const d = (Math.abs(p[i] - q[i]) + Math.abs(p[i + 1] - q[i + 1]) + Math.abs(p[i + 2] - q[i + 2])) / 3;
      sum += d; if (d > 48) ++far;
    }
    return { mean: sum / (p.length / 4), far_share: far / (p.length / 4), size: [x.width, x.height, y.width, y.height] };
  }, `data:image/png;base64,${fs.readFileSync(tray).toString('base64')}`, `data:image/png;base64,${fs.readFileSync(expected).toString('base64')}`);
  check(diff.mean <= 6 && diff.far_share <= 0.03, 'the tray matches the expected picture (mean |Δ| ≤ 6, ≤ 3 % pixels off by > 48)',
        JSON.stringify(diff));

  // ---- the ten items where the simulation has them --------------------------------------------------------------
  let same = false;
  for (let i = 0; i < 50 && !same; ++i) {
    const serverState = await (await fetch(api('/api/state'))).json();
    const pageState = await page.evaluate(() => window.__state);
    if (serverState.seq !== pageState.seq) { await sleep(30); continue; }
    same = serverState.items.length === 10 && JSON.stringify(serverState.items) === JSON.stringify(pageState.items);
  }
  check(same, "the page's ten items equal the simulation's at the same tick");
  const drawn = await frozen.evaluate(() => {
    const s = window.__state, scene = window.__scene, c = document.getElementById('tray'), g = c.getContext('2d');
    let good = 0; const bad = [];
    for (const it of s.items) {
      const x = it.x, y = it.y - 0.006;  // below the label
      const under = s.items.filter((o) => Math.hypot(o.x - x, o.y - y) < scene.items.find((k) => k.name === o.name).box_side_m * 0.3);
      const top = under.length ? under.reduce((a, b) => (b.z > a.z ? b : a)) : it;
      const colour = scene.items.find((k) => k.name === top.name).colour;
      const px = g.getImageData(Math.round(x / 0.6 * c.width), Math.round(-y / 0.335 * c.height), 1, 1).data;
      const ok = [0, 1, 2].every((k) => Math.abs(px[k] - colour[k]) < 40);
      if (ok) ++good; else bad.push(`${it.name}:${[...px.slice(0, 3)]}≠${colour}`);
    }
    return { good, bad };
  });
  check(drawn.good >= 8, 'the canvas draws the items at their simulated places (colour at each centre)', JSON.stringify(drawn));

  // ---- drag an item: the robot moves it there ------------------------------------------------------------------
  await page.bringToFront();
  await page.waitForFunction(() => window.__state.stage === 'freeplay' && window.__state.freeplay_t >= 2 &&
                             window.__state.robot_control && window.__state.robot_control.reach, { timeout: 30000 });
  const plan = await page.evaluate(() => {
    const s = window.__state, reach = s.robot_control.reach;
    const free = s.items.filter((i) => i.visible && i.holder === 'none');
    const item = free.reduce((a, b) => (Math.hypot(b.x - reach.centre[0], b.y - reach.centre[1]) <
                                       Math.hypot(a.x - reach.centre[0], a.y - reach.centre[1]) ? b : a));
    const [cx, cy] = [0.25, -0.17];
    const k = Math.min(1, 0.5 * reach.radius / Math.hypot(cx - reach.centre[0], cy - reach.centre[1]));
    const drop = [reach.centre[0] + k * (cx - reach.centre[0]), reach.centre[1] + k * (cy - reach.centre[1])];
    const clamp = (v, lo, hi) => Math.min(Math.max(v, lo), hi);
    return { item: item.name, from: [item.x, item.y], drop: [clamp(drop[0], 0.05, 0.45), clamp(drop[1], -0.29, -0.05)] };
  });
  const rect = await page.evaluate(() => { const b = document.getElementById('tray').getBoundingClientRect(); return [b.left, b.top, b.width, b.height]; });
  const toClient = ([x, y]) => [rect[0] + x / 0.6 * rect[2], rect[1] - y / 0.335 * rect[3]];
  const [fx, fy] = toClient(plan.from), [dx, dy] = toClient(plan.drop);
  await page.mouse.move(fx, fy);
  await page.mouse.down();
  for (let i = 1; i <= 10; ++i) await page.mouse.move(fx + (dx - fx) * i / 10, fy + (dy - fy) * i / 10);
  await page.mouse.up();
  const result = await until('the wizard move to end', () => page.evaluate((item) =>
    window.__events.find((e) => e.source === 'wizard' && e.type === 'move_result' && e.data.item === item), plan.item), 60000);
  await sleep(1500);  // the game releases the item 1 s after the last pose
  const moved = await page.evaluate((item) => window.__state.items.find((i) => i.name === item), plan.item);
  const command = await page.evaluate((item) =>
    window.__events.find((e) => e.source === 'wizard' && e.type === 'command' && e.data.args.item === item), plan.item);
  const error = Math.hypot(moved.x - plan.drop[0], moved.y - plan.drop[1]);
  check(command && Math.hypot(command.data.args.x - plan.drop[0], command.data.args.y - plan.drop[1]) < 0.002,
        'the drop reaches the session as a wizard move command', JSON.stringify(command && command.data));
  check(result.data.status === 'succeeded' && error <= 0.01, `dragging ${plan.item} makes the robot move it within 1 cm of the drop point`,
        `status ${result.data.status}, error ${(error * 1000).toFixed(1)} mm`);

  // ---- experiment manager ----------------------------------------------------------------------------------------
  await page.select('#participants [name=gender]', 'female');
  await page.$eval('#participants [name=age]', (e) => { e.value = '7'; });
  await page.select('#participants [name=tablet_familiarity]', '2');
  await page.click('#demographics button[type=submit]');
  const yamlPath = path.join(session, 'experiment.yaml');
  await until('experiment.yaml with the demographics', () => /age: 7/.test(readText(yamlPath)));
  const yaml = readText(yamlPath);
  check(/purple-participant:/.test(yaml) && /gender: female/.test(yaml) && /tablet-familiarity: "?2"?/.test(yaml) &&
        /condition: childrobot/.test(yaml), 'the demographics form writes experiment.yaml');
  await page.click('[data-marker=interesting]');
  await page.click('[data-likert="4"]');
  await until('the marker and Likert in experiment.yaml', () => /interesting/.test(readText(yamlPath)) && /social-engagement: 4/.test(readText(yamlPath)));
  check(true, 'marker and Likert buttons write experiment.yaml');
  await page.click('[data-marker=screenshot]');
  const shot = await until('the screenshot file, written', () => {  // named at once, written by the next tick
    const f = fs.readdirSync(session).find((n) => /^freeplay-1-.*\.png$/.test(n));
    return f && fs.statSync(path.join(session, f)).size > 10000 && /screenshot/.test(readText(yamlPath)) ? f : null;
  });
  check(fs.statSync(path.join(session, shot)).size > 10000 && /screenshot/.test(readText(yamlPath)),
        'the screenshot marker saves the game screen as the sessions did', shot);

  // ---- two pages, serialised commands, a page that leaves --------------------------------------------------------
  await Promise.all([page.evaluate(() => window.__send({ type: 'say', text: 'from page one' })),
                     frozen.evaluate(() => window.__send({ type: 'say', text: 'from page two' }))]);
  await until('both utterances in the log', () => { const t = readText(path.join(session, 'events.jsonl')); return t.includes('from page one') && t.includes('from page two'); });
  check(true, "two pages' commands both reach the session, one after the other");
  const framesBefore = await page.evaluate(() => window.__frames);
  check(await frozen.evaluate(() => window.__frames) > 20, 'the second page receives the same state stream');
  await frozen.close();
  await sleep(1000);
  check(await page.evaluate(() => window.__frames) > framesBefore + 5, 'closing a page does not stop the session');
  const stray = await browser.newPage();
  const wsRefused = await stray.evaluate((host) => new Promise((res) => {
    const ws = new WebSocket(`ws://${host}/ws`);
    ws.onopen = () => res(false); ws.onerror = () => res(true);
  }), new URL(base).host);
  check(wsRefused, 'a WebSocket without the token is refused');

  // ---- Foxglove WebSocket protocol: advertise, subscribe, ROS 1 binary messages --------------------------------
  const withoutCamera = await page.evaluate(() => window.__latencies.length);
  await post({ type: 'component', name: 'cameras', action: 'start' });
  const fox = await foxglove(`${base.replace('http', 'ws')}/?token=${token}`);
  check(fox.protocol === 'foxglove.websocket.v1' && fox.serverInfo, 'a Foxglove client gets serverInfo on foxglove.websocket.v1');
  check(['/tf', '/zones', '/footprints', '/sandtray/background/image/compressed'].every((t) => fox.topics.includes(t)) &&
        fox.tfSchema.includes('MSG: geometry_msgs/TransformStamped'), 'the channels are advertised with ros1msg schemas', fox.topics.join(', '));
  const serverItems = (await (await fetch(api('/api/state'))).json()).items;
  const near = fox.tf.filter((t) => { const i = serverItems.find((k) => k.name === t.child); return i && Math.hypot(i.x - t.x, i.y - t.y) < 0.05; });
  check(fox.tf.length >= 10 && near.length >= 8, '/tf messages decode to the items in the sandtray frame', `${near.length} of ${fox.tf.length} near`);
  check(fox.png, "the background arrives as the game's PNG sensor_msgs/CompressedImage (the bag's message)");
  check(fox.topics.includes('/joint_states') && fox.joints >= 20 && fox.links.size >= 10 && ['torso', 'Head'].every((l) => fox.links.has(l)),
        "the Nao's /joint_states and its links on /tf", `${fox.joints} joints, ${fox.links.size} links`);
  check(fox.camera, "the scenario's env_camera arrives as a JPEG CompressedImage in its optical frame");

  // ---- the coder's ground truth and the components panel ---------------------------------------------------------
  const coded = await page.evaluate(() => window.__state.children[0].coded);
  check(coded && coded.task && coded.social && coded.attitude, "the child's coded state reaches the page", JSON.stringify(coded));
  await page.bringToFront();  // clicks scroll into view, which waits for a frame of a visible tab
  await page.click('[data-component-action="recorder:start"]');
  await page.waitForFunction(() => window.__state.components.recorder.state === 'recording', { timeout: 10000 });
  await page.click('[data-component-action="robot:stop"]');
  await page.waitForFunction(() => window.__state.components.robot.state === 'paused', { timeout: 10000 });
  await page.click('[data-component-action="robot:start"]');
  await page.click('[data-component-action="recorder:stop"]');
  await page.click('[data-component-action="cameras:stop"]');
  await page.waitForFunction(() => window.__state.components.cameras.state === 'paused', { timeout: 10000 });
  await page.click('[data-component-action="cameras:start"]');
  await page.waitForFunction(() => window.__state.components.recorder.state === 'paused' &&
                             window.__state.components.robot.state === 'running' && window.__state.components.recorder.messages > 0 &&
                             window.__state.components.cameras.state === 'running',
                             { timeout: 10000 });
  const switches = readText(path.join(session, 'events.jsonl')).split('\n').filter((l) => l.includes('"type":"component"')).length;
  check(switches === 8, 'the components panel starts and stops the recorder, the robot side and the cameras (logged, with the two API switches)', `${switches} logged`);

  // ---- console, latency, screenshot ------------------------------------------------------------------------------
  check(page.errors.length === 0, 'the page logs no console errors', page.errors.join(' | '));
  const all = await page.evaluate(() => window.__latencies);
  const stats = (list) => {
    const lat = [...list].sort((a, b) => a - b);
    const q = (p) => lat[Math.min(lat.length - 1, Math.floor(p * (lat.length - 1)))];
    return { frames: lat.length, p50_ms: q(0.5), p99_ms: q(0.99), max_ms: lat[lat.length - 1] };
  };
  const latency = { ...stats(all.slice(5, withoutCamera)), with_1hz_camera: stats(all.slice(withoutCamera)) };
  console.log(`state push latency tick→page: ${JSON.stringify(latency)}`);
  fs.writeFileSync(path.join(out, 'latency.json'), JSON.stringify(latency) + '\n');
  await page.screenshot({ path: path.join(out, 'web.png') });

  // ---- the 3-D view on request (after the latency figures: it renders on the simulation thread) ----------------
  await page.select('#camera', 'env_camera');
  const camera = await until('a stage camera image', () => page.evaluate(() => {
    const img = document.getElementById('camera-img');
    return !img.hidden && img.complete && img.naturalWidth > 0 ? [img.naturalWidth, img.naturalHeight] : null;
  }), 30000);
  check(camera[0] === 480 && camera[1] === 270, 'the 3-D camera view shows env_camera on request', camera.join('×'));
  await page.screenshot({ path: path.join(out, 'web-camera.png'), fullPage: true });

  // ---- the Debriefing button ends free play in the served episode (last: the server then exits) ------------------
  await page.click('[data-signal=blank_interface][data-debrief]');
  await page.waitForFunction(() => ['debriefing', 'ended'].includes(window.__state.stage), { timeout: 10000 });
  const log = readText(path.join(session, 'events.jsonl'));
  check(log.includes('"topic":"sandtray/signals/blank_interface"') && log.split('\n').some((l) => l.includes('"signal_received"') && l.includes('"blank_interface"')) &&
        /"ended_by":"signal"/.test(log), 'the Debriefing button sends sandtray/signals/blank_interface and ends free play');
} catch (e) {
  check(false, 'the browser test ran to the end', String(e && e.stack || e));
} finally {
  if (browser) await browser.close();
  server.kill('SIGINT');
  await new Promise((res) => server.once('exit', res));
}
console.log(failures.length ? `${failures.length} check(s) failed` : 'all checks passed');
process.exit(failures.length ? 1 : 0);
