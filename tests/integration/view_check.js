// view_check.js - open a page `mpb view` wrote in a real headless Chromium
// (Debian's, driven by playwright-core from .cache/web), with every request
// but the file itself refused, and check it. Used by test_view.sh.
//
//   node view_check.js PAGE EXPECTED_TEXT SCREENSHOT.png [valid]
//
// With "valid", the run's stage shown is valid: no bodies in contact are
// looked for.
//
// Prints one "ok - ..." or "not ok - ..." line per check and the timings
// (not checked), and exits 1 if any check failed.
'use strict';
const path = require('path');
const { chromium } = require(path.join(process.env.MPB_WEB_MODULES, 'playwright-core'));

const [page_path, expected, shot_path, kind] = process.argv.slice(2);
const valid = kind === 'valid';
let failed = 0;
function check(name, ok, detail) {
  if (!ok) failed++;
  console.log((ok ? 'ok - ' : 'not ok - ') + name + (ok || !detail ? '' : ' (' + detail + ')'));
}

// Pixel statistics of a PNG, read back in the page through a 2-D canvas:
// how many pixels differ from the corner's colour (the background), how
// many colours there are (quantised), and, given a second PNG, how many
// pixels differ between the two.
async function pixels(page, png, other) {
  return page.evaluate(async ([a, b]) => {
    async function load(b64) {
      const img = new Image();
      img.src = 'data:image/png;base64,' + b64;
      await img.decode();
      const c = document.createElement('canvas');
      c.width = img.width;
      c.height = img.height;
      const g = c.getContext('2d');
      g.drawImage(img, 0, 0);
      return g.getImageData(0, 0, c.width, c.height).data;
    }
    const p = await load(a);
    const n = p.length / 4;
    let notBackground = 0;
    const colours = new Set();
    for (let i = 0; i < p.length; i += 4) {
      if (Math.abs(p[i] - p[0]) + Math.abs(p[i + 1] - p[1]) + Math.abs(p[i + 2] - p[2]) > 24)
        notBackground++;
      colours.add((p[i] >> 4) << 8 | (p[i + 1] >> 4) << 4 | (p[i + 2] >> 4));
    }
    let differ = null;
    if (b) {
      const q = await load(b);
      differ = 0;
      for (let i = 0; i < p.length; i += 4)
        if (Math.abs(p[i] - q[i]) + Math.abs(p[i + 1] - q[i + 1]) + Math.abs(p[i + 2] - q[i + 2]) > 24)
          differ++;
      differ /= n;
    }
    return { notBackground: notBackground / n, colours: colours.size, differ };
  }, [png.toString('base64'), other ? other.toString('base64') : null]);
}

(async () => {
  const browser = await chromium.launch({
    executablePath: process.env.MPB_CHROMIUM || '/usr/bin/chromium',
    headless: true,
    args: ['--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
           '--disable-background-networking', '--disable-component-update',
           '--disable-sync'],
  });
  const context = await browser.newContext({ viewport: { width: 1200, height: 760 } });
  const requests = [];
  await context.route('**/*', (route) => {
    const url = route.request().url();
    if (url.startsWith('file:') || url.startsWith('blob:') || url.startsWith('data:'))
      return route.continue();
    requests.push(url);
    return route.abort();
  });
  const page = await context.newPage();
  const errors = [];
  page.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
  page.on('pageerror', (e) => errors.push(String(e)));

  const t0 = Date.now();
  await page.goto('file://' + path.resolve(page_path));
  // Ready, or an error on the way (then there is no waiting for the rest).
  let ready = false;
  for (let i = 0; i < 600 && !ready && errors.length === 0; i++) {
    ready = await page.evaluate(() => document.body.dataset.ready === '1');
    if (!ready) await new Promise((r) => setTimeout(r, 100));
  }
  const t_open = (Date.now() - t0) / 1000;
  check('the page draws (it says it is ready)', ready, errors.join('; '));
  check('no console errors', errors.length === 0, errors.join('; '));
  if (!ready) {
    await browser.close();
    process.exit(1);
  }
  check('it asks for nothing over the network', requests.length === 0, requests.join(' '));

  const text = await page.evaluate(() => document.body.innerText);
  check('the verdict is on the page', text.includes(expected), 'looked for: ' + expected);
  if (!valid)
    check('... with the two bodies in contact', / touches /.test(text));

  const canvas = page.locator('#view canvas');
  const shot = await canvas.screenshot();
  const s = await pixels(page, shot);
  check('the 3-D view is not blank', s.notBackground > 0.05 && s.colours > 20,
        JSON.stringify(s));

  // The slider at its two ends: the robot is elsewhere.
  const frames = await page.evaluate(() => Number(document.getElementById('slider').max));
  async function slide(v) {
    await page.evaluate((x) => {
      const el = document.getElementById('slider');
      el.value = x;
      el.dispatchEvent(new Event('input'));
    }, v);
    return canvas.screenshot();
  }
  const first = await slide(0), last = await slide(frames);
  const d = await pixels(page, first, last);
  check('the slider moves the robot', frames > 0 && d.differ > 0.002, JSON.stringify(d));
  const again = await slide(0);
  const same = await pixels(page, first, again);
  check('... and back to where it was', same.differ < 0.0005, JSON.stringify(same));

  // The play button moves the slider on by itself (no time is checked:
  // it only has to get past the first frame, within a minute).
  await slide(0);
  await page.click('#play');
  let played = false;
  for (let i = 0; i < 600 && !played; i++) {
    played = await page.evaluate(() => window.mpbView.frame > 0);
    if (!played) await new Promise((r) => setTimeout(r, 100));
  }
  await page.click('#play');   // pause (or play again if it ended: harmless)
  check('the play button animates the run', played);

  // Every stage can be chosen: the panel then gives its own number of
  // waypoints (the stages of the runs checked here all differ in it).
  const stages = await page.evaluate(() => Array.from(
    document.querySelectorAll('#stage option')).map((o) => o.textContent));
  const counts = [];
  for (let i = 0; i < stages.length; i++) {
    await page.selectOption('#stage', String(i));
    const shown = await page.evaluate(() => document.getElementById('verdict').innerText);
    counts.push((shown.match(/(\d+) waypoints/) || [])[1]);
  }
  check('each of the ' + stages.length + ' stages can be chosen (' + stages.join(', ') + ')',
        counts.every((c) => c) && new Set(counts).size === stages.length, counts.join(' '));
  await page.selectOption('#stage', String(Math.max(0, stages.findIndex((s) => s.includes('(')))));

  // The goal: hiding it changes the picture.
  async function toggle(id) {
    await page.click('#' + id);
    return canvas.screenshot();
  }
  const without = await toggle('show-goal'), withGoal = await toggle('show-goal');
  const g = await pixels(page, withGoal, without);
  check('the goal is drawn', g.differ > 0.0005, JSON.stringify(g));

  // The picture for the docs: the failure, as the page opens on it.
  if (!valid)
    await page.click('#to-failure');
  await page.screenshot({ path: shot_path });
  console.log(`# opened and drawn in ${t_open.toFixed(2)} s, ${frames + 1} frames`);
  await browser.close();
  process.exit(failed ? 1 : 0);
})().catch((e) => {
  console.log('not ok - the browser ran the checks (' + e.message.split('\n')[0] + ')');
  process.exit(1);
});
