// End-to-end test of the studio in a real browser: Debian's chromium, headless with software
// WebGL (SwiftShader), driven by playwright-core. Starts `motiongraph serve` on a free port
// and checks what a user sees: the figure on the canvas (pixels), a clip playing with its
// planted feet marked, a clicked transition's two poses, a drawn path synthesized with its
// deviation, keyboard steering.
// With DATA_DIR, also a graph of subject 16 at 1 cm, which keeps walking alone: the path's tag
// picker and a drawn path asking to run say that running is not in the graph.
// Usage: node studio_browser.mjs MOTIONGRAPH_BINARY GRAPH SCREENSHOT_DIR [DATA_DIR]
// Needs chromium (CHROMIUM=... or /usr/bin/chromium; scripts/install-deps.sh installs it).
import { spawn } from 'node:child_process';
import { existsSync, mkdirSync, mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';

const [motiongraph, graph, shots, dataDir] = process.argv.slice(2);
if (!shots) {
  console.error('usage: node studio_browser.mjs MOTIONGRAPH_BINARY GRAPH SCREENSHOT_DIR');
  process.exit(2);
}
const browserPath = process.env.CHROMIUM || '/usr/bin/chromium';
if (!existsSync(browserPath)) {
  console.error(`studio_browser: FAIL: no browser at ${browserPath}: install Debian's chromium `
    + '(scripts/install-deps.sh does) or set CHROMIUM');
  process.exit(1);
}
let chromium;
try {
  ({ chromium } = await import('playwright-core'));
} catch {
  console.error('studio_browser: FAIL: playwright-core is not installed: run \'npm ci\' in tests/js '
    + '(scripts/install-deps.sh does)');
  process.exit(1);
}
mkdirSync(shots, { recursive: true });

let failures = 0;
function check(ok, what) {
  console.log(`${ok ? 'ok  ' : 'FAIL'} ${what}`);
  if (!ok) failures += 1;
}

// Compares the planted marks sampled on the figure (window.studio.plantedMarks()) with the
// contacts an API answer gives for the frames shown: a foot joint planted there has the planted
// colour and its floor disc, one lifted has neither. rowOf(sample) is the API's
// {joint_indices, row} for the sample's frame. Counts the marks of each kind seen.
async function compareMarks(samples, rowOf) {
  const out = { planted: 0, lifted: 0, wrong: [] };
  for (const sample of samples) {
    const api = await rowOf(sample);
    if (!api || JSON.stringify(api.joint_indices) !== JSON.stringify(sample.indices)
        || api.row.length !== sample.marks.length) {
      out.wrong.push(`frame ${sample.frame}: joints ${JSON.stringify(sample.indices)}, API ${JSON.stringify(api)}`);
      continue;
    }
    sample.marks.forEach((mark, k) => {
      const coloured = mark.sphereColour === sample.plantedColour;
      if (api.row[k] === 1) out.planted += 1; else out.lifted += 1;
      if (coloured !== (api.row[k] === 1) || mark.disc !== (api.row[k] === 1)) {
        out.wrong.push(`frame ${sample.frame} joint ${mark.joint}: API ${api.row[k]}, sphere `
          + `#${mark.sphereColour.toString(16)}, disc ${mark.disc}`);
      }
    });
  }
  return out;
}
async function sampleMarks(page, count, everyMs) {
  const samples = [];
  for (let i = 0; i < count; ++i) {
    samples.push(await page.evaluate(() => window.studio.plantedMarks()));
    await page.waitForTimeout(everyMs);
  }
  return samples;
}

// The studio on a free port for `graphFile`; its address is the line it prints once listening.
async function serve(graphFile) {
  const process_ = spawn(motiongraph, ['serve', graphFile, '--port', '0'], { stdio: ['ignore', 'pipe', 'inherit'] });
  const address = await new Promise((resolve, reject) => {
    let out = '';
    process_.stdout.on('data', (d) => {
      out += d;
      const m = out.match(/studio: (http:\/\/\S+)/);
      if (m) resolve(m[1]);
    });
    process_.on('exit', (code) => reject(new Error(`motiongraph serve exited with ${code} before listening`)));
    setTimeout(() => reject(new Error('motiongraph serve printed no address within 20 s')), 20000);
  });
  return [process_, address];
}
// Stops a server with SIGINT and checks that it stopped cleanly.
async function stopServer(process_, what) {
  process_.kill('SIGINT');
  const code = await new Promise((resolve) => {
    if (process_.exitCode !== null) resolve(process_.exitCode);
    else process_.on('exit', (c) => resolve(c));
  });
  check(code === 0, `motiongraph serve${what} stopped cleanly on SIGINT (exit ${code})`);
}
// Draws a path on the canvas in the top view: up and to the right from below its centre.
async function drawPath(page) {
  await page.click('[data-testid=draw]');
  await page.waitForTimeout(100);
  const view = await page.locator('[data-testid=canvas]').boundingBox();
  const cx = view.x + view.width / 2;
  const cy = view.y + view.height / 2;
  await page.mouse.move(cx, cy + 40);
  await page.mouse.down();
  for (let i = 1; i <= 12; ++i) await page.mouse.move(cx + i * 6, cy + 40 - i * 20);
  await page.mouse.up();
}
async function synthesizePath(page) {
  await page.click('[data-testid=synthesize]');
  await page.waitForFunction(() => window.studio.state.pathResult || /error/.test(
    document.querySelector('[data-testid=path-info]').textContent), null, { timeout: 180000 });
  return page.textContent('[data-testid=path-info]');
}

const [server, url] = await serve(graph);
console.log(`studio at ${url}`);

const browser = await chromium.launch({
  executablePath: browserPath,
  headless: true,
  // Software WebGL: no GPU on CI machines.
  args: ['--use-gl=angle', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--ignore-gpu-blocklist',
    '--no-sandbox'],
});
try {
  const page = await browser.newPage({ viewport: { width: 1100, height: 700 } });
  // Waits are for things to happen, not for speed: a sanitizer build synthesizing on a 2-core
  // machine that is busy with other work took more than 30 s for the drawn path.
  page.setDefaultTimeout(180000);
  const errors = [];
  page.on('pageerror', (e) => errors.push(e.message));
  page.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
  await page.goto(url);
  await page.waitForFunction(() => window.studio && (window.studio.state.ready || window.studio.state.error),
    null, { timeout: 30000 });
  check(!(await page.evaluate(() => window.studio.state.error)), 'the studio loads its data');
  const webgl = await page.evaluate(() => Boolean(document.createElement('canvas').getContext('webgl2')));
  check(webgl, 'WebGL works in this browser');

  // 1. The figure is on the canvas: pixels in its box differ from the same view without it.
  await page.click('[data-testid=play]');  // pause on a frame
  await page.waitForTimeout(300);
  const box = await page.evaluate(() => window.studio.figureScreenBox());
  const clip = { x: Math.max(0, box.left - 4), y: Math.max(0, box.top - 4),
    width: Math.max(8, box.right - box.left + 8), height: Math.max(8, box.bottom - box.top + 8) };
  const withFigure = await page.screenshot({ clip, path: join(shots, '1-figure.png') });
  await page.evaluate(() => window.studio.setFigureVisible(false));
  await page.waitForTimeout(200);
  const without = await page.screenshot({ clip });
  await page.evaluate(() => window.studio.setFigureVisible(true));
  const changed = await page.evaluate(async ([a, b]) => {
    const load = async (b64) => {
      const img = new Image();
      img.src = `data:image/png;base64,${b64}`;
      await img.decode();
      const c = document.createElement('canvas');
      c.width = img.width; c.height = img.height;
      const g = c.getContext('2d');
      g.drawImage(img, 0, 0);
      return g.getImageData(0, 0, c.width, c.height).data;
    };
    const [pa, pb] = [await load(a), await load(b)];
    let n = 0;
    for (let i = 0; i < pa.length; i += 4) {
      if (Math.abs(pa[i] - pb[i]) + Math.abs(pa[i + 1] - pb[i + 1]) + Math.abs(pa[i + 2] - pb[i + 2]) > 40) n += 1;
    }
    return { n, total: pa.length / 4 };
  }, [withFigure.toString('base64'), without.toString('base64')]);
  check(box.bottom - box.top > 40, `the figure is ${Math.round(box.bottom - box.top)} px tall on screen`);
  check(changed.n > 0.05 * changed.total && changed.n > 300,
    `the figure covers ${changed.n} of ${changed.total} pixels of its box`);

  // 2. The clip selector says what the graph keeps of each clip, as the API counts it.
  const clipOptions = await page.$$eval('[data-testid=clip-select] option', (os) => os.map((o) => o.textContent));
  const apiClips = await page.evaluate(async () => (await fetch('/api/clips')).json());
  const keptShown = apiClips.filter((c, i) => clipOptions[i]
    && clipOptions[i].includes(`kept ${Math.round((100 * c.kept_frames) / c.frames)} %`)).length;
  check(clipOptions.length === apiClips.length && keptShown === apiClips.length,
    `${keptShown} of ${apiClips.length} clips show the share the graph keeps (${clipOptions[0]})`);

  // A clip that looks wrong as read (the API's doubts, info's phrases) is marked in the selector.
  const marked = apiClips.filter((c, i) => clipOptions[i]
    && clipOptions[i].startsWith('\u26a0') === (c.doubts.length > 0)).length;
  check(marked === apiClips.length, `${marked} of ${apiClips.length} clips marked as their doubts say`);

  // 2. A clip plays: frames advance and the root moves.
  await page.selectOption('[data-testid=clip-select]', '1');
  await page.waitForFunction(() => window.studio.state.clipIndex === 1 && window.studio.state.playing);
  const doubtsShown = await page.textContent('[data-testid=clip-doubts]');
  const doubtsWanted = apiClips[1].doubts.length ? `Looks wrong as read: ${apiClips[1].doubts.join('; ')}.` : '';
  check(doubtsShown === doubtsWanted, `the clip's doubts are shown as the API gives them ('${doubtsShown}')`);
  const f0 = await page.evaluate(() => window.studio.state.frameIndex);
  await page.waitForTimeout(1000);
  const f1 = await page.evaluate(() => window.studio.state.frameIndex);
  check(f1 !== f0, `the clip plays (frame ${f0} -> ${f1})`);
  await page.screenshot({ path: join(shots, '2-clip.png') });

  // 2b. While it plays, each foot joint is marked planted exactly on the frames the API's
  // contacts for that frame say so (asked again here, frame by frame).
  const clipSamples = (await sampleMarks(page, 16, 110)).filter((m) => m.mode === 'clip' && m.clip === 1);
  const clipMarks = await compareMarks(clipSamples, (sample) => page.evaluate(async (f) => {
    const part = await (await fetch(`/api/clips/1/frames?from=${f}&count=1`)).json();
    return part.contacts && { joint_indices: part.contacts.joint_indices, row: part.contacts.planted[0] };
  }, sample.frame));
  const shownFrames = new Set(clipSamples.map((m) => m.frame)).size;
  check(clipSamples.length === 16 && shownFrames >= 4 && clipMarks.wrong.length === 0
      && clipMarks.planted + clipMarks.lifted > 0,
    `planted feet are marked as the API's contacts say over ${shownFrames} frames of the clip playing `
    + `(${clipMarks.planted} planted, ${clipMarks.lifted} lifted marks)${clipMarks.wrong.length
      ? `: ${clipMarks.wrong.slice(0, 4).join('; ')}` : ''}`);
  // Scrubbed to a frame where the API says a foot joint is lifted and to one where one is
  // planted: both kinds of mark are checked whatever frames playback happened to show.
  const clipContacts = await page.evaluate(async () => (await (await fetch('/api/clips/1/frames')).json()).contacts);
  const scrubFrames = clipContacts ? [clipContacts.planted.findIndex((row) => row.includes(0)),
    clipContacts.planted.findIndex((row) => row.includes(1))] : [-1, -1];
  const scrubSamples = [];
  for (const f of scrubFrames.filter((v) => v >= 0)) {
    await page.evaluate((v) => {
      const scrub = document.querySelector('[data-testid=scrub]');
      scrub.value = String(v);
      scrub.dispatchEvent(new Event('input'));
    }, f);
    await page.waitForFunction((v) => window.studio.state.frameIndex === v, f);
    await page.waitForTimeout(100);
    scrubSamples.push(await page.evaluate(() => window.studio.plantedMarks()));
  }
  const scrubMarks = await compareMarks(scrubSamples,
    async (sample) => ({ joint_indices: clipContacts.joint_indices, row: clipContacts.planted[sample.frame] }));
  check(scrubFrames.every((v) => v >= 0) && scrubMarks.wrong.length === 0 && scrubMarks.planted > 0
      && scrubMarks.lifted > 0,
    `scrubbed to frames ${scrubFrames.join(' and ')}: ${scrubMarks.lifted} lifted, ${scrubMarks.planted} planted `
    + `joints marked as the API says${scrubMarks.wrong.length ? `: ${scrubMarks.wrong.slice(0, 4).join('; ')}` : ''}`);
  await page.screenshot({ path: join(shots, '2-clip-feet.png') });
  // "Mark planted feet" off: no marks, and none while it stays off; on again: marks (paused on
  // the planted frame). Waited for: a loaded machine renders a few frames a second.
  const anyMarked = () => {
    const m = window.studio.plantedMarks();
    return m.marks.some((k) => k.disc || k.sphereColour === m.plantedColour);
  };
  const noneMarked = () => {
    const m = window.studio.plantedMarks();
    return m.marks.length > 0 && !m.marks.some((k) => k.disc || k.sphereColour === m.plantedColour);
  };
  await page.uncheck('[data-testid=mark-feet]');
  const cleared = await page.waitForFunction(noneMarked, null, { timeout: 10000 }).then(() => true, () => false);
  const unmarked = await sampleMarks(page, 4, 150);
  check(cleared && unmarked.every((m) => m.marks.length > 0
      && m.marks.every((k) => !k.disc && k.sphereColour !== m.plantedColour)),
    'with "Mark planted feet" off no foot joint is marked');
  await page.check('[data-testid=mark-feet]');
  const remarked = await page.waitForFunction(anyMarked, null, { timeout: 10000 }).then(() => true, () => false);
  check(remarked, 'with it on again planted feet are marked');

  // 3. Click a transition on the matrix: both poses are shown.
  const point = await page.evaluate(() => window.studio.transitionClientPoint(0));
  await page.mouse.click(point.x, point.y);
  await page.waitForFunction(() => window.studio.state.mode === 'poses', null, { timeout: 10000 });
  const info = await page.textContent('[data-testid=transition-info]');
  check(/transition \d+:/.test(info), `the transition is described: ${info}`);
  // Its frames are frames of the clips it names, numbered from 1 as the scrubber numbers them.
  const [t0, clipList] = await page.evaluate(async () => [(await (await fetch('/api/transitions')).json())[0],
    await (await fetch('/api/clips')).json()]);
  const clipOf = (name) => clipList.find((c) => c.name === name);
  const framesSaid = info.match(/: (\S+) frame (\d+) \(orange\) -> (\S+) frame (\d+) \(blue\)/);
  check(framesSaid && Number(framesSaid[2]) === t0.window_from_frame - clipOf(t0.from_clip).first_frame + 1
    && Number(framesSaid[4]) === t0.window_to_frame - clipOf(t0.to_clip).first_frame + 1
    && Number(framesSaid[2]) <= clipOf(t0.from_clip).frames && Number(framesSaid[4]) <= clipOf(t0.to_clip).frames,
  `the transition's frames are its clips' own: ${info}`);
  await page.waitForFunction(() => document.querySelector('[data-testid=matrix-img]').complete);
  // The per-tag table marks the modifier tags (subject 16 has turn and stop) and says what they are.
  const modifierRows = await page.$$eval('[data-testid=tag-stats] tr.modifier th', (ths) => ths.map((t) => t.textContent));
  const note = await page.textContent('[data-testid=tag-stats-note]');
  check(modifierRows.includes('stop*') && !modifierRows.some((n) => n.startsWith('walk')) && /modifier/.test(note),
    `modifier tags are marked and explained: ${modifierRows.join(', ')}`);
  await page.screenshot({ path: join(shots, '3-transition.png') });

  // 4. Draw a path on the ground (top view) and synthesize it.
  await drawPath(page);
  const pathPoints = await page.evaluate(() => window.studio.state.path.points.length);
  check(pathPoints >= 5, `the path drawn has ${pathPoints} points`);
  const drawnInfo = await page.textContent('[data-testid=path-info]');
  check(/^drawn: [\d.]+ m$/.test(drawnInfo), `the path's length is shown as it is drawn: '${drawnInfo}'`);
  // Dragged on off the view onto the panel, the stroke adds nothing out of sight.
  const drawnPoints = await page.evaluate(() => window.studio.state.path.points.length);
  const viewBox = await page.locator('[data-testid=canvas]').boundingBox();
  await page.mouse.move(viewBox.x + viewBox.width - 5, viewBox.y + viewBox.height / 2);
  await page.mouse.down();
  for (let i = 1; i <= 8; ++i) {
    await page.mouse.move(viewBox.x + viewBox.width + i * 30, viewBox.y + viewBox.height / 2);
  }
  await page.mouse.up();
  const offView = await page.evaluate(() => window.studio.state.path.points.length);
  check(offView <= drawnPoints + 1,
    `a stroke dragged off the view adds no points there (${drawnPoints} -> ${offView})`);
  // (The point pressed at the view's edge is taken back: the path synthesized below is the one drawn.)
  await page.evaluate((n) => {
    const { path } = window.studio.state;
    path.points.length = n;
    path.tags.length = n;
  }, drawnPoints);
  const keyShown = await page.$$eval('[data-testid=path-key] span', (ss) => ss.map((k) => k.textContent));
  const graphTags = await page.evaluate(() => window.studio.state.tags);
  check(keyShown.join(',') === ['any', ...graphTags].join(','),
    `the drawn path's colours are keyed: ${keyShown.join(', ')}`);
  check(!(await page.evaluate(() => document.querySelector('[data-testid=transition-info]').textContent)),
    'the transition picked is let go once the view turns to drawing');
  const pathInfo = await synthesizePath(page);
  check(/deviation mean [\d.]+ m/.test(pathInfo), `the path is synthesized: ${pathInfo}`);
  check(/\d+ transitions \([\d.]+\/s(, \d+ bridges?)?\)/.test(pathInfo), `the path's transitions per second are shown: ${pathInfo}`);
  check(/bent onto the path; as the graph played it [\d.]+ m, max [\d.]+ m/.test(pathInfo),
    `the path is bent onto the path drawn by default, the graph's own deviation shown: ${pathInfo}`);
  check(/feet slide [\d.]+ m\/s \([\d.]+x the capture; [\d.]+x on the frames played\), cleaned up/.test(pathInfo),
    `the path's foot slide beside its source is shown, cleaned up by default: ${pathInfo}`);
  check(await page.evaluate(() => window.studio.state.mode === 'result' && window.studio.state.playing),
    'the path result plays');
  const pathSamples = (await sampleMarks(page, 10, 120)).filter((m) => m.mode === 'result');
  const pathContacts = await page.evaluate(() => window.studio.state.pathResult.contacts);
  const pathMarks = await compareMarks(pathSamples, async (sample) => pathContacts
    && { joint_indices: pathContacts.joint_indices, row: pathContacts.planted[sample.frame] });
  check(pathSamples.length > 0 && pathMarks.wrong.length === 0 && pathMarks.planted > 0,
    `the path result's planted feet are marked as its contacts say (${pathMarks.planted} planted, `
    + `${pathMarks.lifted} lifted marks)${pathMarks.wrong.length
      ? `: ${pathMarks.wrong.slice(0, 4).join('; ')}` : ''}`);
  const href = await page.getAttribute('[data-testid=download]', 'href');
  const bvh = await page.evaluate(async (h) => (await fetch(h)).text(), href);
  check(bvh.startsWith('HIERARCHY'), `the result downloads as BVH (${href})`);
  // The first bytes of what a download link gives, as text.
  const downloadMagic = async (testid, length) => {
    const link = await page.getAttribute(`[data-testid=${testid}]`, 'href');
    const magic = await page.evaluate(async ([h, n]) => {
      const bytes = new Uint8Array(await (await fetch(h)).arrayBuffer());
      return String.fromCharCode(...bytes.slice(0, n));
    }, [link, length]);
    return [magic, link];
  };
  const [glbMagic, glbHref] = await downloadMagic('download-glb', 4);
  check(glbMagic === 'glTF', `the result downloads as binary glTF (${glbHref})`);
  const [gltfMagic, gltfHref] = await downloadMagic('download-gltf', 1);
  check(gltfMagic === '{' && gltfHref.endsWith('.gltf'), `the result downloads as glTF JSON (${gltfHref})`);
  const [fbxMagic, fbxHref] = await downloadMagic('download-fbx', 18);
  check(fbxMagic === 'Kaydara FBX Binary', `the result downloads as binary FBX (${fbxHref})`);
  await page.check('[data-testid=no-figure]');
  const bareHref = await page.getAttribute('[data-testid=download-glb]', 'href');
  const [figured, bare] = await page.evaluate(async ([a, b]) => [
    (await (await fetch(a)).arrayBuffer()).byteLength, (await (await fetch(b)).arrayBuffer()).byteLength], [glbHref, bareHref]);
  check(bareHref.includes('figure=0') && bare < figured,
    `with the no-figure box checked the glTF leaves the stick figure out (${bareHref}: ${bare} bytes, ${figured} with it)`);
  const bareFbxHref = await page.getAttribute('[data-testid=download-fbx]', 'href');
  const bareFbx = await page.evaluate(async (h) => new TextDecoder('latin1').decode(await (await fetch(h)).arrayBuffer()), bareFbxHref);
  check(bareFbxHref.includes('figure=0') && bareFbx.startsWith('Kaydara FBX Binary') && !bareFbx.includes('Geometry'),
    `with the no-figure box checked the FBX has no mesh (${bareFbxHref})`);
  await page.uncheck('[data-testid=no-figure]');
  await page.check('[data-testid=root-motion]');
  const rootMotionHref = await page.getAttribute('[data-testid=download]', 'href');
  const rootMotionBvh = await page.evaluate(async (h) => (await fetch(h)).text(), rootMotionHref);
  check(rootMotionBvh.startsWith('HIERARCHY\nROOT root_motion'),
    `with the root-motion box checked the BVH's root is the root-motion joint (${rootMotionHref})`);
  await page.uncheck('[data-testid=root-motion]');
  await page.waitForTimeout(800);
  await page.screenshot({ path: join(shots, '4-path.png') });
  // The same path asked to end at rest: the character stands at its end.
  await page.check('[data-testid=rest-at-end]');
  await page.evaluate(() => { window.studio.state.pathResult = null; });
  const restPathInfo = await synthesizePath(page);
  const restResult = await page.evaluate(() => window.studio.state.pathResult);
  check(/at rest from [\d.]+ s at the end of 16_\d+, [\d.]+ m from the path's end/.test(restPathInfo)
    && restResult && restResult.rest && restResult.end_distance_m < 0.5,
    `the path asked to end at rest stands at its end: ${restPathInfo}`);
  await page.uncheck('[data-testid=rest-at-end]');
  // At its end, Play plays the result again from its first frame.
  await page.waitForFunction(() => !window.studio.state.playing, null, { timeout: 120000 });
  const endFrame = await page.evaluate(() => window.studio.state.frameIndex);
  await page.click('[data-testid=play]');
  await page.waitForTimeout(300);
  const replay = await page.evaluate(() => [window.studio.state.playing, window.studio.state.frameIndex]);
  check(replay[0] && replay[1] < endFrame, `Play at the end plays it again (frame ${endFrame} -> ${replay[1]})`);
  // A synthesis the user has moved on from (Clear) is not played when it comes; Synthesize waits
  // for the one under way.
  // (A path long enough to take seconds to synthesize, so that the click comes first.)
  await page.evaluate(() => {
    window.studio.state.pathResult = null;
    const points = [];
    for (let i = 0; i <= 150; ++i) points.push([2 * Math.sin(i / 8), -i]);
    Object.assign(window.studio.state.path, { points, tags: points.map(() => 'walk') });
  });
  await page.click('[data-testid=synthesize]');
  const disabled = await page.evaluate(() => document.querySelector('[data-testid=synthesize]').disabled);
  await page.click('[data-testid=clear-path]');
  await page.waitForFunction(() => !window.studio.state.synthesizing, null, { timeout: 180000 });
  const stale = await page.evaluate(() => ({ result: window.studio.state.pathResult, mode: window.studio.state.mode,
    points: window.studio.state.path.points.length }));
  check(disabled && stale.result === null && stale.points === 0,
    `a synthesis cleared before it came is dropped (button disabled meanwhile: ${disabled}; mode ${stale.mode})`);

  // 5. Steer with the keyboard: east (D) for a few seconds moves the root east (+x).
  await page.click('[data-testid=steer]');
  await page.waitForFunction(() => window.studio.state.steer && window.studio.state.steer.received > 0);
  check(await page.evaluate(() => document.querySelector('[data-testid=play]').disabled),
    'Play/Pause is disabled while steering (the session plays as it is steered)');
  // A checkbox clicked while steering keeps the focus; the steering keys still steer.
  await page.click('[data-testid=mark-feet]');
  await page.click('[data-testid=mark-feet]');
  // Hold D (east, the camera looking north) until the character has been heading east for
  // 2 s: its root moved at least 0.8 m, mostly along +x. Turning takes a step or two, more
  // on slow (sanitizer) builds, hence the polling.
  await page.keyboard.down('KeyD');
  const pressed = Date.now();
  const roots = [];
  const steerMarks = [];
  let east = null;
  while (Date.now() - pressed < 15000) {
    await page.waitForTimeout(250);
    roots.push(await page.evaluate(() => window.studio.state.root));
    steerMarks.push(await page.evaluate(() => window.studio.plantedMarks()));
    if (roots.length > 8) {
      const [a, b] = [roots[roots.length - 9], roots[roots.length - 1]];
      const [dx, dz] = [b[0] - a[0], b[2] - a[2]];
      if (dx > 0.8 && dx > 2 * Math.abs(dz)) { east = { a, b, seconds: (Date.now() - pressed) / 1000 }; break; }
    }
  }
  await page.keyboard.up('KeyD');
  const heading = await page.evaluate(() => window.studio.state.steer.heading);
  check(heading === 90, `D steers east, the camera looking north (heading ${heading})`);
  const last = roots[roots.length - 1];
  check(east !== null, east ? `the character went east: x ${east.a[0].toFixed(2)} -> ${east.b[0].toFixed(2)}, `
    + `z ${east.a[2].toFixed(2)} -> ${east.b[2].toFixed(2)} in the 2 s before ${east.seconds.toFixed(1)} s`
    : `the character did not head east within 15 s (root at x ${last[0].toFixed(2)}, z ${last[2].toFixed(2)})`);
  await page.screenshot({ path: join(shots, '5-steer.png') });
  // Steering marks planted feet too (each mark whole: colour and disc together).
  const steerPlanted = steerMarks.filter((m) => m.mode === 'steer' && m.marks.some((k) => k.disc)).length;
  const steerWhole = steerMarks.every((m) => m.marks.every((k) => k.disc === (k.sphereColour === m.plantedColour)));
  check(steerPlanted > 0 && steerWhole,
    `steering marks planted feet (${steerPlanted} of ${steerMarks.length} samples)`);
  // X: the character comes to rest (subject 16's "slow walk, stop" ends standing) and stands still.
  await page.keyboard.press('KeyX');
  const restPressed = Date.now();
  let still = null;
  let before = await page.evaluate(() => window.studio.state.root);
  while (Date.now() - restPressed < 20000) {
    await page.waitForTimeout(1000);
    const now = await page.evaluate(() => window.studio.state.root);
    const rested = await page.evaluate(() => window.studio.state.steer.restS);
    if (rested != null && Math.hypot(now[0] - before[0], now[2] - before[2]) < 0.02) {
      still = { rested, seconds: (Date.now() - restPressed) / 1000 };
      break;
    }
    before = now;
  }
  const restInfo = await page.textContent('[data-testid=steer-info]');
  check(still !== null && /at rest since/.test(restInfo),
    still ? `X brings the character to rest: standing still ${still.seconds.toFixed(1)} s after the key ("${restInfo}")`
      : `X did not bring the character to rest within 20 s ("${restInfo}")`);
  // A move key then starts it off from rest (subject 16's graph has no way on from the frame it
  // holds: a start blends it into a clip that walks off), the panel says so, and it walks away.
  const stood = await page.evaluate(() => window.studio.state.root);
  await page.keyboard.down('KeyD');
  const movePressed = Date.now();
  let startInfo = '';
  let moved = 0;
  while (Date.now() - movePressed < 15000) {
    await page.waitForTimeout(250);
    const info = await page.textContent('[data-testid=steer-info]');
    if (/starting off from rest into 16_/.test(info)) startInfo = info;
    const now = await page.evaluate(() => window.studio.state.root);
    moved = Math.hypot(now[0] - stood[0], now[2] - stood[2]);
    if (startInfo && moved > 1.0) break;
  }
  await page.keyboard.up('KeyD');
  check(startInfo !== '' && moved > 1.0,
    `a move key after rest starts the character off ("${startInfo}"; ${moved.toFixed(2)} m from where it stood)`);
  // A diagonal (W and D: north-east) let go a few tens of milliseconds apart stays the diagonal.
  await page.keyboard.down('KeyW');
  await page.keyboard.down('KeyD');
  await page.waitForFunction(() => window.studio.state.steer.heading === 45, null, { timeout: 10000 });
  await page.keyboard.up('KeyW');
  await page.waitForTimeout(40);
  await page.keyboard.up('KeyD');
  await page.waitForTimeout(500);
  const afterDiagonal = await page.evaluate(() => window.studio.state.steer.heading);
  check(afterDiagonal === 45, `a diagonal let go key by key stays north-east (heading ${afterDiagonal})`);
  check(errors.length === 0, `no errors in the page${errors.length ? `: ${errors.join('; ')}` : ''}`);
  await page.click('[data-testid=steer]');  // stop
  check(!(await page.evaluate(() => window.studio.state.steer)), 'Stop steering stops it');
  // A synthesis the user moved on from by steering: when it comes, its line no longer says
  // "synthesizing..." (it is dropped, not played).
  await page.evaluate(() => {
    const points = [];
    for (let i = 0; i <= 150; ++i) points.push([2 * Math.sin(i / 8), -i]);
    Object.assign(window.studio.state.path, { points, tags: points.map(() => 'walk') });
  });
  await page.click('[data-testid=synthesize]');
  await page.click('[data-testid=steer]');
  await page.waitForFunction(() => !window.studio.state.synthesizing && window.studio.state.steer, null,
    { timeout: 180000 }).catch(() => {});
  const movedOn = await page.textContent('[data-testid=path-info]');
  const steerMode = await page.evaluate(() => [window.studio.state.mode, Boolean(window.studio.state.steer)]);
  check(movedOn === 'the synthesis came after you moved on: not shown' && steerMode[1],
    `a synthesis under way when steering starts is dropped and leaves its line ('${movedOn}') and the steering `
    + `on (${steerMode})`);
  await page.click('[data-testid=steer]');  // stop
  // A transition picked after steering plays its poses under "Pause".
  await page.locator('[data-testid=matrix-overlay]').scrollIntoViewIfNeeded();
  const dot = await page.evaluate(() => window.studio.transitionClientPoint(1));
  await page.mouse.click(dot.x, dot.y);
  await page.waitForFunction(() => window.studio.state.mode === 'poses', null, { timeout: 10000 });
  check(await page.textContent('[data-testid=play]') === 'Pause'
    && await page.evaluate(() => window.studio.state.playing),
    'a transition picked after steering plays under Pause');
  // Every steering session in use (the server's 16): Start steering says why in the steering line.
  const opened = await page.evaluate(async () => {
    let n = 0;
    for (let i = 0; i < 20; ++i) {
      const r = await fetch('/api/steer/sessions', { method: 'POST', headers: { 'Content-Type': 'application/json' },
        body: JSON.stringify({ heading_deg: 0 }) });
      if (r.ok) n += 1; else break;
    }
    return n;
  });
  await page.click('[data-testid=steer]');
  await page.waitForFunction(() => /^error: /.test(document.querySelector('[data-testid=steer-info]').textContent),
    null, { timeout: 10000 }).catch(() => {});
  const refused = await page.textContent('[data-testid=steer-info]');
  check(/^error: .*at most \d+ sessions/.test(refused) && !(await page.evaluate(() => window.studio.state.steer)),
    `with all ${opened} sessions in use, Start steering says so: '${refused}'`);
  const tagOptions = await page.$$eval('[data-testid=path-tag] option', (os) => os.map((o) => o.textContent));
  check(tagOptions.length > 1 && !tagOptions.some((t) => /not in the graph/.test(t)),
    `the default graph plays every type its path picker offers: ${tagOptions.join(', ')}`);
} catch (err) {
  console.log(`FAIL ${err.message}`);
  failures += 1;
}

// A graph that keeps walking alone: running is offered as not in the graph, and a path drawn
// asking to run says so beside its match.
let second = null;
const work = dataDir ? mkdtempSync(join(tmpdir(), 'studio-walk-only-')) : null;
try {
  if (dataDir) {
    const walkOnly = join(work, 'walk-only.mgraph');
    const built = spawn(motiongraph, ['build', join(dataDir, 'cmu/16'), '--threshold', '1cm', '--no-cache', '-q',
      '-o', walkOnly], { stdio: 'ignore' });
    const builtCode = await new Promise((resolve) => built.on('exit', resolve));
    check(builtCode === 0, `the graph at 1 cm is built (exit ${builtCode})`);
    let address;
    [second, address] = await serve(walkOnly);
    const page = await browser.newPage({ viewport: { width: 1100, height: 700 } });
    page.setDefaultTimeout(180000);
    await page.goto(address);
    await page.waitForFunction(() => window.studio && (window.studio.state.ready || window.studio.state.error),
      null, { timeout: 30000 });
    check(!(await page.evaluate(() => window.studio.state.error)), 'the studio loads the walking graph');
    const options = await page.$$eval('[data-testid=path-tag] option', (os) => os.map((o) => [o.value, o.textContent]));
    const label = (tag) => (options.find(([v]) => v === tag) || [])[1];
    check(label('run') === 'run (not in the graph)' && label('walk') === 'walk',
      `the walking graph's picker marks running: ${options.map(([, t]) => t).join(', ')}`);
    await page.selectOption('[data-testid=path-tag]', 'run');
    await drawPath(page);
    const info = await synthesizePath(page);
    check(/run 0 %: not in the graph/.test(info), `a path asking it to run says running is not in the graph: ${info}`);
    const pathWarned = await page.textContent('[data-testid=path-warnings]');
    check(/the segment [\d.]+-[\d.]+ m asks for 'run', which the graph plays in no frame/.test(pathWarned),
      `and warns of it as the CLI does: '${pathWarned}'`);
    // Steered with Shift held (run), the session says once that the graph plays no running.
    await page.click('[data-testid=steer]');
    await page.locator('[data-testid=canvas]').focus();
    await page.keyboard.down('Shift');
    await page.waitForFunction(() => /asks for 'run'/.test(
      document.querySelector('[data-testid=steer-warnings]').textContent), null, { timeout: 60000 });
    await page.waitForTimeout(1500);  // steps asking it again
    await page.keyboard.up('Shift');
    const steerWarned = await page.textContent('[data-testid=steer-warnings]');
    check((steerWarned.match(/asks for 'run'/g) || []).length === 1
      && /which the graph plays in no frame/.test(steerWarned),
      `steering it to run says so once under the steering line: '${steerWarned}'`);
    await page.click('[data-testid=steer]');
    await page.close();
    await stopServer(second, ' (the walking graph)');
    second = null;

    // A library with a clip whose converter offset its root (07_12.bvh, below the floor): the
    // selector marks it, and choosing it shows what looks wrong, as the API (and info) say it.
    const offset = join(work, 'offset.mgraph');
    const builtOffset = spawn(motiongraph, ['build', join(dataDir, 'bvh/07_01.bvh'), join(dataDir, 'bvh/07_12.bvh'),
      '--no-cache', '-q', '-o', offset], { stdio: 'ignore' });
    const offsetCode = await new Promise((resolve) => builtOffset.on('exit', resolve));
    check(offsetCode === 0, `the graph of 07_01 and 07_12 is built (exit ${offsetCode})`);
    [second, address] = await serve(offset);
    const doubted = await browser.newPage({ viewport: { width: 1100, height: 700 } });
    doubted.setDefaultTimeout(180000);
    await doubted.goto(address);
    await doubted.waitForFunction(() => window.studio && (window.studio.state.ready || window.studio.state.error),
      null, { timeout: 30000 });
    const offsetClips = await doubted.evaluate(async () => (await fetch('/api/clips')).json());
    const offsetOptions = await doubted.$$eval('[data-testid=clip-select] option', (os) => os.map((o) => o.textContent));
    const index = offsetClips.findIndex((c) => c.name === '07_12');
    check(index >= 0 && /below the floor/.test(offsetClips[index].doubts.join(' '))
      && offsetOptions[index].startsWith('\u26a0 07_12') && !offsetOptions[1 - index].startsWith('\u26a0'),
      `07_12 is marked as looking wrong: ${offsetOptions.join(' | ')}`);
    await doubted.selectOption('[data-testid=clip-select]', String(index));
    await doubted.waitForFunction((i) => window.studio.state.clipIndex === i, index);
    const said = await doubted.textContent('[data-testid=clip-doubts]');
    check(said === `Looks wrong as read: ${offsetClips[index].doubts.join('; ')}.`, `07_12's doubts are shown: '${said}'`);
  }
} catch (err) {
  console.log(`FAIL ${err.message}`);
  failures += 1;
} finally {
  await browser.close().catch(() => {});
  if (second) await stopServer(second, ' (the second graph)');
  if (work) rmSync(work, { recursive: true, force: true });
}
await stopServer(server, '');
console.log(failures ? `studio_browser: ${failures} check(s) failed` : 'studio_browser: all checks passed');
process.exit(failures ? 1 : 0);
